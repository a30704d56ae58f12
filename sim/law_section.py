"""The front page's section "Does the chaos depend on the contact law?": the flagship run
under each contact law of docs/model.md (the study that config `report.contact_laws` names,
one case per law), with the clearance diagram under the paper's law and under the law
without memory (`report.bifurcation_clearance`, `report.bifurcation_clearance_memoryless`).

Per law: the model exponent over the ensemble's members on each link model the study takes it
on (median and its distribution-free interval), the verdict of claim 5 (the flagship's
channels: A x, A y and B x chaotic, B y periodic; sim.claims.flagship_verdicts) and, where a
clearance diagram ran under that law, of claim 6's clearance part (chaos grows from 0 to 1 mm
and B y stays periodic; sim.claims.growth). Then one sentence: whether the paper's chaos
claims hold under every law, and where along the clearance they do not.
"""

from collections.abc import Mapping, Sequence

import numpy as np
import pandas as pd

from sim import front_page as page
from sim.analysis.verdicts import NOT_EVALUATED, SUPPORTED
from sim.case_chaos import case_chaos, exponents_text
from sim.claims import chaos_onset, growth, states_verdict
from sim.model.contact_laws import LAWS

#: the scene name of each law and whether its damping remembers the onset rate δ̇⁻
MEMORY = {law.name: law.memory for law in LAWS}

#: why the laws are compared, for the reader who meets the section first
WHY = (
    "Every chaos result above comes from one contact law, the paper's Lankarani–Nikravesh "
    "law, whose damping remembers the rate at which each impact began. The flagship (A and B "
    "at 0.5 mm, 150 rpm) runs here under each law of docs/model.md at the same nominal "
    "restitution, as an ensemble, and the clearance diagram runs again under the law without "
    "memory, whose exponent is defined at grazing impacts too. Where the verdicts agree, the "
    "chaos is the mechanism's; where they part, the contact law decides it."
)


def _diagram(path: str) -> tuple[str, str, str]:
    """Claim 6's clearance part on one bifurcation table: its verdict, its key numbers and
    where chaos starts (in mm)."""
    _, _, states, key = growth(path)
    table = pd.read_csv(path)
    values = np.sort(table[table.columns[0]].unique())
    start = chaos_onset(table, values)
    onset = "nowhere" if start is None else f"from {values[start] * 1e3:g} mm"
    return states_verdict(list(states)), key, onset


def law_rows(
    inputs: Mapping[str, object], contacts: Mapping[str, Mapping[str, dict]]
) -> list[dict]:
    """One row per case of the contact-law study, in its order: {case, law, memory, chaos
    (sim.case_chaos.CaseChaos), clearance: (verdict, key, onset) or None}. `inputs` are the
    landing rule's (sim.studies.config.LANDING_INPUTS), `contacts` the contact law of each
    case of each role (sim.studies.config.landing_contacts)."""
    diagrams = {
        contacts[role]["sweep"]["law"]: _diagram(inputs[f"{role}_table"])
        for role in ("bifurcation_clearance", "bifurcation_clearance_memoryless")
        if f"{role}_table" in inputs and role in contacts
    }
    rows = []
    for case, chaos in case_chaos(inputs, "contact_laws").items():
        law = contacts["contact_laws"][case]["law"]
        rows.append(
            {
                "case": case,
                "law": law,
                "memory": MEMORY.get(law, True),
                "chaos": chaos,
                "clearance": diagrams.get(law),
            }
        )
    return rows


def conclusion(rows: Sequence[Mapping]) -> str:
    """One sentence: whether claims 5 and 6 (clearance) hold under every law, and where not."""
    drawn = [r for r in rows if r["clearance"] is not None]
    held = all(r["chaos"].verdict == SUPPORTED for r in rows) and all(
        r["clearance"][0] == SUPPORTED for r in drawn
    )
    onsets = "; ".join(f"under {r['law']} chaos appears {r['clearance'][2]}" for r in drawn)
    where = f" ({onsets})" if onsets else ""
    if held:
        return (
            f"The paper's chaos claims hold under every law run here{where}: the chaos is the "
            "mechanism's, not the contact law's."
        )
    parts = [f"claim 5 is {r['chaos'].verdict} under {r['law']}" for r in rows]
    parts += [f"claim 6 (clearance) is {r['clearance'][0]} under {r['law']}" for r in drawn]
    return f"The paper's chaos claims do not hold under every law: {', '.join(parts)}{where}."


def law_section(inputs: Mapping[str, object], contacts: Mapping[str, Mapping[str, dict]]) -> str:
    """The section (rst), or "" when the contact-law study did not run."""
    rows = law_rows(inputs, contacts)
    if not rows:
        return ""
    cells = []
    for r in rows:
        clearance = r["clearance"]
        cells.append(
            [
                page.escaped(f"{r['law']} ({'remembers δ̇⁻' if r['memory'] else 'no memory'})"),
                page.escaped(exponents_text(r["chaos"])),
                f"<b>{page.escaped(r['chaos'].verdict)}</b>: {page.escaped(r['chaos'].channels)}",
                page.escaped(
                    f"{NOT_EVALUATED}: no clearance diagram under this law"
                    if clearance is None
                    else f"{clearance[0]}: {clearance[1]}"
                ),
            ]
        )
    header = [
        "contact law",
        "model exponent over the members",
        "claim 5: A x, A y, B x chaotic; B y periodic",
        "claim 6: chaos grows with clearance",
    ]
    body = (
        page.paragraph(WHY)
        + page.table(header, cells, cells_are_html=True)
        + page.paragraph(conclusion(rows))
    )
    return page.heading("Does the chaos depend on the contact law?", "-") + page.raw(
        f'<div class="sim-paper">{body}</div>'
    )

"""The front page's section "Does lubrication remove the chaos?": the flagship with its
clearance joints dry and with an oil film (the study that config `report.lubrication` names),
and the lubricated flagship against the oil's viscosity (`report.lubrication_viscosity`).

Per case: the model exponent over the ensemble's members on each link model, with its interval,
and claim 5's reading of its chaos analysis (sim.case_chaos). For each lubricated case against
the dry one: the difference of the median per-revolution peak contact force of each oiled
joint, with its bootstrap interval over members and blocks of revolutions
(sim.analysis.verdicts.compare). Per viscosity: the model exponent and how many channels are
chaotic. Then one sentence: whether the film removes the chaos.
"""

from collections.abc import Mapping

import pandas as pd

from sim import front_page as page
from sim.analysis.revolutions import Bootstrap, contact_force
from sim.analysis.verdicts import compare
from sim.case_chaos import CaseChaos, case_chaos, exponents_text

#: why the film is compared, for the reader who meets the section first
WHY = (
    "An oil film in a revolute clearance carries the journal on a pressure that grows as the "
    "film thins and damps its squeeze, so the journal may float instead of striking the "
    "bearing: the film force has no memory of an impact. The flagship runs here with its "
    "clearance joints dry and with joint A lubricated (docs/model.md, “Lubricated revolute "
    "joints”; the oil, its temperature and the bearing's length are assumptions of the "
    "scene), as ensembles, and the lubricated flagship again at several viscosities."
)


def _force_change(
    revolutions: pd.DataFrame, dry: str, oiled: str, joint: str, boot: Bootstrap
) -> str:
    """The median peak contact force of `joint`, `oiled` case minus `dry`, with its interval
    and as a share of the dry median."""
    quantity = contact_force(joint)
    change = compare(revolutions, dry, oiled, quantity, "median", -1, boot)
    dry_median = float(revolutions.loc[revolutions.case == dry, quantity].median())
    share = change.estimate / dry_median if dry_median else float("nan")
    return (
        f"joint {joint}: {page.digits(change.estimate, '+')} N "
        f"{page.interval(*change.interval, 'N')} ({page.number(100 * share, '%')} of the dry "
        f"median {page.number(dry_median, 'N')}; {change.verdict} that the film lowers it)"
    )


def _viscosity_rows(path: str) -> list[list[str]]:
    """Per viscosity of the sweep's bifurcation table: its model exponent and chaotic
    channels."""
    table = pd.read_csv(path)
    parameter = table.columns[0]
    rows = []
    for value, part in table.groupby(parameter, sort=True):
        exponent = part.model_lyapunov_exponent_per_s.iloc[0]
        stderr = part.model_lyapunov_stderr_per_s.iloc[0]
        chaotic = int((part.verdict == "chaotic").sum())
        rows.append(
            [
                f"{page.digits(value)} Pa s",
                f"{page.number(exponent)} ± {page.number(stderr, '1/s')}",
                f"{chaotic} of {len(part)} channels chaotic",
            ]
        )
    return rows


def _primary(chaos: CaseChaos) -> str:
    """A case's primary model exponent in a few words."""
    return chaos.exponents[0][2] if chaos.exponents else "not computed"


def conclusion(chaos: Mapping[str, CaseChaos], oiled: list[str], dry: list[str]) -> str:
    """One sentence: whether the lubricated cases lose the chaos the dry ones show, with the
    primary model exponents."""
    dry_chaotic = any("chaotic" in chaos[c].channels for c in dry)
    oiled_chaotic = [c for c in oiled if "chaotic" in chaos[c].channels]
    exponents = "; ".join(f"{c} {_primary(chaos[c])}" for c in [*dry, *oiled])
    if not dry_chaotic:
        return (
            "The dry mechanism shows no chaotic channel here, so there is no chaos to remove "
            f"(model exponents: {exponents})."
        )
    if oiled_chaotic:
        return (
            f"The oil film does not remove the chaos: {', '.join(oiled_chaotic)} keeps chaotic "
            f"channels (model exponents: {exponents})."
        )
    return (
        "The oil film removes the chaos: no lubricated case has a chaotic channel (model "
        f"exponents: {exponents})."
    )


def lubrication_section(
    inputs: Mapping[str, object], contacts: Mapping[str, Mapping[str, dict]], boot: Bootstrap
) -> str:
    """The section (rst), or "" when the lubrication study did not run."""
    chaos = case_chaos(inputs, "lubrication")
    if not chaos:
        return ""
    films = {case: contacts["lubrication"][case]["lubricated"] for case in chaos}
    dry = [case for case, joints in films.items() if not joints]
    oiled = [case for case, joints in films.items() if joints]
    rows = [
        [
            page.escaped(
                f"{case} ({'oil in ' + ', '.join(films[case]) if films[case] else 'dry'})"
            ),
            page.escaped(exponents_text(c)),
            f"<b>{page.escaped(c.verdict)}</b>: {page.escaped(c.channels)}",
        ]
        for case, c in chaos.items()
    ]
    header = [
        "case",
        "model exponent over the members",
        "claim 5: A x, A y, B x chaotic; B y periodic",
    ]
    body = page.paragraph(WHY) + page.table(header, rows, cells_are_html=True)
    if "lubrication_revolutions" in inputs and dry:
        revolutions = pd.read_csv(inputs["lubrication_revolutions"])
        changes = [
            f"{case} against {dry[0]}: " + _force_change(revolutions, dry[0], case, joint, boot)
            for case in oiled
            for joint in films[case]
        ]
        body += page.paragraph(
            "Peak contact force, median over revolutions and members, lubricated minus dry: "
            + "; ".join(changes)
        )
    if "lubrication_viscosity_table" in inputs:
        body += page.table(
            ["viscosity", "model exponent", "channels"],
            _viscosity_rows(inputs["lubrication_viscosity_table"]),
        )
    body += page.paragraph(conclusion(chaos, oiled, dry))
    return page.heading("Does lubrication remove the chaos?", "-") + page.raw(
        f'<div class="sim-paper">{body}</div>'
    )

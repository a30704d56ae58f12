"""The paper's section of the report's front page (sim.paper_section): each claim of
docs/studies.md judged on our results (sim.claims), with the headline figures, then the sections
on the contact laws (sim.law_section) and the oil film (sim.lubrication_section) when their
studies ran; and claims.csv."""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import pandas as pd

from sim.analysis.revolutions import Bootstrap
from sim.atomic import write_atomically
from sim.claims import judge_all
from sim.law_section import law_section
from sim.lubrication_section import lubrication_section
from sim.paper_section import paper_section


def main(sm) -> None:
    inputs = dict(sm.input.items())
    boot = Bootstrap(**sm.params.statistics)
    claims, meta = judge_all(inputs, boot)
    table = pd.DataFrame(claims)
    table.to_csv(sm.output.csv, index=False)
    text = (
        paper_section(
            inputs, claims, meta, sm.params.recording, sm.params.statistics, sm.params.ensemble
        )
        + law_section(inputs, sm.params.contacts)
        + lubrication_section(inputs, sm.params.contacts, boot)
    )
    write_atomically(Path(sm.output.rst), lambda temporary: temporary.write_text(text))
    with open(sm.log[0], "w") as log:
        log.write(table[["short", "verdict", "key"]].to_string() + "\n")


main(snakemake)  # noqa: F821 (injected by Snakemake)

"""Per-revolution peaks of every ensemble member of a study's cases (one row per revolution),
and their distributions with bootstrap intervals (sim.analysis.revolutions)."""

import pandas as pd
import xarray as xr

from sim.analysis.revolutions import Bootstrap, revolution_table, summarise
from sim.plots import tables


def main(sm) -> None:
    cases = list(sm.params.cases)
    runs = list(sm.input.runs)
    per_case = len(runs) // len(cases)
    parts = []
    for i, path in enumerate(runs):
        with xr.open_dataset(path) as run:
            parts.append(revolution_table(run.load(), cases[i // per_case], sm.params.transient))
    table = pd.concat(parts, ignore_index=True)
    table.to_csv(sm.output.revolutions, index=False)
    boot = Bootstrap(**sm.params.statistics)
    summary = summarise(table, boot)
    note = (
        f"{per_case} members per case, {sm.params.transient} transient revolutions dropped; "
        f"{boot.level:.0%} percentile intervals of a two-stage bootstrap (members, then moving "
        f"blocks of revolutions), {boot.resamples} resamples, seed {boot.seed}"
    )
    title = f"Per-revolution peaks: {sm.wildcards.study}"
    tables.write_table(summary, sm.output.csv, sm.output.html, title, note)
    with open(sm.log[0], "w") as log:
        log.write(summary.to_string() + "\n")


main(snakemake)  # noqa: F821 (injected by Snakemake)

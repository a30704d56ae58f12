"""Table of a study's model-based exponents over ensemble members: per case and link model
the median, a distribution-free interval for the median (sim.analysis.members) and the mean of
the members' own standard errors. The first link model of the study's (`links`, then
`compare`) is the one its verdicts and claims read: its rows are marked `primary`."""

import pandas as pd
import xarray as xr

from sim.analysis.members import median_interval
from sim.plots import tables


def read_member(path: str) -> dict:
    """A member's exponent file: its case, link model, exponent, standard error and attributes."""
    with xr.open_dataset(path) as ds:
        return {
            "case": str(ds.attrs["case"]),
            "links": str(ds.attrs["model_lyapunov_links"]),
            "exponent": float(ds.model_lyapunov_exponent),
            "stderr": float(ds.model_lyapunov_stderr),
            "attrs": dict(ds.attrs),
        }


def case_row(case: str, members: list[dict], level: float) -> dict:
    """One case's row from its members' exponents on one link model (`read_member`)."""
    interval = median_interval([m["exponent"] for m in members], level)
    attrs = members[-1]["attrs"]
    return {
        "case": case,
        "links": attrs["model_lyapunov_links"],
        "members": interval.n,
        "median_exponent_per_s": interval.median,
        "interval_low_per_s": interval.low,
        "interval_high_per_s": interval.high,
        "interval_coverage": interval.coverage,
        "mean_member_stderr_per_s": sum(m["stderr"] for m in members) / len(members),
        "revolutions": attrs["model_lyapunov_revolutions"],
        "transient_revolutions": attrs["model_lyapunov_transient_revolutions"],
        "rtol": attrs["model_lyapunov_rtol"],
        "renormalisation_interval_s": attrs["model_lyapunov_interval_s"],
    }


def main(sm) -> None:
    links = list(sm.params.links)
    level = float(sm.params.statistics.get("level", 0.95))
    groups: dict[tuple[str, str], list[dict]] = {}
    for path in sm.input:
        member = read_member(path)
        groups.setdefault((member["case"], member["links"]), []).append(member)
    rows = [
        case_row(case, groups[case, model], level) | {"primary": model == links[0]}
        for case in sm.params.cases
        for model in links
    ]
    table = pd.DataFrame(rows)
    note = (
        "Benettin on the model's own integrator, on the link model the links column names "
        f"(primary: {links[0]}, the one the verdicts and claims read), one exponent per "
        "ensemble member; interval: order statistics of the members enclosing the population "
        "median with the stated coverage (the narrowest reaching "
        f"{level:.0%}, else the range)"
    )
    title = f"Model-based largest Lyapunov exponent over members: {sm.wildcards.study}"
    tables.write_table(table, sm.output.csv, sm.output.html, title, note)
    with open(sm.log[0], "w") as log:
        log.write(table.to_string() + "\n")


main(snakemake)  # noqa: F821 (injected by Snakemake)

"""Table of a study's model-based exponents over ensemble members: per case the median, a
distribution-free interval for the median (sim.analysis.members) and the mean of the members'
own standard errors."""

import pandas as pd
import xarray as xr

from sim.analysis.members import median_interval
from sim.plots import tables


def case_row(case: str, paths: list[str], level: float) -> dict:
    """One case's row from its members' exponent files."""
    exponents, stderrs, attrs = [], [], {}
    for path in paths:
        with xr.open_dataset(path) as ds:
            exponents.append(float(ds.model_lyapunov_exponent))
            stderrs.append(float(ds.model_lyapunov_stderr))
            attrs = dict(ds.attrs)
    interval = median_interval(exponents, level)
    return {
        "case": case,
        "members": interval.n,
        "median_exponent_per_s": interval.median,
        "interval_low_per_s": interval.low,
        "interval_high_per_s": interval.high,
        "interval_coverage": interval.coverage,
        "mean_member_stderr_per_s": sum(stderrs) / len(stderrs),
        "revolutions": attrs["model_lyapunov_revolutions"],
        "transient_revolutions": attrs["model_lyapunov_transient_revolutions"],
        "links": attrs["model_lyapunov_links"],
        "rtol": attrs["model_lyapunov_rtol"],
        "renormalisation_interval_s": attrs["model_lyapunov_interval_s"],
    }


def main(sm) -> None:
    cases = list(sm.params.cases)
    per_case = len(sm.input) // len(cases)  # the input is case by case, members in order
    level = float(sm.params.statistics.get("level", 0.95))
    table = pd.DataFrame(
        [
            case_row(case, sm.input[i * per_case : (i + 1) * per_case], level)
            for i, case in enumerate(cases)
        ]
    )
    note = (
        "Benettin on the model's own integrator (on the links the links column names), one "
        "exponent per ensemble member; interval: "
        "order statistics of the members enclosing the population median with the stated "
        f"coverage (the narrowest reaching {level:.0%}, else the range)"
    )
    title = f"Model-based largest Lyapunov exponent over members: {sm.wildcards.study}"
    tables.write_table(table, sm.output.csv, sm.output.html, title, note)
    with open(sm.log[0], "w") as log:
        log.write(table.to_string() + "\n")


main(snakemake)  # noqa: F821 (injected by Snakemake)

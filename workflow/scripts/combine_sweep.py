"""Combine the per-point runs of a sweep into one bifurcation dataset (combine_sweep)."""

import xarray as xr

from sim.analysis.bifurcation import combine_sweep
from sim.results import write_netcdf


def main(snakemake) -> None:
    datasets = [xr.open_dataset(path) for path in snakemake.input.runs]
    combined = combine_sweep(datasets, snakemake.params.parameter, snakemake.params.values)
    combined.attrs["runs"] = " ".join(snakemake.input.runs)
    # a point with every joint ideal has an empty `joint` coordinate read back as float:
    # its on-disk encoding must not be carried over to the combined names
    for variable in combined.variables.values():
        variable.encoding = {}
    write_netcdf(combined, snakemake.output[0])
    for ds in datasets:
        ds.close()
    with open(snakemake.log[0], "w") as log:
        log.write(f"{len(datasets)} points of {snakemake.params.parameter}\n")


main(snakemake)  # noqa: F821 (injected by Snakemake)

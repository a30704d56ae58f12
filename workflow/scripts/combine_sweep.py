"""Stack the batches of a sweep into one bifurcation dataset (rule combine_sweep)."""

from pathlib import Path

import xarray as xr

from sim.analysis.bifurcation import stack_points
from sim.results import write_netcdf


def main(snakemake) -> None:
    parts = [xr.open_dataset(Path(folder) / "batch.nc") for folder in snakemake.input.batches]
    combined = stack_points(parts)
    combined.attrs["runs"] = " ".join(part.attrs["runs"] for part in parts)
    # a point with every joint ideal has an empty `joint` coordinate read back as float:
    # its on-disk encoding must not be carried over to the combined names
    for variable in combined.variables.values():
        variable.encoding = {}
    write_netcdf(combined, snakemake.output[0])
    for part in parts:
        part.close()
    with open(snakemake.log[0], "w") as log:
        log.write(f"{combined.sizes['parameter']} points of {snakemake.params.parameter}\n")


main(snakemake)  # noqa: F821 (injected by Snakemake)

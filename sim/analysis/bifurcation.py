"""Bifurcation data: the Poincaré samples of a parameter sweep stacked in one dataset."""

from collections.abc import Sequence

import numpy as np
import xarray as xr

#: the run variables sampled once per revolution
SECTION_VARIABLES = (
    "section_eccentricity",
    "section_eccentricity_rate",
    "section_position",
    "section_velocity",
)


def combine_sweep(
    datasets: Sequence[xr.Dataset], parameter: str, values: Sequence[float]
) -> xr.Dataset:
    """Stack the section variables of the runs of a sweep along a new dimension ``parameter``.

    Plotting every section value of a channel against the parameter gives the bifurcation
    diagram: one point per value where the response is period-1, k points for period k, a
    vertical smear for quasi-periodic or chaotic motion.

    Args:
        datasets: run datasets (the contract of :func:`sim.analysis.run.analyze_run`), one per
            parameter value, all with the same joints, bodies and axes.
        parameter: the scene key swept, such as ``joints.A.clearance`` (stored as the
            ``name`` attribute of the ``parameter`` coordinate).
        values: the parameter value of every dataset, in the same order.

    Returns:
        A dataset with the section variables on (parameter, revolution, …); runs with fewer
        revolutions are padded with NaN.
    """
    if len(datasets) != len(values):
        raise ValueError(f"combine_sweep: {len(datasets)} datasets but {len(values)} values")
    for index, ds in enumerate(datasets):
        missing = [name for name in SECTION_VARIABLES if name not in ds.variables]
        if missing:
            raise ValueError(f"combine_sweep: dataset {index} lacks variable(s) {missing}")
    sections = [ds[list(SECTION_VARIABLES)] for ds in datasets]
    coordinate = xr.Variable(
        "parameter", np.asarray(values, dtype=float), {"name": parameter, "long_name": parameter}
    )
    # an outer join on revolution pads the shorter runs with NaN
    combined = xr.concat(sections, dim=coordinate, join="outer", fill_value=np.nan)
    combined.attrs = {
        "Conventions": "CF-1.8",
        "title": f"Poincaré samples against {parameter}",
        "source": "sim.analysis.bifurcation.combine_sweep",
    }
    return combined

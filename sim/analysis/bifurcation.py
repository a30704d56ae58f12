"""Bifurcation data: the Poincaré samples of a parameter sweep stacked in one dataset, with
each point's chaos indicators (model exponent, 0–1 K) beside them."""

from collections.abc import Sequence

import numpy as np
import xarray as xr

from sim.analysis.classify import VERDICTS, classify
from sim.analysis.poincare import MIN_REVOLUTIONS, SECTION_RESOLUTION
from sim.analysis.run import after_transient, run_scene
from sim.analysis.section import section_evidence
from sim.analysis.zero_one import zero_one_test

#: the run variables sampled once per revolution
SECTION_VARIABLES = (
    "section_eccentricity",
    "section_eccentricity_rate",
    "section_position",
    "section_velocity",
)


#: the per-point indicators stacked beside the section variables (see
#: :func:`section_indicators`; the model exponent comes from sim.studies.model_lyapunov)
INDICATOR_VARIABLES = (
    "model_lyapunov_exponent",
    "model_lyapunov_stderr",
    "zero_one_K",
    "section_period",
    "verdict",
)
#: section points after the transient the indicators need (the period search's 2 · 12 + 1)
MIN_SECTION_POINTS = MIN_REVOLUTIONS


def section_indicators(
    run: xr.Dataset, transient_revolutions: int, exponent: float, stderr: float
) -> xr.Dataset:
    """The chaos indicators of one sweep point, channel by channel, after the transient.

    For every clearance joint and axis of ``run`` (as :func:`sim.analysis.run.analyze_run`
    computes them, but with the model's exponent in place of the per-channel time-series one):
    K of the 0–1 test on the Poincaré eccentricity (fluctuations below ``SECTION_RESOLUTION``
    of the channel's range count as noise, K = 0), the period of the section points
    (:func:`sim.analysis.section.section_evidence`, 0 when they do not repeat) and the
    verdict (:func:`sim.analysis.classify.classify` with ``exponent`` ± ``stderr``, 1/s, the
    model-based largest exponent of the whole linkage, as the Lyapunov vote).

    Returns:
        ``model_lyapunov_exponent`` and ``model_lyapunov_stderr`` (scalars, 1/s), and
        ``zero_one_K``, ``section_period``, ``verdict`` on (joint, axis); the per-channel
        variables are empty for an all-ideal run.
    """
    crank_period = float(run.attrs["crank_period"])
    steady = after_transient(run, transient_revolutions)
    if steady.sizes["revolution"] < MIN_SECTION_POINTS:
        raise ValueError(
            f"section_indicators: {steady.sizes['revolution']} section points after the "
            f"transient of {transient_revolutions}; the indicators need {MIN_SECTION_POINTS}"
        )
    shape = (run.sizes["joint"], run.sizes["axis"])
    K, period = np.full(shape, np.nan), np.zeros(shape, dtype=np.int64)
    verdict = np.full(shape, "", dtype=object)
    evidence = section_evidence(steady, run_scene(run)) if run.sizes["joint"] else {}
    for i, joint in enumerate(run.joint.values):
        for j, axis in enumerate(run.axis.values):
            channel, section = evidence[f"{joint}.{axis}"]
            K[i, j] = zero_one_test(
                channel.section_value, noise_floor=SECTION_RESOLUTION * channel.extent[0]
            ).K
            period[i, j] = section.period
            verdict[i, j] = classify(
                section=section,
                model_exponent=exponent,
                model_stderr=stderr,
                lyapunov_exponent=np.nan,
                lyapunov_stderr=np.nan,
                zero_one_K=K[i, j],
                time_scale=crank_period,
            ).verdict
    dims = ("joint", "axis")
    return xr.Dataset(
        {
            "model_lyapunov_exponent": (
                (),
                exponent,
                {"units": "s-1", "long_name": "largest Lyapunov exponent of the model (Benettin)"},
            ),
            "model_lyapunov_stderr": (
                (),
                stderr,
                {"units": "s-1", "long_name": "standard error of the model exponent over blocks"},
            ),
            "zero_one_K": (
                dims,
                K,
                {"units": "1", "long_name": "0-1 test for chaos K on the Poincare eccentricity"},
            ),
            "section_period": (
                dims,
                period,
                {"units": "1", "long_name": "period of the Poincare points in crossings (0: none)"},
            ),
            "verdict": (
                dims,
                verdict.astype(str),
                {"units": "1", "long_name": f"verdict: one of {', '.join(VERDICTS)}"},
            ),
        },
        coords={"joint": run.joint.values, "axis": run.axis.values},
    )


def stack_points(parts: Sequence[xr.Dataset], dim: str | xr.Variable = "parameter") -> xr.Dataset:
    """Concatenate sweep points (or batches of them) along ``dim``: an outer join pads the
    shorter runs, and the channels of a point whose joints are ideal, with NaN (verdicts with
    ""); the first part's attributes are kept."""
    fill = {name: np.nan for part in parts for name in part.data_vars}
    fill["verdict"] = ""
    return xr.concat(parts, dim=dim, join="outer", fill_value=fill, combine_attrs="override")


def combine_sweep(
    datasets: Sequence[xr.Dataset],
    parameter: str,
    values: Sequence[float],
    indicators: Sequence[xr.Dataset] | None = None,
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
        indicators: optionally, each point's ``INDICATOR_VARIABLES`` (the model exponent and
            its standard error, scalars in 1/s; K on (joint, axis)), in the same order.

    Returns:
        A dataset with the section variables on (parameter, revolution, …) and the indicators
        on (parameter[, joint, axis]); runs with fewer revolutions or joints are padded with
        NaN.
    """
    if len(datasets) != len(values):
        raise ValueError(f"combine_sweep: {len(datasets)} datasets but {len(values)} values")
    for index, ds in enumerate(datasets):
        missing = [name for name in SECTION_VARIABLES if name not in ds.variables]
        if missing:
            raise ValueError(f"combine_sweep: dataset {index} lacks variable(s) {missing}")
    sections = [ds[list(SECTION_VARIABLES)] for ds in datasets]
    if indicators is not None:
        if len(indicators) != len(datasets):
            raise ValueError(
                f"combine_sweep: {len(indicators)} indicator sets but {len(datasets)} datasets"
            )
        for index, ds in enumerate(indicators):
            missing = [name for name in INDICATOR_VARIABLES if name not in ds.variables]
            if missing:
                raise ValueError(f"combine_sweep: indicators {index} lack variable(s) {missing}")
        sections = [
            xr.merge([section, extra[list(INDICATOR_VARIABLES)]], combine_attrs="drop")
            for section, extra in zip(sections, indicators, strict=True)
        ]
    coordinate = xr.Variable(
        "parameter", np.asarray(values, dtype=float), {"name": parameter, "long_name": parameter}
    )
    combined = stack_points(sections, coordinate)
    combined.attrs = {
        "Conventions": "CF-1.8",
        "title": f"Poincaré samples against {parameter}",
        "source": "sim.analysis.bifurcation.combine_sweep",
    }
    return combined

"""Chaos analysis of one simulation output dataset, channel by channel."""

import json
import math

import numpy as np
import xarray as xr

from sim.analysis.classify import VERDICTS, Verdict, classify, indicator_agreement
from sim.analysis.lyapunov import rosenstein
from sim.analysis.poincare import MIN_REVOLUTIONS, SECTION_RESOLUTION
from sim.analysis.section import STILL_RANGE, Coordinate, SectionEvidence, section_evidence
from sim.analysis.zero_one import zero_one_test

#: variables :func:`analyze_run` reads, with their dimensions
REQUIRED_VARIABLES = {
    "eccentricity": ("time", "joint", "axis"),
    "eccentricity_rate": ("time", "joint", "axis"),
    "section_eccentricity": ("revolution", "joint", "axis"),
    "section_eccentricity_rate": ("revolution", "joint", "axis"),
    "position": ("time", "body", "axis"),
    "velocity": ("time", "body", "axis"),
    "section_position": ("revolution", "body", "axis"),
    "section_velocity": ("revolution", "body", "axis"),
}
#: relative deviation of the time steps tolerated as uniform sampling
UNIFORM_SAMPLING_RTOL = 1e-6


def validate_run(ds: xr.Dataset, *, transient_revolutions: int) -> None:
    """Raise ValueError naming what is missing when ``ds`` does not follow the run contract."""
    for name, dims in REQUIRED_VARIABLES.items():
        if name not in ds.variables:
            raise ValueError(f"missing variable '{name}' (dimensions {', '.join(dims)})")
        if ds[name].dims != dims:
            raise ValueError(f"variable '{name}' has dimensions {ds[name].dims}, expected {dims}")
    if "crank_period" not in ds.attrs:
        raise ValueError("missing global attribute 'crank_period' (s)")
    available = ds.sizes["revolution"] - transient_revolutions
    if available < MIN_REVOLUTIONS:
        raise ValueError(
            f"variable 'revolution' has {ds.sizes['revolution']} revolutions; the analysis needs "
            f"{transient_revolutions} transient + {MIN_REVOLUTIONS} recorded"
        )
    steps = np.diff(ds["time"].values)
    if np.ptp(steps) > UNIFORM_SAMPLING_RTOL * np.mean(steps):
        raise ValueError("variable 'time' is not uniformly sampled")


def _analyze_channel(
    channel: Coordinate,
    section: SectionEvidence,
    dt: float,
    crank_period: float,
    model: tuple[float, float],
) -> tuple[dict, Verdict]:
    """The indicators of one channel and its verdict; ``model``: the model exponent and its
    standard error (1/s; NaN when not computed)."""
    if channel.extent[0] > STILL_RANGE * np.max(np.abs(channel.value)):
        exponent = rosenstein(channel.value, dt)
        lyap = (exponent.exponent, exponent.stderr, exponent.emb_dim, exponent.lag)
    else:
        lyap = (np.nan, np.nan, 0, 0)  # a channel that does not move has no divergence
    K = zero_one_test(channel.section_value, noise_floor=SECTION_RESOLUTION * channel.extent[0]).K
    verdict = classify(
        section=section,
        lyapunov_exponent=lyap[0],
        lyapunov_stderr=lyap[1],
        zero_one_K=K,
        time_scale=crank_period,
        model_exponent=model[0],
        model_stderr=model[1],
    )
    numbers = {
        "lyapunov_exponent": lyap[0],
        "lyapunov_stderr": lyap[1],
        "embedding_dimension": lyap[2],
        "embedding_lag": lyap[3] * dt,
        "zero_one_K": K,
        "section_period": section.period,
        "section_return_distance": section.return_distance,
        "section_spread": channel.structure.spread,
        "section_held": int(section.held),
        "state_period": section.state_period,
        "indicator_agreement": verdict.agreement,
    }
    return numbers, verdict


_ATTRIBUTES = {
    "lyapunov_exponent": ("s-1", "largest Lyapunov exponent (Rosenstein) of the channel value"),
    "lyapunov_stderr": ("s-1", "standard error of the largest Lyapunov exponent over sub-series"),
    "embedding_dimension": ("1", "delay-embedding dimension (false nearest neighbours)"),
    "embedding_lag": ("s", "delay-embedding lag (first minimum of mutual information)"),
    "zero_one_K": ("1", "0-1 test for chaos K on the Poincare section values"),
    "section_period": ("1", "period of the Poincare section points in crossings (0: none)"),
    "section_return_distance": (
        "1",
        "median distance between section points one period apart, over the orbit extent",
    ),
    "section_spread": ("1", "RMS distance of section points from their centroid, over extent"),
    "section_held": (
        "1",
        "1: the channel's section value lies at its clearance bound in most crossings",
    ),
    "state_period": (
        "1",
        "period of every recorded coordinate of the mechanism at the section (0: none)",
    ),
    "indicator_agreement": ("1", "fraction of chaos indicators consistent with the verdict"),
}


def after_transient(ds: xr.Dataset, transient_revolutions: int) -> xr.Dataset:
    """A run's samples and section points after its first ``transient_revolutions``."""
    time = ds["time"].values
    return ds.isel(
        time=time >= time[0] + transient_revolutions * float(ds.attrs["crank_period"]),
        revolution=slice(transient_revolutions, None),
    )


def run_scene(ds: xr.Dataset) -> dict | None:
    """The resolved scene a run records (its ``scene`` attribute, JSON); None without."""
    return json.loads(ds.attrs["scene"]) if "scene" in ds.attrs else None


def analyze_run(
    ds: xr.Dataset,
    *,
    transient_revolutions: int,
    model_exponent: float = math.nan,
    model_stderr: float = math.nan,
) -> xr.Dataset:
    """Phase portraits, Poincaré points, exponents and verdicts of every channel of a run.

    Channels are the eccentricity of every clearance joint along every axis ('A.x', …) or,
    for an all-ideal run (empty ``joint``), the position of every body along every axis. The
    first ``transient_revolutions`` crank revolutions are dropped. Per channel:

    - the phase portrait (value against rate) after the transient;
    - the Poincaré points (one per revolution), their period
      (:func:`sim.analysis.poincare.section_structure`), whether the joint's wall holds the
      channel there and whether the mechanism's whole state returns with it
      (:func:`sim.analysis.section.section_evidence`);
    - the largest Lyapunov exponent from the value series
      (:func:`sim.analysis.lyapunov.rosenstein`, automatic embedding and fit range);
    - the 0–1 test on the section values (:func:`sim.analysis.zero_one.zero_one_test`), with
      fluctuations below the section resolution taken as numerical noise;
    - the verdict and its reason (:func:`sim.analysis.classify.classify`), with the crank
      period as time scale and the model's exponent, when given, as the first chaos vote.

    Args:
        ds: a run dataset following the contract of ``REQUIRED_VARIABLES`` (uniform ``time``
            in s, ``revolution``, global attribute ``crank_period`` in s; the attribute
            ``scene``, the resolved scene as JSON, gives the clearance bounds).
        transient_revolutions: revolutions dropped before analysing.
        model_exponent, model_stderr: the model-based largest exponent of the linkage and its
            standard error (1/s, :mod:`sim.studies.model_lyapunov`); NaN: not computed.

    Returns:
        A CF-annotated dataset with dimensions ``channel``, ``sample`` and ``revolution``.
    """
    validate_run(ds, transient_revolutions=transient_revolutions)
    crank_period = float(ds.attrs["crank_period"])
    steady = after_transient(ds, transient_revolutions)
    dt = float(np.mean(np.diff(ds["time"].values)))
    evidence = section_evidence(steady, run_scene(ds))
    channels = [channel for channel, _ in evidence.values()]
    model = (model_exponent, model_stderr)
    results = [
        _analyze_channel(channel, section, dt, crank_period, model)
        for channel, section in evidence.values()
    ]
    verdicts = [verdict for _, verdict in results]

    def per_channel(values: list, units: str, long_name: str) -> xr.Variable:
        return xr.Variable("channel", values, {"units": units, "long_name": long_name})

    def per_point(dim: str, values: list, units: str, long_name: str) -> xr.Variable:
        data = np.column_stack(values) if values else np.empty((steady.sizes[dim], 0))
        return xr.Variable((dim, "channel"), data, {"units": units, "long_name": long_name})

    variables = {
        "channel_joint": per_channel(
            [c.item for c in channels], "1", "clearance joint (or body, all-ideal run)"
        ),
        "channel_axis": per_channel([c.axis for c in channels], "1", "axis of the channel"),
        "channel_quantity": per_channel(
            [c.quantity for c in channels], "1", "quantity analysed: eccentricity or position"
        ),
        "phase_time": xr.Variable(
            "sample", steady["time"].values, {"units": "s", "long_name": "time of phase sample"}
        ),
        "phase_eccentricity": per_point(
            "sample", [c.value for c in channels], "m", "channel value after the transient"
        ),
        "phase_eccentricity_rate": per_point(
            "sample", [c.rate for c in channels], "m s-1", "channel rate after the transient"
        ),
        "poincare_eccentricity": per_point(
            "revolution", [c.section_value for c in channels], "m", "channel value on section"
        ),
        "poincare_eccentricity_rate": per_point(
            "revolution", [c.section_rate for c in channels], "m s-1", "channel rate on section"
        ),
        "verdict": xr.Variable(
            "channel",
            [v.verdict for v in verdicts],
            {"units": "1", "long_name": f"verdict: one of {', '.join(VERDICTS)}"},
        ),
        "verdict_reason": per_channel(
            [str(v.evidence["reason"]) for v in verdicts], "1", "evidence behind the verdict"
        ),
        "verdict_basis": per_channel(
            [str(v.evidence["basis"]) for v in verdicts], "1", "what decided the verdict"
        ),
    }
    for name, (units, long_name) in _ATTRIBUTES.items():
        variables[name] = per_channel([numbers[name] for numbers, _ in results], units, long_name)

    agreement = indicator_agreement(verdicts)
    return xr.Dataset(
        variables,
        coords={
            "channel": ("channel", [c.name for c in channels], {"long_name": "channel"}),
            "revolution": (
                "revolution",
                steady["revolution"].values,
                {"units": "1", "long_name": "crank revolution"},
            ),
        },
        attrs={
            "Conventions": "CF-1.8",
            "title": "Chaos analysis of a linkage run",
            "source": "sim.analysis.run.analyze_run",
            "transient_revolutions": transient_revolutions,
            "crank_period": crank_period,
            "mean_indicator_agreement": agreement["mean_agreement"],
            "lyapunov_zero_one_agreement": agreement["lyapunov_zero_one"],
        },
    )

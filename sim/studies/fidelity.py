"""Accuracy of one run against a reference run of the same scene (work–precision).

Two horizons, because the flagship motion is chaotic:

- Short horizon, pointwise: over the first revolutions, while the two trajectories are still
  close, the difference of a response at the same sample times, as RMS and maximum over the
  window, relative to the reference's peak in the window (:func:`short_horizon_errors`), and
  the time at which the difference first exceeds a share of that peak
  (:func:`separation_time`: how long the run stays a prediction of the reference).
- Long horizon, statistical: after chaos has separated the trajectories, only their statistics
  can agree: peak values (:func:`peak_differences`), largest Lyapunov exponents
  (:func:`lyapunov_differences`, from :func:`sim.analysis.run.analyze_run`) and the
  distribution of Poincaré section points (:func:`poincare_distances`, the first Wasserstein
  distance per joint and axis over the joint's clearance).

Runs are output datasets of :func:`sim.run.simulate` (``time`` in s, attribute
``crank_period`` in s, the resolved ``scene`` as JSON).
"""

import numpy as np
import xarray as xr
from scipy.stats import wasserstein_distance

from sim.results import scene_of

#: the responses compared pointwise: name → (variable, selection); a vector response (the
#: eccentricity, x and y) is compared by the Euclidean norm of its difference
SHORT_CHANNELS = {
    "slider_acceleration": ("acceleration", {"body": "slider", "axis": "y"}),
    "drive_torque": ("drive_torque", {}),
    "eccentricity_A": ("eccentricity", {"joint": "A"}),
}
#: sample times of two runs closer than this share of the crank period are the same time
SAME_TIME = 1e-9


def channel(ds: xr.Dataset, name: str) -> xr.DataArray:
    """The response ``name`` of :data:`SHORT_CHANNELS`, shaped (time, components)."""
    variable, selection = SHORT_CHANNELS[name]
    values = ds[variable].sel(selection)
    if values.ndim == 1:
        values = values.expand_dims("component", axis=1)
    return values


def _common_samples(
    run: xr.DataArray, reference: xr.DataArray, t_end: float, period: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Reference times up to t_end, and both runs' values at exactly those times."""
    ref = reference.isel(time=np.flatnonzero(reference.time.values <= t_end + SAME_TIME * period))
    try:
        values = run.sel(time=ref.time, method="nearest", tolerance=SAME_TIME * period)
    except KeyError:
        raise ValueError(
            f"the run is not sampled at the reference's times up to t = {t_end:.6g} s: compare "
            "runs sampled on the same times (the same output_per_revolution, or a multiple of "
            "it) and at least as long"
        ) from None
    return ref.time.values, values.values, ref.values


def short_horizon_errors(
    run: xr.Dataset,
    reference: xr.Dataset,
    *,
    revolutions: float,
    channels: tuple[str, ...] = tuple(SHORT_CHANNELS),
) -> dict[str, tuple[float, float]]:
    """Pointwise error of ``run`` against ``reference`` over the first ``revolutions``.

    For each response x (:data:`SHORT_CHANNELS`), with d(t) = |x(t) − x_ref(t)| (Euclidean
    norm over components) at the reference's sample times t ≤ revolutions · T (T the crank
    period) and P = max |x_ref| over the same times:

        RMS error = sqrt(mean d²) / P,   maximum error = max d / P   (dimensionless).

    The run must be sampled at the reference's times (it may be sampled more finely on the
    same grid): values are never interpolated, since an impact's spike would be smeared.

    Returns:
        {response name: (RMS error, maximum error)}.
    """
    period = float(reference.attrs["crank_period"])
    out = {}
    for name in channels:
        _, x, x_ref = _common_samples(
            channel(run, name), channel(reference, name), revolutions * period, period
        )
        d = np.linalg.norm(x - x_ref, axis=1)
        peak = float(np.max(np.linalg.norm(x_ref, axis=1)))
        out[name] = (float(np.sqrt(np.mean(d**2))) / peak, float(d.max()) / peak)
    return out


def separation_time(
    run: xr.Dataset, reference: xr.Dataset, *, name: str = "eccentricity_A", share: float = 0.1
) -> float:
    """Time (s) at which the response ``name`` of ``run`` first differs from the reference's
    by more than ``share`` of the reference's peak over the whole common duration: the
    horizon over which the run predicts the reference pointwise (chaotic motion separates
    two runs exponentially, so this grows only with the logarithm of their accuracy).
    ``inf`` when they never differ that much."""
    period = float(reference.attrs["crank_period"])
    t_end = min(float(run.time[-1]), float(reference.time[-1]))
    t, x, x_ref = _common_samples(channel(run, name), channel(reference, name), t_end, period)
    d = np.linalg.norm(x - x_ref, axis=1)
    beyond = d > share * np.max(np.linalg.norm(x_ref, axis=1))
    return float(t[np.argmax(beyond)]) if beyond.any() else float("inf")


def peaks(ds: xr.Dataset) -> dict[str, float]:
    """The peak values the studies report (Tables 4 and 5): slider acceleration along the
    guide (m/s²), driving torque (N·m) and the contact force of every clearance joint (N),
    each the largest over every accepted step and sample of the run."""
    out = {
        "slider_acceleration": float(ds.peak_acceleration.sel(body="slider", axis="y")),
        "drive_torque": float(ds.peak_drive_torque),
    }
    for joint in ds.joint.values:
        out[f"contact_force_{joint}"] = float(ds.peak_normal_force.sel(joint=joint))
    return out


def peak_differences(run: xr.Dataset, reference: xr.Dataset) -> dict[str, float]:
    """Relative difference of each peak value (:func:`peaks`) from the reference's,
    (p − p_ref) / p_ref, for the peaks both runs have."""
    ours, theirs = peaks(run), peaks(reference)
    return {name: (ours[name] - theirs[name]) / theirs[name] for name in ours if name in theirs}


def lyapunov_differences(analysis: xr.Dataset, reference: xr.Dataset) -> dict[str, float]:
    """Difference λ − λ_ref (1/s) of the largest Lyapunov exponent of every channel ('A.x', …)
    both chaos analyses (:func:`sim.analysis.run.analyze_run`) have, matched by name."""
    common = [c for c in analysis.channel.values if c in set(reference.channel.values)]
    ours = analysis.lyapunov_exponent.sel(channel=common).values
    theirs = reference.lyapunov_exponent.sel(channel=common).values
    return {str(c): float(a - b) for c, a, b in zip(common, ours, theirs, strict=True)}


def section_distance(points: np.ndarray, reference: np.ndarray, scale: float) -> float:
    """First Wasserstein distance between two sets of scalar section values, over ``scale``.

    W₁ is the area between the two empirical distribution functions: the mean distance the
    points of one set must move to become the other (Villani, "Optimal Transport", 2009,
    ch. 6). Shifting every point by s gives s; a set against itself gives 0. Over the
    clearance, it reads as the share of the clearance by which the maps differ.
    """
    return float(wasserstein_distance(points, reference)) / scale


def poincare_distances(
    run: xr.Dataset, reference: xr.Dataset, *, transient_revolutions: int
) -> dict[str, float]:
    """Distance between the Poincaré maps of two runs, per clearance joint and axis ('A.x', …):
    :func:`section_distance` of the section eccentricities after ``transient_revolutions``,
    over the joint's clearance in the reference's scene."""
    joints = scene_of(reference)["joints"]
    out = {}
    for joint in run.joint.values:
        if joint not in reference.joint.values:
            continue
        for axis in run.axis.values:
            where = {"joint": joint, "axis": axis, "revolution": slice(transient_revolutions, None)}
            out[f"{joint}.{axis}"] = section_distance(
                run.section_eccentricity.sel(where).values,
                reference.section_eccentricity.sel(where).values,
                joints[str(joint)]["clearance"],
            )
    return out

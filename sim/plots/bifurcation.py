"""Bifurcation diagrams with the largest Lyapunov exponent beneath."""

import numpy as np
import pandas as pd
import xarray as xr
from matplotlib.figure import Figure

from sim.plots import style

MM = 1e3


def lyapunov_against_parameter(
    analyses: list[xr.Dataset], values: list[float], parameter: str
) -> pd.DataFrame:
    """One row per sweep point and channel: the parameter value, the largest Lyapunov
    exponent (1/s) with its standard error, the Poincaré period and the verdict. A point
    whose joints are all ideal (clearance 0) is analysed on body positions instead; its
    channels are named after bodies."""
    rows = []
    for value, analysis in zip(values, analyses, strict=True):
        for channel in analysis.channel.values:
            one = analysis.sel(channel=channel)
            rows.append(
                {
                    parameter: value,
                    "channel": str(channel),
                    "quantity": str(one.channel_quantity.item()),
                    "lyapunov_exponent_per_s": float(one.lyapunov_exponent),
                    "lyapunov_stderr_per_s": float(one.lyapunov_stderr),
                    "section_period": int(one.section_period),
                    "verdict": str(one.verdict.item()),
                }
            )
    return pd.DataFrame(rows)


def _scale(unit: str) -> tuple[float, str]:
    return (MM, "mm") if unit == "m" else (1.0, unit)


def plot_bifurcation(
    combined: xr.Dataset,
    lyapunov: pd.DataFrame,
    *,
    label: str,
    unit: str,
    transient: int,
) -> Figure:
    """Bifurcation diagram of every clearance channel (joint and axis): the Poincaré samples
    of the eccentricity (mm) after ``transient`` revolutions against the swept parameter
    (in ``unit``, clearances in mm), and beneath each, the largest Lyapunov exponent (1/s)
    with its standard error; filled markers where the verdict is chaotic. A point where the
    joint is ideal (clearance 0) has no eccentricity and no exponent for it."""
    factor, shown = _scale(unit)
    x = combined.parameter.values * factor
    joints = [str(j) for j in combined.joint.values]
    channels = [(j, a) for j in joints for a in ("x", "y")]
    samples = combined.section_eccentricity.sel(revolution=combined.revolution >= transient)
    with style.style():
        fig = style.figure(2.6 * max(len(channels), 1) + 0.5, 5.2)
        axes = np.atleast_2d(
            fig.subplots(2, max(len(channels), 1), sharex=True, height_ratios=(2, 1))
        )
        if axes.shape[0] != 2:
            axes = axes.T
        for col, (joint, axis) in enumerate(channels):
            top, bottom = axes[0, col], axes[1, col]
            values = samples.sel(joint=joint, axis=axis).values * MM
            for i, xv in enumerate(x):
                finite = values[i][np.isfinite(values[i])]
                top.plot(np.full(finite.size, xv), finite, ".", color="k", ms=style.POINT)
            top.set_title(f"{joint} {axis}")
            top.set_ylabel("Poincaré eccentricity [mm]" if col == 0 else "")
            rows = lyapunov[lyapunov.channel == f"{joint}.{axis}"]
            p = rows.iloc[:, 0].to_numpy() * factor
            lam = rows.lyapunov_exponent_per_s.to_numpy()
            err = rows.lyapunov_stderr_per_s.to_numpy()
            chaotic = (rows.verdict == "chaotic").to_numpy()
            bottom.axhline(0.0, color=style.BOUND, lw=0.8)
            bottom.errorbar(p, lam, yerr=err, color=style.CLEARANCE, lw=0.8, capsize=2)
            bottom.plot(p[chaotic], lam[chaotic], "o", color=style.CLEARANCE, ms=4)
            bottom.plot(p[~chaotic], lam[~chaotic], "o", mfc="white", color=style.CLEARANCE, ms=4)
            bottom.set_xlabel(f"{label} [{shown}]")
            bottom.set_ylabel("largest Lyapunov exponent [1/s]" if col == 0 else "")
        fig.suptitle(
            f"{combined.attrs.get('title', 'bifurcation')} "
            f"(filled: verdict chaotic; first {transient} revolutions dropped)"
        )
    return fig

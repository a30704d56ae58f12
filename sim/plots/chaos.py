"""Phase portraits, Poincaré maps and the Lyapunov table of an analysis dataset
(:func:`sim.analysis.run.analyze_run`)."""

import numpy as np
import pandas as pd
import xarray as xr
from matplotlib.figure import Figure

from sim.plots import style

MM = 1e3


def _grid(n: int):
    cols = 2 if n > 1 else 1
    return int(np.ceil(n / cols)), cols


def _axes(analysis: xr.Dataset, width: float = 3.2):
    n = analysis.sizes["channel"]
    rows, cols = _grid(n)
    fig = style.figure(width * cols + 0.4, width * 0.85 * rows + 0.6)
    axes = np.atleast_1d(fig.subplots(rows, cols)).ravel()
    for ax in axes[n:]:
        ax.set_axis_off()
    return fig, axes


def _labels(ax, analysis: xr.Dataset, value: str, rate: str) -> None:
    ax.set_xlabel(f"{analysis[value].attrs['long_name']} [mm]")
    ax.set_ylabel(f"rate [{style.unit_text(analysis[rate].attrs['units'])}]")


def plot_phase(analysis: xr.Dataset) -> Figure:
    """Phase portrait of every channel after the transient: eccentricity (mm) against its rate
    (m/s), with the verdict and the channel's largest Lyapunov exponent (1/s, Rosenstein) in
    each title, and the model's exponent in the figure's title when the analysis has it."""
    with style.style():
        fig, axes = _axes(analysis)
        for ax, channel in zip(axes, analysis.channel.values, strict=False):
            one = analysis.sel(channel=channel)
            ax.plot(
                one.phase_eccentricity * MM,
                one.phase_eccentricity_rate,
                color=style.CLEARANCE,
                lw=0.3,
            )
            exponent = float(one.lyapunov_exponent)
            series = "λ not estimated" if np.isnan(exponent) else f"λ = {exponent:.3g} 1/s"
            ax.set_title(f"{channel}: {one.verdict.item()}, {series}")
            _labels(ax, analysis, "phase_eccentricity", "phase_eccentricity_rate")
        model = (
            f"; model exponent {float(analysis.model_lyapunov_exponent):.3g} ± "
            f"{float(analysis.model_lyapunov_stderr):.2g} 1/s"
            if "model_lyapunov_exponent" in analysis
            else ""
        )
        fig.suptitle(
            f"Phase portraits after {analysis.attrs['transient_revolutions']} transient "
            f"revolutions{model}"
        )
    return fig


def plot_poincare(analysis: xr.Dataset) -> Figure:
    """Poincaré map of every channel (one point per crank revolution): eccentricity (mm)
    against its rate (m/s), with the detected period in each title."""
    with style.style():
        fig, axes = _axes(analysis)
        for ax, channel in zip(axes, analysis.channel.values, strict=False):
            one = analysis.sel(channel=channel)
            ax.plot(
                one.poincare_eccentricity * MM,
                one.poincare_eccentricity_rate,
                ".",
                color=style.CLEARANCE,
                ms=style.POINT * 1.5,
            )
            period = int(one.section_period)
            ax.set_title(f"{channel}: period {period if period else 'none found'}")
            _labels(ax, analysis, "poincare_eccentricity", "poincare_eccentricity_rate")
        fig.suptitle(f"Poincaré maps ({analysis.sizes['revolution']} crank revolutions)")
    return fig


def lyapunov_table(analysis: xr.Dataset) -> pd.DataFrame:
    """Table 3 equivalent: largest Lyapunov exponent (1/s) per joint and axis, with its
    standard error, the 0–1 test K, the Poincaré period and the verdict."""
    return pd.DataFrame(
        {
            "joint": analysis.channel_joint.values,
            "axis": analysis.channel_axis.values,
            "lyapunov_exponent_per_s": analysis.lyapunov_exponent.values,
            "lyapunov_stderr_per_s": analysis.lyapunov_stderr.values,
            "zero_one_K": analysis.zero_one_K.values,
            "section_period": analysis.section_period.values,
            "verdict": analysis.verdict.values,
        }
    )

"""Figures of the cross-check: the two codes overlaid, their differences, and for chaotic runs
the statistics compared (Poincaré points, per-revolution peaks)."""

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from sim.crosscheck.compare import SIGNALS, lowpass, revolution_peaks, slider_signals
from sim.plots import style

#: colour of the Exudyn run (ours is style.IDEAL, dark)
EXUDYN = "#c0392b"
UNITS = {"displacement": "m", "velocity": "m/s", "acceleration": "m/s²", "drive_torque": "N·m"}
TITLES = {
    "displacement": "slider displacement",
    "velocity": "slider velocity",
    "acceleration": "slider acceleration",
    "drive_torque": "driving torque",
}


def plot_overlay(
    ours: xr.Dataset, theirs: xr.Dataset, *, cutoff: float | None = None, revolutions=None
) -> Figure:
    """Left: each signal of both codes against time (s), ours dark, Exudyn red dashed; right:
    Exudyn minus ours, raw (grey) and, with `cutoff` (Hz), after the zero-phase low-pass
    (red). `revolutions` limits the plot to the first crank revolutions."""
    a, b = slider_signals(ours), slider_signals(theirs)
    t = ours.time.values
    keep = np.ones(t.size, bool)
    if revolutions is not None:
        keep = t <= revolutions * float(ours.attrs["crank_period"]) + 1e-12
    fs = 1.0 / (t[1] - t[0])
    with style.style():
        fig = style.figure(9.0, 8.0)
        axes = fig.subplots(len(SIGNALS), 2, sharex=True)
        for row, name in zip(axes, SIGNALS, strict=True):
            row[0].plot(t[keep], a[name][keep], color=style.IDEAL, lw=style.LINE, label="sim")
            row[0].plot(
                t[keep], b[name][keep], color=EXUDYN, lw=style.LINE, ls="--", label="Exudyn"
            )
            row[0].set_ylabel(f"{TITLES[name]}\n[{UNITS[name]}]")
            diff = b[name] - a[name]
            row[1].plot(t[keep], diff[keep], color=style.BOUND, lw=style.LINE, label="raw")
            if cutoff is not None:
                low = lowpass(b[name], fs, cutoff) - lowpass(a[name], fs, cutoff)
                row[1].plot(
                    t[keep], low[keep], color=EXUDYN, lw=style.LINE, label=f"{cutoff:g} Hz low-pass"
                )
            row[1].set_ylabel(f"Exudyn − sim [{UNITS[name]}]")
        axes[0, 0].legend(loc="upper left", ncols=2)
        axes[0, 1].legend(loc="upper left", ncols=2)
        for ax in axes[-1]:
            ax.set_xlabel("time [s]")
        fig.suptitle(_title(theirs))
    return fig


def plot_statistics(ours: xr.Dataset, theirs: xr.Dataset, transient: int = 0) -> Figure:
    """Top: Poincaré points (eccentricity at each crank revolution after `transient`, mm) of
    every clearance joint in both codes; bottom: the distributions of per-revolution peaks of
    |slider acceleration| and |driving torque|."""
    joints = list(ours.joint.values)
    a, b = slider_signals(ours), slider_signals(theirs)
    with style.style():
        fig = style.figure(9.0, 6.5)
        grid = fig.add_gridspec(2, max(len(joints), 2))
        for k, joint in enumerate(joints):
            ax = fig.add_subplot(grid[0, k])
            for ds, colour, label in ((ours, style.IDEAL, "sim"), (theirs, EXUDYN, "Exudyn")):
                pts = ds.section_eccentricity.sel(joint=joint).values[transient + 1 :] * 1e3
                ax.plot(pts[:, 0], pts[:, 1], "o", ms=style.POINT + 1, color=colour, label=label)
            ax.set_title(f"Poincaré points of joint {joint}", loc="left")
            ax.set_xlabel("x [mm]")
            ax.set_ylabel("y [mm]")
            ax.legend(loc="best")
        for k, name in enumerate(("acceleration", "drive_torque")):
            ax = fig.add_subplot(grid[1, k])
            pa = revolution_peaks(ours, a[name], transient)
            pb = revolution_peaks(theirs, b[name], transient)
            bins = np.linspace(min(pa.min(), pb.min()), max(pa.max(), pb.max()), 12)
            ax.hist(pa, bins=bins, color=style.IDEAL, alpha=0.6, label="sim")
            ax.hist(pb, bins=bins, color=EXUDYN, alpha=0.6, label="Exudyn")
            ax.set_xlabel(f"per-revolution peak |{TITLES[name]}| [{UNITS[name]}]")
            ax.set_ylabel("revolutions")
            ax.legend(loc="best")
        fig.suptitle(_title(theirs))
    return fig


def _title(theirs: xr.Dataset) -> str:
    return (
        f"sim against {theirs.attrs['source'].split(' via')[0]} ({theirs.attrs['solver_method']}, "
        f"step {theirs.attrs['solver_step_s']:.3g} s)"
    )

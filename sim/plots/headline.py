"""The headline figures of the paper's section of the front page, drawn from the workflow's own
tables: the model exponent of every ensemble case on each link model, and the dense sweeps
with the exponent beneath and where chaos starts."""

from collections.abc import Sequence

import numpy as np
import pandas as pd
import xarray as xr
from matplotlib.figure import Figure

from sim.plots import style
from sim.plots.bifurcation import MM, scaled_unit

#: marker of each link model of the exponents (sim.studies.config: `model_lyapunov.links`)
LINK_MARKERS = {"modal": ("o", style.CLEARANCE), "rigid": ("s", style.IDEAL), "run": ("^", "0.4")}


def plot_exponents(tables: Sequence[tuple[str, pd.DataFrame]]) -> Figure:
    """The model exponent (1/s) of every ensemble case of each study (``tables``: the study's
    name and its `model_exponent.csv`), one column per case, a marker per link model side by
    side: the median over the members with the interval of order statistics for the median
    (one member: ± its standard error). The primary link model (the one the verdicts read) is
    named in the legend."""
    cases = [(study, case) for study, table in tables for case in dict.fromkeys(table.case)]
    rows = pd.concat([table.assign(study=study) for study, table in tables], ignore_index=True)
    links = list(dict.fromkeys(rows.links))
    offsets = np.linspace(-0.15, 0.15, len(links)) if len(links) > 1 else [0.0]
    with style.style():
        fig = style.figure(max(6.5, 1.2 * len(cases) + 2.0), 3.4)
        ax = fig.subplots()
        for offset, model in zip(offsets, links, strict=True):
            marker, colour = LINK_MARKERS.get(model, ("D", "k"))
            part = rows[rows.links == model]
            x, y, low, high = [], [], [], []
            for i, (study, case) in enumerate(cases):
                row = part[(part.study == study) & (part.case == case)]
                if row.empty:
                    continue
                row = row.iloc[0]
                one = int(row.members) == 1
                median = float(row.median_exponent_per_s)
                x.append(i + offset)
                y.append(median)
                low.append(
                    median - float(row.mean_member_stderr_per_s) if one else row.interval_low_per_s
                )
                high.append(
                    median + float(row.mean_member_stderr_per_s) if one else row.interval_high_per_s
                )
            y, low, high = (np.asarray(v, dtype=float) for v in (y, low, high))
            primary = bool(part.primary.any())
            ax.errorbar(
                x,
                y,
                yerr=[y - low, high - y],
                fmt=marker,
                color=colour,
                ms=5,
                capsize=3,
                lw=style.LINE,
                label=f"{model} links" + (" (the verdicts read it)" if primary else ""),
            )
        ax.axhline(0.0, color=style.BOUND, lw=style.LINE)
        ax.set_xticks(range(len(cases)), [f"{study}\n{case}" for study, case in cases])
        ax.set_ylabel("model exponent [1/s]")
        ax.legend(loc="upper left", bbox_to_anchor=(1.0, 1.0))
        ax.set_title("Median over the members, its interval; one member: ± its error", loc="left")
    return fig


def plot_sweeps(sweeps: Sequence[tuple[str, xr.Dataset, np.ndarray]]) -> Figure:
    """Each dense sweep (``sweeps``: its name, its bifurcation dataset and, per point, whether
    some channel is judged chaotic there) in a column: the Poincaré samples of its first
    clearance channel after the transient against the parameter, and beneath them the model
    exponent (1/s, band ± one standard error), filled where some channel is chaotic; a dashed
    line where chaos starts (the lowest such point)."""
    with style.style():
        fig = style.figure(4.2 * len(sweeps) + 0.4, 4.6)
        axes = np.asarray(
            fig.subplots(2, len(sweeps), sharex="col", height_ratios=(3, 2), squeeze=False)
        )
        for col, (name, combined, chaotic) in enumerate(sweeps):
            top, bottom = axes[:, col]
            parameter = combined.parameter
            factor, unit = scaled_unit(parameter.attrs.get("units", ""))
            x = parameter.values * factor
            joint, axis = str(combined.joint.values[0]), str(combined.axis.values[0])
            transient = int(combined.attrs.get("transient_revolutions", 0))
            samples = combined.section_eccentricity.sel(joint=joint, axis=axis)
            values = samples.sel(revolution=combined.revolution >= transient).values * MM
            finite = np.isfinite(values)
            top.plot(
                np.broadcast_to(x[:, None], values.shape)[finite],
                values[finite],
                ".",
                color="k",
                ms=style.POINT / 2,
            )
            top.set_title(f"{name}: {joint} {axis}", loc="left")
            top.set_ylabel("Poincaré eccentricity [mm]" if col == 0 else "")
            lam = combined.model_lyapunov_exponent.values
            err = combined.model_lyapunov_stderr.values
            bottom.fill_between(x, lam - err, lam + err, color=style.CLEARANCE, alpha=0.25, lw=0)
            bottom.plot(x, lam, color=style.CLEARANCE, lw=style.LINE)
            bottom.plot(x[chaotic], lam[chaotic], "o", color=style.CLEARANCE, ms=style.POINT * 1.5)
            bottom.axhline(0.0, color=style.BOUND, lw=style.LINE)
            bottom.set_ylabel("model exponent [1/s]" if col == 0 else "")
            label = str(parameter.attrs.get("name", "parameter"))
            bottom.set_xlabel(f"{label} [{unit}]" if unit else label)
            if chaotic.any():
                onset = int(np.argmax(chaotic))
                for ax in (top, bottom):
                    ax.axvline(x[onset], color=style.BOUND, ls="--", lw=style.LINE)
                bottom.annotate(
                    f"chaos from {x[onset]:g}",
                    (x[onset], 1.0),
                    xycoords=("data", "axes fraction"),
                    xytext=(3, -10),
                    textcoords="offset points",
                    fontsize=7,
                )
        fig.suptitle(
            "Dense sweeps: filled, some channel judged chaotic; dashed, where chaos starts"
        )
    return fig

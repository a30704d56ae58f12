"""Bifurcation diagrams with the model-based Lyapunov exponent and the 0–1 K beneath."""

import numpy as np
import pandas as pd
import xarray as xr
from matplotlib.figure import Figure

from sim.plots import style

MM = 1e3


def indicators_table(combined: xr.Dataset) -> pd.DataFrame:
    """One row per sweep point and clearance channel (joint.axis) of a bifurcation dataset
    (:func:`sim.analysis.bifurcation.combine_sweep` with indicators): the parameter value, the
    model-based largest Lyapunov exponent (1/s, of the whole linkage, so the same on every
    channel of a point) with its standard error, the 0–1 K, the Poincaré period (0: none) and
    the verdict. A point whose joints are all ideal (clearance 0) has no channels: no rows."""
    parameter = str(combined.parameter.attrs.get("name", "parameter"))
    rows = []
    for i, value in enumerate(combined.parameter.values):
        point = combined.isel(parameter=i)
        for joint in combined.joint.values:
            for axis in combined.axis.values:
                channel = point.sel(joint=joint, axis=axis)
                verdict = str(channel.verdict.item())
                if not verdict:  # padding: the joint is ideal at this point
                    continue
                rows.append(
                    {
                        parameter: float(value),
                        "channel": f"{joint}.{axis}",
                        "model_lyapunov_exponent_per_s": float(point.model_lyapunov_exponent),
                        "model_lyapunov_stderr_per_s": float(point.model_lyapunov_stderr),
                        "zero_one_K": float(channel.zero_one_K),
                        "section_period": int(channel.section_period),
                        "verdict": verdict,
                    }
                )
    return pd.DataFrame(rows)


def scaled_unit(unit: str) -> tuple[float, str]:
    """The factor and unit a parameter is drawn in: lengths in mm, the rest as given."""
    return (MM, "mm") if unit == "m" else (1.0, unit)


def plot_bifurcation(combined: xr.Dataset, *, label: str, unit: str, transient: int) -> Figure:
    """Bifurcation diagram of every clearance channel (joint and axis): the Poincaré samples
    of the eccentricity (mm) after ``transient`` revolutions against the swept parameter
    (in ``unit``, clearances in mm); beneath, when the sweep computed its indicators, the
    model-based largest Lyapunov exponent of the linkage (1/s, band: ± one standard error;
    filled where the channel's verdict is chaotic), and beneath that the channel's 0–1 K
    (0 regular, 1 chaotic). A point where the joint is ideal (clearance 0) has no
    eccentricity, no K and no verdict for it. The title names the link model and integrator
    that drew the diagram (the dataset's ``model`` attribute)."""
    factor, shown = scaled_unit(unit)
    x = combined.parameter.values * factor
    joints = [str(j) for j in combined.joint.values]
    channels = [(j, a) for j in joints for a in ("x", "y")]
    samples = combined.section_eccentricity.sel(revolution=combined.revolution >= transient)
    indicators = "model_lyapunov_exponent" in combined
    columns = max(len(channels), 1)
    with style.style():
        fig = style.figure(2.6 * columns + 0.5, 6.4 if indicators else 3.4)
        axes = np.asarray(
            fig.subplots(
                3 if indicators else 1,
                columns,
                sharex=True,
                height_ratios=(2, 1, 1) if indicators else None,
                squeeze=False,
            )
        )
        for col, (joint, axis) in enumerate(channels):
            top = axes[0, col]
            where = {"joint": joint, "axis": axis}
            values = samples.sel(where).values * MM
            xs = np.broadcast_to(x[:, None], values.shape)
            finite = np.isfinite(values)
            top.plot(xs[finite], values[finite], ".", color="k", ms=style.POINT / 2)
            top.set_title(f"{joint} {axis}")
            top.set_ylabel("Poincaré eccentricity [mm]" if col == 0 else "")
            axes[-1, col].set_xlabel(f"{label} [{shown}]" if shown else label)
            if indicators:
                _indicator_panels(combined, where, x, axes[1:, col], first=col == 0)
        note = "filled: verdict chaotic; " if indicators else "no indicators computed; "
        fig.suptitle(
            f"{combined.attrs.get('title', 'bifurcation')}: {combined.sizes['parameter']} points, "
            f"{combined.attrs.get('model', 'model not recorded')}\n"
            f"({note}first {transient} revolutions dropped)"
        )
    return fig


def _indicator_panels(combined: xr.Dataset, where: dict, x: np.ndarray, axes, first: bool):
    """The model exponent (1/s, ± one standard error, filled where the channel is chaotic) and
    the channel's 0–1 K against the parameter, on the two ``axes`` beneath its diagram."""
    middle, bottom = axes
    lam = combined.model_lyapunov_exponent.values
    err = combined.model_lyapunov_stderr.values
    chaotic = combined.verdict.sel(where).values == "chaotic"
    middle.axhline(0.0, color=style.BOUND, lw=style.LINE)
    middle.fill_between(x, lam - err, lam + err, color=style.CLEARANCE, alpha=0.25, lw=0)
    middle.plot(x, lam, color=style.CLEARANCE, lw=style.LINE)
    middle.plot(x[chaotic], lam[chaotic], "o", color=style.CLEARANCE, ms=style.POINT)
    middle.set_ylabel("model exponent [1/s]" if first else "")
    K = combined.zero_one_K.sel(where).values
    bottom.axhline(0.5, color=style.BOUND, lw=style.LINE, ls="--")
    bottom.plot(x, K, ".-", color=style.IDEAL, lw=style.LINE / 2, ms=style.POINT)
    bottom.set_ylim(-0.1, 1.1)
    bottom.set_ylabel("0–1 test K" if first else "")

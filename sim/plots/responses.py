"""Slider and crank responses of a run against the ideal mechanism."""

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from sim.plots import style
from sim.results import scene_of

#: (variable, body or None, axis or None, title of the panel)
PANELS = (
    ("position", "slider", "y", "slider displacement (along the guide)"),
    ("velocity", "slider", "y", "slider velocity"),
    ("acceleration", "slider", "y", "slider acceleration"),
    ("drive_torque", None, None, "driving torque"),
)


def _series(ds: xr.Dataset, variable: str, body, axis) -> xr.DataArray:
    data = ds[variable]
    if body is not None:
        data = data.sel(body=body, axis=axis)
    return data


def _window(ds: xr.Dataset, revolutions: float) -> slice:
    period = float(ds.attrs["crank_period"])
    end = float(ds.time[-1])
    return slice(max(float(ds.time[0]), end - revolutions * period), end)


def _zoom(ax, t: np.ndarray, sim: np.ndarray, ref: np.ndarray, width: float) -> None:
    """Inset magnifying ``width`` seconds around the largest deviation from the ideal."""
    centre = t[int(np.argmax(np.abs(sim - ref)))]
    keep = (t >= centre - width / 2) & (t <= centre + width / 2)
    if keep.sum() < 3:
        return
    inset = ax.inset_axes((0.62, 0.55, 0.36, 0.42))
    inset.plot(t[keep], ref[keep], color=style.IDEAL, lw=style.LINE)
    inset.plot(t[keep], sim[keep], color=style.CLEARANCE, lw=style.LINE)
    inset.tick_params(labelsize=6)
    inset.grid(False)
    ax.indicate_inset_zoom(inset, edgecolor="0.4")


def plot_responses(run: xr.Dataset, ideal: xr.Dataset, *, revolutions: float = 2.0) -> Figure:
    """Slider displacement (m), velocity (m/s), acceleration (m/s²) and driving torque (N·m)
    against time (s) over the last ``revolutions`` crank revolutions, the run with clearances
    over the ideal mechanism; the acceleration and torque panels carry an inset zoomed on the
    largest deviation (impacts)."""
    with style.style():
        fig = style.figure(7.0, 8.0)
        axes = fig.subplots(len(PANELS), 1, sharex=True)
        window = _window(run, revolutions)
        sim_ds, ref_ds = run.sel(time=window), ideal.sel(time=window)
        period = float(run.attrs["crank_period"])
        for ax, (variable, body, axis, title) in zip(axes, PANELS, strict=True):
            sim = _series(sim_ds, variable, body, axis)
            ref = _series(ref_ds, variable, body, axis).interp(time=sim.time)
            ax.plot(ref.time, ref, color=style.IDEAL, lw=style.LINE, label="ideal")
            ax.plot(sim.time, sim, color=style.CLEARANCE, lw=style.LINE, label="clearance")
            prefix = f"{body} {axis}" if body else ""
            ax.set_title(style.label(run[variable], prefix=prefix), loc="left")
            ax.set_ylabel(
                f"{title.split(' (')[0]}\n[{style.unit_text(run[variable].attrs['units'])}]"
            )
            if variable in ("acceleration", "drive_torque"):
                _zoom(ax, sim.time.values, sim.values, ref.values, 0.04 * period)
        axes[0].legend(loc="upper left", ncols=2)
        axes[-1].set_xlabel(style.label(run.time))
        fig.suptitle(_title(run))
    return fig


def _title(run: xr.Dataset) -> str:
    scene = scene_of(run)
    joints = [
        f"{name} {joint['clearance'] * 1e3:g} mm"
        for name, joint in scene["joints"].items()
        if joint["clearance"] > 0
    ]
    rpm = scene["drive"]["speed_rpm"]
    return f"{', '.join(joints) or 'no clearance'} at {rpm:g} rpm"

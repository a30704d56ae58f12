"""Output-channel and crank responses of a run against the ideal mechanism."""

import numpy as np
import xarray as xr
from matplotlib.figure import Figure
from matplotlib.ticker import MaxNLocator

from sim.plots import style
from sim.results import output_series, scene_of
from sim.scene import output_channel

#: (variable, whether it is the output channel's, title of the panel)
PANELS = (
    ("position", True, "displacement"),
    ("velocity", True, "velocity"),
    ("acceleration", True, "acceleration"),
    ("drive_torque", False, "driving torque"),
)


def _series(ds: xr.Dataset, variable: str, on_channel: bool) -> xr.DataArray:
    return output_series(ds, variable) if on_channel else ds[variable]


def _window(ds: xr.Dataset, revolutions: float) -> slice:
    period = float(ds.attrs["crank_period"])
    end = float(ds.time[-1])
    return slice(max(float(ds.time[0]), end - revolutions * period), end)


#: fewest samples an inset spans: a narrower one shows too few points to read a shape from
INSET_SAMPLES = 24


def _how_sampled(data: xr.DataArray) -> str:
    """What the samples of a variable are, from its attributes: point values, or interval
    means with the boxcar's −3 dB frequency (`sim.quantities.bandwidth`)."""
    if data.attrs.get("sampling") != "interval mean":
        return "point samples"
    corner = data.attrs["bandwidth"].split("-3 dB at ")[1].split(",")[0]
    return f"interval means, -3 dB at {corner}"


def _zoom(ax, t: np.ndarray, sim: np.ndarray, ref: np.ndarray, width: float, how: str) -> None:
    """Inset magnifying ``width`` seconds (at least INSET_SAMPLES samples) around the largest
    deviation from the ideal, its time axis in ms from the inset's centre (three ticks, which
    do not overlap), the samples marked and what they are (`how`) in its title."""
    centre = t[int(np.argmax(np.abs(sim - ref)))]
    width = max(width, INSET_SAMPLES * float(t[1] - t[0]))
    keep = (t >= centre - width / 2) & (t <= centre + width / 2)
    if keep.sum() < 3:
        return
    inset = ax.inset_axes((0.62, 0.55, 0.36, 0.42))
    ms = (t[keep] - centre) * 1e3
    inset.plot(ms, ref[keep], color=style.IDEAL, lw=style.LINE)
    inset.plot(ms, sim[keep], color=style.CLEARANCE, lw=style.LINE, marker=".", ms=2)
    inset.xaxis.set_major_locator(MaxNLocator(nbins=3))
    inset.yaxis.set_major_locator(MaxNLocator(nbins=3))
    inset.tick_params(labelsize=6)
    inset.set_xlabel(f"ms from t = {centre:.4g} s", fontsize=6, labelpad=1)
    inset.set_title(how, fontsize=6, pad=2)
    inset.grid(False)
    # the inset's time axis is in ms from `centre`: the marked region in the panel's seconds
    lo, hi = inset.get_ylim()
    ax.indicate_inset((centre - width / 2, lo, width, hi - lo), inset, edgecolor="0.4")


def plot_responses(run: xr.Dataset, ideal: xr.Dataset, *, revolutions: float = 2.0) -> Figure:
    """Displacement (m), velocity (m/s) and acceleration (m/s²) of the scene's output channel
    (`output`, by default the slider along its guide) and the driving torque (N·m) against
    time (s) over the last ``revolutions`` crank revolutions, the run with clearances
    over the ideal mechanism; the acceleration and torque panels carry an inset zoomed on the
    largest deviation (impacts), which says whether its samples are point values or interval
    means and their bandwidth (the variable's `sampling` and `bandwidth` attributes)."""
    with style.style():
        fig = style.figure(7.0, 8.0)
        axes = fig.subplots(len(PANELS), 1, sharex=True)
        window = _window(run, revolutions)
        sim_ds, ref_ds = run.sel(time=window), ideal.sel(time=window)
        period = float(run.attrs["crank_period"])
        channel = output_channel(scene_of(run))
        for ax, (variable, on_channel, title) in zip(axes, PANELS, strict=True):
            sim = _series(sim_ds, variable, on_channel)
            ref = _series(ref_ds, variable, on_channel).interp(time=sim.time)
            ax.plot(ref.time, ref, color=style.IDEAL, lw=style.LINE, label="ideal")
            ax.plot(sim.time, sim, color=style.CLEARANCE, lw=style.LINE, label="clearance")
            prefix = channel.label if on_channel else ""
            ax.set_title(style.label(sim, prefix=prefix), loc="left")
            ax.set_ylabel(f"{title}\n[{style.unit_text(sim.attrs['units'])}]")
            if variable in ("acceleration", "drive_torque"):
                how = _how_sampled(sim)
                _zoom(ax, sim.time.values, sim.values, ref.values, 0.04 * period, how)
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

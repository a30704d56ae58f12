"""Centre trajectories of clearance joints inside their clearance circle or band."""

import numpy as np
import xarray as xr
from matplotlib.figure import Figure

from sim.plots import style
from sim.results import scene_of

MM = 1e3


def plot_trajectories(run: xr.Dataset) -> Figure:
    """The eccentricity of every clearance joint (mm) over the whole run: a revolute joint's
    journal centre relative to its bearing, x against y, inside the circle of radius equal to
    the radial clearance; the slider of a translational joint, its offset across the guide (x)
    against its position along the guide (y), inside the band |x| ≤ clearance."""
    scene = scene_of(run)
    joints = [str(j) for j in run.joint.values]
    with style.style():
        n = max(len(joints), 1)
        cols = min(n, 3)
        rows = int(np.ceil(n / cols))
        fig = style.figure(3.0 * cols + 0.5, 3.0 * rows + 0.6)
        axes = np.atleast_1d(fig.subplots(rows, cols)).ravel()
        ecc = run.eccentricity
        units = "mm"
        for ax, joint in zip(axes, joints, strict=False):
            spec = scene["joints"][joint]
            c = spec["clearance"] * MM
            x = ecc.sel(joint=joint, axis="x").values * MM
            y = ecc.sel(joint=joint, axis="y").values * MM
            if spec["type"] == "revolute":
                angle = np.linspace(0.0, 2.0 * np.pi, 361)
                ax.plot(c * np.cos(angle), c * np.sin(angle), color=style.BOUND, lw=1.0)
                ax.plot(x, y, color=style.CLEARANCE, lw=0.4)
                ax.set_aspect("equal")
                ax.set_title(f"revolute {joint}: clearance {c:g} mm")
            else:
                ax.axvline(-c, color=style.BOUND, lw=1.0)
                ax.axvline(c, color=style.BOUND, lw=1.0)
                ax.plot(x, y, color=style.CLEARANCE, lw=0.4)
                ax.set_xlim(-1.3 * c, 1.3 * c)
                ax.set_title(f"translational {joint}: clearance {c:g} mm")
            ax.set_xlabel(f"eccentricity x [{units}]")
            ax.set_ylabel(f"eccentricity y [{units}]")
        for ax in axes[len(joints) :]:
            ax.set_axis_off()
        if not joints:
            axes[0].text(0.5, 0.5, "no clearance joint", ha="center", va="center")
        fig.suptitle(f"{ecc.attrs.get('long_name', 'eccentricity')} (whole run)")
    return fig

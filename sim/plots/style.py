"""The one figure style of the workflow: sizes, colours, labels from dataset attributes.

Figures are ``matplotlib.figure.Figure`` objects built without pyplot, so they render with the
Agg backend in any session (batch jobs, tests) and hold no global state.
"""

import io
from contextlib import contextmanager
from pathlib import Path

import matplotlib as mpl
import xarray as xr
from matplotlib.figure import Figure

from sim.atomic import write_atomically

#: colour of the simulated mechanism with clearances
CLEARANCE = "#c0392b"
#: colour of the ideal reference mechanism
IDEAL = "#2c3e50"
#: colour of bounds (clearance circle, band)
BOUND = "0.55"
#: line width of time series
LINE = 0.8
#: marker size of Poincaré and bifurcation points
POINT = 2.0
DPI = 150

RC = {
    "font.size": 9,
    "axes.titlesize": 9,
    "axes.labelsize": 9,
    "legend.fontsize": 8,
    "xtick.labelsize": 8,
    "ytick.labelsize": 8,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "grid.linewidth": 0.5,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "savefig.dpi": DPI,
}


@contextmanager
def style():
    """Context in which figures are built and saved with the shared rc settings."""
    with mpl.rc_context(RC):
        yield


def figure(width: float = 7.0, height: float = 5.0) -> Figure:
    """A new constrained-layout figure, width and height in inches."""
    return Figure(figsize=(width, height), layout="constrained")


def unit_text(units: str) -> str:
    """CF units as printed on an axis: 'm s-2' → 'm/s²'."""
    table = {
        "m s-1": "m/s",
        "m s-2": "m/s²",
        "s-1": "1/s",
        "N m": "N·m",
        "1": "–",
    }
    return table.get(units, units)


def label(data: xr.DataArray, prefix: str = "", scale_units: str | None = None) -> str:
    """Axis label from a variable's ``long_name`` and ``units`` attributes (``scale_units``
    replaces the unit when the values were rescaled, e.g. 'mm')."""
    name = data.attrs.get("long_name", data.name or "")
    units = scale_units or unit_text(data.attrs.get("units", ""))
    text = f"{prefix}{name}" if not prefix else f"{prefix}: {name}"
    return f"{text} [{units}]" if units else text


#: the figure formats written, by file suffix
FORMATS = ("png", "svg")


def png_bytes(fig: Figure) -> bytes:
    """A figure as PNG at the shared resolution, in memory (to embed in a page)."""
    buffer = io.BytesIO()
    with style():
        fig.savefig(buffer, dpi=DPI, format="png")
    return buffer.getvalue()


def save(fig: Figure, path) -> None:
    """Write a figure at the shared resolution in the format its suffix names (``FORMATS``),
    through a temporary file: no reader sees it half-written."""
    path = Path(path)
    kind = path.suffix.lstrip(".").lower()
    if kind not in FORMATS:
        raise ValueError(f"{path}: a figure is written as {' or '.join(FORMATS)}, not {kind!r}")
    with style():
        write_atomically(path, lambda temporary: fig.savefig(temporary, dpi=DPI, format=kind))

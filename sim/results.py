"""Simulation output as a CF-annotated xarray Dataset, and its netCDF file.

Every variable carries `units` and `long_name`; global attributes hold the
resolved scene (JSON text), the version and the solver statistics, so that an
output file says what made it (CF conventions 1.8).
"""

import json
import math
import os
import threading
from pathlib import Path

import numpy as np
import xarray as xr

from sim import __version__
from sim.atomic import write_atomically
from sim.provenance import library_versions_json
from sim.quantities import (
    AXES,
    BY_NAME,
    COORDINATE_BY_NAME,
    PEAK,
    REVOLUTION_COUNT,
    REVOLUTION_PEAK,
    SAMPLE,
    SECTION,
    attributes,
    recorded,
)
from sim.scene import output_channel, with_defaults
from sim.solve.record import column_layout, peak_layout

NETCDF_LOCK = threading.Lock()
"""Held while a netCDF file is written: the netCDF4 wheels release the GIL inside a library
that is not built thread-safe, and two threads writing at once crash the process."""


def decode_rows(rows: np.ndarray, bodies: list[str], joints: list[str]) -> dict[str, np.ndarray]:
    """Column blocks of sample rows → each sampled quantity (`sim.quantities`), shaped
    (samples, ...)."""
    out = {}
    for name, (first, shape) in column_layout(len(bodies), len(joints)).items():
        width = math.prod(shape)
        out[name] = rows[:, first : first + width].reshape((rows.shape[0], *shape))
    return out


def annotate(ds: xr.Dataset, sampling: str) -> xr.Dataset:
    """`ds` with the CF attributes of `sim.quantities` on every declared variable and
    coordinate it holds: units, long_name, and for a sampled quantity how it was sampled
    (`sampling`: the run's simulation.sampling, "mean" or "point") and its bandwidth."""
    times = ds["time"].values
    interval = float(times[1] - times[0]) if times.size > 1 else None
    for name in ds.variables:
        if name in BY_NAME or name in COORDINATE_BY_NAME:
            ds[name].attrs.update(attributes(str(name), interval, sampling))
    return ds


def energy_balance(data: xr.Dataset | dict[str, np.ndarray]) -> xr.DataArray | np.ndarray:
    """T + V + U + U_c − W + D minus its initial value (J): zero up to numerical error.
    `data`: a run's Dataset, or sample columns as `decode_rows` gives them."""
    total = (
        data["kinetic_energy"]
        + data["potential_energy"]
        + data["strain_energy"]
        + data["contact_energy"]
        - data["drive_work"]
        + data["dissipated_energy"]
    )
    return total - total[0]


def energy_scale(data: xr.Dataset | dict[str, np.ndarray]) -> float:
    """The energy the audit is judged against (J): the largest of the kinetic
    energy, the potential energy's range and the drive's work."""
    return float(
        max(
            data["kinetic_energy"].max(),
            data["potential_energy"].max() - data["potential_energy"].min(),
            abs(data["drive_work"]).max(),
            1e-12,
        )
    )


def energy_error_relative(data: xr.Dataset | dict[str, np.ndarray]) -> float:
    """The energy audit: the largest |energy balance| over the energy scale."""
    return float(abs(energy_balance(data)).max()) / energy_scale(data)


def _peak_blocks(vector: np.ndarray, layout: dict) -> list[np.ndarray]:
    """The PEAK quantities' blocks of a peak vector (or of rows of them: leading axes kept)."""
    lead = vector.shape[:-1]
    return [
        vector[..., first : first + math.prod(block)].reshape((*lead, *block))
        for first, block in layout.values()
    ]


def _revolution_peaks(
    rev_peaks: np.ndarray, rev_events: np.ndarray, n_sections: int, layout: dict
) -> dict[str, np.ndarray]:
    """Per-revolution peaks over every accepted step and output sample (the integrator's
    `rev_peaks` rows), as the whole-run peaks are; the part after the last section (a
    fractional last revolution) is left out."""
    out = {
        q.name: block
        for q, block in zip(
            recorded(REVOLUTION_PEAK), _peak_blocks(rev_peaks[:n_sections], layout), strict=True
        )
    }
    (events,) = recorded(REVOLUTION_COUNT)
    out[events.name] = rev_events[:n_sections].copy()
    return out


def build_dataset(
    *,
    times: np.ndarray,
    rows: np.ndarray,
    section_rows: np.ndarray,
    peaks: np.ndarray,
    bodies: list[str],
    joints: list[str],
    scene: dict,
    provenance: dict,
    rev_peaks: np.ndarray | None = None,
    rev_events: np.ndarray | None = None,
) -> xr.Dataset:
    """The output Dataset of one run from the integrator's sample rows. With `rev_peaks` and
    `rev_events` (sim.solve.stepping.integrate) it also holds the peaks and contact events
    of each revolution, on the sections' `revolution` dimension."""
    data = decode_rows(rows, bodies, joints)
    sections = decode_rows(section_rows, bodies, joints)
    coords = {
        "time": times,
        "body": bodies,
        "axis": AXES,
        "joint": joints,
        "revolution": np.arange(section_rows.shape[0]),
    }
    variables = {q.name: (q.dims, data[q.name]) for q in recorded(SAMPLE)}
    variables.update({q.name: (q.dims, sections[q.source]) for q in recorded(SECTION)})
    # the largest |value| over the accepted steps' ends and the output samples' point values
    # (the integrator's: a sample row holds interval means of the fast quantities)
    layout = peak_layout(len(bodies), len(joints))
    for q, block in zip(recorded(PEAK), _peak_blocks(peaks, layout), strict=True):
        variables[q.name] = (q.dims, block)
    variables["energy_error"] = (BY_NAME["energy_error"].dims, energy_balance(data))
    if rev_peaks is not None and rev_events is not None:
        per_revolution = _revolution_peaks(rev_peaks, rev_events, section_rows.shape[0], layout)
        variables.update({name: (BY_NAME[name].dims, v) for name, v in per_revolution.items()})
    # one construction: a Dataset grown a variable at a time aligns its indexes at every
    # step, which took 8 % of a 20-revolution rigid run (before ca28e38)
    ds = xr.Dataset(variables, coords=coords)
    annotate(ds, scene["simulation"]["sampling"])
    ds.attrs.update(
        Conventions="CF-1.8",
        title=f"sim run of scene '{scene['name']}'",
        source=f"sim {__version__}",
        history=provenance.pop("history"),
        scene=json.dumps(scene),
        assumptions=json.dumps(scene["assumptions"]),
        sim_version=__version__,
        energy_error_relative=energy_error_relative(data),
        **provenance,
    )
    return ds


def encoding_for(ds: xr.Dataset) -> dict:
    """float32 + zlib for the long time series, no fill value on coordinates."""
    enc = {}
    for name, var in ds.variables.items():
        if name in ds.coords:
            enc[name] = {"_FillValue": None}
        elif "time" in var.dims and var.dtype.kind == "f":
            enc[name] = {"dtype": "float32", "zlib": True, "complevel": 4}
    return enc


def write_netcdf(ds: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write `ds` to `path` through a temporary file in the same folder, then
    rename, so that a crash never leaves a half-written file under that name.

    Writes are serialised by :data:`NETCDF_LOCK`, so threads may call this.

    The file records the library versions it was written with (``library_versions``,
    JSON); a dataset that already carries them (a combination of runs) keeps its own.
    """
    path = Path(path)
    ds = ds.assign_attrs(library_versions=ds.attrs.get("library_versions", library_versions_json()))
    path.parent.mkdir(parents=True, exist_ok=True)

    def write(temporary: Path) -> None:
        with NETCDF_LOCK:
            ds.to_netcdf(temporary, encoding=encoding_for(ds), engine="netcdf4")

    write_atomically(path, write)
    return path


def scene_of(ds: xr.Dataset) -> dict:
    """The resolved scene a run was made from, defaults filled (a file written before a
    default was declared has them too)."""
    return with_defaults(json.loads(ds.attrs["scene"]))


#: the output point's variable of each quantity of a body's reference point
OUTPUT_VARIABLES = {
    "position": "output_position",
    "velocity": "output_velocity",
    "acceleration": "output_acceleration",
    "peak_acceleration": "peak_output_acceleration",
    "revolution_peak_acceleration": "revolution_peak_output_acceleration",
}


def output_series(run: xr.Dataset, name: str) -> xr.DataArray:
    """The run's output point (the scene's `output`) along the channel's axis, for `name`, a
    key of OUTPUT_VARIABLES (m, m/s, m/s²)."""
    return run[OUTPUT_VARIABLES[name]].sel(axis=output_channel(scene_of(run)).axis)


def open_run(
    path: str | os.PathLike, what: str = "run file", writer: str = "`sim run`"
) -> xr.Dataset:
    """The file at `path` (netCDF written by `writer`; `what` names it in messages), read into
    memory; ValueError naming the file when it is missing, a directory or not netCDF (`sim`
    reports it with exit code 2)."""
    path = Path(path)
    if not path.is_file():
        problem = "is a directory, not a netCDF file" if path.is_dir() else "does not exist"
        raise ValueError(f"{what} '{path}' {problem}")
    try:
        return xr.load_dataset(path)
    except (OSError, ValueError) as exc:
        # xarray's ValueError lists its IO backends; only a netCDF library's reason helps.
        reason = f" ({exc})" if isinstance(exc, OSError) else ""
        raise ValueError(
            f"{what} '{path}' is not a netCDF file{reason}: give a file written by {writer}"
        ) from None

"""Parameter sweeps: one scene simulated at every value of a parameter, its Poincaré samples
collected into one bifurcation dataset (``sim sweep``)."""

import json
from collections.abc import Sequence
from pathlib import Path

import xarray as xr

from sim.analysis.bifurcation import SECTION_VARIABLES, combine_sweep
from sim.results import write_netcdf
from sim.run import simulate
from sim.scene import load_scene


def point_file(label: str, value: float) -> str:
    """File name of the run of one sweep value, e.g. ``clearance-0.0005.nc``."""
    return f"{label}-{value:g}.nc"


def point_overrides(keys: Sequence[str], value: float) -> list[str]:
    """``--set`` overrides of one sweep value: every swept key set to it (a whole number is
    written as an integer, so integer keys such as ``bodies.rod2.elements`` can be swept)."""
    value = float(value)
    text = str(int(value)) if value.is_integer() else repr(value)
    return [f"{key}={text}" for key in keys]


def run_sweep(
    scene_source: str,
    overrides: Sequence[str],
    keys: Sequence[str],
    values: Sequence[float],
    *,
    out_dir: Path,
    label: str,
    transient_revolutions: int,
    progress: bool = False,
) -> xr.Dataset:
    """Simulate a scene at every value of a parameter and stack the Poincaré samples.

    Every value gives one scene: the scene with ``overrides``, then every key of ``keys``
    set to the value (so ``joints.A.clearance`` and ``joints.B.clearance`` can move
    together). All scenes are loaded and validated before the first simulation, so a bad key
    or value fails at once. Each is simulated by :func:`sim.run.simulate` (the code of
    ``sim run``) from its assembled initial state, over ``simulation.revolutions``, and
    written to ``out_dir / point_file(label, value)``.

    Args:
        scene_source: built-in scene name or YAML path.
        overrides: ``dotted.key=value`` overrides applied to every point.
        keys: the swept scene keys.
        values: the parameter values, in sweep order.
        out_dir: folder of the per-value run files.
        label: short name of the parameter, used in file names.
        transient_revolutions: revolutions a reader should drop before plotting; recorded
            in the combined dataset (every revolution is kept).
        progress: show each run's progress line.

    Returns:
        The bifurcation dataset of :func:`sim.analysis.bifurcation.combine_sweep` (dimension
        ``parameter``), with the scene, overrides, transient and run files as attributes.
    """
    if not keys:
        raise ValueError("sim sweep: give at least one --key to sweep")
    if not values:
        raise ValueError("sim sweep: give at least one value")
    scenes = [load_scene(scene_source, [*overrides, *point_overrides(keys, v)]) for v in values]
    for scene in scenes:
        revolutions = scene["simulation"]["revolutions"]
        if revolutions <= transient_revolutions:
            raise ValueError(
                f"sim sweep: simulation.revolutions = {revolutions:g} must exceed the "
                f"transient of {transient_revolutions} revolutions"
            )
    sections, paths = [], []
    for scene, value in zip(scenes, values, strict=True):
        run = simulate(scene, progress=progress)
        paths.append(write_netcdf(run, Path(out_dir) / point_file(label, value)))
        sections.append(run[list(SECTION_VARIABLES)])
    combined = combine_sweep(sections, ",".join(keys), values)
    combined.attrs.update(
        scene=scene_source,
        overrides=json.dumps(list(overrides)),
        transient_revolutions=transient_revolutions,
        runs=" ".join(str(path) for path in paths),
    )
    return combined

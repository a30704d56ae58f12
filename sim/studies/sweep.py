"""Parameter sweeps: one scene simulated at every value of a parameter, its Poincaré samples
collected into one bifurcation dataset (``sim sweep``), each value started from its assembled
state or, by continuation, from the previous value's final state."""

import json
from collections.abc import Sequence
from pathlib import Path

import xarray as xr

from sim.analysis.bifurcation import SECTION_VARIABLES, combine_sweep
from sim.model.continuation import ContinuationError
from sim.results import write_netcdf
from sim.run import simulate_from
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
    continuation: bool = False,
    progress: bool = False,
) -> xr.Dataset:
    """Simulate a scene at every value of a parameter and stack the Poincaré samples.

    Every value gives one scene: the scene with ``overrides``, then every key of ``keys``
    set to the value (so ``joints.A.clearance`` and ``joints.B.clearance`` can move
    together). All scenes are loaded and validated before the first simulation, so a bad key
    or value fails at once. Each is simulated by :func:`sim.run.simulate_from` (the code of
    ``sim run``) over ``simulation.revolutions`` and written to
    ``out_dir / point_file(label, value)``.

    Every value starts from its assembled state, or with ``continuation`` from the previous
    value's final state projected onto its scene (:mod:`sim.model.continuation`: angles
    back by whole turns, velocities scaled with the crank speed, clearance coordinates with
    the clearance). The motion then starts on (or near) the neighbouring attractor, so the
    transient to drop is shorter; the values should be in sweep order. A value whose model
    differs (a clearance of 0 makes the joint ideal) starts assembled. Each run's
    ``initial_state`` attribute says which, and why.

    Args:
        scene_source: built-in scene name or YAML path.
        overrides: ``dotted.key=value`` overrides applied to every point.
        keys: the swept scene keys.
        values: the parameter values, in sweep order.
        out_dir: folder of the per-value run files.
        label: short name of the parameter, used in file names.
        transient_revolutions: revolutions a reader should drop before plotting; recorded
            in the combined dataset (every revolution is kept).
        continuation: start each value from the previous value's final state.
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
    final, previous_value = None, None
    for scene, value in zip(scenes, values, strict=True):
        start, origin = None, "assembled"
        if continuation and final is not None:
            start, origin = final, f"continued from {label} = {previous_value:g}"
        try:
            run, final = simulate_from(scene, start, progress=progress)
        except ContinuationError as why:
            run, final = simulate_from(scene, None, progress=progress)
            origin = f"assembled: no continuation from {label} = {previous_value:g}, {why}"
        run.attrs["initial_state"] = origin
        previous_value = value
        paths.append(write_netcdf(run, Path(out_dir) / point_file(label, value)))
        sections.append(run[list(SECTION_VARIABLES)])
    combined = combine_sweep(sections, ",".join(keys), values)
    combined.attrs.update(
        scene=scene_source,
        overrides=json.dumps(list(overrides)),
        transient_revolutions=transient_revolutions,
        continuation=int(continuation),
        runs=" ".join(str(path) for path in paths),
    )
    return combined

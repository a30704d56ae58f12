"""Parameter sweeps: one scene simulated at every value of a parameter, its Poincaré samples
collected into one bifurcation dataset (``sim sweep``), each value started from its assembled
state or, by continuation, from the previous value's final state; optionally each value's
chaos indicators (the model exponent, the 0–1 K) beside them. The values may be shared among
the worker processes of one job (:mod:`sim.studies.batch`)."""

import functools
import json
import sys
import time
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path

import xarray as xr

from sim.analysis.bifurcation import (
    MIN_SECTION_POINTS,
    SECTION_VARIABLES,
    combine_sweep,
    section_indicators,
)
from sim.model.continuation import ContinuationError, State
from sim.results import write_netcdf
from sim.run import Interrupted, simulate_from
from sim.scene import key_field, load_scene
from sim.studies.batch import contiguous_chunks, run_batch
from sim.studies.model_lyapunov import run_with_exponent


@dataclass(frozen=True)
class Indicators:
    """The chaos indicators computed at every sweep point: the model-based largest Lyapunov
    exponent over the revolutions after the transient, with the point's run as the reference
    trajectory (:func:`sim.studies.model_lyapunov.run_with_exponent`), and the channels' 0–1 K,
    section period and verdict (:func:`sim.analysis.bifurcation.section_indicators`).

    Attributes:
        alignment_revolutions: revolutions at the end of the transient over which the
            exponent's perturbed trajectory aligns before recording.
    """

    alignment_revolutions: float


def simulate_point(
    scene: dict,
    start: State | None,
    transient_revolutions: int,
    indicators: Indicators | None,
    progress: bool = False,
    announce_assembly: bool = True,
) -> tuple[xr.Dataset, State, xr.Dataset | None]:
    """One sweep point: its run and final state (:func:`sim.run.simulate_from`) and, with
    ``indicators``, its chaos indicators (None without); with ``progress``, its progress line
    and, if ``announce_assembly``, the assembly branch it took."""
    shown = {"progress": progress, "announce_assembly": announce_assembly}
    if indicators is None:
        return *simulate_from(scene, start, **shown), None
    run, final, exponent = run_with_exponent(
        scene,
        start,
        transient_revolutions=transient_revolutions,
        alignment_revolutions=indicators.alignment_revolutions,
        **shown,
    )
    extra = section_indicators(run, transient_revolutions, exponent.exponent, exponent.stderr)
    return run, final, extra


def model_text(scene: dict) -> str:
    """The link model and integrator of a scene in words, e.g. ``rigid links, dopri5 rtol
    1e-05``, ``beams rod2, rod3, rod4 (2 elements), generalized_alpha rtol 1e-05`` or
    ``modal links rod2, rod3, rod4 (1 bending mode), dopri5 rtol 1e-06``."""
    bodies = scene["bodies"]
    beams = [name for name, body in bodies.items() if body["kind"] == "beam"]
    modal = [name for name, body in bodies.items() if body["kind"] == "modal"]
    parts = []
    if beams:
        elements = sorted({int(bodies[name]["elements"]) for name in beams})
        parts.append(f"beams {', '.join(beams)} ({'/'.join(map(str, elements))} elements)")
    if modal:
        modes = sorted({int(bodies[name]["modes"]) for name in modal})
        axial = sorted({int(bodies[name]["axial_modes"]) for name in modal})
        size = f"{'/'.join(map(str, modes))} bending mode{'s' * (modes != [1])}"
        if axial != [0]:
            size += f", {'/'.join(map(str, axial))} axial"
        parts.append(f"modal links {', '.join(modal)} ({size})")
    solver = scene["solver"]
    return f"{'; '.join(parts) or 'rigid links'}, {solver['method']} rtol {solver['rtol']:g}"


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
    workers: int = 1,
    indicators: Indicators | None = None,
    file_names: Sequence[str] | None = None,
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

    With ``workers`` > 1 the values are run by as many worker processes
    (:func:`sim.studies.batch.run_batch`), each taking the next value when it is free. With
    ``continuation`` they are split instead into that many contiguous chunks
    (:func:`sim.studies.batch.contiguous_chunks`) and continuation runs along each chunk, so
    the first value of a chunk starts assembled. Every value computes bitwise what it
    computes alone.

    Args:
        scene_source: built-in scene name or YAML path.
        overrides: ``dotted.key=value`` overrides applied to every point.
        keys: the swept scene keys.
        values: the parameter values, in sweep order.
        out_dir: folder of the per-value run files.
        label: short name of the parameter, used in file names.
        transient_revolutions: revolutions a reader should drop before plotting; recorded
            in the combined dataset (every revolution is kept); the indicators drop them.
        continuation: start each value from the previous value's final state (in its chunk).
        progress: with one worker, announce each value with the sweep's time left, show each
            run's progress line and the first run's assembly branch.
        workers: worker processes sharing the values.
        indicators: compute each value's chaos indicators (:func:`simulate_point`).
        file_names: the run file of each value in ``out_dir`` (default ``point_file``).

    Returns:
        The bifurcation dataset of :func:`sim.analysis.bifurcation.combine_sweep` (dimension
        ``parameter``, its unit the swept key's), with the label, scene, overrides, transient
        and run files as attributes.
    """
    if not keys:
        raise ValueError("sim sweep: give at least one --key to sweep")
    if not values:
        raise ValueError("sim sweep: give at least one value")
    if file_names is None:
        file_names = [point_file(label, value) for value in values]
    if len(file_names) != len(values):
        raise ValueError(f"sim sweep: {len(file_names)} file names for {len(values)} values")
    scenes = [load_scene(scene_source, [*overrides, *point_overrides(keys, v)]) for v in values]
    need = transient_revolutions + (MIN_SECTION_POINTS if indicators else 1)
    for scene in scenes:
        revolutions = scene["simulation"]["revolutions"]
        if revolutions < need:
            raise ValueError(
                f"sim sweep: simulation.revolutions = {revolutions:g} must be at least the "
                f"transient of {transient_revolutions} revolutions + "
                f"{need - transient_revolutions}"
                + (" (section points of the indicators)" if indicators else "")
            )
    paths = [Path(out_dir) / name for name in file_names]

    # Continuation runs along contiguous chunks; without it each value is a task of its own,
    # taken by whichever process is free, so that costly values (small clearances, slow
    # speeds, which lie together) do not leave one process working alone at the end.
    chunks = (
        contiguous_chunks(len(values), workers)
        if continuation
        else [range(i, i + 1) for i in range(len(values))]
    )
    # one worker runs the values in order: the progress lines and Ctrl-C can name the point
    schedule = SweepClock(len(values), time.perf_counter()) if workers == 1 else None
    tasks = [
        functools.partial(
            _run_chunk,
            [scenes[i] for i in chunk],
            [values[i] for i in chunk],
            [paths[i] for i in chunk],
            label=label,
            transient_revolutions=transient_revolutions,
            continuation=continuation,
            indicators=indicators,
            first=chunk.start,
            clock=schedule,
            progress=progress,
        )
        for chunk in chunks
    ]
    points = [point for done in run_batch(tasks, workers) for point in done]
    combined = combine_sweep(
        [section for section, _ in points],
        ",".join(keys),
        values,
        [extra for _, extra in points] if indicators else None,
    )
    field = key_field(scenes[0], keys[0])
    if field is not None and field.unit:
        combined.parameter.attrs["units"] = field.unit
    combined.attrs.update(
        label=label,
        scene=scene_source,
        overrides=json.dumps(list(overrides)),
        transient_revolutions=transient_revolutions,
        continuation=int(continuation),
        model=model_text(scenes[0]),
        runs=" ".join(str(path) for path in paths),
    )
    return combined


@dataclass(frozen=True)
class SweepClock:
    """What a sweep's progress lines need: its number of points and its start (s,
    ``time.perf_counter``), the points running one after the other in order."""

    total: int
    started: float

    def line(self, index: int, label: str, value: float, path: Path) -> str:
        """The line announcing point ``index`` (from 0): which of how many, where it goes, and
        the sweep's time left, from the mean time of the points finished."""
        elapsed = time.perf_counter() - self.started
        left = (
            f"{index} done in {elapsed:.0f} s, ~{elapsed / index * (self.total - index):.0f} s left"
            if index
            else "the first point sets the estimate of the time left"
        )
        return f"point {index + 1} of {self.total}: {label} = {value:g}, to {path}; {left}"


def _run_chunk(
    scenes: Sequence[dict],
    values: Sequence[float],
    paths: Sequence[Path],
    *,
    label: str,
    transient_revolutions: int,
    continuation: bool,
    indicators: Indicators | None,
    first: int = 0,
    clock: SweepClock | None = None,
    progress: bool = False,
) -> list[tuple[xr.Dataset, xr.Dataset | None]]:
    """Run consecutive sweep values in order, continuing along them if asked; write each run
    and return each value's section variables and indicators (None without ``indicators``).
    ``first``: the index of the chunk's first value in the sweep. With a ``clock`` (the
    values run one after the other) Ctrl-C raises :class:`sim.run.Interrupted` naming the
    point and what the sweep kept, and with ``progress`` a line on stderr announces each value
    as its run starts with the sweep's time left, each run shows its progress line and the
    first says which assembly branch it took."""
    points = []
    final, previous_value = None, None
    for k, (scene, value, path) in enumerate(zip(scenes, values, paths, strict=True)):
        index = first + k
        start, origin = None, "assembled"
        if continuation and final is not None:
            start, origin = final, f"continued from {label} = {previous_value:g}"
        shown = (transient_revolutions, indicators, progress and clock is not None, index == 0)
        try:
            if clock is not None and progress:
                print(clock.line(index, label, value, path), file=sys.stderr, flush=True)
            try:
                run, final, extra = simulate_point(scene, start, *shown)
            except ContinuationError as why:
                run, final, extra = simulate_point(scene, None, *shown)
                origin = f"assembled: no continuation from {label} = {previous_value:g}, {why}"
        except KeyboardInterrupt as stop:
            if clock is None:
                raise
            at = f", {stop.where}" if isinstance(stop, Interrupted) else ""
            done = "point 1" if index == 1 else f"points 1–{index}"
            raise Interrupted(
                f"at point {index + 1} of {clock.total} ({label} = {value:g}){at}",
                (f"kept the run files of {done} in {path.parent}; " if index else "")
                + "no bifurcation dataset written",
            ) from None
        run.attrs["initial_state"] = origin
        previous_value = value
        write_netcdf(run, path)
        points.append((run[list(SECTION_VARIABLES)], extra))
    return points

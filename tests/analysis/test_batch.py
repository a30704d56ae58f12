"""Batched sweeps: points shared among worker processes compute bitwise what they compute
alone."""

import functools
import operator

import numpy as np
import pytest
import xarray as xr

from sim.studies.batch import contiguous_chunks, run_batch
from sim.studies.sweep import run_sweep

# Rigid links (the scene's default), A and B with clearance: impacts from the first revolution.
OVERRIDES = ["simulation.revolutions=1", "simulation.output_per_revolution=50"]
CLEARANCES = [1.0e-4, 2.0e-4, 3.0e-4, 4.0e-4]
KEYS = ["joints.A.clearance", "joints.B.clearance"]


def sweep(tmp_path, name: str, values, *, workers: int, continuation: bool) -> list[xr.Dataset]:
    """The run files of a short clearance sweep, loaded."""
    out_dir = tmp_path / name
    out_dir.mkdir()
    run_sweep(
        "sixbar",
        OVERRIDES,
        KEYS,
        values,
        out_dir=out_dir,
        label="clearance",
        transient_revolutions=0,
        continuation=continuation,
        workers=workers,
    )
    runs = []
    for value in values:
        with xr.open_dataset(out_dir / f"clearance-{value:g}.nc") as run:
            runs.append(run.load())
    return runs


def assert_same_runs(left: list[xr.Dataset], right: list[xr.Dataset]) -> None:
    """Every data variable bitwise equal (NaN where NaN), and the same step counts."""
    for a, b in zip(left, right, strict=True):
        for name in a.data_vars:
            np.testing.assert_array_equal(a[name].values, b[name].values, err_msg=name)
        for key in ("solver_accepted_steps", "solver_rejected_steps", "solver_contact_events"):
            assert a.attrs[key] == b.attrs[key], key
        assert a.attrs["initial_state"] == b.attrs["initial_state"]


def test_processes_compute_what_the_points_compute_one_by_one(tmp_path):
    """Two worker processes over four points against one by one in this process: no state is
    shared, so the runs are bitwise identical."""
    alone = sweep(tmp_path, "alone", CLEARANCES, workers=1, continuation=False)
    batched = sweep(tmp_path, "batched", CLEARANCES, workers=2, continuation=False)
    assert_same_runs(alone, batched)
    assert all(run.attrs["solver_contact_events"] > 0 for run in alone)


def test_continuation_runs_along_each_chunk(tmp_path):
    """With continuation, each process's chunk continues as that chunk would alone: the second
    chunk's first point starts assembled."""
    batched = sweep(tmp_path, "batched", CLEARANCES, workers=2, continuation=True)
    first = sweep(tmp_path, "first", CLEARANCES[:2], workers=1, continuation=True)
    second = sweep(tmp_path, "second", CLEARANCES[2:], workers=1, continuation=True)
    assert_same_runs(batched, first + second)
    assert [run.attrs["initial_state"] for run in batched] == [
        "assembled",
        "continued from clearance = 0.0001",
        "assembled",
        "continued from clearance = 0.0003",
    ]


def test_chunks_cover_the_values_in_order():
    for count in range(0, 20):
        for workers in (1, 2, 3, 16):
            chunks = contiguous_chunks(count, workers)
            assert [i for chunk in chunks for i in chunk] == list(range(count))
            assert len(chunks) == min(count, workers)
            lengths = [len(chunk) for chunk in chunks]
            assert not lengths or max(lengths) - min(lengths) <= 1


def _fails(message: str) -> None:
    raise ValueError(message)


def test_batch_returns_in_task_order_and_raises_a_tasks_error():
    squares = [functools.partial(operator.mul, k, k) for k in range(7)]
    assert run_batch(squares, 3) == [k * k for k in range(7)]
    one, two = functools.partial(int, 1), functools.partial(int, 2)
    with pytest.raises(ValueError, match="point 3 failed"):
        run_batch([one, functools.partial(_fails, "point 3 failed"), two], 2)
    with pytest.raises(ValueError, match="workers = 0"):
        run_batch([], 0)

"""Fixtures of the experiment tests: a fake run file's content and a fake simulator."""

import sys
import types
from collections.abc import Callable

import numpy as np
import pytest
import xarray as xr


def _run(bodies: tuple[str, ...] = ("slider",), body: str = "slider", axis: str = "y"):
    """A 6 s run at 60 rpm: `body`'s acceleration along `axis` (m/s^2) is a periodic signal
    with one decaying impact per revolution; every other channel an unrelated 7.3 Hz sine."""
    time = np.arange(0.0, 6.0, 2e-4)
    phase = 2.0 * np.pi * time
    signal = -2.9 * np.cos(phase) - 0.8 * np.cos(2 * phase + 0.4)
    after = np.maximum(np.mod(time, 1.0) - 0.3, 0.0)
    signal += 20.0 * np.exp(-after / 0.004) * np.sin(2.0 * np.pi * 150.0 * after)
    acceleration = np.empty((time.size, len(bodies), 2))
    acceleration[:] = 0.5 * np.sin(2.0 * np.pi * 7.3 * time)[:, None, None]
    acceleration[:, bodies.index(body), "xy".index(axis)] = signal
    return xr.Dataset(
        {"acceleration": (("time", "body", "axis"), acceleration)},
        coords={"time": time, "body": list(bodies), "axis": ["x", "y"]},
    )


@pytest.fixture
def make_run() -> Callable[..., xr.Dataset]:
    """The factory of fake run datasets (see `_run`)."""
    return _run


@pytest.fixture
def fake_simulator(monkeypatch: pytest.MonkeyPatch) -> list:
    """The scene loader and the simulator replaced: `load_scene` records its arguments and
    gives a scene with one body, `slider`, output at `_run()`'s rate; `simulate` gives `_run()`.
    Returns the calls."""
    calls: list = []
    scene = {
        "bodies": {"slider": {}},
        "drive": {"speed_rpm": 60.0},
        "simulation": {"output_per_revolution": 5000, "sampling": "mean"},
    }
    run_module = types.ModuleType("sim.run")
    run_module.simulate = lambda scene, progress=False: calls.append("simulate") or _run()
    # what `sim.cli.main` imports
    run_module.SimulationError, run_module.Interrupted = RuntimeError, KeyboardInterrupt
    monkeypatch.setattr(
        "sim.scene.load_scene",
        lambda name, overrides=(): calls.append((name, overrides)) or {"name": name, **scene},
    )
    monkeypatch.setitem(sys.modules, "sim.run", run_module)
    return calls

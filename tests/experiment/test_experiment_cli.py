"""`sim experiment synthesize` and `compare` end to end, with a fake simulator."""

import argparse
import json
import sys
import types
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from sim.experiment import cli, load_recording


def _fake_run() -> xr.Dataset:
    time = np.arange(0.0, 6.0, 2e-4)
    phase = 2.0 * np.pi * time
    slider = -2.9 * np.cos(phase) - 0.8 * np.cos(2 * phase + 0.4)
    after = np.maximum(np.mod(time, 1.0) - 0.3, 0.0)
    slider += 20.0 * np.exp(-after / 0.004) * np.sin(2.0 * np.pi * 150.0 * after)
    acceleration = np.zeros((time.size, 1, 2))
    acceleration[:, 0, 1] = slider
    return xr.Dataset(
        {"acceleration": (("time", "body", "axis"), acceleration)},
        coords={"time": time, "body": ["slider"], "axis": ["x", "y"]},
    )


@pytest.fixture
def fake_simulator(monkeypatch: pytest.MonkeyPatch) -> list:
    calls: list = []
    scene_module = types.ModuleType("sim.scene")
    run_module = types.ModuleType("sim.run")
    scene_module.load_scene = lambda name, overrides=(): (
        calls.append((name, overrides)) or {"name": name}
    )
    run_module.simulate = lambda scene, progress=False: _fake_run()
    monkeypatch.setitem(sys.modules, "sim.scene", scene_module)
    monkeypatch.setitem(sys.modules, "sim.run", run_module)
    return calls


def _parse(*argv: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="sim")
    cli.register(parser.add_subparsers(dest="command", required=True))
    return parser.parse_args(list(argv))


def test_synthesize_then_compare(tmp_path: Path, fake_simulator: list, capsys) -> None:
    recording = tmp_path / "data" / "synthetic.csv"
    sensor = tmp_path / "sensor.yaml"
    sensor.write_text("sampling_rate_hz: 1000.0\nbandwidth_hz: 250.0\n")
    args = _parse(
        *("experiment", "synthesize", "sixbar", "--set", "speed_rpm=60", "--sensor", str(sensor)),
        *("--seed", "3", "-o", str(recording)),
    )
    assert args.func(args) == 0
    assert fake_simulator == [("sixbar", ["speed_rpm=60"])]
    loaded = load_recording(recording)
    assert loaded.synthetic and loaded.sampling_rate_hz == 1000.0
    assert loaded.metadata["synthesis"]["seed"] == 3
    assert loaded.metadata["synthesis"]["provenance"]["overrides"] == ["speed_rpm=60"]

    simulation = tmp_path / "run.nc"
    _fake_run().to_netcdf(simulation)
    out = tmp_path / "compare"
    args = _parse(
        *("experiment", "compare", str(recording), str(simulation), "--crank-rpm", "60"),
        *("--out-dir", str(out)),
    )
    assert args.func(args) == 0
    summary = json.loads((out / cli.COMPARISON_JSON).read_text())
    assert summary["data_kind"] == "synthetic recording"
    # the truth drawn by the sensor model is reported beside the recovered shift
    injected = loaded.metadata["synthesis"]["sensor_draws"]["time_shift_s"]
    assert summary["alignment"]["injected_shift_s"] == injected
    assert abs(summary["alignment"]["shift_s"] - injected) * 1000.0 < 1.0
    printed = capsys.readouterr().out
    assert "synthetic recording" in printed and "correlation" in printed
    assert f"injected {injected * 1e3:.4g} ms" in printed
    assert sorted(path.name for path in out.iterdir()) == sorted(
        [cli.COMPARISON_NETCDF, cli.COMPARISON_JSON, cli.OVERLAY_FIGURE, cli.SPECTRA_FIGURE]
    )
    assert summary["metrics"]["correlation"]["mean"] > 0.99
    with xr.open_dataset(out / cli.COMPARISON_NETCDF) as dataset:
        assert dataset.attrs["synthetic"] == 1
        assert dataset.rms_error.attrs["units"] == "m s-2"
    assert (out / cli.OVERLAY_FIGURE).stat().st_size > 0
    assert (out / cli.SPECTRA_FIGURE).stat().st_size > 0


def test_compare_reports_a_malformed_recording(tmp_path: Path, capsys) -> None:
    recording = tmp_path / "rig.csv"
    recording.write_text("time;acceleration\n0;1\n")
    (tmp_path / "rig.meta.yaml").write_text("format_version: 1\n")
    args = _parse(
        *("experiment", "compare", str(recording), str(tmp_path / "run.nc")),
        *("--crank-rpm", "60", "--out-dir", str(tmp_path / "out")),
    )
    assert args.func(args) == 1
    assert "missing metadata key 'description'" in capsys.readouterr().err

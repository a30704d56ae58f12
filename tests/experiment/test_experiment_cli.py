"""`sim experiment synthesize` and `compare` end to end, with a fake simulator."""

import argparse
import json
from collections.abc import Callable
from pathlib import Path

import xarray as xr

from sim.cli import experiment as cli
from sim.cli import main
from sim.experiment import load_recording


def _parse(*argv: str) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="sim")
    cli.register(parser.add_subparsers(dest="command", required=True))
    return parser.parse_args(list(argv))


def test_synthesize_then_compare(
    tmp_path: Path, fake_simulator: list, make_run: Callable, capsys
) -> None:
    recording = tmp_path / "data" / "synthetic.csv"
    sensor = tmp_path / "sensor.yaml"
    sensor.write_text("sampling_rate_hz: 1000.0\nbandwidth_hz: 250.0\n")
    args = _parse(
        *("experiment", "synthesize", "sixbar", "--set", "speed_rpm=60", "--sensor", str(sensor)),
        *("--seed", "3", "-o", str(recording)),
    )
    assert args.func(args) == 0
    assert fake_simulator == [("sixbar", ["speed_rpm=60"]), "simulate"]
    loaded = load_recording(recording)
    assert loaded.synthetic and loaded.sampling_rate_hz == 1000.0
    assert loaded.metadata["synthesis"]["seed"] == 3
    assert loaded.metadata["synthesis"]["provenance"]["overrides"] == ["speed_rpm=60"]
    # the default channel, written out: the slider's vertical acceleration
    assert loaded.metadata["channel"] == {"body": "slider", "point": "centre", "axis": "y"}

    simulation = tmp_path / "run.nc"
    make_run().to_netcdf(simulation)
    out = tmp_path / "compare"
    args = _parse(
        *("experiment", "compare", str(recording), str(simulation), "--crank-rpm", "60"),
        *("--out-dir", str(out)),
    )
    assert args.func(args) == 0
    summary = json.loads((out / cli.COMPARISON_JSON).read_text())
    assert summary["data_kind"] == "synthetic recording"
    assert summary["channel"] == loaded.metadata["channel"]
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
    argv = ["experiment", "compare", str(recording), str(tmp_path / "run.nc")]
    assert main([*argv, "--crank-rpm", "60", "--out-dir", str(tmp_path / "out")]) == 2
    assert "missing metadata key 'description'" in capsys.readouterr().err

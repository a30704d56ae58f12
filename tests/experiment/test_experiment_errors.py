"""Bad input to `sim experiment synthesize | compare` is refused through `sim`'s one error
path (exit code 2, one line naming the file or option and what is accepted), before any
computation; and the measured channel comes from the recording's metadata."""

import json
from collections.abc import Callable
from pathlib import Path

import pytest

from sim.cli import main
from sim.cli.experiment import COMPARISON_JSON
from sim.experiment import (
    RecordingError,
    SensorSettings,
    load_recording,
    metadata_path,
    synthesize_recording,
    write_recording,
)
from sim.experiment.metadata import DEFAULT_CHANNEL

SENSOR = SensorSettings(sampling_rate_hz=1000.0, bandwidth_hz=250.0)


def _recording(folder: Path, make_run: Callable, channel: dict | None = None) -> Path:
    """A synthetic recording of `make_run`'s signal on `channel` (None: no channel key)."""
    body, axis = (channel or DEFAULT_CHANNEL)["body"], (channel or DEFAULT_CHANNEL)["axis"]
    run = make_run(bodies=(body,), body=body, axis=axis)
    frame, metadata = synthesize_recording(
        run.time.values,
        run.acceleration.sel(body=body, axis=axis).values,
        sensor=SENSOR,
        seed=5,
        provenance={"scene": "test"},
        channel=channel or DEFAULT_CHANNEL,
    )
    if channel is None:
        del metadata["channel"]
    return write_recording(folder / "rig.csv", frame, metadata)


def _compare(recording: Path, run: Path, out: Path, *options: str) -> int:
    argv = ["experiment", "compare", str(recording), str(run), "--out-dir", str(out)]
    return main([*argv, *(options or ("--crank-rpm", "60"))])


@pytest.mark.parametrize("rpm", ["0", "-60", "nan", "inf"])
def test_crank_speed_is_checked_first(tmp_path: Path, capsys, rpm: str) -> None:
    # The files need not exist: options are checked before anything is read.
    code = _compare(tmp_path / "r.csv", tmp_path / "r.nc", tmp_path / "out", "--crank-rpm", rpm)
    assert code == 2
    expected = f"--crank-rpm = {float(rpm)!r} is not accepted; expected a number 0 < x ≤ 100000"
    assert expected in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize(
    ("options", "message"),
    [
        (
            ("--max-shift", "0.6"),
            "--max-shift = 0.6 is not accepted; expected a number 0 < x ≤ 0.5 (s)",
        ),
        (("--max-shift", "0"), "--max-shift = 0.0 is not accepted"),
        (("--crank-angle-at-zero", "nan"), "--crank-angle-at-zero = nan is not accepted"),
    ],
)
def test_other_numeric_options_are_checked(tmp_path: Path, capsys, options, message) -> None:
    out = tmp_path / "out"
    assert _compare(tmp_path / "r.csv", tmp_path / "r.nc", out, "--crank-rpm", "60", *options) == 2
    assert message in capsys.readouterr().err


@pytest.mark.parametrize(
    ("kind", "message"),
    [
        ("text", "is not a netCDF file: give a file written by `sim run`"),
        ("directory", "is a directory, not a netCDF file"),
        ("missing", "does not exist"),
    ],
)
def test_simulation_file_that_cannot_be_read(
    tmp_path: Path, make_run: Callable, capsys, kind: str, message: str
) -> None:
    recording = _recording(tmp_path, make_run)
    simulation = tmp_path / "run.nc"
    if kind == "text":
        simulation.write_text("not a netCDF file\n")
    elif kind == "directory":
        simulation.mkdir()
    assert _compare(recording, simulation, tmp_path / "out") == 2
    assert f"run file '{simulation}' {message}" in capsys.readouterr().err


def test_run_without_the_measured_body(tmp_path: Path, make_run: Callable, capsys) -> None:
    recording = _recording(tmp_path, make_run)  # no channel key: the slider by default
    simulation = tmp_path / "run.nc"
    make_run(bodies=("crank", "ram"), body="ram").to_netcdf(simulation)
    assert _compare(recording, simulation, tmp_path / "out") == 2
    err = capsys.readouterr().err
    assert f"{metadata_path(recording)}: the recording measures the acceleration of body " in err
    assert "'slider', point 'centre', axis 'y' (the default: no 'channel' key)" in err
    assert f"run file '{simulation}' has no body 'slider'; its bodies: crank, ram" in err
    assert "Set channel.body in the metadata" in err


def test_channel_of_the_metadata_is_compared(tmp_path: Path, make_run: Callable) -> None:
    """A mechanism whose output is not a vertical slider: the ram's x acceleration."""
    channel = {"body": "ram", "point": "centre", "axis": "x"}
    recording = _recording(tmp_path, make_run, channel)
    simulation = tmp_path / "run.nc"
    # the ram's y and the crank carry an unrelated signal: only the right channel matches
    make_run(bodies=("crank", "ram"), body="ram", axis="x").to_netcdf(simulation)
    assert _compare(recording, simulation, tmp_path / "out") == 0
    summary = json.loads((tmp_path / "out" / COMPARISON_JSON).read_text())
    assert summary["channel"] == channel
    assert summary["metrics"]["correlation"]["mean"] > 0.99


def _meta_file(tmp_path: Path, make_run: Callable, text: str) -> Path:
    """A recording whose metadata file is replaced by `text`."""
    recording = _recording(tmp_path, make_run)
    metadata_path(recording).write_text(text)
    return recording


# Valid metadata for `_recording`'s data, one key per line (the line numbers are checked).
META = """format_version: 1
description: test
synthetic: false
sampling_rate_hz: 1000.0
units: {time: s, acceleration: m/s^2}
sensor: {axis: y, bandwidth_hz: 250.0, range: 490.0}
"""


def test_metadata_channel_is_checked(tmp_path: Path, make_run: Callable) -> None:
    recording = _meta_file(tmp_path, make_run, META + "channel:\n  body: ram\n  axis: z\n")
    with pytest.raises(RecordingError) as error:
        load_recording(recording)
    assert str(error.value) == (
        f"{metadata_path(recording)}, line 9: metadata key 'channel.axis' = 'z' is not "
        "accepted; a run records 'x', 'y' (channel: body, point, axis)"
    )


def test_metadata_key_given_twice(tmp_path: Path, make_run: Callable) -> None:
    recording = _meta_file(tmp_path, make_run, META + "synthetic: true\n")
    with pytest.raises(RecordingError, match=r"line 7: key 'synthetic' is given twice \(lines 3 "):
        load_recording(recording)


def test_recording_that_is_not_utf8(tmp_path: Path, make_run: Callable) -> None:
    recording = _recording(tmp_path, make_run)
    recording.write_bytes(recording.read_bytes() + "# fin é\n".encode("latin-1"))
    with pytest.raises(RecordingError, match=rf"^{recording}: not UTF-8 text \(byte 0xe9"):
        load_recording(recording)


@pytest.mark.parametrize(
    ("options", "sensor_text", "message"),
    [
        (("--body", "ram"), None, "--body 'ram' is not a body of scene 'sixbar'; accepted: slider"),
        (("--seed", "-1"), None, "--seed = -1 is not accepted; expected a whole number 0 ≤ x"),
        (
            (),
            "bandwidth_hz: fast\n",
            "{sensor}: sensor setting bandwidth_hz = 'fast' is not accepted; expected a finite "
            "number",
        ),
        (
            (),
            "bandwidth_hz: 100.0\nbandwidth_hz: 200.0\n",
            "{sensor}, line 2: key 'bandwidth_hz' is given twice (lines 1 and 2)",
        ),
        (
            (),
            "sampling_rate_hz: 8000.0\nbandwidth_hz: 3000.0\n",
            "is 5000 Hz: too coarse for the sensor's bandwidth_hz 3000 Hz (it must exceed twice "
            "that); set simulation.output_per_revolution to at least 6001",
        ),
    ],
)
def test_synthesize_refuses_bad_input_before_simulating(
    tmp_path: Path, fake_simulator: list, capsys, options, sensor_text, message
) -> None:
    argv = ["experiment", "synthesize", "sixbar", "-o", str(tmp_path / "s.csv"), *options]
    if sensor_text is not None:
        (tmp_path / "sensor.yaml").write_text(sensor_text)
        argv += ["--sensor", str(tmp_path / "sensor.yaml")]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert message.format(sensor=tmp_path / "sensor.yaml") in err
    assert "simulate" not in fake_simulator
    assert not (tmp_path / "s.csv").exists()


def test_point_samples_are_refused_on_both_sides(
    tmp_path: Path, make_run: Callable, fake_simulator: list, capsys, monkeypatch
) -> None:
    # The sensor model filters samples: they must be interval means (sim.quantities), which a
    # run file's acceleration attributes say; a scene set to point samples is refused before
    # it is simulated.
    recording = _recording(tmp_path, make_run)
    simulation = tmp_path / "run.nc"
    run = make_run()
    run.acceleration.attrs["sampling"] = "point"
    run.to_netcdf(simulation)
    assert _compare(recording, simulation, tmp_path / "out") == 2
    assert f"run file '{simulation}' records the acceleration as point samples" in (
        capsys.readouterr().err
    )
    import sim.scene

    loaded = sim.scene.load_scene("sixbar")  # the fake: a scene output at 5000 a revolution
    loaded["simulation"] = {**loaded["simulation"], "sampling": "point"}
    monkeypatch.setattr("sim.scene.load_scene", lambda name, overrides=(): loaded)
    argv = ["experiment", "synthesize", "sixbar", "-o", str(tmp_path / "s.csv")]
    assert main(argv) == 2
    assert "simulation.sampling = 'point': the sensor model filters samples" in (
        capsys.readouterr().err
    )
    assert "simulate" not in fake_simulator
    assert not (tmp_path / "s.csv").exists()

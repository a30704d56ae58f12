"""The recording format: round trip through the writer, and rejection of malformed files."""

import math
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import yaml

from sim.experiment import RecordingError, load_recording, metadata_path, write_recording

RATE_HZ = 1000.0
SAMPLES = 200


def _metadata(**changes: object) -> dict:
    metadata = {
        "format_version": 1,
        "description": "test recording written by the test suite",
        "synthetic": False,
        "sampling_rate_hz": RATE_HZ,
        "units": {"time": "s", "acceleration": "m/s^2"},
        "sensor": {"axis": "y", "bandwidth_hz": 200.0, "range": 50.0},
    }
    metadata.update(changes)
    return metadata


def _lines() -> list[str]:
    """Header plus one line per sample; sample k sits on line k + 2."""
    rows = [
        f"{k / RATE_HZ:.6f},{3.0 * math.sin(2.0 * math.pi * k / RATE_HZ * 5.0):.6f}"
        for k in range(SAMPLES)
    ]
    return ["time,acceleration", *rows]


def _write(folder: Path, lines: list[str], metadata: dict) -> Path:
    path = folder / "rig.csv"
    path.write_text("\n".join(lines) + "\n" if lines else "")
    metadata_path(path).write_text(yaml.safe_dump(metadata, sort_keys=False))
    return path


def _replace(lines: list[str], line: int, text: str) -> list[str]:
    """Lines with the 1-based ``line`` replaced."""
    return [text if number == line else old for number, old in enumerate(lines, start=1)]


def test_writer_output_loads_back_in_si_units(tmp_path: Path) -> None:
    time = np.arange(SAMPLES) / RATE_HZ
    frame = pd.DataFrame({"time": time * 1e3, "acceleration": np.sin(time) / 9.80665})
    metadata = _metadata(units={"time": "ms", "acceleration": "g"})
    path = write_recording(tmp_path / "out" / "rig.csv", frame, metadata)
    recording = load_recording(path)
    np.testing.assert_allclose(recording.time, time, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(recording.acceleration, np.sin(time), rtol=1e-9)
    assert recording.sampling_rate_hz == RATE_HZ and not recording.synthetic
    # Only the two files, no temporary left behind.
    assert sorted(p.name for p in path.parent.iterdir()) == ["rig.csv", "rig.meta.yaml"]


def test_writer_refuses_what_the_loader_would_reject(tmp_path: Path) -> None:
    frame = pd.DataFrame({"time": [0.0, 0.002, 0.001], "acceleration": [0.0, 1.0, 2.0]})
    with pytest.raises(RecordingError, match=r"line 4: time 0\.001 s does not increase"):
        write_recording(tmp_path / "rig.csv", frame, _metadata())
    assert not any(tmp_path.iterdir())


MALFORMED = {
    "non-monotonic time": (
        lambda: _replace(_lines(), 50, "0.047000,0.1"),
        {},
        r"rig\.csv, line 50: time 0\.047 s does not increase after 0\.047 s",
    ),
    "missing column": (
        lambda: ["time", *(line.split(",")[0] for line in _lines()[1:])],
        {"units": {"time": "s"}},
        r"rig\.csv, line 1: missing column 'acceleration'",
    ),
    "wrong units": (
        _lines,
        {"units": {"time": "s", "acceleration": "m/s"}},
        r"rig\.meta\.yaml, line 7: unit 'm/s' is not known for column 'acceleration' "
        r"\(known: m/s\^2, mm/s\^2, g\)",
    ),
    "NaN run": (
        lambda: [
            f"{line.split(',')[0]},NaN" if 12 <= n <= 16 else line
            for n, line in enumerate(_lines(), start=1)
        ],
        {},
        r"rig\.csv, lines 12-16: 5 consecutive missing value\(s\) in column 'acceleration'",
    ),
    "clipping": (
        lambda: [
            f"{line.split(',')[0]},-50.0" if 30 <= n <= 32 else line
            for n, line in enumerate(_lines(), start=1)
        ],
        {},
        r"rig\.csv, lines 30-32: acceleration reaches the sensor range of ±50 m/s\^2 "
        r"\(3 sample\(s\) in all\): the recording is clipped",
    ),
    "empty file": (list, {}, r"rig\.csv: file is empty"),
    "header only": (
        lambda: _lines()[:1],
        {},
        r"rig\.csv, line 1: no samples: the file has a header line only",
    ),
    "wrong delimiter": (
        lambda: [line.replace(",", ";") for line in _lines()],
        {},
        r"rig\.csv, line 1: columns are separated by semicolons, but the format is "
        r"comma-separated",
    ),
    "sampling rate disagrees with time column": (
        _lines,
        {"sampling_rate_hz": 2000.0},
        r"rig\.meta\.yaml, line 4: sampling_rate_hz is 2000 Hz but the time column of "
        r".*rig\.csv is sampled at 1000 Hz",
    ),
    "dropped sample": (
        lambda: [line for n, line in enumerate(_lines(), start=1) if n != 100],
        {},
        r"rig\.csv, line 100: time step 0\.002 s from the line before differs from "
        r"1/sampling_rate_hz = 0\.001 s",
    ),
    "unknown metadata key": (
        _lines,
        {"samplerate": 1000},
        r"rig\.meta\.yaml, line 12: unknown metadata key 'samplerate'",
    ),
    "misspelt sensor key": (
        _lines,
        {"sensor": {"axis": "y", "bandwith_hz": 200.0, "range": 50.0}},
        r"rig\.meta\.yaml, line 10: unknown metadata key 'sensor\.bandwith_hz'",
    ),
    "not a number": (
        lambda: _replace(_lines(), 77, "0.075000,abc"),
        {},
        r"rig\.csv, line 77: column 'acceleration' value 'abc' is not a finite number",
    ),
    "ragged line": (
        lambda: _replace(_lines(), 20, "0.018000,1.0,2.0"),
        {},
        r"rig\.csv, line 20: 3 fields where the header has 2",
    ),
    "synthetic without its settings": (
        _lines,
        {"synthetic": True},
        r"rig\.meta\.yaml, line 3: synthetic: true needs a 'synthesis' block",
    ),
    "bandwidth above Nyquist": (
        _lines,
        {"sensor": {"axis": "y", "bandwidth_hz": 600.0, "range": 50.0}},
        r"rig\.meta\.yaml, line 10: sensor bandwidth_hz 600.0 Hz is not below the Nyquist",
    ),
}


@pytest.mark.parametrize("kind", MALFORMED)
def test_malformed_recording_is_rejected_with_its_reason(tmp_path: Path, kind: str) -> None:
    make_lines, metadata_changes, message = MALFORMED[kind]
    path = _write(tmp_path, make_lines(), _metadata(**metadata_changes))
    with pytest.raises(RecordingError, match=message):
        load_recording(path)


def test_missing_metadata_file_is_named(tmp_path: Path) -> None:
    path = tmp_path / "rig.csv"
    path.write_text("\n".join(_lines()))
    with pytest.raises(RecordingError, match=r"rig\.meta\.yaml: file not found"):
        load_recording(path)


def test_valid_lines_load(tmp_path: Path) -> None:
    recording = load_recording(_write(tmp_path, _lines(), _metadata()))
    assert recording.time.size == SAMPLES
    assert recording.trigger is None and recording.crank_angle is None

"""Alignment and metrics on a slider-like acceleration (60 rpm, harmonics and impacts)."""

import dataclasses

import numpy as np
import pytest

from sim.experiment import (
    SensorSettings,
    align_signals,
    align_simulation,
    compare,
    estimate_shift,
    synthesize_recording,
    validate_recording,
)

CRANK_PERIOD_S = 1.0  # 60 rpm
SIMULATION_RATE_HZ = 10_000.0


def slider_acceleration(time: np.ndarray) -> np.ndarray:
    """A slider-like acceleration in m/s^2: crank harmonics plus two impacts per revolution.

    Each impact rings at 180 Hz and decays in a few ms, the pattern clearance impacts leave.
    """
    phase = 2.0 * np.pi * time / CRANK_PERIOD_S
    acceleration = -2.9 * np.cos(phase) - 0.8 * np.cos(2 * phase + 0.4) + 0.25 * np.cos(3 * phase)
    for start in np.arange(time[0], time[-1], CRANK_PERIOD_S):
        for fraction, amplitude in ((0.23, 25.0), (0.71, -18.0)):
            since = time - (start + fraction * CRANK_PERIOD_S)
            after = np.maximum(since, 0.0)
            ringing = amplitude * np.exp(-after / 0.004) * np.sin(2.0 * np.pi * 180.0 * after)
            acceleration += ringing
    return acceleration


@pytest.fixture(scope="module")
def simulation() -> tuple[np.ndarray, np.ndarray]:
    time = np.arange(0.0, 8.0, 1.0 / SIMULATION_RATE_HZ)
    return time, slider_acceleration(time)


def _record(simulation, sensor: SensorSettings, seed: int):
    frame, metadata = synthesize_recording(
        *simulation, sensor=sensor, seed=seed, provenance={"test": "slider-like signal"}
    )
    return validate_recording(frame, metadata, source="synthetic.csv"), metadata


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_injected_shift_is_recovered_within_one_sample(simulation, seed: int) -> None:
    sensor = SensorSettings()  # noise, gain and offset at the synthetic sensor's level
    recording, metadata = _record(simulation, sensor, seed)
    injected = metadata["synthesis"]["sensor_draws"]["time_shift_s"]
    alignment = align_simulation(recording, *simulation, crank_period_s=CRANK_PERIOD_S)
    assert alignment.method == "cross-correlation"
    error_samples = abs(alignment.shift_s - injected) * sensor.sampling_rate_hz
    assert error_samples < 1.0


def test_recording_aligned_with_itself_agrees_exactly(simulation) -> None:
    recording, _ = _record(simulation, SensorSettings(), seed=4)
    time, measured = recording.time, recording.acceleration
    shift = estimate_shift(time, measured, time, measured, max_shift_s=0.5)
    alignment = align_signals(
        time,
        measured,
        time,
        measured,
        shift_s=shift,
        method="cross-correlation",
        bandwidth_hz=recording.bandwidth_hz,
    )
    comparison = compare(alignment, crank_period_s=CRANK_PERIOD_S, synthetic=True)
    summary = comparison.summary()["metrics"]
    assert abs(shift) * recording.sampling_rate_hz < 1e-9
    assert summary["rms_error"]["mean"] == pytest.approx(0.0, abs=1e-9)
    assert summary["correlation"]["mean"] == pytest.approx(1.0, abs=1e-12)
    assert summary["peak_ratio"]["mean"] == pytest.approx(1.0, abs=1e-9)
    assert comparison.spectral_distance_db == pytest.approx(0.0, abs=1e-9)


@pytest.mark.parametrize("recording_rate_hz", [1200.0, 2000.0, 4096.0])
def test_recording_at_another_rate_than_the_simulation(simulation, recording_rate_hz) -> None:
    sensor = dataclasses.replace(SensorSettings(), sampling_rate_hz=recording_rate_hz)
    recording, metadata = _record(simulation, sensor, seed=5)
    alignment = align_simulation(recording, *simulation, crank_period_s=CRANK_PERIOD_S)
    injected = metadata["synthesis"]["sensor_draws"]["time_shift_s"]
    assert abs(alignment.shift_s - injected) * recording_rate_hz < 1.0
    np.testing.assert_array_equal(alignment.time, recording.time[: alignment.time.size])
    comparison = compare(alignment, crank_period_s=CRANK_PERIOD_S, synthetic=True)
    metrics = comparison.summary()["metrics"]
    # What is left is the sensor's noise and gain error, nothing of a misalignment.
    assert metrics["correlation"]["mean"] > 0.999
    assert metrics["peak_to_peak_ratio"]["mean"] == pytest.approx(
        metadata["synthesis"]["sensor_draws"]["gain"], rel=0.02
    )


def test_trigger_channel_gives_the_shift(simulation) -> None:
    recording, metadata = _record(simulation, SensorSettings(), seed=6)
    injected = metadata["synthesis"]["sensor_draws"]["time_shift_s"]
    # A once-per-revolution pulse, 5 ms wide, when the simulated crank passes angle 0.
    crank_time = recording.time - injected
    trigger = np.where(np.mod(crank_time, CRANK_PERIOD_S) < 0.005, 5.0, 0.0)
    with_trigger = dataclasses.replace(recording, trigger=trigger)
    alignment = align_simulation(with_trigger, *simulation, crank_period_s=CRANK_PERIOD_S)
    assert alignment.method == "trigger channel"
    assert abs(alignment.shift_s - injected) * recording.sampling_rate_hz < 1.0


def test_shift_beyond_the_search_window_is_reported(simulation) -> None:
    recording, _ = _record(simulation, SensorSettings(max_time_shift_s=0.0), seed=7)
    late = recording.time + 0.3
    with pytest.raises(ValueError, match="edge of the search"):
        estimate_shift(late, recording.acceleration, *simulation, max_shift_s=0.1)

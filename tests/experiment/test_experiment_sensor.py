"""The sensor model is deterministic for a seed and records at its own rate and band."""

import numpy as np
from scipy.signal import welch

from sim.experiment import SensorSettings, apply_sensor


def _input() -> tuple[np.ndarray, np.ndarray]:
    time = np.arange(0.0, 4.0, 1e-4)
    return time, 3.0 * np.sin(2.0 * np.pi * time) + np.sin(2.0 * np.pi * 2000.0 * time)


def test_same_seed_same_output_other_seed_other_output() -> None:
    settings = SensorSettings()
    first = apply_sensor(*_input(), settings, seed=11)
    again = apply_sensor(*_input(), settings, seed=11)
    other = apply_sensor(*_input(), settings, seed=12)
    np.testing.assert_array_equal(first.acceleration, again.acceleration)
    assert first.draws == again.draws
    assert first.draws != other.draws


def test_samples_at_the_sensor_rate_without_aliasing() -> None:
    settings = SensorSettings(noise_std_m_s2=0.0, offset_std_m_s2=0.0, gain_error_std=0.0)
    output = apply_sensor(*_input(), settings, seed=0)
    np.testing.assert_allclose(np.diff(output.time), 1.0 / settings.sampling_rate_hz)
    # 2 kHz lies at the recorder's 2 kHz rate and would alias to DC without the low-pass.
    frequency, power = welch(output.acceleration, fs=settings.sampling_rate_hz, nperseg=2000)
    assert power[frequency == 1.0][0] > 1e6 * power[frequency > 600.0].max()

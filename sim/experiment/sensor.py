"""Sensor model: what an accelerometer and its recorder make of a true acceleration.

The chain, in order: anti-alias low-pass (zero-phase Butterworth, see
:mod:`sim.experiment.sampling` for why zero phase), sampling at the recorder's rate on the
recorder's clock, which runs ahead of the simulation's by an unknown shift, gain error, offset
error, additive white Gaussian noise, saturation at the sensor's range.

A real sensor's chain filters the continuous signal before it samples. The model filters
samples, so they must already be free of aliasing in the sensor's band: a run's acceleration
recorded as interval means (`simulation.sampling: mean`, the default: each sample the mean over
its window, a boxcar that attenuates the flexible links' 5–10 kHz ringing before it folds) at a
rate well above the sensor's bandwidth (the experiment study: 4 kHz for a 500 Hz sensor). Point
samples of a flexible run fold that ringing into the band, where no filter can remove it.

The random parts (gain, offset, shift, noise) are drawn from
``numpy.random.default_rng(seed)`` in that fixed order, so the same seed gives the same output.

The default values are assumptions typical of an industrial piezoelectric or MEMS
accelerometer read by a 2 kHz data acquisition card, not properties of the paper's rig (which
are not published).
"""

import dataclasses
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from sim.experiment.errors import RecordingError
from sim.experiment.metadata import DEFAULT_FILTER_ORDER, load_yaml
from sim.experiment.recording import read_text
from sim.experiment.sampling import lowpass, resample, uniform_rate


@dataclass(frozen=True)
class SensorSettings:
    """Settings of the sensor model (units in the names; the random ones are spreads).

    ``gain_error_std`` is relative (0.02 = 2 % calibration error, standard deviation);
    ``offset_std_m_s2`` and ``noise_std_m_s2`` are standard deviations in m/s^2; the time
    shift is drawn uniformly in ±``max_time_shift_s``, which must stay below half a crank
    period for the cross-correlation alignment to be unambiguous; ``range_m_s2`` is the
    symmetric measuring range (±) beyond which the sensor saturates.
    """

    sampling_rate_hz: float = 2000.0
    bandwidth_hz: float = 500.0
    filter_order: int = DEFAULT_FILTER_ORDER
    range_m_s2: float = 490.0
    gain_error_std: float = 0.02
    offset_std_m_s2: float = 0.2
    noise_std_m_s2: float = 0.05
    max_time_shift_s: float = 0.2
    axis: str = "y, along the slider guide"

    def __post_init__(self) -> None:
        if not 0.0 < self.bandwidth_hz < self.sampling_rate_hz / 2.0:
            raise ValueError(
                f"sensor bandwidth_hz {self.bandwidth_hz:g} must lie between 0 and the "
                f"Nyquist frequency {self.sampling_rate_hz / 2.0:g} Hz of sampling_rate_hz"
            )
        if self.filter_order < 1 or self.range_m_s2 <= 0:
            raise ValueError("sensor filter_order must be >= 1 and range_m_s2 positive")
        spreads = (
            self.gain_error_std,
            self.offset_std_m_s2,
            self.noise_std_m_s2,
            self.max_time_shift_s,
        )
        if min(spreads) < 0:
            raise ValueError("sensor error spreads must not be negative")

    @classmethod
    def from_mapping(cls, mapping: Mapping[str, Any]) -> "SensorSettings":
        """Settings from a mapping of field names to values; unknown names and values of the
        wrong type (text for a number, a fraction for a whole number) are errors."""
        kinds = {f.name: f.type for f in dataclasses.fields(cls)}
        unknown = sorted(set(mapping) - set(kinds))
        if unknown:
            raise ValueError(
                f"unknown sensor setting(s) {', '.join(map(str, unknown))} "
                f"(known: {', '.join(sorted(kinds))})"
            )
        for name, value in mapping.items():
            if not _has_kind(value, kinds[name]):
                expected = {float: "a finite number", int: "a whole number", str: "text"}
                raise ValueError(
                    f"sensor setting {name} = {value!r} is not accepted; expected "
                    + expected[kinds[name]]
                )
        return cls(**mapping)

    def to_dict(self) -> dict[str, Any]:
        """Plain-Python mapping of every setting (for metadata files)."""
        return dataclasses.asdict(self)


def _has_kind(value: Any, kind: type) -> bool:
    """Whether a settings value is of a field's type (bool is no number; an int is a float)."""
    if isinstance(value, bool):
        return False
    if kind is float:
        return isinstance(value, int | float) and math.isfinite(value)
    return isinstance(value, kind)


def load_sensor_settings(path: str | os.PathLike[str]) -> SensorSettings:
    """Sensor settings from a YAML mapping; settings it leaves out keep their defaults.
    Raises RecordingError (a ValueError) naming the file for anything it cannot use."""
    source = Path(path)
    mapping, _ = load_yaml(read_text(source), str(source))
    if not isinstance(mapping, dict | None):
        raise RecordingError(str(source), "sensor settings must be a YAML mapping")
    try:
        return SensorSettings.from_mapping(mapping or {})
    except ValueError as exc:
        raise RecordingError(str(source), str(exc)) from None


@dataclass(frozen=True)
class SensorDraws:
    """The random sensor errors of one synthetic recording.

    ``gain`` (dimensionless, 1 = exact), ``offset_m_s2`` (m/s^2), ``time_shift_s`` (s): the
    recorder's clock reads ``t_simulation + time_shift_s``.
    """

    gain: float
    offset_m_s2: float
    time_shift_s: float


@dataclass(frozen=True)
class SensorOutput:
    """Recorded samples: ``time`` on the recorder's clock in s, ``acceleration`` in m/s^2."""

    time: np.ndarray
    acceleration: np.ndarray
    draws: SensorDraws


def apply_sensor(
    time: np.ndarray, acceleration: np.ndarray, settings: SensorSettings, *, seed: int
) -> SensorOutput:
    """Record a true acceleration (m/s^2, uniformly sampled at ``time`` in s) with the sensor.

    Recorder samples fall at integer multiples of 1/``sampling_rate_hz`` on the recorder's
    clock, over the span the input covers. Samples beyond ±``range_m_s2`` saturate at the
    range, as a real sensor does; the recording checks then reject the result as clipped.
    """
    rng = np.random.default_rng(seed)
    draws = SensorDraws(
        gain=float(1.0 + rng.normal(0.0, settings.gain_error_std)),
        offset_m_s2=float(rng.normal(0.0, settings.offset_std_m_s2)),
        time_shift_s=float(rng.uniform(-settings.max_time_shift_s, settings.max_time_shift_s)),
    )
    filtered = lowpass(
        acceleration, uniform_rate(time), settings.bandwidth_hz, settings.filter_order
    )
    rate = settings.sampling_rate_hz
    first = math.ceil((time[0] + draws.time_shift_s) * rate)
    last = math.floor((time[-1] + draws.time_shift_s) * rate)
    recorder_time = np.arange(first, last + 1) / rate
    true_value = resample(time, filtered, recorder_time - draws.time_shift_s)
    noise = rng.normal(0.0, settings.noise_std_m_s2, recorder_time.size)
    measured = draws.gain * true_value + draws.offset_m_s2 + noise
    saturated = np.clip(measured, -settings.range_m_s2, settings.range_m_s2)
    return SensorOutput(time=recorder_time, acceleration=saturated, draws=draws)

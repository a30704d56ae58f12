"""Output samples of an Exudyn run at our output times (no dependency on exudyn itself)."""

from dataclasses import dataclass, field

import numpy as np


@dataclass
class Recorder:
    """Sensor values at our output times, read at the start of the step that begins there.

    Exudyn's own sensor output is written when the summed step sizes reach the next write time
    to within 1e-10 s; over 1e6 steps their round-off exceeds that and a sample slips by one
    step. Here a step that starts at an output time (to within 1e-6 of a step) is sampled there;
    one that passes over it (after Exudyn reduced a step that did not converge, or one that
    met a contact onset) is sampled at its start and end and interpolated linearly, and
    counted in `interpolated`; a step retried from the same start replaces its first try.
    `times` (s) are the output times, `step` (s) Exudyn's nominal step."""

    sensors: list
    times: np.ndarray = field(default_factory=lambda: np.zeros(0))
    step: float = 0.0
    values: list = field(default_factory=list)  # per sample: one array per sensor
    interpolated: int = 0
    pending: tuple | None = None  # (start time, values) of a step passing an output time

    def _read(self, mbs) -> list[np.ndarray]:
        return [np.atleast_1d(mbs.GetSensorValues(s)) for s in self.sensors]

    def take(self, mbs, start: float, end: float) -> None:
        """At the start of a step from `start` to `end` (s), with the current state there."""
        tolerance = 1e-6 * self.step
        k = len(self.values)
        if self.pending is not None and abs(start - self.pending[0]) <= tolerance:
            self.pending = None  # the same step again, reduced (its first try was rejected)
        if self.pending is not None and k < self.times.size:
            t0, before = self.pending
            after = self._read(mbs)
            w = (self.times[k] - t0) / (start - t0)
            self.values.append([a + w * (b - a) for a, b in zip(before, after, strict=True)])
            self.pending = None
            self.interpolated += 1
            k += 1
        if k >= self.times.size:
            return
        if abs(start - self.times[k]) <= tolerance:
            self.values.append(self._read(mbs))
        elif start < self.times[k] < end - tolerance:
            self.pending = (start, self._read(mbs))

    def series(self, sensor) -> np.ndarray:
        """(samples, components) of one sensor."""
        i = self.sensors.index(sensor)
        return np.array([sample[i] for sample in self.values])

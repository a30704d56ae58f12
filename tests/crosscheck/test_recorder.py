"""The recorder of Exudyn's output samples (sim.crosscheck.recorder) on a fake system whose two
sensors read x(t) = 2 + 3 t and (sin t, t²) at the current time; needs no Exudyn."""

import itertools

import numpy as np

from sim.crosscheck.recorder import Recorder


class FakeSystem:
    def __init__(self):
        self.t = 0.0

    def GetSensorValues(self, sensor):  # Exudyn's name
        return 2.0 + 3.0 * self.t if sensor == "x" else [np.sin(self.t), self.t**2]


def _run(starts: np.ndarray, times: np.ndarray, step: float) -> Recorder:
    """Drive the recorder through steps with the given start times (the last is the end)."""
    system = FakeSystem()
    recorder = Recorder(["x", "y"], times=times, step=step)
    for start, end in itertools.pairwise(starts):
        system.t = start
        recorder.take(system, start, end)
    system.t = starts[-1]
    recorder.take(system, starts[-1], np.inf)
    return recorder


def test_steps_on_the_output_grid_sample_exactly():
    """Ten steps per sample whose start times carry round-off: every output time is sampled
    at a step start, none interpolated."""
    times = np.arange(11) * 0.01
    starts = np.cumsum(np.r_[0.0, np.full(100, 0.001)])  # summed steps: round-off in the last bits
    recorder = _run(starts, times, 0.001)
    assert recorder.interpolated == 0
    np.testing.assert_allclose(recorder.series("x")[:, 0], 2.0 + 3.0 * starts[::10], rtol=0, atol=0)


def test_a_halved_step_off_the_grid_is_interpolated():
    """Steps of 0.001 s until a halved step shifts the grid by 0.0005 s: the output times after
    it fall inside steps and are interpolated linearly (exact for the linear sensor, within the
    second-order error h²/8 |x''| for t²)."""
    times = np.arange(6) * 0.01
    starts = np.r_[np.arange(0, 0.0201, 0.001), 0.0205 + np.arange(0, 0.03, 0.001), 0.05]
    recorder = _run(np.unique(np.round(starts, 12)), times, 0.001)
    assert len(recorder.values) == times.size
    assert recorder.interpolated == 2  # 0.03 and 0.04 fall inside steps; 0.05 ends the run
    np.testing.assert_allclose(recorder.series("x")[:, 0], 2.0 + 3.0 * times, atol=1e-12)
    np.testing.assert_allclose(recorder.series("y")[:, 1], times**2, atol=0.001**2 / 8 * 2 + 1e-15)


def test_a_retried_step_replaces_its_first_try():
    """Exudyn retries a step from the same start with a smaller size when it meets a contact
    onset: the first try passed over the output time 0.02 s, the retry does not. The sample
    is interpolated between the retry's start and the next step's, never divided by the zero
    span between the two tries."""
    times = np.arange(4) * 0.01
    system = FakeSystem()
    recorder = Recorder(["x", "y"], times=times, step=0.001)
    steps = [(t, t + 0.001) for t in np.round(np.arange(0.0, 0.0195, 0.001), 12)]
    steps += [(0.0195, 0.0205), (0.0195, 0.0197)]  # the first try, then the retry
    steps += [(t, t + 0.001) for t in np.round(0.0197 + np.arange(0.0, 0.0103, 0.001), 12)]
    steps.append((0.0307, np.inf))  # the run's end
    for start, end in steps:
        system.t = start
        recorder.take(system, start, end)
    assert len(recorder.values) == times.size
    np.testing.assert_allclose(recorder.series("x")[:, 0], 2.0 + 3.0 * times, atol=1e-12)

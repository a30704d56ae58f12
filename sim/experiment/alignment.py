"""Alignment of a recording with the simulation: time shift, then resampling onto its times.

Convention: the recorder's clock reads ``t_recording = t_simulation + shift``.

The shift comes from, in order of preference, the once-per-revolution trigger channel, the
crank-angle channel, or the cross-correlation of the acceleration signals. The simulation is
first passed through the same anti-alias filter as the sensor (:mod:`sim.experiment.sampling`)
so that the two signals share one band, then resampled onto the recording's times, whatever
the two sampling rates.
"""

import math
from dataclasses import dataclass

import numpy as np
from scipy.signal import correlate, correlation_lags

from sim.experiment.recording import Recording
from sim.experiment.sampling import lowpass, resample, uniform_rate

# Lags whose overlap covers less than this fraction of the shorter signal are not trusted:
# a normalised correlation over a few samples can reach 1 by chance.
_MIN_OVERLAP = 0.5
# Fraction of a sample by which a span may fall short of a whole number of samples.
_GRID_SLACK = 1e-6


@dataclass(frozen=True)
class Alignment:
    """A recording and the simulation on the same times.

    ``time`` (s, recorder clock) are the recording's samples that the simulation covers;
    ``measured`` and ``simulated`` are accelerations in m/s^2 at those times; ``shift_s`` the
    estimated shift (s); ``method`` how it was found; ``sampling_rate_hz`` the recording's rate;
    ``bandwidth_hz`` the sensor band in which both signals are comparable.
    """

    time: np.ndarray
    measured: np.ndarray
    simulated: np.ndarray
    shift_s: float
    method: str
    sampling_rate_hz: float
    bandwidth_hz: float


def estimate_shift(
    recording_time: np.ndarray,
    recording: np.ndarray,
    reference_time: np.ndarray,
    reference: np.ndarray,
    *,
    max_shift_s: float,
) -> float:
    """Time shift (s) of a recording against a band-limited reference, by cross-correlation.

    The reference is resampled onto a grid at the recording's rate, both signals lose their
    mean (the sensor offset), and the normalised cross-correlation (each lag divided by the
    signal energies within its overlap, Lewis 1995, "Fast normalized cross-correlation") is
    maximised over shifts within ±``max_shift_s``. The peak is refined to a fraction of a
    sample by a parabola through it and its two neighbours (Jacovitti & Scarano 1993, IEEE
    Trans. Signal Processing 41(2), 525-533).

    For a periodic response the correlation repeats every crank period, so ``max_shift_s``
    must stay below half a period; use a trigger or crank-angle channel for larger shifts.
    Both signals must be sampled uniformly, and must overlap by at least half the shorter one.
    """
    rate = uniform_rate(recording_time)
    # A span of exactly n steps can compute as n - 1e-12 steps: without the slack the grid
    # would lose its last sample and the correlation its symmetry.
    count = math.floor((reference_time[-1] - reference_time[0]) * rate + _GRID_SLACK) + 1
    grid = reference_time[0] + np.arange(count) / rate
    x = resample(reference_time, reference, grid)
    x -= x.mean()
    y = np.asarray(recording, dtype=float) - np.mean(recording)
    lags = correlation_lags(x.size, y.size, mode="full")
    # Lag l pairs x[n + l] with y[n]; so the shift is the start offset minus l samples.
    shifts = recording_time[0] - grid[0] - lags / rate
    overlap = np.minimum(y.size, x.size - lags) - np.maximum(0, -lags)
    allowed = (np.abs(shifts) <= max_shift_s) & (overlap >= _MIN_OVERLAP * min(x.size, y.size))
    if not allowed.any():
        raise ValueError("the recording and the reference do not overlap within max_shift_s")
    numerator = correlate(x, y, mode="full", method="fft")
    energy_x = correlate(x**2, np.ones(y.size), mode="full", method="fft")
    energy_y = correlate(np.ones(x.size), y**2, mode="full", method="fft")
    score = np.full(lags.size, -np.inf)
    score[allowed] = numerator[allowed] / np.sqrt(energy_x[allowed] * energy_y[allowed])
    best = int(np.argmax(score))
    if best in (0, lags.size - 1) or not (allowed[best - 1] and allowed[best + 1]):
        raise ValueError(
            f"the correlation peaks at the edge of the search (shift {shifts[best]:.6g} s): "
            "the true shift exceeds max_shift_s, or the signals are unrelated"
        )
    # The FFT sums carry rounding errors relative to the largest values, which would bias the
    # sub-sample fraction; the three points of the parabola are summed directly instead.
    before, peak, after = (
        _normalized_correlation(x, y, lags[i]) for i in (best - 1, best, best + 1)
    )
    fraction = 0.5 * (before - after) / (before - 2.0 * peak + after)
    return float(recording_time[0] - grid[0] - (lags[best] + fraction) / rate)


def _normalized_correlation(x: np.ndarray, y: np.ndarray, lag: int) -> float:
    """Normalised cross-correlation of x[n + lag] with y[n] over their overlap."""
    start, stop = max(0, -lag), min(y.size, x.size - lag)
    a, b = x[start + lag : stop + lag], y[start:stop]
    return float(np.dot(a, b) / np.sqrt(np.dot(a, a) * np.dot(b, b)))


def estimate_shift_from_trigger(
    recording_time: np.ndarray,
    trigger: np.ndarray,
    *,
    crank_period_s: float,
    trigger_angle_rad: float = 0.0,
    crank_angle_at_zero_rad: float = 0.0,
) -> float:
    """Time shift (s) from a once-per-revolution trigger channel.

    Each rising crossing of the trigger's mid-level (located between samples by linear
    interpolation) marks the crank passing ``trigger_angle_rad``; the simulated crank turns
    uniformly, ``angle = crank_angle_at_zero_rad + 2π t / crank_period_s``. The shift is the
    circular mean over all revolutions (Mardia & Jupp 2000, *Directional Statistics*, sec.
    2.2), so it is known modulo one period and returned within ±half a period.
    """
    level = 0.5 * (np.min(trigger) + np.max(trigger))
    rising = np.flatnonzero((trigger[:-1] < level) & (trigger[1:] >= level))
    if rising.size == 0:
        raise ValueError("the trigger channel has no rising edge")
    fraction = (level - trigger[rising]) / (trigger[rising + 1] - trigger[rising])
    edges = recording_time[rising] + fraction * (
        recording_time[rising + 1] - recording_time[rising]
    )
    return _shift_from_angles(
        edges, np.full(edges.size, trigger_angle_rad), crank_period_s, crank_angle_at_zero_rad
    )


def estimate_shift_from_crank_angle(
    recording_time: np.ndarray,
    crank_angle: np.ndarray,
    *,
    crank_period_s: float,
    crank_angle_at_zero_rad: float = 0.0,
) -> float:
    """Time shift (s) from a recorded crank angle (rad, wrapped or not).

    Same model and circular mean as :func:`estimate_shift_from_trigger`, over every sample.
    """
    return _shift_from_angles(recording_time, crank_angle, crank_period_s, crank_angle_at_zero_rad)


def _shift_from_angles(
    times: np.ndarray, angles: np.ndarray, period: float, angle_at_zero: float
) -> float:
    # At recorder time t the crank stood at angle a; the simulation reaches a at
    # (a - angle_at_zero) * period / 2π (modulo a period), so each sample gives one shift.
    phase = 2.0 * np.pi * times / period - (angles - angle_at_zero)
    return float(period * np.angle(np.mean(np.exp(1j * phase))) / (2.0 * np.pi))


def align_signals(
    recording_time: np.ndarray,
    recording: np.ndarray,
    reference_time: np.ndarray,
    reference: np.ndarray,
    *,
    shift_s: float,
    method: str,
    bandwidth_hz: float,
) -> Alignment:
    """Resample a band-limited reference (s, m/s^2) onto the recording's times, given the shift.

    Keeps the recording samples whose instant on the reference's clock lies within the
    reference's span.
    """
    instants = recording_time - shift_s
    inside = (instants >= reference_time[0]) & (instants <= reference_time[-1])
    if inside.sum() < 2:
        raise ValueError("the shifted recording does not overlap the reference")
    return Alignment(
        time=recording_time[inside],
        measured=np.asarray(recording, dtype=float)[inside],
        simulated=resample(reference_time, reference, instants[inside]),
        shift_s=float(shift_s),
        method=method,
        sampling_rate_hz=uniform_rate(recording_time),
        bandwidth_hz=float(bandwidth_hz),
    )


def align_simulation(
    recording: Recording,
    simulation_time: np.ndarray,
    simulation: np.ndarray,
    *,
    crank_period_s: float,
    crank_angle_at_zero_rad: float = 0.0,
    max_shift_s: float | None = None,
) -> Alignment:
    """Align a simulated acceleration (m/s^2 at uniform ``simulation_time`` in s) to a recording.

    The simulation goes through the recording's sensor filter at its own rate, then the shift
    is taken from the trigger channel, else the crank-angle channel, else cross-correlation
    within ±``max_shift_s`` (default: half a crank period).
    """
    filtered = lowpass(
        simulation, uniform_rate(simulation_time), recording.bandwidth_hz, recording.filter_order
    )
    if recording.trigger is not None:
        shift = estimate_shift_from_trigger(
            recording.time,
            recording.trigger,
            crank_period_s=crank_period_s,
            trigger_angle_rad=float(recording.metadata.get("trigger_angle_rad", 0.0)),
            crank_angle_at_zero_rad=crank_angle_at_zero_rad,
        )
        method = "trigger channel"
    elif recording.crank_angle is not None:
        shift = estimate_shift_from_crank_angle(
            recording.time,
            recording.crank_angle,
            crank_period_s=crank_period_s,
            crank_angle_at_zero_rad=crank_angle_at_zero_rad,
        )
        method = "crank-angle channel"
    else:
        shift = estimate_shift(
            recording.time,
            recording.acceleration,
            simulation_time,
            filtered,
            max_shift_s=0.5 * crank_period_s if max_shift_s is None else max_shift_s,
        )
        method = "cross-correlation"
    return align_signals(
        recording.time,
        recording.acceleration,
        simulation_time,
        filtered,
        shift_s=shift,
        method=method,
        bandwidth_hz=recording.bandwidth_hz,
    )

"""The sensor's anti-alias filter and band-limited resampling, shared by sensor and alignment.

Filter: a Butterworth low-pass in second-order sections, applied forward and backward
(``scipy.signal.sosfiltfilt``), i.e. zero-phase (Oppenheim & Schafer, *Discrete-Time Signal
Processing*, 3rd ed., 2010, sec. 5.1 and 7.3; Gustafsson 1996 for the initial conditions).
Zero phase is chosen because the recording and the simulation are both passed through this
same filter before they are compared: a causal filter's group delay would then be a second,
frequency-dependent time shift folded into the estimated one, while with zero phase the
estimated shift is the physical one. A real sensor's phase lag is part of the unknown shift
that the alignment estimates. Forward-backward filtering squares the magnitude response, so
the filter sits -6 dB (not -3 dB) at ``bandwidth_hz``.

Resampling: a cubic spline through the filtered samples (de Boor, *A Practical Guide to
Splines*, 1978). After the low-pass the signal is oversampled, where the spline is accurate
to well below the sensor noise.
"""

import numpy as np
from scipy.interpolate import CubicSpline
from scipy.signal import butter, sosfiltfilt

# Sample times may carry rounding from text files; a step within this fraction of the mean
# counts as uniform.
_UNIFORM_TOLERANCE = 1e-3


def uniform_rate(time: np.ndarray) -> float:
    """Sampling rate in Hz of a strictly increasing, uniformly spaced time vector in s."""
    time = np.asarray(time, dtype=float)
    if time.ndim != 1 or time.size < 2:
        raise ValueError("a time vector needs at least two samples")
    step = np.diff(time)
    mean_step = (time[-1] - time[0]) / (time.size - 1)
    if np.any(step <= 0) or np.max(np.abs(step - mean_step)) > _UNIFORM_TOLERANCE * mean_step:
        raise ValueError("time must be strictly increasing and uniformly sampled")
    return 1.0 / mean_step


def lowpass(signal: np.ndarray, rate_hz: float, bandwidth_hz: float, order: int) -> np.ndarray:
    """Zero-phase Butterworth low-pass of ``signal`` sampled at ``rate_hz`` (Hz).

    ``bandwidth_hz`` is the cut-off of each pass; ``order`` the order of one pass (the
    forward-backward result has twice the order). The cut-off must lie below the Nyquist
    frequency of the input, or the signal is too coarsely sampled to emulate the sensor.
    """
    nyquist = rate_hz / 2.0
    if not 0.0 < bandwidth_hz < nyquist:
        raise ValueError(
            f"cannot low-pass at {bandwidth_hz:g} Hz a signal sampled at {rate_hz:g} Hz "
            f"(Nyquist {nyquist:g} Hz): sample the input more finely"
        )
    sos = butter(order, bandwidth_hz, btype="low", fs=rate_hz, output="sos")
    return sosfiltfilt(sos, np.asarray(signal, dtype=float))


def resample(time: np.ndarray, signal: np.ndarray, at: np.ndarray) -> np.ndarray:
    """Values of a band-limited ``signal`` sampled at ``time`` (s), at the times ``at`` (s).

    Every time in ``at`` must lie within the span of ``time`` (no extrapolation).
    """
    at = np.asarray(at, dtype=float)
    # Times computed as (k / rate - shift) may cross the ends by a rounding error only.
    slack = _UNIFORM_TOLERANCE * (time[-1] - time[0]) / (len(time) - 1)
    if at.size and (at.min() < time[0] - slack or at.max() > time[-1] + slack):
        raise ValueError("resampling times fall outside the sampled span (no extrapolation)")
    return CubicSpline(time, signal)(np.clip(at, time[0], time[-1]))

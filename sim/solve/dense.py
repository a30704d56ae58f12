"""Continuous extension of a step: y(θ) on the step from t to t + h, θ ∈ [0, 1].

One form serves both methods, y(θ) = d0 + θ(d1 + (1−θ)(d2 + θ(d3 + (1−θ) d4))),
the form of Hairer's DOPRI5 (Hairer, Nørsett & Wanner, Solving ODEs I, 2nd ed.,
1993, II.6). Its first four terms are the cubic Hermite interpolant of y and
h ẏ at both ends of the step; d4 adds DOPRI5's fourth-order correction.
"""

import numpy as np

from sim.jit import kernel


@kernel
def hermite_coefficients(work, y: np.ndarray, k0: np.ndarray, h: float) -> None:
    """d0…d3 of the cubic Hermite interpolant of y (start), work.ynew (end) and
    their derivatives k0 and work.ydot_end; d4 = 0."""
    k6 = work.ydot_end
    d = work.dense
    yn = work.ynew
    for i in range(y.shape[0]):
        ydiff = yn[i] - y[i]
        d[0, i] = y[i]
        d[1, i] = ydiff
        d[2, i] = h * k0[i] - ydiff
        d[3, i] = ydiff - h * k6[i] - d[2, i]
        d[4, i] = 0.0


@kernel
def interpolate(work, theta: float, count: int, out: np.ndarray) -> None:
    """The first `count` state entries at fraction θ of the step into `out`."""
    d = work.dense
    t1 = 1.0 - theta
    for i in range(count):
        out[i] = d[0, i] + theta * (d[1, i] + t1 * (d[2, i] + theta * (d[3, i] + t1 * d[4, i])))

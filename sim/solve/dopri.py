"""Dormand–Prince 5(4): one explicit step with its error estimate and dense output.

The explicit embedded Runge–Kutta pair of Dormand & Prince (J. Comput. Appl.
Math. 6, 1980) with the PI step-size controller and 4th-order continuous
extension of Hairer, Nørsett & Wanner (Solving ODEs I, 2nd ed., 1993, II.4–II.6
and the code DOPRI5). The loop around it (events, sampling, step control) is
`sim.solve.stepping`. Compiled with numba; nothing here allocates.
"""

from typing import NamedTuple

import numpy as np

from sim.jit import kernel, kernel_inline, spliced
from sim.solve.control import ERR_MIN, ERR_OLD_MIN
from sim.solve.dae import adopt_tree_state, rhs_inline
from sim.solve.dense import hermite_coefficients, interpolate
from sim.solve.record import record_row
from sim.solve.status import OK

# Dormand–Prince tableau.
C2, C3, C4, C5 = 0.2, 0.3, 0.8, 8.0 / 9.0
A21 = 0.2
A31, A32 = 3.0 / 40.0, 9.0 / 40.0
A41, A42, A43 = 44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0
A51, A52, A53, A54 = 19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0
A61, A62, A63 = 9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0
A64, A65 = 49.0 / 176.0, -5103.0 / 18656.0
A71, A73, A74, A75, A76 = 35.0 / 384.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0
E1, E3, E4 = 71.0 / 57600.0, -71.0 / 16695.0, 71.0 / 1920.0
E5, E6, E7 = -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0
D1, D3 = -12715105075.0 / 11282082432.0, 87487479700.0 / 32700410799.0
D4, D5 = -10690763975.0 / 1880347072.0, 701980252875.0 / 199316789632.0
D6, D7 = -1453857185.0 / 822651844.0, 69997945.0 / 29380423.0
# Step-size controller (Hairer's DOPRI5 defaults: PI control with β = 0.04): safety factor
# against the next step's error exceeding the tolerance, the gain on the previous error, and
# the exponent of this one, 1/5 − 0.75 β for the 5th-order step.
SAFE, BETA = 0.9, 0.04
EXPO1 = 0.2 - BETA * 0.75
STRETCH = 1.01
"""A step that would end within this factor of t_end is stretched to end on it: no sliver
step is left over."""


STAGE_A = np.array(
    [
        [A21, 0.0, 0.0, 0.0, 0.0, 0.0],
        [A31, A32, 0.0, 0.0, 0.0, 0.0],
        [A41, A42, A43, 0.0, 0.0, 0.0],
        [A51, A52, A53, A54, 0.0, 0.0],
        [A61, A62, A63, A64, A65, 0.0],
        [A71, 0.0, A73, A74, A75, A76],
    ]
)
"""The tableau's rows of the stages k2…k6 and of the new state (where k7 is evaluated), its
columns k1…k6; a zero is no term at all."""
STAGE_C = np.array([C2, C3, C4, C5, 1.0, 1.0])
"""The nodes of those rows: fractions of the step."""


@spliced
def _stages(sys, work, carry, mem, t: float, h: float, y: np.ndarray) -> int:
    """Stages k2…k6 from k1 = carry.derivative into carry.stages; the new state into
    work.ynew, k7 = its derivative into work.ydot_end. One loop over the rows of STAGE_A,
    so that the evaluation, inlined (`rhs_inline`), is compiled once and not called six
    times with `System` and `Work` passed field by field; the sums in the tableau's order,
    term by term, as six written-out combinations would make them."""
    k1 = carry.derivative
    ny = y.shape[0]
    for s in range(STAGE_A.shape[0]):
        last = s == STAGE_A.shape[0] - 1
        state = work.ynew if last else work.ytmp
        derivative = work.ydot_end if last else carry.stages[s]
        if s == 0:
            # one term: (h a) k1, the rounding order of y + h a21 k1 written out
            for i in range(ny):
                state[i] = y[i] + h * STAGE_A[0, 0] * k1[i]
        else:
            # the sum term by term over all of the state, then the state: loops that vectorise
            for i in range(ny):
                state[i] = STAGE_A[s, 0] * k1[i]
            for r in range(1, s + 1):
                a = STAGE_A[s, r]
                if a != 0.0:
                    k = carry.stages[r - 1]
                    for i in range(ny):
                        state[i] += a * k[i]
            for i in range(ny):
                state[i] = y[i] + h * state[i]
        status = rhs_inline(sys, work, mem, t + STAGE_C[s] * h, state, derivative)
        if status != OK:
            return status
    return OK


@spliced
def _error_norm(work, carry, y: np.ndarray, h: float, n2: int, rtol: float, atol: float) -> float:
    """RMS of the embedded error estimate over q and q̇, scaled by atol + rtol·|y|.
    The energy quadratures are left out: they follow the motion's accuracy."""
    k1 = carry.derivative
    k3, k4, k5, k6 = carry.stages[1], carry.stages[2], carry.stages[3], carry.stages[4]
    k7 = work.ydot_end
    yn = work.ynew
    total = 0.0
    for i in range(n2):
        e = h * (E1 * k1[i] + E3 * k3[i] + E4 * k4[i] + E5 * k5[i] + E6 * k6[i] + E7 * k7[i])
        sc = atol + rtol * max(abs(y[i]), abs(yn[i]))
        total += (e / sc) ** 2
    return np.sqrt(total / n2)


@spliced
def _dense_coefficients(work, carry, y: np.ndarray, h: float) -> None:
    """Coefficients of the continuous extension over the step just computed: the
    Hermite part and DOPRI5's fourth-order term d4."""
    k1 = carry.derivative
    hermite_coefficients(work, y, k1, h)
    k3, k4, k5, k6 = carry.stages[1], carry.stages[2], carry.stages[3], carry.stages[4]
    k7 = work.ydot_end
    d = work.dense
    for i in range(y.shape[0]):
        d[4, i] = h * (D1 * k1[i] + D3 * k3[i] + D4 * k4[i] + D5 * k5[i] + D6 * k6[i] + D7 * k7[i])


@kernel_inline
def plan(t: float, h: float, t_end: float, buffers, tally) -> float:
    """The step to take from t given the step size h the controller wants: h, stretched
    or shortened to land on t_end when it ends within 1 % of it (samples come from the
    continuous extension, so steps need not end on them)."""
    return t_end - t if t + STRETCH * h >= t_end else h


@kernel_inline
def mark_grazes(sys, work, mem) -> None:
    """Nothing to do: a stage evaluation that penetrated a gap has marked it MEM_GRAZED
    (`sim.model.gaps`)."""


@kernel
def sample(sys, work, mem, t0: float, h: float, time: float, row: np.ndarray) -> int:
    """Record the sample at `time` in (t0, t0 + h] from the continuous extension, the
    model evaluated afresh there; the right-hand side status."""
    theta = min((time - t0) / h, 1.0)
    interpolate(work, theta, work.yint.shape[0], work.yint)
    return record_row(sys, work, mem, time, work.yint, row)


class Carry(NamedTuple):
    """What a step hands to the next besides the trajectory (valid while clock.started),
    and the method's own scratch."""

    derivative: np.ndarray  # (2n + 2,) ẏ at (t, y): the first stage k1 (FSAL)
    stages: np.ndarray  # (5, 2n + 2) scratch: the step's stages k2…k6


def make_carry(n: int, m: int) -> Carry:
    """The carry of a system of n coordinates and m constraints."""
    return Carry(derivative=np.zeros(2 * n + 2), stages=np.zeros((5, 2 * n + 2)))


@kernel_inline
def start(sys, work, carry) -> None:
    """Nothing to prepare: a step starts from y and Carry.derivative alone."""


@kernel_inline
def step(sys, work, carry, mem, t: float, h: float, y: np.ndarray, options, tally):
    """One step from (t, y), k1 = ẏ in carry.derivative: the new state into work.ynew,
    its derivative into work.ydot_end, the dense output into work.dense; its six
    evaluations counted in tally. Returns (status, error estimate scaled to the tolerance).
    Inlined into the loops that take it (the integration and the lockstep follower)."""
    tally.evaluations += 6
    s = _stages(sys, work, carry, mem, t, h, y)
    if s != OK:
        return s, np.inf
    # a tree mechanism's absolute coordinates follow its angles, so that the events and the
    # continuous extension read the gaps where its forces read them (k7 depends on the angles
    # only, and its evaluation, the last, rebuilt them at the step's end: the projection onto
    # the tree without a second rebuild)
    adopt_tree_state(sys, work, work.ynew)
    _dense_coefficients(work, carry, y, h)
    return OK, _error_norm(work, carry, y, h, 2 * sys.n, options.rtol, options.atol)


@kernel_inline
def accept(sys, work, carry) -> None:
    """Nothing beyond the loop's own: the step's end derivative becomes the next k1 (FSAL)."""


@kernel_inline
def step_factor(err: float, err_old: float) -> float:
    """Ratio of the next step size to this one: PI control
    SAFE · err_old^β / err^(1/5 − 0.75 β) (Hairer & Wanner's DOPRI5)."""
    return SAFE * max(err_old, ERR_OLD_MIN) ** BETA / max(err, ERR_MIN) ** EXPO1

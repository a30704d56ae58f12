"""Dormand–Prince 5(4) with dense output, contact events and exact sampling.

The explicit embedded Runge–Kutta pair of Dormand & Prince (J. Comput. Appl.
Math. 6, 1980) with the step-size controller and 4th-order continuous extension
of Hairer, Nørsett & Wanner (Solving ODEs I, 2nd ed., 1993, II.4–II.6 and the
code DOPRI5). Compiled with numba; the loop allocates nothing.

Contact events: after a step passes the error test, every gap whose sign
disagrees with its in-contact flag is located on the dense output by the
Illinois method; the step is redone to end exactly at the earliest crossing,
where the flag flips and the onset rate δ̇⁻ is captured (the memory the
Lankarani–Nikravesh law needs). Output samples, Poincaré sections (exact times)
and peaks are taken from the dense output and the accepted steps.

The caller advances the integration in chunks (`integrate` returns at t_end);
all state between chunks lives in the arrays it passes.
"""

import numpy as np

from sim.jit import kernel
from sim.model.clearance import face_switch_energy, gap
from sim.model.system import OUT_NORMAL_FORCE, OUT_PENETRATION
from sim.solve.dae import NONFINITE, OK, SC_DRIVE_TORQUE, rhs
from sim.solve.record import record_row, reference_point

# Integrator status codes beyond the right-hand side's OK / SINGULAR / NONFINITE.
MAX_STEPS, STEP_COLLAPSE, PENETRATION, VIOLATION = 3, 4, 5, 6

# Indices into the integrator state `st`.
ST_T, ST_H, ST_FACOLD, ST_FSAL = range(4)
N_ST = 4
# Indices into `opts`.
OPT_RTOL, OPT_ATOL, OPT_HMAX, OPT_HMIN, OPT_VIOLATION_BOUND, OPT_MAX_STEPS = range(6)
N_OPTS = 6
# Indices into `stats` (counters) and `diag` (failure details).
S_ACCEPTED, S_REJECTED, S_NFEV, S_EVENTS, S_CULPRIT, S_OUT, S_SEC = range(7)
N_STATS = 7
D_TIME, D_VALUE = range(2)

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
# Step-size controller (Hairer's DOPRI5 defaults: PI control with β = 0.04).
SAFE, BETA, FAC_MIN, FAC_MAX = 0.9, 0.04, 0.2, 10.0
EXPO1 = 0.2 - BETA * 0.75


@kernel
def _stages(sys, work, mem, t: float, h: float, y: np.ndarray) -> int:
    """Stages 2–7 from k1 = work.stages[0]; the new state into work.ynew."""
    k = work.stages
    yt = work.ytmp
    yn = work.ynew
    ny = y.shape[0]
    for i in range(ny):
        yt[i] = y[i] + h * A21 * k[0, i]
    s = rhs(sys, work, mem, t + C2 * h, yt, k[1])
    if s != OK:
        return s
    for i in range(ny):
        yt[i] = y[i] + h * (A31 * k[0, i] + A32 * k[1, i])
    s = rhs(sys, work, mem, t + C3 * h, yt, k[2])
    if s != OK:
        return s
    for i in range(ny):
        yt[i] = y[i] + h * (A41 * k[0, i] + A42 * k[1, i] + A43 * k[2, i])
    s = rhs(sys, work, mem, t + C4 * h, yt, k[3])
    if s != OK:
        return s
    for i in range(ny):
        yt[i] = y[i] + h * (A51 * k[0, i] + A52 * k[1, i] + A53 * k[2, i] + A54 * k[3, i])
    s = rhs(sys, work, mem, t + C5 * h, yt, k[4])
    if s != OK:
        return s
    for i in range(ny):
        yt[i] = y[i] + h * (
            A61 * k[0, i] + A62 * k[1, i] + A63 * k[2, i] + A64 * k[3, i] + A65 * k[4, i]
        )
    s = rhs(sys, work, mem, t + h, yt, k[5])
    if s != OK:
        return s
    for i in range(ny):
        yn[i] = y[i] + h * (
            A71 * k[0, i] + A73 * k[2, i] + A74 * k[3, i] + A75 * k[4, i] + A76 * k[5, i]
        )
    return rhs(sys, work, mem, t + h, yn, k[6])


@kernel
def _error_norm(work, y: np.ndarray, h: float, n2: int, rtol: float, atol: float) -> float:
    """RMS of the embedded error estimate over q and q̇, scaled by atol + rtol·|y|.
    The energy quadratures are left out: they follow the motion's accuracy."""
    k = work.stages
    yn = work.ynew
    total = 0.0
    for i in range(n2):
        e = h * (
            E1 * k[0, i] + E3 * k[2, i] + E4 * k[3, i] + E5 * k[4, i] + E6 * k[5, i] + E7 * k[6, i]
        )
        sc = atol + rtol * max(abs(y[i]), abs(yn[i]))
        total += (e / sc) ** 2
    return np.sqrt(total / n2)


@kernel
def _dense_coefficients(work, y: np.ndarray, h: float) -> None:
    """Coefficients of the continuous extension over the step just computed."""
    k = work.stages
    d = work.dense
    yn = work.ynew
    for i in range(y.shape[0]):
        ydiff = yn[i] - y[i]
        bspl = h * k[0, i] - ydiff
        d[0, i] = y[i]
        d[1, i] = ydiff
        d[2, i] = bspl
        d[3, i] = ydiff - h * k[6, i] - bspl
        d[4, i] = h * (
            D1 * k[0, i] + D3 * k[2, i] + D4 * k[3, i] + D5 * k[4, i] + D6 * k[5, i] + D7 * k[6, i]
        )


@kernel
def _interpolate(work, theta: float, count: int, out: np.ndarray) -> None:
    """The first `count` state entries at fraction θ of the step into `out`."""
    d = work.dense
    t1 = 1.0 - theta
    for i in range(count):
        out[i] = d[0, i] + theta * (d[1, i] + t1 * (d[2, i] + theta * (d[3, i] + t1 * d[4, i])))


@kernel
def _gap_at(sys, work, g: int, theta: float) -> float:
    """δ of gap g on the dense output at fraction θ of the step (positions only)."""
    n = sys.n
    _interpolate(work, theta, 2 * n, work.ytmp)
    delta, _ = gap(sys, g, work.ytmp[:n], work.ytmp[n : 2 * n])
    return delta


@kernel
def _locate(sys, work, g: int, d0: float, d1: float) -> float:
    """Fraction θ ∈ (0, 1] of the step where gap g changes sign (Illinois method,
    Dowell & Jarratt, BIT 11, 1971), from end values d0 and d1 of opposite sign."""
    a, b = 0.0, 1.0
    fa, fb = d0, d1
    side = 0
    for _ in range(60):
        c = (a * fb - b * fa) / (fb - fa)
        fc = _gap_at(sys, work, g, c)
        if fc == 0.0 or b - a < 1e-13:
            return c
        if (fc > 0.0) == (fb > 0.0):
            b, fb = c, fc
            if side == -1:
                fa *= 0.5
            side = -1
        else:
            a, fa = c, fc
            if side == 1:
                fb *= 0.5
            side = 1
    # The crossing is bracketed by [a, b]: end the step just past it.
    return b


@kernel
def _first_event(sys, work, mem, y: np.ndarray) -> tuple[int, float]:
    """Earliest gap whose sign disagrees with its flag at the end of the step, and
    the fraction of the step where it crosses (0 when it already disagreed at the
    start). (-1, 1.0) when there is none."""
    n = sys.n
    yn = work.ynew
    best = -1
    best_theta = 1.0
    for g in range(work.gaps.shape[0]):
        d1, _ = gap(sys, g, yn[:n], yn[n : 2 * n])
        closed = mem[g, 0] > 0.0
        if (d1 > 0.0) == closed or d1 == 0.0:
            continue
        d0, _ = gap(sys, g, y[:n], y[n : 2 * n])
        if (d0 > 0.0) == closed and d0 != 0.0:
            theta = _locate(sys, work, g, d0, d1)
        else:
            theta = 0.0
        if best < 0 or theta < best_theta:
            best = g
            best_theta = theta
    return best, best_theta


@kernel
def _grazed(sys, work, mem) -> bool:
    """True if a stage of the step penetrated a gap that is apart at both ends of
    the step: a contact the sign test at the step's ends cannot see."""
    n = sys.n
    yn = work.ynew
    for g in range(mem.shape[0]):
        if mem[g, 2] > 0.0 and mem[g, 0] == 0.0:
            d1, _ = gap(sys, g, yn[:n], yn[n : 2 * n])
            if d1 <= 0.0:
                return True
    return False


@kernel
def _flip(sys, mem, g: int, y: np.ndarray) -> None:
    """Toggle the contact flag of gap g at state y; at an onset, remember δ̇⁻.
    A switch between the slider's corner and face laws books its energy jump
    with the dissipated energy (y's last entry)."""
    n = sys.n
    q = y[:n]
    qd = y[n : 2 * n]
    jump = face_switch_energy(sys, mem, g, q, qd)
    if mem[g, 0] > 0.0:
        mem[g, 0] = 0.0
        mem[g, 1] = 0.0
        y[2 * n + 1] += jump
    else:
        _, rate = gap(sys, g, q, qd)
        mem[g, 0] = 1.0
        mem[g, 1] = rate
        y[2 * n + 1] -= jump


@kernel
def _flip_and_refresh(sys, work, mem, g: int, t: float, y: np.ndarray, stats) -> int:
    """Apply the event of gap g at (t, y) and re-evaluate the first stage, which
    the changed contact state invalidates."""
    _flip(sys, mem, g, y)
    stats[S_EVENTS] += 1
    stats[S_NFEV] += 1
    return rhs(sys, work, mem, t, y, work.stages[0])


@kernel
def _update_peaks(sys, work, peaks: np.ndarray) -> None:
    """Peaks (max |·|) of reference-point accelerations, drive torque and normal
    forces from the last right-hand side evaluation."""
    nb = sys.ref_idx.shape[0]
    for b in range(nb):
        for a in range(2):
            v = abs(reference_point(sys, b, work.qdd, a))
            if v > peaks[2 * b + a]:
                peaks[2 * b + a] = v
    v = abs(work.scalars[SC_DRIVE_TORQUE])
    if v > peaks[2 * nb]:
        peaks[2 * nb] = v
    for j in range(work.jout.shape[0]):
        v = work.jout[j, OUT_NORMAL_FORCE]
        if v > peaks[2 * nb + 1 + j]:
            peaks[2 * nb + 1 + j] = v


@kernel
def _check_state(sys, work, opts, pen_bound, stats) -> int:
    """Sanity of the last evaluation: penetration and constraint violation bounds."""
    for j in range(work.jout.shape[0]):
        if work.jout[j, OUT_PENETRATION] > pen_bound[j]:
            stats[S_CULPRIT] = j
            return PENETRATION
    viol = 0.0
    for i in range(sys.m):
        viol += work.phi[i] * work.phi[i]
    if np.sqrt(viol) > opts[OPT_VIOLATION_BOUND]:
        return VIOLATION
    return OK


@kernel
def _sample(sys, work, mem, t0, h, times, rows, stats, slot, scratch) -> int:
    """Record every requested time in (t0, t0 + h] from the dense output."""
    n2 = 2 * sys.n
    ny = n2 + 2
    # Round-off in t0 + h must not drop a sample that falls on the step's end.
    t1 = t0 + h + 1e-12 * max(1.0, abs(t0))
    while stats[slot] < times.shape[0] and times[stats[slot]] <= t1:
        i = stats[slot]
        theta = min((times[i] - t0) / h, 1.0)
        _interpolate(work, theta, ny, scratch)
        s = record_row(sys, work, mem, times[i], scratch, rows[i])
        if s != OK:
            return s
        stats[slot] += 1
    return OK


@kernel
def integrate(
    sys,
    work,
    mem: np.ndarray,
    y: np.ndarray,
    st: np.ndarray,
    t_end: float,
    opts: np.ndarray,
    out_t: np.ndarray,
    out_rows: np.ndarray,
    sec_t: np.ndarray,
    sec_rows: np.ndarray,
    peaks: np.ndarray,
    pen_bound: np.ndarray,
    stats: np.ndarray,
    diag: np.ndarray,
) -> int:
    """Advance y from st[ST_T] to t_end. Returns OK or a failure status, with the
    time in diag[D_TIME] and the responsible joint (if any) in stats[S_CULPRIT]."""
    n2 = 2 * sys.n
    ny = n2 + 2
    k = work.stages
    rtol = opts[OPT_RTOL]
    atol = opts[OPT_ATOL]
    hmax = opts[OPT_HMAX]
    hmin = opts[OPT_HMIN]
    t = st[ST_T]
    h = st[ST_H]
    facold = st[ST_FACOLD]
    if st[ST_FSAL] == 0.0:
        s = rhs(sys, work, mem, t, y, k[0])
        stats[S_NFEV] += 1
        if s != OK:
            diag[D_TIME] = t
            return s
        st[ST_FSAL] = 1.0
    forced = 0.0  # > 0: the next step must end exactly at a located event
    pending = -1  # the gap to flip at the end of the forced step
    flips_at_t = 0
    while t_end - t > 1e-12 * max(1.0, abs(t)):
        if stats[S_ACCEPTED] + stats[S_REJECTED] >= opts[OPT_MAX_STEPS]:
            diag[D_TIME] = t
            return MAX_STEPS
        if forced > 0.0:
            hs = forced
        else:
            hs = min(h, hmax)
            if t + 1.01 * hs >= t_end:
                hs = t_end - t
        mem[:, 2] = 0.0
        s = _stages(sys, work, mem, t, hs, y)
        stats[S_NFEV] += 6
        err = _error_norm(work, y, hs, n2, rtol, atol) if s == OK else np.inf
        if err <= 1.0 and forced == 0.0 and hs > 4.0 * hmin and _grazed(sys, work, mem):
            err = np.inf  # resolve the graze with shorter steps
        if not err <= 1.0:
            stats[S_REJECTED] += 1
            forced = 0.0
            pending = -1
            if np.isfinite(err):
                h = hs / min(1.0 / FAC_MIN, err**EXPO1 / SAFE)
            else:
                h = hs * FAC_MIN
            if h < hmin:
                diag[D_TIME] = t
                diag[D_VALUE] = h
                return STEP_COLLAPSE if s == OK else s
            continue
        _dense_coefficients(work, y, hs)
        if forced == 0.0 and flips_at_t <= 2 * work.gaps.shape[0]:
            g, theta = _first_event(sys, work, mem, y)
            if g >= 0:
                if theta * hs <= hmin:
                    # Already across at the start of the step (a previous event
                    # ended a hair's breadth on the other side): flip now.
                    flips_at_t += 1
                    s = _flip_and_refresh(sys, work, mem, g, t, y, stats)
                    if s != OK:
                        diag[D_TIME] = t
                        return s
                    continue
                forced = theta * hs
                pending = g
                continue
        # The step is accepted; work holds the evaluation at its end (stage 7).
        _update_peaks(sys, work, peaks)
        s = _check_state(sys, work, opts, pen_bound, stats)
        if s != OK:
            diag[D_TIME] = t + hs
            return s
        s = _sample(sys, work, mem, t, hs, out_t, out_rows, stats, S_OUT, work.yint)
        if s == OK:
            s = _sample(sys, work, mem, t, hs, sec_t, sec_rows, stats, S_SEC, work.yint)
        if s != OK:
            diag[D_TIME] = t
            return s
        t += hs
        stats[S_ACCEPTED] += 1
        for i in range(ny):
            y[i] = work.ynew[i]
            k[0, i] = k[6, i]
        for i in range(ny):
            if not np.isfinite(y[i]):
                diag[D_TIME] = t
                return NONFINITE
        if pending >= 0:
            s = _flip_and_refresh(sys, work, mem, pending, t, y, stats)
            if s != OK:
                diag[D_TIME] = t
                return s
            # Resume with the step size that found the event, not the short
            # step that ended on it.
            forced = 0.0
            pending = -1
            flips_at_t = 0
            continue
        flips_at_t = 0
        fac = err**EXPO1 / facold**BETA
        fac = max(1.0 / FAC_MAX, min(1.0 / FAC_MIN, fac / SAFE))
        h = hs / fac
        facold = max(err, 1e-4)
    st[ST_T] = t
    st[ST_H] = h
    st[ST_FACOLD] = facold
    return OK

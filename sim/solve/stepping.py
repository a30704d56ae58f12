"""The integration loop shared by every method: step control, contact events,
exact sampling, peaks and sanity checks.

A method supplies one step: from (t, y) and a step size h it computes the new
state (work.ynew), the state derivative at the step's end (work.stages[6]) and
the coefficients of a continuous extension over the step (work.dense), and
returns an error estimate scaled so that 1 is the tolerance. The loop does
the rest, identically for the explicit and the implicit method:

- contact events: after a step passes the error test, every gap whose sign
  disagrees with its in-contact flag is located on the continuous extension by
  the Illinois method; the step is redone to end exactly at the earliest
  crossing, where the flag flips and the onset rate δ̇⁻ is captured (the memory
  the Lankarani–Nikravesh law needs);
- output samples and Poincaré sections at exact times from the continuous
  extension; peaks over every accepted step's end, for the whole run and for
  each revolution (the rows of `rev_peaks`, one per Poincaré section), and the
  contact events of each revolution (`rev_events`);
- a penetration or constraint drift beyond a sane bound stops the run with the
  time and the joint.

The caller advances the integration in chunks (`integrate` returns at t_end);
all state between chunks lives in the arrays it passes.
"""

import numpy as np

from sim.jit import kernel
from sim.model.clearance import face_switch_energy, gap
from sim.model.system import OUT_NORMAL_FORCE, OUT_PENETRATION
from sim.solve import dopri, galpha
from sim.solve.dae import NONFINITE, OK, SC_DRIVE_TORQUE, rhs
from sim.solve.dense import interpolate
from sim.solve.record import record_row, reference_point, write_row

# Integration methods (solver.method).
METHOD_DOPRI5, METHOD_GENERALIZED_ALPHA = 0, 1
METHODS = {"dopri5": METHOD_DOPRI5, "generalized_alpha": METHOD_GENERALIZED_ALPHA}

# Integrator status codes beyond the right-hand side's OK / SINGULAR / NONFINITE.
MAX_STEPS, STEP_COLLAPSE, PENETRATION, VIOLATION = 3, 4, 5, 6
GRAZE_PROBES = (0.25, 0.5, 0.75)  # fractions of a generalized-α step probed for a graze

# Indices into the integrator state `st`.
ST_T, ST_H, ST_FACOLD, ST_FSAL = range(4)
N_ST = 4
# Indices into `opts`.
(
    OPT_RTOL,
    OPT_ATOL,
    OPT_HMAX,
    OPT_HMIN,
    OPT_VIOLATION_BOUND,
    OPT_MAX_STEPS,
    OPT_METHOD,
    OPT_RHO_INF,
) = range(8)
N_OPTS = 8
# Indices into `stats` (counters) and `diag` (failure details).
(
    S_ACCEPTED,
    S_REJECTED,
    S_NFEV,
    S_EVENTS,
    S_CULPRIT,
    S_OUT,
    S_SEC,
    S_JACOBIANS,
    S_NEWTON_FAILURES,
) = range(9)
N_STATS = 9
D_TIME, D_VALUE = range(2)

# Step-size bounds per step: at most this much smaller or larger.
FAC_MIN, FAC_MAX = 0.2, 10.0


@kernel
def _gap_at(sys, work, g: int, theta: float) -> float:
    """δ of gap g on the continuous extension at fraction θ of the step."""
    n = sys.n
    interpolate(work, theta, 2 * n, work.ytmp)
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
def _grazed(sys, work, mem, method: int) -> bool:
    """True if the motion inside the step penetrated a gap that is apart at both
    ends of the step: a contact the sign test at the step's ends cannot see.
    DOPRI5: a stage evaluation penetrated it (marked in mem[g, 2]). Generalized-α:
    its Newton iterates are not points of the motion (an iterate that overshoots
    into a wall says nothing about the motion), so the step's continuous
    extension is probed at GRAZE_PROBES instead."""
    n = sys.n
    yn = work.ynew
    if method == METHOD_GENERALIZED_ALPHA:
        for g in range(mem.shape[0]):
            mem[g, 2] = 0.0
        for theta in GRAZE_PROBES:
            interpolate(work, theta, 2 * n, work.yint)
            for g in range(mem.shape[0]):
                if mem[g, 0] == 0.0 and gap(sys, g, work.yint[:n], work.yint[n : 2 * n])[0] > 0.0:
                    mem[g, 2] = 1.0
    for g in range(mem.shape[0]):
        if mem[g, 2] > 0.0 and mem[g, 0] == 0.0:
            if gap(sys, g, yn[:n], yn[n : 2 * n])[0] <= 0.0:
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
def _flip_and_refresh(sys, work, mem, g: int, t: float, y: np.ndarray, stats, rev_events) -> int:
    """Apply the event of gap g at (t, y) and re-evaluate the derivative at the
    step's start, which the changed contact state invalidates. The event is booked to
    the revolution after the last recorded section (sections at t are recorded first)."""
    _flip(sys, mem, g, y)
    stats[S_EVENTS] += 1
    rev_events[min(stats[S_SEC], rev_events.shape[0] - 1)] += 1
    stats[S_NFEV] += 1
    return rhs(sys, work, mem, t, y, work.stages[0])


@kernel
def _update_peaks(sys, work, peaks: np.ndarray) -> None:
    """Peaks (max |·|) of reference-point accelerations, drive torque and normal
    forces from the evaluation at the end of the accepted step."""
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
def _revolution_row(t_step_end: float, sec_t, stats, rows: int) -> int:
    """Row of `rev_peaks` for an accepted step that ends at t_step_end, called before the
    step's sections are recorded: row r holds revolution r, the steps ending in
    (sec_t[r - 1], sec_t[r]]; the last row (r = sec_t.size) what follows the last section.
    A DOPRI5 step that straddles a section is booked to the revolution it ends in."""
    r = stats[S_SEC]
    if r < sec_t.shape[0] and sec_t[r] < t_step_end - 1e-12 * max(1.0, abs(t_step_end)):
        r += 1
    return min(r, rows - 1)


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
def _sample(sys, work, mem, method, t0, h, times, rows, stats, slot, scratch) -> int:
    """Record every requested time in (t0, t0 + h]. DOPRI5: from its continuous
    extension, evaluated afresh. Generalized-α ends a step at every requested
    time (`_next_sample`) and records the step's own state, accelerations and
    multipliers: accelerations evaluated afresh at an interpolated state would
    carry its interpolation error times the beams' axial stiffness."""
    ny = 2 * sys.n + 2
    # Round-off in t0 + h must not drop a sample that falls on the step's end.
    t1 = t0 + h + 1e-12 * max(1.0, abs(t0))
    while stats[slot] < times.shape[0] and times[stats[slot]] <= t1:
        i = stats[slot]
        if method == METHOD_GENERALIZED_ALPHA:
            write_row(sys, work, work.ynew, rows[i])
        else:
            theta = min((times[i] - t0) / h, 1.0)
            interpolate(work, theta, ny, scratch)
            s = record_row(sys, work, mem, times[i], scratch, rows[i])
            if s != OK:
                return s
        stats[slot] += 1
    return OK


@kernel
def _next_sample(t: float, out_t, sec_t, stats) -> float:
    """The earliest output or section time after t (∞ when none is left)."""
    nxt = np.inf
    if stats[S_OUT] < out_t.shape[0]:
        nxt = out_t[stats[S_OUT]]
    if stats[S_SEC] < sec_t.shape[0]:
        nxt = min(nxt, sec_t[stats[S_SEC]])
    return nxt if nxt > t else np.inf


@kernel
def _step(sys, work, mem, method: int, t: float, h: float, y: np.ndarray, opts, stats):
    """One step of the chosen method: (status, error estimate scaled to the tolerance)."""
    rtol = opts[OPT_RTOL]
    atol = opts[OPT_ATOL]
    if method == METHOD_DOPRI5:
        stats[S_NFEV] += 6
        return dopri.step(sys, work, mem, t, h, y, rtol, atol)
    s, err, evaluations, jacobians = galpha.step(
        sys, work, mem, t, h, y, rtol, atol, opts[OPT_RHO_INF]
    )
    stats[S_NFEV] += evaluations
    stats[S_JACOBIANS] += jacobians
    if s == OK and not np.isfinite(err):
        stats[S_NEWTON_FAILURES] += 1
    return s, err


@kernel
def _grown_step(method: int, hs: float, err: float, facold: float) -> float:
    """The next step size after an accepted step of size hs with error err."""
    if method == METHOD_DOPRI5:
        fac = dopri.step_factor(err, facold)
    else:
        fac = galpha.step_factor(err)
    return hs * max(FAC_MIN, min(FAC_MAX, fac))


@kernel
def _shrunk_step(method: int, hs: float, err: float) -> float:
    """The retry step size after a rejected step (err > 1, or ∞ when the step
    itself failed: a stage non-finite or Newton not converging)."""
    if not np.isfinite(err):
        return hs * FAC_MIN
    if method == METHOD_DOPRI5:
        fac = dopri.step_factor(err, 1.0)
    else:
        fac = galpha.step_factor(err)
    return hs * max(FAC_MIN, min(1.0, fac))


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
    rev_peaks: np.ndarray,
    rev_events: np.ndarray,
    pen_bound: np.ndarray,
    stats: np.ndarray,
    diag: np.ndarray,
) -> int:
    """Advance y from st[ST_T] to t_end. Returns OK or a failure status, with the
    time in diag[D_TIME] and the responsible joint (if any) in stats[S_CULPRIT].
    rev_peaks (sec_t.size + 1, peaks.size) and rev_events (sec_t.size + 1) take the same
    peaks and the contact events per revolution (`_revolution_row`)."""
    ny = 2 * sys.n + 2
    k = work.stages
    method = int(opts[OPT_METHOD])
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
        if method == METHOD_GENERALIZED_ALPHA:
            galpha.start(sys, work)
        st[ST_FSAL] = 1.0
    wanted = h
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
            wanted = hs
            if method == METHOD_GENERALIZED_ALPHA:
                # Equal steps to the next sample or t_end, none longer than h.
                left = min(t_end, _next_sample(t, out_t, sec_t, stats)) - t
                hs = left / np.ceil(left / hs * (1.0 - 1e-9))
            elif t + 1.01 * hs >= t_end:
                hs = t_end - t
        mem[:, 2] = 0.0
        s, err = _step(sys, work, mem, method, t, hs, y, opts, stats)
        if s != OK:
            err = np.inf
        if err <= 1.0 and forced == 0.0 and hs > 4.0 * hmin and _grazed(sys, work, mem, method):
            err = np.inf  # resolve the graze with shorter steps
        if not err <= 1.0:
            stats[S_REJECTED] += 1
            forced = 0.0
            pending = -1
            h = _shrunk_step(method, hs, err)
            if h < hmin:
                diag[D_TIME] = t
                diag[D_VALUE] = h
                return STEP_COLLAPSE if s == OK else s
            continue
        if forced == 0.0 and flips_at_t <= 2 * work.gaps.shape[0]:
            g, theta = _first_event(sys, work, mem, y)
            if g >= 0:
                if theta * hs <= hmin:
                    # Already across at the start of the step (a previous event
                    # ended a hair's breadth on the other side): flip now.
                    flips_at_t += 1
                    s = _flip_and_refresh(sys, work, mem, g, t, y, stats, rev_events)
                    if s != OK:
                        diag[D_TIME] = t
                        return s
                    continue
                forced = theta * hs
                pending = g
                continue
        # The step is accepted; work holds the evaluation at its end.
        _update_peaks(sys, work, peaks)
        row = _revolution_row(t + hs, sec_t, stats, rev_peaks.shape[0])
        _update_peaks(sys, work, rev_peaks[row])
        s = _check_state(sys, work, opts, pen_bound, stats)
        if s != OK:
            diag[D_TIME] = t + hs
            return s
        if method == METHOD_GENERALIZED_ALPHA:
            galpha.accept(work)
        s = _sample(sys, work, mem, method, t, hs, out_t, out_rows, stats, S_OUT, work.yint)
        if s == OK:
            s = _sample(sys, work, mem, method, t, hs, sec_t, sec_rows, stats, S_SEC, work.yint)
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
            s = _flip_and_refresh(sys, work, mem, pending, t, y, stats, rev_events)
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
        grown = _grown_step(method, hs, err, facold)
        # A step cut short to land on t_end or a sample says nothing against
        # the step size that was wanted.
        h = max(grown, h) if hs < wanted else grown
        facold = max(err, 1e-4)
    st[ST_T] = t
    st[ST_H] = h
    st[ST_FACOLD] = facold
    return OK

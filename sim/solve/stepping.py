"""The integration loop shared by every method: step control, contact events,
exact sampling, peaks and sanity checks.

A method (`sim.solve.methods`) supplies one step: from (t, y) and a step size h
it computes the new state (work.ynew), the state derivative at the step's end
(work.ydot_end) and the coefficients of a continuous extension over the step
(work.dense), and returns an error estimate scaled so that 1 is the tolerance.
The loop does the rest, identically for the explicit and the implicit method:

- contact events: after a step passes the error test, every gap whose sign
  disagrees with its in-contact flag is located on the continuous extension by
  the Illinois method; the step is redone to end exactly at the earliest
  crossing, where the flag flips and the onset rate δ̇⁻ is captured (the memory
  the Lankarani–Nikravesh law needs);
- output samples and Poincaré sections at exact times from the continuous
  extension, the fast quantities' interval means over the steps (`sim.solve.means`);
  peaks over every accepted step's end and every output sample, for the whole run and
  for each revolution (the rows of `rev_peaks`, one per Poincaré section), and the
  contact events of each revolution (`rev_events`) and the onsets of each gap (`gap_onsets`);
- a penetration or constraint drift beyond a sane bound stops the run with the
  time and the joint.

The caller advances the integration in chunks (`integrate` returns at t_end);
all state between chunks lives in the structures it passes (`sim.solve.state`).
"""

from typing import NamedTuple

import numpy as np

from sim.jit import entry, spliced
from sim.model.clearance import face_switch_energy, gap, gap_depths
from sim.model.gaps import MEM_GRAZED, MEM_IN_CONTACT, MEM_ONSET_RATE
from sim.model.system import OUT_PENETRATION
from sim.solve import methods
from sim.solve.control import ERR_OLD_MIN, T_ROUNDOFF
from sim.solve.dae import project_onto_tree, rhs
from sim.solve.dense import interpolate
from sim.solve.means import close_windows, start_windows
from sim.solve.record import record_row, write_fast_values
from sim.solve.status import MAX_STEPS, NONFINITE, OK, PENETRATION, STEP_COLLAPSE, VIOLATION

LOCATE_ITERATIONS = 60
"""Illinois iterations locating a crossing before the bracket's end is taken: a bound only
(the method converges superlinearly, to LOCATE_TOL in far fewer)."""
LOCATE_TOL = 1e-13
"""Width of the bracket (a fraction of the step) at which a crossing counts as located: a
few hundred round-offs of θ ≤ 1, below which the bracket cannot shrink reliably."""
GRAZE_MIN_STEPS = 4.0
"""A graze is resolved by shorter steps only while the step exceeds this many hmin: shorter
ones would end the run in STEP_COLLAPSE for a contact too brief to matter."""
FLIPS_PER_GAP = 2
"""Flips at one instant per gap after which events are not looked for again at that instant:
a gap a hair's breadth from its wall would otherwise flip for ever."""
NO_GAP = np.int64(-1)
"""No gap to flip. A numpy integer, not -1: numba would type a variable assigned the literal
-1 as Literal[int](-1) and compile the kernels it is passed to a second time for it."""


@spliced
def _gap_at(sys, work, g: int, theta: float) -> float:
    """δ of gap g on the continuous extension at fraction θ of the step."""
    n = sys.n
    interpolate(work, theta, 2 * n, work.ytmp)
    delta, _ = gap(sys, g, work.ytmp[:n], work.ytmp[n : 2 * n])
    return delta


@spliced
def _locate(sys, work, g: int, d0: float, d1: float) -> float:
    """Fraction θ ∈ (0, 1] of the step where gap g changes sign (Illinois method,
    Dowell & Jarratt, BIT 11, 1971), from end values d0 and d1 of opposite sign."""
    a, b = 0.0, 1.0
    fa, fb = d0, d1
    side = 0
    for _ in range(LOCATE_ITERATIONS):
        c = (a * fb - b * fa) / (fb - fa)
        fc = _gap_at(sys, work, g, c)
        if fc == 0.0 or b - a < LOCATE_TOL:
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


@spliced
def _first_event(sys, work, mem, y: np.ndarray) -> tuple[int, float]:
    """Earliest gap whose sign disagrees with its flag at the end of the step, and
    the fraction of the step where it crosses (0 when it already disagreed at the
    start). (-1, 1.0) when there is none."""
    n = sys.n
    best = -1
    best_theta = 1.0
    gap_depths(sys, work.ynew[:n], work.gaps)
    for g in range(work.gaps.shape[0]):
        d1 = work.gaps[g]
        closed = mem[g, MEM_IN_CONTACT] > 0.0
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


@spliced
def _grazed(sys, work, mem, options) -> bool:
    """True if the motion inside the step penetrated a gap that is apart at both
    ends of the step: a contact the sign test at the step's ends cannot see. The
    method marks the gaps its step passed through (`mark_grazes`)."""
    n = sys.n
    yn = work.ynew
    methods.mark_grazes(sys, work, mem, options)
    for g in range(mem.shape[0]):
        if mem[g, MEM_GRAZED] > 0.0 and mem[g, MEM_IN_CONTACT] == 0.0:
            if gap(sys, g, yn[:n], yn[n : 2 * n])[0] <= 0.0:
                return True
    return False


@spliced
def _flip(sys, mem, g: int, y: np.ndarray) -> None:
    """Toggle the contact flag of gap g at state y; at an onset, remember δ̇⁻.
    A switch between the slider's corner and face laws books its energy jump
    with the dissipated energy (y's last entry)."""
    n = sys.n
    q = y[:n]
    qd = y[n : 2 * n]
    jump = face_switch_energy(sys, mem, g, q, qd)
    if mem[g, MEM_IN_CONTACT] > 0.0:
        mem[g, MEM_IN_CONTACT] = 0.0
        mem[g, MEM_ONSET_RATE] = 0.0
        y[2 * n + 1] += jump
    else:
        _, rate = gap(sys, g, q, qd)
        mem[g, MEM_IN_CONTACT] = 1.0
        mem[g, MEM_ONSET_RATE] = rate
        y[2 * n + 1] -= jump


@spliced
def _flip_and_refresh(sys, work, carry, mem, g: int, t: float, y: np.ndarray, buffers, tally):
    """Apply the event of gap g at (t, y) and re-evaluate the derivative at the
    step's start, which the changed contact state invalidates. The event is booked to
    the revolution after the last recorded section (sections at t are recorded first), an
    onset also to its gap."""
    _flip(sys, mem, g, y)
    tally.events += 1
    rev_events = buffers.rev_events
    rev_events[min(tally.sections, rev_events.shape[0] - 1)] += 1
    if mem[g, MEM_IN_CONTACT] > 0.0:
        buffers.gap_onsets[g] += 1
    tally.evaluations += 1
    return rhs(sys, work, mem, t, y, carry.derivative)


class EventCheck(NamedTuple):
    """What the loop does about contact events after a step passed its error test
    (:func:`event_in_step`).

    Attributes:
        status: OK, or the failure status of a flip's re-evaluation at the step's start.
        retake: the step does not stand: the next one starts from the same t.
        forced: the retaken step's length (s), ending on the event; 0 after a flip at t.
        pending: the gap to flip at the end of the forced step (NO_GAP after a flip at t).
        flips_at_t: flips made at the step's start time so far.
    """

    status: int
    retake: bool
    forced: float
    pending: np.int64
    flips_at_t: int


@spliced
def event_in_step(sys, work, carry, mem, t, hs, y, forced, flips_at_t, hmin, buffers, tally):
    """The first contact event inside the step from (t, y) of length hs (s) that passed its
    error test, work holding its end (:class:`EventCheck`). None is looked for in a forced
    step (it ends on its event) nor after FLIPS_PER_GAP flips per gap at t. A gap already
    across at t (a previous event ended a hair's breadth on the other side) flips now and the
    step is retaken; one that crosses inside the step makes the retaken step end on its
    crossing. Inlined: it runs after every accepted step of both loops."""
    if forced > 0.0 or flips_at_t > FLIPS_PER_GAP * work.gaps.shape[0]:
        return EventCheck(OK, False, forced, NO_GAP, flips_at_t)
    g, theta = _first_event(sys, work, mem, y)
    if g < 0:
        return EventCheck(OK, False, forced, NO_GAP, flips_at_t)
    if theta * hs > hmin:
        return EventCheck(OK, True, theta * hs, np.int64(g), flips_at_t)
    s = _flip_and_refresh(sys, work, carry, mem, g, t, y, buffers, tally)
    return EventCheck(s, True, 0.0, NO_GAP, flips_at_t + 1)


@spliced
def _raise(row: np.ndarray, first: int, count: int, peaks: np.ndarray, slot: int) -> None:
    """peaks[slot : slot + count] raised to |row[first : first + count]|."""
    for k in range(count):
        v = abs(row[first + k])
        if v > peaks[slot + k]:
            peaks[slot + k] = v


@spliced
def update_peaks(row: np.ndarray, cols, slots, nb: int, nj: int, peaks: np.ndarray) -> None:
    """Raise the peaks (max |·|, in their `sim.solve.record.PeakSlots` slots) to the point
    values of a row (blocks at its `RowColumns` cols) of nb bodies and nj clearance joints:
    reference-point and output-point accelerations, angular velocities and accelerations,
    drive torque and contact normal forces."""
    _raise(row, cols.acceleration, 2 * nb, peaks, slots.acceleration)
    _raise(row, cols.output_acceleration, 2, peaks, slots.output_acceleration)
    _raise(row, cols.angular_velocity, nb, peaks, slots.angular_velocity)
    _raise(row, cols.angular_acceleration, nb, peaks, slots.angular_acceleration)
    _raise(row, cols.drive_torque, 1, peaks, slots.drive_torque)
    _raise(row, cols.normal_force, nj, peaks, slots.normal_force)


@spliced
def _update_peaks(sys, row: np.ndarray, t: float, buffers, tally) -> None:
    """The run's peaks and those of the revolution holding time t raised to the point values
    of a row taken at t (an accepted step's end, or an output sample)."""
    nb = sys.ref_idx.shape[0]
    nj = sys.rj_pts.shape[0] + sys.tj_off.shape[0]
    cols = buffers.means.columns
    slots = buffers.peak_slots
    update_peaks(row, cols, slots, nb, nj, buffers.peaks)
    r = _revolution_row(t, buffers.sec_t, tally, buffers.rev_peaks.shape[0])
    update_peaks(row, cols, slots, nb, nj, buffers.rev_peaks[r])


@spliced
def _revolution_row(t_step_end: float, sec_t, tally, rows: int) -> int:
    """Row of `rev_peaks` for an accepted step that ends at t_step_end, called before the
    step's sections are recorded: row r holds revolution r, the steps ending in
    (sec_t[r - 1], sec_t[r]]; the last row (r = sec_t.size) what follows the last section.
    A DOPRI5 step that straddles a section is booked to the revolution it ends in."""
    r = tally.sections
    if r < sec_t.shape[0] and sec_t[r] < t_step_end - T_ROUNDOFF * max(1.0, abs(t_step_end)):
        r += 1
    return min(r, rows - 1)


@spliced
def _check_state(sys, work, options, tally) -> int:
    """Sanity of the last evaluation: penetration and constraint violation bounds (a tree
    mechanism's constraints hold by construction: it has no residual to check)."""
    for j in range(work.jout.shape[0]):
        if work.jout[j, OUT_PENETRATION] > options.pen_bound[j]:
            tally.culprit = j
            return PENETRATION
    if sys.tree.shape[0] > 0:
        return OK
    viol = 0.0
    for i in range(sys.m):
        viol += work.phi[i] * work.phi[i]
    if np.sqrt(viol) > options.violation_bound:
        return VIOLATION
    return OK


@spliced
def _sample(sys, work, mem, t0, h, buffers, tally, options) -> int:
    """Record every output sample, then every section, requested in (t0, t0 + h], as
    the method records them (`sample`): point values, which the peaks take; the interval
    means replace the fast quantities' later (`sim.solve.means.close_windows`)."""
    # Round-off in t0 + h must not drop a sample that falls on the step's end.
    t1 = t0 + h + T_ROUNDOFF * max(1.0, abs(t0))
    while tally.outputs < buffers.out_t.shape[0] and buffers.out_t[tally.outputs] <= t1:
        i = tally.outputs
        s = methods.sample(sys, work, mem, t0, h, buffers.out_t[i], buffers.out_rows[i], options)
        if s != OK:
            return s
        _update_peaks(sys, buffers.out_rows[i], buffers.out_t[i], buffers, tally)
        tally.outputs += 1
    while tally.sections < buffers.sec_t.shape[0] and buffers.sec_t[tally.sections] <= t1:
        i = tally.sections
        s = methods.sample(sys, work, mem, t0, h, buffers.sec_t[i], buffers.sec_rows[i], options)
        if s != OK:
            return s
        tally.sections += 1
    return OK


@spliced
def _record_start(sys, work, mem, t: float, y: np.ndarray, buffers, tally) -> int:
    """Record the run's first sample and section, at its start time t, unless recorded: point
    values, which start the interval means' first window and the peaks. Returns the
    evaluation's status."""
    if tally.outputs > 0:
        return OK
    row = buffers.out_rows[0]
    s = record_row(sys, work, mem, t, y, row)
    for c in range(row.shape[0]):
        buffers.sec_rows[0, c] = row[c]
    start_windows(sys, work, buffers.means, y, row)
    cols = buffers.means.columns
    nb = sys.ref_idx.shape[0]
    nj = sys.rj_pts.shape[0] + sys.tj_off.shape[0]
    update_peaks(row, cols, buffers.peak_slots, nb, nj, buffers.peaks)
    update_peaks(row, cols, buffers.peak_slots, nb, nj, buffers.rev_peaks[0])
    tally.outputs = 1
    tally.sections = 1
    return s


@spliced
def _log_step(buffers, tally, t: float) -> None:
    """Log the end t of an accepted step for a lockstep follower (`sim.solve.lockstep`), when
    the run keeps a log; the count goes on past the log's size, so an overflow shows."""
    if buffers.step_ends.shape[0] > 0:
        if tally.logged < buffers.step_ends.shape[0]:
            buffers.step_ends[tally.logged] = t
        tally.logged += 1


@spliced
def _fail(tally, status: int, t: float) -> int:
    """Book a failure at time t; returns its status."""
    tally.failure_time = t
    return status


@spliced
def start_trajectory(sys, work, carry, trajectory, options, tally) -> int:
    """Evaluate the step data carried from (t, y) when the trajectory has none (a fresh or a
    restored one: `clock.started` false): the derivative, the method's start data. Returns
    the right-hand side's status."""
    clock = trajectory.clock[0]
    if clock.started:
        return OK
    y = trajectory.y
    # a restored state may lie off a tree mechanism's manifold (a Lyapunov perturbation):
    # its gaps must be those its forces see
    project_onto_tree(sys, work, clock.t, y)
    s = rhs(sys, work, trajectory.mem, clock.t, y, carry.derivative)
    tally.evaluations += 1
    if s != OK:
        return s
    methods.start(sys, work, carry, options)
    clock.started = True
    return OK


@spliced
def take_step(sys, work, carry, y: np.ndarray) -> bool:
    """Move the trajectory's state y and carried derivative to the accepted step's end
    (work.ynew, work.ydot_end); False when the new state is not finite."""
    ny = 2 * sys.n + 2
    for i in range(ny):
        y[i] = work.ynew[i]
        carry.derivative[i] = work.ydot_end[i]
    for i in range(ny):
        if not np.isfinite(y[i]):
            return False
    return True


@entry
def integrate(sys, work, carry, trajectory, t_end: float, options, buffers, tallies) -> int:
    """Advance the trajectory (`sim.solve.state.Trajectory`) from its clock's t to t_end,
    recording into `buffers` and counting into tallies[0] (`sim.solve.state.TALLY`).
    Returns OK or a failure status (`sim.solve.status`), with the time in
    tally.failure_time and the responsible joint (if any) in tally.culprit.
    rev_peaks (sec_t.size + 1, peaks.size) and rev_events (sec_t.size + 1) take the same
    peaks and the contact events per revolution (`_revolution_row`)."""
    tally = tallies[0]
    clock = trajectory.clock[0]
    y = trajectory.y
    mem = trajectory.mem
    hmax = options.hmax
    hmin = options.hmin
    t = clock.t
    h = clock.h
    facold = clock.facold
    s = _record_start(sys, work, mem, t, y, buffers, tally)
    if s != OK:
        return _fail(tally, s, t)
    s = start_trajectory(sys, work, carry, trajectory, options, tally)
    if s != OK:
        return _fail(tally, s, t)
    wanted = h
    forced = 0.0  # > 0: the next step must end exactly at a located event
    pending = NO_GAP  # the gap to flip at the end of the forced step
    flips_at_t = 0
    while t_end - t > T_ROUNDOFF * max(1.0, abs(t)):
        if tally.accepted + tally.rejected >= options.max_steps:
            return _fail(tally, MAX_STEPS, t)
        if forced > 0.0:
            hs = forced
        else:
            hs = min(h, hmax)
            wanted = hs
            hs = methods.plan(t, hs, t_end, buffers, tally, options)
        mem[:, MEM_GRAZED] = 0.0
        s, err = methods.step(sys, work, carry, mem, t, hs, y, options, tally)
        if s != OK:
            err = np.inf
        long_enough = hs > GRAZE_MIN_STEPS * hmin
        if err <= 1.0 and forced == 0.0 and long_enough and _grazed(sys, work, mem, options):
            err = np.inf  # resolve the graze with shorter steps
        if not err <= 1.0:
            tally.rejected += 1
            forced = 0.0
            pending = NO_GAP
            h = methods.shrunk_step(hs, err, options)
            if h < hmin:
                tally.failure_step = h
                return _fail(tally, STEP_COLLAPSE if s == OK else s, t)
            continue
        check = event_in_step(
            sys, work, carry, mem, t, hs, y, forced, flips_at_t, hmin, buffers, tally
        )
        if check.status != OK:
            return _fail(tally, check.status, t)
        if check.retake:
            forced, pending, flips_at_t = check.forced, check.pending, check.flips_at_t
            continue
        # The step is accepted; work holds the evaluation at its end.
        means = buffers.means
        write_fast_values(sys, work, work.ynew, means.columns, means.end)
        _update_peaks(sys, means.end, t + hs, buffers, tally)
        s = _check_state(sys, work, options, tally)
        if s != OK:
            return _fail(tally, s, t + hs)
        methods.accept(sys, work, carry, options)
        s = _sample(sys, work, mem, t, hs, buffers, tally, options)
        if s != OK:
            return _fail(tally, s, t)
        close_windows(sys, work, means, buffers.out_t, buffers.out_rows, t, hs)
        t += hs
        tally.accepted += 1
        _log_step(buffers, tally, t)
        if not take_step(sys, work, carry, y):
            return _fail(tally, NONFINITE, t)
        if pending >= 0:
            s = _flip_and_refresh(sys, work, carry, mem, pending, t, y, buffers, tally)
            if s != OK:
                return _fail(tally, s, t)
            # Resume with the step size that found the event, not the short
            # step that ended on it.
            forced = 0.0
            pending = NO_GAP
            flips_at_t = 0
            continue
        flips_at_t = 0
        grown = methods.grown_step(hs, err, facold, options)
        # A step cut short to land on t_end or a sample says nothing against
        # the step size that was wanted.
        h = max(grown, h) if hs < wanted else grown
        facold = max(err, ERR_OLD_MIN)
    clock.t = t
    clock.h = h
    clock.facold = facold
    return OK

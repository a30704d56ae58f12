"""A trajectory advanced through another trajectory's accepted steps (lockstep).

The model's Lyapunov exponent (`sim.studies.model_lyapunov`) follows a reference trajectory
and a perturbed one. Integrated each with its own step control, they differ by their local
integration errors as well as by the dynamics: the two step sequences part at the first
accept/reject decision that goes differently, and from then on the separation carries noise of
the size of the tolerance, which the exponent reads as divergence. `follow` instead advances
the perturbed trajectory through the reference's own step ends (`Buffers.step_ends`, logged by
`sim.solve.stepping.integrate`), with the same method and no error control of its own, so the
two are two orbits of one discrete map and their separation is that map's derivative applied
to the perturbation: integration error never enters it.

Contact events stay the follower's own: a gap of the follower that changes sign inside a step
ends that step where it crosses (located on the continuous extension, as the loop does), its
flag flips there and the next step resumes towards the same logged end. The event times then
differ from the reference's by O(separation), and so do the steps that end on them. A step the
follower's method cannot take whole (a Newton failure of the implicit method), or whose error
estimate exceeds ``REFINE`` times the tolerance (the follower meets a contact the reference
does not), is halved until it can.

References:
    G. Benettin, L. Galgani, A. Giorgilli, J.-M. Strelcyn, Meccanica 15 (1980) 9–20 (the
    tangent map of the discrete flow).
    E. Hairer, G. Wanner, C. Lubich, "Geometric Numerical Integration", 2nd ed., Springer
    (2006), ch. VI (a one-step method as a map of the state; its derivative).
"""

import numpy as np

from sim.jit import entry
from sim.model.gaps import MEM_GRAZED
from sim.solve import methods
from sim.solve.control import T_ROUNDOFF
from sim.solve.status import NONFINITE, OK, STEP_COLLAPSE
from sim.solve.stepping import (
    NO_GAP,
    _check_state,
    _fail,
    _flip_and_refresh,
    event_in_step,
    start_trajectory,
    take_step,
)

#: the follower halves a logged step when its own error estimate exceeds this many times its
#: tolerance: never while it tracks the reference (their errors differ by O(separation)), but
#: where their motions part in kind, as when the follower's journal strikes and the
#: reference's does not, and a step chosen for free flight would carry it through an impact
REFINE = 10.0


@entry
def follow(sys, work, carry, trajectory, step_ends, n_steps: int, options, buffers, tallies):
    """Advance the trajectory (`sim.solve.state.Trajectory`) through the first n_steps step
    ends of `step_ends` (s, increasing, after its clock's t), splitting a step at each of its
    own contact events. Counts into tallies[0]; returns OK or a failure status as
    `sim.solve.stepping.integrate` does. `buffers` only takes the contact events per
    revolution (nothing is sampled)."""
    tally = tallies[0]
    clock = trajectory.clock[0]
    y = trajectory.y
    mem = trajectory.mem
    hmin = options.hmin
    t = clock.t
    s = start_trajectory(sys, work, carry, trajectory, options, tally)
    if s != OK:
        return _fail(tally, s, t)
    i = 0
    forced = 0.0  # > 0: the next step ends exactly at a located event of this trajectory
    pending = NO_GAP  # the gap to flip at the end of the forced step
    cap = np.inf  # the largest step the method managed since the last logged end
    flips_at_t = 0
    while i < n_steps:
        target = step_ends[i]
        if target - t <= T_ROUNDOFF * max(1.0, abs(t)):
            i += 1
            cap = np.inf
            continue
        hs = forced if forced > 0.0 else min(target - t, cap)
        mem[:, MEM_GRAZED] = 0.0
        s, err = methods.step(sys, work, carry, mem, t, hs, y, options, tally)
        if s != OK or not err <= REFINE:
            tally.rejected += 1
            forced = 0.0
            pending = NO_GAP
            cap = 0.5 * hs
            if cap < hmin:
                tally.failure_step = cap
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
        s = _check_state(sys, work, options, tally)
        if s != OK:
            return _fail(tally, s, t + hs)
        methods.accept(sys, work, carry, options)
        t += hs
        tally.accepted += 1
        if not take_step(sys, work, carry, y):
            return _fail(tally, NONFINITE, t)
        flips_at_t = 0
        if pending >= 0:
            s = _flip_and_refresh(sys, work, carry, mem, pending, t, y, buffers, tally)
            if s != OK:
                return _fail(tally, s, t)
            forced = 0.0
            pending = NO_GAP
    clock.t = t
    return OK

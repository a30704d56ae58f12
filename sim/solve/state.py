"""The named structures the integration loop (`sim.solve.stepping.integrate`) reads and writes.

- `Options`: the run's solver settings (immutable).
- `Trajectory`: what the future of a run depends on: the state y, the contact memory and the
  step controller's `CLOCK` record. A copy of it is a restart point (`sim.run.Snapshot`).
- the carry, each method's own (`sim.solve.dopri.Carry`, `sim.solve.galpha.Carry`, made by
  `sim.solve.methods.make_carry`): what one step hands to the next besides the trajectory
  and can be recomputed from it (the derivative at the step's start, the generalized-α start
  data) or kept as an economy (the Newton factors); `sim.solve.work.Work` is pure scratch.
- `Buffers`: the requested output times and the rows, sections and peaks recorded, and the
  log of accepted step ends a lockstep follower takes (`sim.solve.lockstep`).
- `TALLY`: counters of the run and the details of a failure.

Mutable scalars are numba structured records, one-element arrays (`record[0]` in compiled
code is a reference into the array, so the loop's writes reach the caller).
"""

from typing import NamedTuple

import numpy as np

from sim.jit import kernel

CLOCK = np.dtype(
    [
        ("t", np.float64),  # s, time reached
        ("h", np.float64),  # s, step size the controller proposes next
        # the previous accepted step's error: the step controller's memory, part of a restart
        # point; the method's step_factor reads it (DOPRI5's PI control does)
        ("facold", np.float64),
        ("started", np.bool_),  # Carry holds the start data of the step from (t, y)
    ]
)
TALLY = np.dtype(
    [
        ("accepted", np.int64),  # accepted steps
        ("rejected", np.int64),  # rejected steps
        ("evaluations", np.int64),  # right-hand side evaluations
        ("events", np.int64),  # contact events (flag flips)
        ("jacobians", np.int64),  # Newton iteration matrices formed
        ("newton_failures", np.int64),  # steps whose Newton iteration did not converge
        ("outputs", np.int64),  # output samples recorded
        ("sections", np.int64),  # Poincaré sections recorded
        ("culprit", np.int64),  # the joint of a PENETRATION failure
        ("failure_time", np.float64),  # s, time of a failure
        ("failure_step", np.float64),  # s, the step size of a STEP_COLLAPSE
        ("logged", np.int64),  # accepted steps logged in Buffers.step_ends (may exceed its size)
    ]
)


class Options(NamedTuple):
    """Solver settings of one run (sim.run.prepare fills them from the scene's `solver`)."""

    method: object  # sim.solve.methods.Dopri5 or GeneralizedAlpha: the method and its parameters
    rtol: float  # relative tolerance
    atol: float  # absolute tolerance (m, rad, m/s, rad/s)
    hmax: float  # s, largest step
    hmin: float  # s, smallest step before STEP_COLLAPSE
    violation_bound: float  # m, largest constraint residual before VIOLATION
    max_steps: int  # accepted + rejected steps before MAX_STEPS
    pen_bound: np.ndarray  # (joints,) m, largest penetration before PENETRATION


class Trajectory(NamedTuple):
    """The state of an integration: y = (q, q̇, W_drive, E_dissipated), the contact memory
    (gaps, MEM_COLUMNS: in-contact flag, onset rate δ̇⁻ in m/s, graze mark; named and
    allocated by `sim.model.gaps`) and the CLOCK record."""

    y: np.ndarray
    mem: np.ndarray
    clock: np.ndarray  # (1,) CLOCK


class Buffers(NamedTuple):
    """Output times and what the loop records (rows in sim.solve.record's layout)."""

    out_t: np.ndarray  # (samples,) s
    out_rows: np.ndarray  # (samples, width)
    sec_t: np.ndarray  # (sections,) s, one Poincaré section per crank revolution
    sec_rows: np.ndarray  # (sections, width)
    peaks: np.ndarray  # (peaks,) max |·| over the run (sim.solve.stepping._update_peaks)
    peak_slots: object  # sim.solve.record.PeakSlots: where each peak lies in `peaks`
    rev_peaks: np.ndarray  # (sections + 1, peaks) the same per revolution
    rev_events: np.ndarray  # (sections + 1,) contact events per revolution
    gap_onsets: np.ndarray  # (gaps,) located contact onsets of each gap since the start
    means: object  # sim.solve.means.Means: the out_rows' interval means in progress
    # (capacity,) s, the end of every accepted step since tally.logged was last zeroed, for a
    # trajectory that follows this one (sim.solve.lockstep); empty: nothing is logged
    step_ends: np.ndarray


@kernel
def next_sample(t: float, buffers, tally) -> float:
    """The earliest output or section time after t (∞ when none is left)."""
    nxt = np.inf
    if tally.outputs < buffers.out_t.shape[0]:
        nxt = buffers.out_t[tally.outputs]
    if tally.sections < buffers.sec_t.shape[0]:
        nxt = min(nxt, buffers.sec_t[tally.sections])
    return nxt if nxt > t else np.inf

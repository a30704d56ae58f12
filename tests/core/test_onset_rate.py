"""The onset rate δ̇⁻ every damping law with memory reads is the penetration rate at the
located onset δ = 0, in the reference trajectory and in a perturbed one that follows its steps
(sim.solve.lockstep, the model exponent's), not the rate at the end of the first step inside
the contact.

The crossing's rate is measured apart from the integrator's event location: the same
trajectory re-integrated from before the onset in pieces of 1/400 of the coarse interval,
(δ, δ̇) read after each piece, and δ̇ interpolated linearly to δ = 0 between the last piece
apart and the first in contact. Joint A of the rigid six-bar at 0.5 mm meets its bearing at
0.156 m/s; the located onset reads it within 1e-9 of itself, the perturbed trajectory's within
2e-8 of its own crossing, while the end of the first step inside (1.8 µs later) reads a rate
2e-4 of itself off: 20 times the tolerance (the test checks that it would miss).
"""

import numpy as np
import pytest

from sim.model.assembly import crank_period
from sim.model.clearance import gap
from sim.model.gaps import MEM_IN_CONTACT, MEM_ONSET_RATE
from sim.run import Integration, prepare
from sim.scene import load_scene

SCENE = [
    "joints.A.clearance=5e-4",
    "joints.B.clearance=5e-4",
    "solver.rtol=1e-9",
    "solver.atol=1e-12",
]
JOINT_A = 0  # gap 0: the first revolute clearance
#: the located onset against the crossing measured apart, relative: both integrate at rtol
#: 1e-9 (measured: 8e-10 on the reference, 1.5e-8 on the perturbed trajectory, whose two
#: integrations take different steps)
TOLERANCE = 1e-7


def rate(integ: Integration) -> tuple[float, float]:
    """(δ, δ̇) of joint A's gap at the integration's state."""
    n = integ.system.n
    return gap(integ.system, JOINT_A, integ.y[:n], integ.y[n : 2 * n])


def in_contact(integ: Integration) -> bool:
    return integ.mem[JOINT_A, MEM_IN_CONTACT] > 0.0


def first_onset(integ: Integration, dt: float):
    """Advance by dt until joint A is flagged in contact; the snapshot and time before."""
    for _ in range(10_000):
        before, t_before = integ.snapshot(), integ.t
        integ.advance(t_before + dt)
        if in_contact(integ):
            return before, t_before
    raise AssertionError("no contact onset")


def crossing(integ: Integration, piece: float) -> tuple[float, float]:
    """(t, δ̇) at δ = 0, interpolated between pieces of length `piece` (s)."""
    while not in_contact(integ):
        (d0, r0), t0 = rate(integ), integ.t
        integ.advance(t0 + piece)
    (d1, r1), t1 = rate(integ), integ.t
    share = -d0 / (d1 - d0)
    return t0 + share * (t1 - t0), r0 + share * (r1 - r0)


@pytest.fixture(scope="module")
def onsets():
    scene = load_scene("sixbar", SCENE)
    dt = crank_period(scene) / 4000
    leader = prepare(scene, rigid=True, revolutions=0.5, step_log=1 << 16)
    before, t_before = first_onset(leader, dt)
    leader_onset = leader.mem[JOINT_A, MEM_ONSET_RATE]

    # the reference's crossing, measured apart
    leader.restore(before)
    t_cross, leader_cross = crossing(leader, dt / 400)

    # the rate at the end of the first accepted step inside the contact
    leader.restore(before)
    leader.clear_step_log()
    leader.advance(t_before + dt)
    ends = leader.buffers.step_ends[: leader.count("logged")]
    located = int(np.argmin(np.abs(ends - t_cross)))
    # a step ends on the crossing (the event located on it), the next one inside the contact
    assert abs(ends[located] - t_cross) < 1e-3 * (ends[located + 1] - ends[located])
    leader.restore(before)
    leader.advance(ends[located + 1])
    inside_rate = rate(leader)[1]

    # a perturbed trajectory (velocities 1e-4 larger) following the reference's step ends
    follower = prepare(scene, rigid=True, revolutions=0.5)
    follower.restore(before)
    n = follower.system.n
    follower.y[n : 2 * n] *= 1.0 + 1e-4
    perturbed = follower.snapshot()
    leader.restore(before)
    leader.clear_step_log()
    leader.advance(t_before + dt)
    assert follower.follow(leader) == 0 and in_contact(follower)
    follower_onset = follower.mem[JOINT_A, MEM_ONSET_RATE]
    follower.restore(perturbed)
    _, follower_cross = crossing(follower, dt / 400)
    return leader_onset, leader_cross, inside_rate, follower_onset, follower_cross


def test_the_reference_takes_the_onset_rate_at_the_located_crossing(onsets):
    leader_onset, leader_cross, inside_rate, _, _ = onsets
    assert leader_onset == pytest.approx(leader_cross, rel=TOLERANCE)
    # the test discriminates: the first step inside reads a rate far off
    assert abs(inside_rate - leader_cross) > 100 * TOLERANCE * leader_cross


def test_the_perturbed_trajectory_takes_its_own_onset_rate_at_its_crossing(onsets):
    leader_onset, _, _, follower_onset, follower_cross = onsets
    assert follower_onset == pytest.approx(follower_cross, rel=TOLERANCE)
    # its own: the perturbation moved the onset rate by far more than the tolerance
    assert abs(follower_onset - leader_onset) > 10 * TOLERANCE * leader_onset
    assert np.isfinite(follower_onset) and follower_onset > 0.0

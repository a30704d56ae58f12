"""Continuation: the end of one run as the start of a neighbouring scene (issue 3).

References: the drive law θ = θ₀ + ωt (the crank is back at θ₀ after whole revolutions and
turns at the new ω), the constraint equations themselves, and the uninterrupted run."""

import math

import numpy as np
import pytest

from sim.model.continuation import ContinuationError, clearance_coordinates
from sim.model.initial import constraint_values
from sim.run import prepare, simulate_from
from sim.scene import load_scene

FLAGSHIP = ["joints.A.clearance=5e-4", "joints.B.clearance=5e-4"]


def scene(*overrides: str, revolutions: float = 2) -> dict:
    return load_scene(
        "sixbar",
        [*FLAGSHIP, f"simulation.revolutions={revolutions}", *overrides],
    )


@pytest.fixture(scope="module")
def flagship_end():
    """The flagship after 2 revolutions: impacts have happened, contact memory is live."""
    return simulate_from(scene(), None)


def start_of(integ):
    n = integ.system.n
    return integ.y[:n], integ.y[n : 2 * n]


def crank_coordinate(integ) -> int:
    return integ.layout.offset["crank"] + 2


def test_smaller_clearance_scales_the_clearance_coordinates(flagship_end):
    _, end = flagship_end
    integ = prepare(scene("joints.A.clearance=4e-4", "joints.B.clearance=4e-4"), start=end)
    q, qd = start_of(integ)
    phi, jac, nu = constraint_values(integ.system, q, np.zeros_like(q), 0.0)
    assert np.abs(phi).max() < 1e-12
    assert np.abs(jac @ qd - nu).max() < 1e-10
    np.testing.assert_allclose(
        clearance_coordinates(integ.system, q),
        0.8 * clearance_coordinates(end.system, end.q),
        rtol=1e-9,
        atol=1e-15,
    )
    # the crank is back at its drive angle of t = 0 and turns at the drive speed
    assembled, _ = start_of(prepare(scene()))
    i = crank_coordinate(integ)
    assert end.q[i] - assembled[i] == pytest.approx(2 * 2 * math.pi, abs=1e-8)
    assert q[i] == pytest.approx(assembled[i], abs=1e-12)
    assert qd[i] == pytest.approx(150 * 2 * math.pi / 60, rel=1e-12)


def test_new_speed_scales_every_velocity(flagship_end):
    _, end = flagship_end
    integ = prepare(scene("drive.speed_rpm=120"), start=end)
    q, qd = start_of(integ)
    # only the 1e-9 m Baumgarte drift of the previous run is projected out of q
    assert np.abs(q - end.q)[: crank_coordinate(integ)].max() < 1e-8
    np.testing.assert_allclose(qd, 0.8 * end.qd, rtol=1e-6, atol=1e-9 * np.abs(end.qd).max())


def test_continuing_the_same_scene_follows_the_uninterrupted_run(flagship_end):
    """Positions and velocities carry over (contact memory too): the continued revolution
    tracks revolutions 2–3 of one run until chaos separates them. The two runs restart their
    step sequences differently, so they part from the integrator's local error (~1e-11 m
    after the first sample, minimal coordinates) and the impacts' expansion carries that to
    ~1e-7 m by 0.05 revolution (8e-8 measured, margin 6); a state that did not carry over
    would be off by the motion of one sample interval (~1e-5 m) at once."""
    _, end = flagship_end
    per_rev = ["simulation.output_per_revolution=1000"]
    whole, _ = simulate_from(scene(*per_rev, revolutions=3), None)
    continued, _ = simulate_from(scene(*per_rev, revolutions=1), end)
    window = slice(0, 51)  # the first 0.05 revolution
    tail = whole.eccentricity.isel(time=slice(2000, None)).values[window]
    gap = np.abs(tail - continued.eccentricity.values[window]).max()
    assert gap < 1e-3 * 5e-4
    assert continued.attrs["initial_state"] == "continued"


def test_a_joint_made_ideal_cannot_be_continued(flagship_end):
    _, end = flagship_end
    with pytest.raises(ContinuationError, match="a clearance of 0 makes a joint ideal"):
        prepare(scene("joints.A.clearance=0.0"), start=end)


def test_only_whole_revolutions_continue():
    _, end = simulate_from(scene(revolutions=0.5), None)
    with pytest.raises(ContinuationError, match=r"after 0\.5 revolutions, not whole"):
        prepare(scene(), start=end)

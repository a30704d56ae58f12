"""The implicit integrator through sustained, rattling contact (issue 7).

At 30 rpm the journal of A and the slider rest on and rattle against their walls: the contact
closes and opens between Newton iterates, where a matrix formed out of contact lacks its
stiffness. Before Newton re-formed its matrix on slow contraction, this rigid case collapsed
the step at t = 0.085 s. The pointwise motion is too sensitive to compare (DOPRI5 at rtol 1e-5
and 1e-8 differ by half the clearance within 0.1 revolution), so the references are the energy
balance and the clearance itself."""

import numpy as np
import pytest

from sim.run import simulate
from sim.scene import load_scene

RATTLE = [
    "drive.speed_rpm=30",
    "joints.A.clearance=2e-4",
    "joints.B.clearance=2e-4",
    "contact.friction=0",
    "simulation.revolutions=0.25",
    "solver.method=generalized_alpha",
    "solver.rtol=1e-4",
    "solver.atol=1e-6",
]


def test_rattling_contact_runs_with_a_closing_energy_audit():
    ds = simulate(load_scene("sixbar", RATTLE))
    assert ds.attrs["solver_contact_events"] > 100  # it did rattle
    # measured 1.4e-4; the audit of a sound run at this tolerance
    assert ds.attrs["energy_error_relative"] < 1e-3
    journal = np.hypot(*ds.eccentricity.sel(joint="A").values.T)
    assert journal.max() < 1.05 * 2e-4  # Hertz penetration, far below 5 % of the clearance
    # Newton converges on most steps (measured: fails on 4.6 %, then the step is retried)
    assert ds.attrs["solver_newton_failures"] < 0.15 * ds.attrs["solver_accepted_steps"]


def _rigid_audit(rpm: float, rtol: float, *sets: str) -> float:
    """Energy audit of a quarter revolution of the rigid six-bar, A and B at 0.5 mm, by
    generalized-α at `rtol` (atol = rtol/100)."""
    case = [
        f"drive.speed_rpm={rpm}",
        "joints.A.clearance=5e-4",
        "joints.B.clearance=5e-4",
        "simulation.revolutions=0.25",
        "solver.method=generalized_alpha",
        f"solver.rtol={rtol}",
        f"solver.atol={rtol * 1e-2}",
        *sets,
    ]
    return simulate(load_scene("sixbar", case)).attrs["energy_error_relative"]


def test_energy_audit_converges_through_contact_events_at_tight_tolerances():
    """After a contact event the steps restart near 1e-9 s, where the index-3 method's
    velocities carry the position constraints' convergence error times γ/(β h): before the
    velocities were projected onto Φ_q q̇ = ν, the kinetic energy tripled for a few steps
    at t = 0.0396 s and the audit at rtol 1e-8 ended at 1.5e-3, worse than at 1e-6."""
    audit = {rtol: _rigid_audit(30, rtol) for rtol in (1e-6, 1e-8)}
    # measured 7.5e-5 and 4.9e-6: the audit falls with the tolerance
    assert audit[1e-8] < 1e-5
    assert audit[1e-8] < 0.2 * audit[1e-6]


@pytest.mark.parametrize(("samples", "rtol"), [(400, 1e-7), (3000, 1e-8)])
def test_energy_audit_holds_when_newton_fails_at_a_contact(samples, rtol):
    """A Newton that fails with a kept iteration matrix is retried at the same step size
    from a fresh one before the step is rejected. Without that retry these two runs of the
    rigid six-bar at 40 rpm ended with audits of 2.5e-2 and 4.8e-3 (measured). Traced on a
    30 rpm run that failed likewise: after a contact the steps grew long in free flight
    while the method's decaying (−ρ∞)ⁿ mode carried an alternating error of the kinetic
    energy that the error estimate of q does not see. Measured with the retry: 2.0e-5 and
    4.2e-6, as at 20 and 30 rpm."""
    audit = _rigid_audit(40, rtol, f"simulation.output_per_revolution={samples}")
    assert audit < 1e-4

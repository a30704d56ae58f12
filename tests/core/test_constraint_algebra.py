"""The constraint terms and the Schur complement against independent references.

Φ_q against central differences of Φ, γ = −(Φ_q q̇)_q q̇ against central differences
of Φ_q q̇ along q̇ (the six-bar's constraints other than the drive do not depend on
t, and the drive's row is linear in q), and the factored Schur complement
L Lᵀ against the dense product Φ_q M⁻¹ Φ_qᵀ formed by numpy, at generic states of
the rigid six-bar and of the six-bar with beams.
"""

import numpy as np
import pytest

from sim.model.assembly import build_system
from sim.model.constraints import constraint_terms
from sim.scene import load_scene
from sim.solve.dae import OK, factor_schur
from sim.solve.work import make_work

CASES = {
    "rigid": ["joints.A.clearance=0.5e-3", "joints.B.clearance=0.5e-3"],
    "beams": [
        "joints.A.clearance=0.5e-3",
        "bodies.rod2.kind=beam",
        "bodies.rod3.kind=beam",
        "bodies.rod4.kind=beam",
    ],
}
EPS = 1e-6  # central-difference step; its truncation error is O(EPS²) ≈ 1e-12 here
FD_TOL = 1e-7  # central differences of terms of size ~1 with round-off ~1e-16 / EPS


def terms(system, q, qd):
    phi = np.zeros(system.m)
    jac = np.zeros((system.m, system.n))
    gamma = np.zeros(system.m)
    nu = np.zeros(system.m)
    constraint_terms(system, 0.0, q, qd, phi, jac, gamma, nu)
    return phi, jac, gamma


@pytest.fixture(scope="module", params=sorted(CASES))
def system_state(request):
    system, _ = build_system(load_scene("sixbar", CASES[request.param]))
    rng = np.random.default_rng(1)
    return system, rng.uniform(-1.0, 1.0, system.n), rng.uniform(-1.0, 1.0, system.n)


def test_jacobian_and_gamma_match_central_differences(system_state):
    system, q, qd = system_state
    _, jac, gamma = terms(system, q, qd)
    fd_jac = np.empty_like(jac)
    for k in range(system.n):
        dq = np.zeros(system.n)
        dq[k] = EPS
        fd_jac[:, k] = (terms(system, q + dq, qd)[0] - terms(system, q - dq, qd)[0]) / (2 * EPS)
    np.testing.assert_allclose(jac, fd_jac, rtol=0.0, atol=FD_TOL)
    ahead = terms(system, q + EPS * qd, qd)[1] @ qd
    behind = terms(system, q - EPS * qd, qd)[1] @ qd
    np.testing.assert_allclose(gamma, -(ahead - behind) / (2 * EPS), rtol=0.0, atol=FD_TOL)


def test_factored_schur_complement_matches_dense_product(system_state):
    system, q, qd = system_state
    work = make_work(system)
    constraint_terms(system, 0.0, q, qd, work.phi, work.jac, work.gamma, work.nu)
    assert factor_schur(system, work) == OK
    low = np.tril(work.schur)
    reference = work.jac @ system.mass_inv @ work.jac.T
    # Each entry against the Cauchy–Schwarz bound of its size, sqrt(S_ii S_jj): a
    # coupling left out of the sparse product would be wrong by a fair fraction of it,
    # round-off of an 11- to 30-row Cholesky factorisation by ~1e-15 of it.
    scale = np.sqrt(np.outer(np.diag(reference), np.diag(reference)))
    assert np.all(np.abs(low @ low.T - reference) <= 1e-12 * scale)

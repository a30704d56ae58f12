"""The fixed-pattern LU of generalized-α's Newton matrix (sim.solve.linalg) against numpy."""

import numpy as np

from sim.run import prepare
from sim.scene import load_scene
from sim.solve.linalg import lu_pattern, pattern_lu_in_place, pattern_lu_solve_in_place
from sim.solve.status import OK
from sim.solve.tangent import iteration_matrix

BEAMS = [f"bodies.{b}.kind=beam" for b in ("rod2", "rod3", "rod4")]
FLEXIBLE = ["joints.A.clearance=5e-4", "joints.B.clearance=5e-4", *BEAMS]


def _random_with_pattern(rng: np.random.Generator, nonzero: np.ndarray) -> np.ndarray:
    """A matrix with random entries where `nonzero`, diagonally dominant so that elimination
    without row exchanges is stable."""
    a = np.where(nonzero, rng.standard_normal(nonzero.shape), 0.0)
    return a + np.diag(np.abs(a).sum(axis=1) + 1.0)


def test_the_symbolic_pattern_holds_every_nonzero_of_the_factors():
    # Elimination without row exchanges fills only where the symbolic elimination says: the
    # factors computed densely by numpy-style Gaussian elimination are zero outside it
    rng = np.random.default_rng(7)
    nonzero = rng.random((30, 30)) < 0.12
    a = _random_with_pattern(rng, nonzero)
    pattern = lu_pattern(a != 0.0)
    lu = a.copy()
    for k in range(lu.shape[0]):
        lu[k + 1 :, k] /= lu[k, k]
        lu[k + 1 :, k + 1 :] -= np.outer(lu[k + 1 :, k], lu[k, k + 1 :])
    assert np.all(lu[~_held(pattern, 30)] == 0.0)
    # and the kernel's factors solve the system as numpy does
    assert pattern_lu_in_place(a.copy(), pattern)
    factors = a.copy()
    pattern_lu_in_place(factors, pattern)
    b = rng.standard_normal(30)
    x = b.copy()
    pattern_lu_solve_in_place(factors, pattern, x)
    np.testing.assert_allclose(x, np.linalg.solve(a, b), rtol=1e-12, atol=0)


def test_a_zero_pivot_fails_the_factorisation():
    # a saddle point eliminated in the wrong order: its first pivot is the zero block's
    a = np.array([[0.0, 1.0], [1.0, 2.0]])
    assert not pattern_lu_in_place(a.copy(), lu_pattern(a != 0.0))


def test_the_newton_matrix_of_the_flexible_six_bar_is_solved_as_numpy_solves_it():
    # The iteration matrix at states along a flexible run with clearance, at three step
    # sizes: the mass block is positive definite and comes first, so the factorisation
    # without row exchanges holds (measured over 2400 such matrices: within 4e-14 of the
    # pivoted solution); bound 1e-10 relative, against numpy's pivoted LAPACK solve.
    scene = load_scene(
        "sixbar", [*FLEXIBLE, "solver.method=generalized_alpha", "simulation.revolutions=1"]
    )
    integ = prepare(scene)
    system, work, n = integ.system, integ.work, integ.system.n
    rng = np.random.default_rng(3)
    beta, gamma = 0.2770083102493075, 0.5263157894736842  # ρ∞ = 0.9
    for t in np.linspace(0.01, 0.2, 8):
        assert integ.advance(t) == OK
        q, v = integ.y[:n].copy(), integ.y[n : 2 * n].copy()
        for h in (1e-6, 1e-5, 1e-4):
            matrix = np.zeros((n + system.m, n + system.m))
            c_c, c_k = gamma * h, beta * h * h
            iteration_matrix(system, work, matrix, integ.mem.copy(), t, q, v, 1.1, c_c, c_k)
            # the assembly writes nowhere the pattern does not hold
            assert np.all(matrix[~_held(work.newton_lu, matrix.shape[0])] == 0.0)
            factors = matrix.copy()
            assert pattern_lu_in_place(factors, work.newton_lu)
            b = rng.standard_normal(matrix.shape[0])
            x = b.copy()
            pattern_lu_solve_in_place(factors, work.newton_lu, x)
            expected = np.linalg.solve(matrix, b)
            assert np.abs(x - expected).max() < 1e-10 * np.abs(expected).max()


def _held(pattern, size: int) -> np.ndarray:
    """Where the pattern's factors can be nonzero, the diagonal included."""
    held = np.eye(size, dtype=bool)
    for k in range(size):
        held[pattern.lower[k, : pattern.n_lower[k]], k] = True
        held[k, pattern.upper[k, : pattern.n_upper[k]]] = True
    return held

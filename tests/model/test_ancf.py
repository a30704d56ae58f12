"""Checks of the planar ANCF beam (sim.model.ancf) against independent references.

References are computed here: Euler–Bernoulli statics and vibration, the inextensible elastica
(scipy solve_bvp), textbook element matrices, finite differences, and energy conservation of
free motion (scipy solve_ivp). All units SI.
"""

import numpy as np
import pytest
from scipy.integrate import quad, solve_bvp, solve_ivp
from scipy.linalg import cho_factor, cho_solve, eigh
from scipy.optimize import brentq

from sim.model.ancf import (
    beam_constants,
    beam_damping_forces,
    beam_damping_jacobians,
    beam_elastic_forces,
    beam_elastic_jacobian,
    beam_mass_matrix,
    beam_midspan_deflection,
    beam_point,
    beam_point_jacobian,
    beam_strain_energy,
    element_mass_matrix,
    straight_beam_coordinates,
)

# Steel beam of the large-deflection check (issue 7): L = 2 m, 0.1 m × 0.1 m square section.
E_STEEL = 2.07e11  # Pa
RHO_STEEL = 7800.0  # kg/m³
L_CANTILEVER = 2.0  # m
A_SQUARE = 0.1 * 0.1  # m²
I_SQUARE = 0.1**4 / 12.0  # m⁴
EA_SQUARE = E_STEEL * A_SQUARE
EI_SQUARE = E_STEEL * I_SQUARE


def rotation(angle: float) -> np.ndarray:
    return np.array([[np.cos(angle), -np.sin(angle)], [np.sin(angle), np.cos(angle)]])


def rigidly_moved(q: np.ndarray, angle: float, shift: np.ndarray) -> np.ndarray:
    """q after a rotation by ``angle`` about the origin and a translation by ``shift``."""
    nodes = q.reshape(-1, 2, 2)  # (node, [position, slope], xy)
    moved = nodes @ rotation(angle).T
    moved[:, 0, :] += shift
    return moved.reshape(-1)


def elastic_forces(q, constants):
    out = np.empty_like(q)
    beam_elastic_forces(q, *constants, out)
    return out


def elastic_jacobian(q, constants):
    out = np.empty((q.size, q.size))
    beam_elastic_jacobian(q, *constants, out)
    return out


def central_difference_jacobian(function, x: np.ndarray, step: float) -> np.ndarray:
    columns = []
    for j in range(x.size):
        dx = np.zeros_like(x)
        dx[j] = step
        columns.append((function(x + dx) - function(x - dx)) / (2.0 * step))
    return np.array(columns).T


def randomly_deformed(n: int, length: float, amplitude: float, seed: int) -> np.ndarray:
    """A straight beam along x with seeded random perturbations of every coordinate."""
    rng = np.random.default_rng(seed)
    q = straight_beam_coordinates(np.zeros(2), np.array([length, 0.0]), n)
    return q + amplitude * rng.standard_normal(q.size)


def solve_cantilever(n: int, EA: float, EI: float, tip_load: float, load_steps: int) -> np.ndarray:
    """Static equilibrium F(q) = Q of a cantilever along +x with a dead tip load −tip_load·ŷ.

    Clamp: node 0 position and slope fixed. Newton's method on the analytic Jacobian, with the
    load applied in ``load_steps`` equal increments, each solved to convergence.
    """
    constants = beam_constants(L_CANTILEVER / n, EA, EI)
    q = straight_beam_coordinates(np.zeros(2), np.array([L_CANTILEVER, 0.0]), n)
    free = slice(4, None)
    for load_factor in np.arange(1, load_steps + 1) / load_steps:
        external = np.zeros_like(q)
        external[4 * n + 1] = -load_factor * tip_load
        for _ in range(40):
            residual = elastic_forces(q, constants) - external
            step = np.linalg.solve(elastic_jacobian(q, constants)[free, free], residual[free])
            q[free] -= step
            # Converged when the update reaches round-off of the coordinates (order L).
            if np.max(np.abs(step)) < 1e-13 * L_CANTILEVER:
                break
        else:
            pytest.fail(f"Newton did not converge at load factor {load_factor}")
    return q


def elastica_tip(load_parameter: float, length: float) -> np.ndarray:
    """Tip position of the inextensible elastica cantilever under a vertical dead tip load.

    θ(s) is the tangent angle from +x (counter-clockwise), s the arc length. For the part of
    the beam beyond s, moment balance about r(s) gives EI θ'(s) = −P (x(L) − x(s)) (the load
    −P ŷ at the tip bends the beam clockwise, θ' < 0); differentiating, with x' = cos θ:
    θ'' = (P/EI) cos θ (equivalently φ'' = −(P/EI) cos φ for the downward angle φ = −θ). Clamp
    θ(0) = 0, free end θ'(L) = 0, and x' = cos θ, y' = sin θ from x(0) = y(0) = 0.
    """

    def rhs(s, y):
        theta, dtheta, _, _ = y
        return np.vstack(
            [dtheta, load_parameter / length**2 * np.cos(theta), np.cos(theta), np.sin(theta)]
        )

    def boundary(ya, yb):
        return np.array([ya[0], ya[2], ya[3], yb[1]])

    s = np.linspace(0.0, length, 41)
    guess = np.zeros((4, s.size))
    guess[2] = s
    solution = solve_bvp(rhs, boundary, s, guess, tol=1e-10, max_nodes=100_000)
    assert solution.status == 0, solution.message
    return solution.y[2:, -1]


def deformed_length(q: np.ndarray, n: int, length: float) -> float:
    """Length of the deformed centre line, as a polyline through 4001 material points."""
    point = np.empty(2)
    points = []
    for s in np.linspace(0.0, length, 4001):
        beam_point(q, n, length / n, s, point)
        points.append(point.copy())
    return float(np.sum(np.linalg.norm(np.diff(points, axis=0), axis=1)))


# --- element matrices -----------------------------------------------------------------------


def test_element_matrices_equal_the_textbook_hermite_matrices():
    # Classical consistent mass and Euler–Bernoulli stiffness of the cubic Hermite element
    # (e.g. Przemieniecki, Theory of Matrix Structural Analysis), per displacement component.
    rho_A, l, EI = 3.0, 0.7, 11.0
    mass = (
        rho_A
        * l
        / 420.0
        * np.array(
            [
                [156, 22 * l, 54, -13 * l],
                [22 * l, 4 * l**2, 13 * l, -3 * l**2],
                [54, 13 * l, 156, -22 * l],
                [-13 * l, -3 * l**2, -22 * l, 4 * l**2],
            ]
        )
    )
    stiffness = (
        EI
        / l**3
        * np.array(
            [
                [12, 6 * l, -12, 6 * l],
                [6 * l, 4 * l**2, -6 * l, 2 * l**2],
                [-12, -6 * l, 12, -6 * l],
                [6 * l, 2 * l**2, -6 * l, 4 * l**2],
            ]
        )
    )
    np.testing.assert_allclose(element_mass_matrix(rho_A, l), np.kron(mass, np.eye(2)), rtol=1e-13)
    # Bending stiffness K_b: the tangent stiffness of a straight element without axial stiffness.
    straight = straight_beam_coordinates(np.zeros(2), np.array([l, 0.0]), 1)
    np.testing.assert_allclose(
        elastic_jacobian(straight, beam_constants(l, 0.0, EI)),
        np.kron(stiffness, np.eye(2)),
        rtol=1e-13,
        atol=1e-13 * EI / l**3,
    )


def test_mass_matrix_gives_rigid_body_kinetic_energy():
    rho_A, length, n = 2.5, 1.3, 3
    mass_matrix = beam_mass_matrix(rho_A, length, n)
    mass = rho_A * length
    q = rigidly_moved(straight_beam_coordinates(np.zeros(2), np.array([length, 0.0]), n), 0.4, 0)
    # Rotation at rate ω about the mid-length point c: ṙ = ω ẑ × (r − c) for positions, ω ẑ × r'
    # for slopes. Kinetic energy ½ (m L²/12) ω² (and ½ m v² for a translation).
    omega = 1.7
    nodes = q.reshape(-1, 2, 2)
    centre = 0.5 * (nodes[0, 0] + nodes[-1, 0])
    arms = nodes.copy()
    arms[:, 0, :] -= centre
    qdot = (omega * arms[:, :, ::-1] * np.array([-1.0, 1.0])).reshape(-1)
    assert 0.5 * qdot @ mass_matrix @ qdot == pytest.approx(
        0.5 * mass * length**2 / 12 * omega**2, rel=1e-13
    )
    translation = np.tile([0.3, -0.8, 0.0, 0.0], n + 1)
    assert 0.5 * translation @ mass_matrix @ translation == pytest.approx(
        0.5 * mass * 0.73, rel=1e-13
    )


def test_strain_energy_equals_adaptive_quadrature_and_forces_are_its_gradient():
    n, length, EA, EI = 2, 1.0, 50.0, 3.0
    constants = beam_constants(length / n, EA, EI)
    q = randomly_deformed(n, length, 0.05, seed=1)

    # Reference energy: the strain energy integrals by adaptive quadrature, with the Hermite
    # shape function derivatives written out again here.
    def slope_and_curvature(element_q, l, xi):
        d1 = np.array(
            [
                (-6 * xi + 6 * xi**2) / l,
                1 - 4 * xi + 3 * xi**2,
                (6 * xi - 6 * xi**2) / l,
                3 * xi**2 - 2 * xi,
            ]
        )
        d2 = np.array(
            [(-6 + 12 * xi) / l**2, (-4 + 6 * xi) / l, (6 - 12 * xi) / l**2, (6 * xi - 2) / l]
        )
        nodal = element_q.reshape(4, 2)
        return d1 @ nodal, d2 @ nodal

    l = length / n
    reference = 0.0
    for e in range(n):
        element_q = q[4 * e : 4 * e + 8]

        def density(x, element_q=element_q):
            slope, curvature = slope_and_curvature(element_q, l, x / l)
            strain = 0.5 * (slope @ slope - 1.0)
            return 0.5 * EA * strain**2 + 0.5 * EI * curvature @ curvature

        reference += quad(density, 0.0, l, epsabs=0.0, epsrel=1e-13)[0]
    energy = beam_strain_energy(q, *constants)
    assert energy == pytest.approx(reference, rel=1e-12)

    gradient = central_difference_jacobian(
        lambda x: np.array([beam_strain_energy(x, *constants)]), q, 1e-6
    )[0]
    forces = elastic_forces(q, constants)
    assert np.max(np.abs(gradient - forces)) < 1e-8 * np.max(np.abs(forces))


# --- check 1: cantilever, small tip load ----------------------------------------------------


@pytest.mark.parametrize("n", [1, 2, 4])
def test_cantilever_small_tip_load_matches_beam_theory(n):
    # Load parameter α = P L²/(EI) = 1e-4, so that geometric nonlinearity and axial stretch are
    # negligible. The elastica tip deflection is (α L/3)(1 − 0.114 α² + …) (coefficient fitted
    # to the solve_bvp reference of elastica_tip at α = 0.03 and 0.3): 1e-9 relative. A single
    # element cannot pair the cubic deflection with the axial shortening it needs (a quintic),
    # so it stiffens by ≈ 1.4 α² = 1.4e-8 relative (measured; 0.15 α² with two elements). Both
    # are far below the 1e-6 tolerance, which therefore measures the element: cubic Hermite
    # interpolation contains the exact cubic deflection under a tip load.
    load_parameter = 1e-4
    tip_load = load_parameter * EI_SQUARE / L_CANTILEVER**2
    beam_theory = tip_load * L_CANTILEVER**3 / (3.0 * EI_SQUARE)

    q = solve_cantilever(n, EA_SQUARE, EI_SQUARE, tip_load, load_steps=1)
    nonlinear_tip = -q[4 * n + 1]
    assert nonlinear_tip == pytest.approx(beam_theory, rel=1e-6)

    # Linear solution: tangent stiffness of the straight beam.
    constants = beam_constants(L_CANTILEVER / n, EA_SQUARE, EI_SQUARE)
    straight = straight_beam_coordinates(np.zeros(2), np.array([L_CANTILEVER, 0.0]), n)
    load = np.zeros_like(straight)
    load[4 * n + 1] = -tip_load
    free = slice(4, None)
    linear = np.linalg.solve(elastic_jacobian(straight, constants)[free, free], load[free])
    linear_tip = -linear[4 * n - 3]
    assert linear_tip == pytest.approx(beam_theory, rel=1e-10)
    assert nonlinear_tip == pytest.approx(linear_tip, rel=2.0 * load_parameter**2)


# --- check 2: cantilever, large deflection --------------------------------------------------


def test_cantilever_large_deflection_matches_the_elastica():
    # Tip load 3 EI/L² (α = 3): the tip drops about 0.6 L. 16 elements, load in 6 steps.
    n = 16
    tip_load = 3.0 * EI_SQUARE / L_CANTILEVER**2
    reference = elastica_tip(3.0, L_CANTILEVER)
    q = solve_cantilever(n, EA_SQUARE, EI_SQUARE, tip_load, load_steps=6)
    tip = q[4 * n : 4 * n + 2]
    miss = np.linalg.norm(tip - reference)

    # ANCF with the Green strain is extensible, the elastica is not. The axial strain is at
    # most ε = P/(EA) = 3 I/(A L²) = 6.25e-4; the centre line lengthens by ≈ 2e-4 m < ε L.
    strain = tip_load / EA_SQUARE
    stretch = deformed_length(q, n, L_CANTILEVER) - L_CANTILEVER
    assert 0.0 < stretch < strain * L_CANTILEVER

    # Strains of O(ε) also change the bending response (the constant K_b measures |r''|, not
    # the curvature of a stretched line), so the tip misses the inextensible elastica by a
    # model difference of order ε L = 1.25e-3 m (measured 8.8e-4 m = 0.70 ε L), not by
    # discretisation error. Bound: 2 ε L, a factor 2.8 above the measurement.
    assert miss < 2.0 * strain * L_CANTILEVER
    # First order in ε: with 10 × EA (32 elements, as a stiffer axial response needs more
    # elements) the miss must fall tenfold (measured 0.106); second-order terms (ε² ~ 4e-7)
    # and discretisation cannot move the ratio by a factor 2.
    n_stiff = 32
    stiff = solve_cantilever(n_stiff, 10.0 * EA_SQUARE, EI_SQUARE, tip_load, load_steps=6)
    miss_stiff = np.linalg.norm(stiff[4 * n_stiff : 4 * n_stiff + 2] - reference)
    assert 0.05 < miss_stiff / miss < 0.2


# --- check 3: natural frequencies -----------------------------------------------------------


def test_clamped_beam_frequencies_converge_to_euler_bernoulli():
    # Slender steel beam, L = 1 m, 10 mm square (slenderness L/√(I/A) ≈ 350): the first axial
    # frequency (π/2L)√(E/ρ) is 8.8 times the third bending one, so the three lowest modes are
    # bending modes.
    length, side = 1.0, 0.01
    area, inertia = side**2, side**4 / 12.0
    # Clamped-free roots of cos(βL) cosh(βL) + 1 = 0: 1.8751, 4.6941, 7.8548.
    roots = [brentq(lambda x: np.cos(x) * np.cosh(x) + 1.0, a, a + 2.0) for a in (1.0, 4.0, 7.0)]
    exact = np.array(roots) ** 2 * np.sqrt(E_STEEL * inertia / (RHO_STEEL * area * length**4))

    errors = []
    for n in (2, 4, 8):
        constants = beam_constants(length / n, E_STEEL * area, E_STEEL * inertia)
        q = straight_beam_coordinates(np.zeros(2), np.array([length, 0.0]), n)
        free = slice(4, None)
        stiffness = elastic_jacobian(q, constants)[free, free]
        mass = beam_mass_matrix(RHO_STEEL * area, length, n)[free, free]
        squared, modes = eigh(stiffness, mass, subset_by_index=[0, 2])
        # Transverse modes: the axial (x) components vanish at the straight configuration.
        assert np.max(np.abs(modes[0::4])) < 1e-10 * np.max(np.abs(modes))
        errors.append(np.abs(np.sqrt(squared) / exact - 1.0))
    errors = np.array(errors)
    assert np.all(np.diff(errors, axis=0) < 0.0)
    assert np.all(errors[1:] < 0.01)  # 4 and 8 elements; 2 elements miss mode 3 by 22 %


# --- check 4: rigid-body motion --------------------------------------------------------------


@pytest.mark.parametrize("angle", [0.3, 2.0, -2.9])
def test_rigid_motion_has_no_elastic_force_or_energy(angle):
    n, length = 3, 2.0
    constants = beam_constants(length / n, EA_SQUARE, EI_SQUARE)
    straight = straight_beam_coordinates(np.zeros(2), np.array([length, 0.0]), n)
    q = rigidly_moved(straight, angle, np.array([0.4, -1.1]))
    # Zero to round-off: ε is computed from |r'|² − 1 with r' summed from nodal values of order
    # 1, so |ε| is a few 1e-16 and the axial force EA·l·ε a few 1e-16 EA (measured ≤ 1.8e-16 EA);
    # the energy bound allows |ε| and l²|r''| up to 1e-14 (measured U ≤ 3e-22 J).
    forces = elastic_forces(q, constants)
    assert np.max(np.abs(forces)) < 1e-14 * EA_SQUARE
    assert beam_strain_energy(q, *constants) < 1e-28 * EA_SQUARE * length
    # Structural damping vanishes for a rigid velocity too (rotation rate 0.8 rad/s about the
    # origin plus a translation).
    nodes = q.reshape(-1, 2, 2)
    qdot = 0.8 * nodes[:, :, ::-1] * np.array([-1.0, 1.0])
    qdot[:, 0, :] += np.array([1.5, 0.2])
    damping = np.empty_like(q)
    beam_damping_forces(q, qdot.reshape(-1), *constants, 1e-3, damping)
    assert np.max(np.abs(damping)) < 1e-14 * 1e-3 * EA_SQUARE


def test_free_beam_launched_rigidly_keeps_its_energy():
    # Soft beam (EA = 1e4 N, EI = 10 N m², 1 kg/m, L = 1 m, 3 elements) so that the spin at
    # ω = 10 rad/s visibly stretches it and the ODE is not stiff. The velocity is rigid
    # (translation + rotation about the mid-point); the start is slightly bent (seeded, 2 mm)
    # so that bending energy takes part in the exchange as well.
    n, length, rho_A, EA, EI = 3, 1.0, 1.0, 1e4, 10.0
    constants = beam_constants(length / n, EA, EI)
    mass = beam_mass_matrix(rho_A, length, n)
    mass_factor = cho_factor(mass)
    q0 = rigidly_moved(randomly_deformed(n, length, 2e-3, seed=4), 0.7, np.array([0.1, 0.2]))
    nodes = q0.reshape(-1, 2, 2)
    arms = nodes.copy()
    arms[:, 0, :] -= 0.5 * (nodes[0, 0] + nodes[-1, 0])
    qdot0 = 10.0 * arms[:, :, ::-1] * np.array([-1.0, 1.0])
    qdot0[:, 0, :] += np.array([0.5, -0.3])

    forces = np.empty_like(q0)

    def rhs(_, y):
        beam_elastic_forces(y[: q0.size], *constants, forces)
        return np.concatenate([y[q0.size :], -cho_solve(mass_factor, forces)])

    def total_energy(y):
        q, qdot = y[: q0.size], y[q0.size :]
        return 0.5 * qdot @ mass @ qdot + beam_strain_energy(q, *constants)

    solution = solve_ivp(
        rhs,
        (0.0, 0.5),
        np.concatenate([q0, qdot0.reshape(-1)]),
        method="DOP853",
        rtol=1e-12,
        atol=1e-12,
        t_eval=np.linspace(0.0, 0.5, 501),
    )
    assert solution.success
    energies = np.array([total_energy(y) for y in solution.y.T])
    strain = np.array([beam_strain_energy(y[: q0.size], *constants) for y in solution.y.T])
    drift = np.max(np.abs(energies - energies[0])) / energies[0]
    # The exchange is real (strain energy swings by 8 % of the total) and the sum holds to the
    # integration tolerance: drift measured 6e-13 at rtol = atol = 1e-12 (1.4e-10 at 1e-10).
    assert np.ptp(strain) > 0.01 * energies[0]
    assert drift < 1e-11


# --- check 5: analytic Jacobians against finite differences ---------------------------------


# Central differences with step 1e-6 on coordinates of order 1: truncation error ~1e-12 and
# round-off ~1e-16/1e-6 = 1e-10 relative to the largest entry (measured 0.4–1.6e-10).


def test_elastic_jacobian_equals_finite_differences():
    # Strains of a few percent, so the geometric part ε S'ᵀS' of the tangent matters here.
    n, length, EA, EI = 3, 1.5, 2e3, 40.0
    constants = beam_constants(length / n, EA, EI)
    q = randomly_deformed(n, length, 0.05, seed=7)
    analytic = elastic_jacobian(q, constants)
    numeric = central_difference_jacobian(lambda x: elastic_forces(x, constants), q, 1e-6)
    np.testing.assert_allclose(analytic, analytic.T, rtol=0, atol=1e-12 * np.max(np.abs(analytic)))
    assert np.max(np.abs(analytic - numeric)) < 1e-8 * np.max(np.abs(analytic))


def test_damping_jacobians_equal_finite_differences_and_damping_dissipates():
    n, length, EA, EI, beta = 2, 1.0, 2e3, 40.0, 0.01
    constants = beam_constants(length / n, EA, EI)
    q = randomly_deformed(n, length, 0.05, seed=11)
    qdot = np.random.default_rng(12).standard_normal(q.size)

    def damping(x, v):
        out = np.empty_like(x)
        beam_damping_forces(x, v, *constants, beta, out)
        return out

    by_q = np.empty((q.size, q.size))
    by_qdot = np.empty((q.size, q.size))
    beam_damping_jacobians(q, qdot, *constants, beta, by_q, by_qdot)
    numeric_q = central_difference_jacobian(lambda x: damping(x, qdot), q, 1e-6)
    numeric_qdot = central_difference_jacobian(lambda v: damping(q, v), qdot, 1e-6)
    assert np.max(np.abs(by_q - numeric_q)) < 1e-8 * np.max(np.abs(by_q))
    assert np.max(np.abs(by_qdot - numeric_qdot)) < 1e-8 * np.max(np.abs(by_qdot))
    assert qdot @ damping(q, qdot) > 0.0


# --- material points -------------------------------------------------------------------------


def test_points_and_midspan_deflection_of_a_bent_beam():
    # A parabolic deflection v(x) = c x (L − x) is a cubic, so the Hermite mesh represents it
    # exactly: node values v(x_j) and slopes (1, v'(x_j)). The mid-length material point then
    # lies c L²/4 to the left of the chord from node 0 to node n, whatever the rigid placement.
    n, length, c = 4, 1.2, 0.05
    x = np.linspace(0.0, length, n + 1)
    q = np.column_stack([x, c * x * (length - x), np.ones_like(x), c * (length - 2.0 * x)]).reshape(
        -1
    )
    q = rigidly_moved(q, 2.4, np.array([-0.3, 0.9]))
    l = length / n
    assert beam_midspan_deflection(q, n, l) == pytest.approx(c * length**2 / 4.0, rel=1e-13)

    reversed_q = q.reshape(-1, 2, 2)[::-1].copy()
    reversed_q[:, 1, :] *= -1.0  # slopes point along the new direction of increasing s
    assert beam_midspan_deflection(reversed_q.reshape(-1), n, l) == pytest.approx(
        -c * length**2 / 4.0, rel=1e-13
    )

    point = np.empty(2)
    shape = np.empty(4)
    for s in (0.0, 0.17, 0.3, 0.61, length):
        beam_point(q, n, l, s, point)
        along = np.array([s, c * s * (length - s)])
        expected = rotation(2.4) @ along + np.array([-0.3, 0.9])
        np.testing.assert_allclose(point, expected, rtol=0, atol=1e-14)
        e = beam_point_jacobian(n, l, s, shape)
        from_jacobian = shape @ q[4 * e : 4 * e + 8].reshape(4, 2)
        np.testing.assert_allclose(from_jacobian, point, rtol=0, atol=1e-15)

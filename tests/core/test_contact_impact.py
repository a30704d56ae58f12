"""The contact laws against analytic Hertz impact and the restitution they give.

Two free bodies (steel ball, radius 10 mm, on a steel block) meet head-on; the
engine's force law (`normal_force` under Lankarani–Nikravesh) drives the relative
coordinate, which
scipy integrates at tight tolerance. Hertz's analytic impact (Johnson, Contact
Mechanics, 1985, §11.4) with reduced mass m* and approach speed v:
    δ_max = (5 m* v² / (4K))^(2/5),  F_max = K δ_max^1.5,
    t_c = 2 (δ_max / v) ∫₀¹ (1 − x^(5/2))^(-1/2) dx = 2 (δ_max / v) (2/5) B(2/5, 1/2).
"""

import numpy as np
from scipy.integrate import solve_ivp
from scipy.special import beta

from sim.model.contact import corner_stiffness, effective_modulus, normal_force
from sim.model.contact_laws import LAW_CODES, damping_coefficient

E_STEEL, NU, RHO = 207e9, 0.3, 7801.0
RADIUS = 0.01
M1 = RHO * 4 / 3 * np.pi * RADIUS**3  # ball
M2 = 5.0  # block
M_STAR = M1 * M2 / (M1 + M2)
K = corner_stiffness(RADIUS, effective_modulus(E_STEEL, NU, E_STEEL, NU))
V_IN = 0.5
LN = LAW_CODES["lankarani-nikravesh"]


def lankarani_nikravesh(delta: float, rate: float, onset: float, restitution: float):
    """The engine's normal force (N) and its elastic part under Lankarani–Nikravesh, zero
    apart; guard v_min = 1e-4 m/s."""
    if delta <= 0.0:
        return 0.0, 0.0
    chi = damping_coefficient("lankarani-nikravesh", restitution, 1.5, 0.0, K)
    elastic = K * delta**1.5
    return normal_force(LN, chi, elastic, delta, rate, onset, 1.5, 1e-4), elastic


def impact(restitution: float):
    """Integrate the two bodies through one impact; returns the solution and the
    force history. State: x1, x2, v1, v2 (ball moves +x into the block)."""

    def force(y):
        delta, rate = y[0] - y[1], y[2] - y[3]
        fn, _ = lankarani_nikravesh(delta, rate, V_IN, restitution)
        return fn

    def rhs(_t, y):
        f = force(y)
        return [y[2], y[3], -f / M1, f / M2]

    def separated(_t, y):
        return y[0] - y[1] + 1e-12

    separated.terminal = True
    separated.direction = -1
    v1 = V_IN * M2 / (M1 + M2)
    v2 = -V_IN * M1 / (M1 + M2)
    y0 = [0.0, 0.0, v1, v2]
    sol = solve_ivp(rhs, (0, 1e-3), y0, events=separated, rtol=1e-12, atol=1e-16, dense_output=True)
    t = np.linspace(0, sol.t[-1], 20001)
    f = np.array([force(sol.sol(ti)) for ti in t])
    return sol, t, f


def test_hertz_impact_maximum_indentation_force_and_duration():
    sol, t, f = impact(1.0)
    d_max = (5 * M_STAR * V_IN**2 / (4 * K)) ** 0.4
    t_c = 2 * d_max / V_IN * 0.4 * beta(0.4, 0.5)
    delta = sol.sol(t)[0] - sol.sol(t)[1]
    # 0.5 % as the specification asks; the integration is far tighter.
    assert abs(delta.max() / d_max - 1) < 5e-3
    assert abs(f.max() / (K * d_max**1.5) - 1) < 5e-3
    assert abs(sol.t[-1] / t_c - 1) < 5e-3


def test_restitution_of_the_lankarani_nikravesh_law_and_momentum():
    sol, _, _ = impact(0.9)
    y = sol.y[:, -1]
    v_rel_out = y[3] - y[2]
    e_eff = v_rel_out / V_IN
    p0 = M1 * V_IN * M2 / (M1 + M2) - M2 * V_IN * M1 / (M1 + M2)
    assert abs(M1 * y[2] + M2 * y[3] - p0) < 1e-12 * M2 * V_IN
    # Lankarani & Nikravesh derive the law for c_e near 1; its energy balance is
    # first order in (1 − c_e²), so at c_e = 0.9 the achieved restitution comes out
    # above 0.9. The reference is their law made dimensionless, integrated here.
    e_ref = lankarani_nikravesh_restitution(0.9)
    assert e_ref > 0.9
    # both integrations run at rtol 1e-12: 1e-6 leaves a margin of orders of magnitude
    assert abs(e_eff - e_ref) < 1e-6


def lankarani_nikravesh_restitution(c_e: float) -> float:
    """Restitution achieved by the Lankarani–Nikravesh law (1990), independently of the
    engine: with δ in units of (m* v²/K)^(2/5) and time in units of that over v, an
    impact is x'' = −x^1.5 (1 + 3 (1 − c_e²)/4 · x'), x(0) = 0, x'(0) = 1, and the
    restitution is the speed −x' at which x returns to 0 (independent of K, m*, v)."""
    damping = 0.75 * (1.0 - c_e**2)

    def rhs(_t, y):
        x = max(y[0], 0.0)
        return [y[1], -(x**1.5) * (1.0 + damping * y[1])]

    def separated(_t, y):
        return y[0]

    separated.terminal = True
    separated.direction = -1
    sol = solve_ivp(rhs, (0.0, 10.0), [1e-12, 1.0], events=separated, rtol=1e-12, atol=1e-15)
    return -float(sol.y_events[0][0][1])


def test_grazing_contact_has_a_finite_force():
    # δ̇⁻ = 0 (resting or grazing contact): the guard bounds the damping term.
    fn, fel = lankarani_nikravesh(1e-6, 0.01, 0.0, 0.9)
    assert np.isfinite(fn) and fn > fel > 0
    assert fn == lankarani_nikravesh(1e-6, 0.01, 1e-4, 0.9)[0]

"""Contact force laws: stiffness from geometry and materials, Lankarani–Nikravesh
normal force with hysteresis damping, modified Coulomb friction.

Symbols: δ penetration (m), δ̇ its rate (m/s), δ̇⁻ the rate at the onset of the
current contact, c_e the coefficient of restitution, K the contact stiffness,
n the force exponent (1.5 for Hertz), μ the friction coefficient, v_t the slip
velocity, v0 < v1 the friction tolerances of the modified Coulomb law.
"""

import math

from sim.jit import kernel


def effective_modulus(e1: float, nu1: float, e2: float, nu2: float) -> float:
    """E* with 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2, in Pa (Johnson, Contact Mechanics, 1985)."""
    return 1.0 / ((1.0 - nu1**2) / e1 + (1.0 - nu2**2) / e2)


def revolute_stiffness(r_bearing: float, r_journal: float, e_star: float) -> float:
    """Hertz stiffness K = (4/3) E* √(R_B R_J / (R_B − R_J)) of a journal in its
    bearing (two cylinders in internal contact), in N/m^1.5 (Lankarani & Nikravesh,
    J. Mech. Des. 112, 1990; the paper's eq. 6)."""
    if r_bearing <= r_journal:
        raise ValueError("revolute clearance stiffness needs R_B > R_J (clearance > 0)")
    return 4.0 / 3.0 * e_star * math.sqrt(r_bearing * r_journal / (r_bearing - r_journal))


def corner_stiffness(corner_radius: float, e_star: float) -> float:
    """Hertz stiffness K = (4/3) E* √R of a rounded slider corner (radius R, m)
    against a flat guide, in N/m^1.5 (the paper's eq. 18)."""
    return 4.0 / 3.0 * e_star * math.sqrt(corner_radius)


def face_stiffness(half_perimeter: float, e1: float, nu1: float, e2: float, nu2: float) -> float:
    """Linear stiffness K_T = a E1 E2 / (0.475 (E2 (1 − ν1²) + E1 (1 − ν2²))) of a
    slider face flat on the guide, a the half perimeter of the rectangular contact
    face (m), in N/m (the paper's eq. 16, after Flores et al. 2006)."""
    return half_perimeter * e1 * e2 / (0.475 * (e2 * (1.0 - nu1**2) + e1 * (1.0 - nu2**2)))


@kernel
def lankarani_nikravesh(
    stiffness: float,
    delta: float,
    rate: float,
    onset_rate: float,
    restitution: float,
    exponent: float,
    min_impact_speed: float,
) -> tuple[float, float]:
    """Normal force F = K δⁿ [1 + 3(1 − c_e²) δ̇ / (4 δ̇⁻)], never negative, and its
    elastic part K δⁿ (N). Zero for δ ≤ 0.

    Guard: δ̇⁻ is replaced by max(δ̇⁻, v_min). A resting or grazing contact has an
    onset rate near zero, where the law's damping coefficient grows without bound;
    below v_min (the scene's `contact.min_impact_speed`) the contact is treated as
    an impact at v_min, which bounds the damping and leaves real impacts untouched
    (Lankarani & Nikravesh, J. Mech. Des. 112, 1990, eq. 30)."""
    if delta <= 0.0:
        return 0.0, 0.0
    elastic = stiffness * delta**exponent
    v_ref = max(onset_rate, min_impact_speed)
    force = elastic * (1.0 + 0.75 * (1.0 - restitution * restitution) * rate / v_ref)
    return max(force, 0.0), elastic


@kernel
def coulomb_factor(slip_speed: float, v0: float, v1: float) -> float:
    """Correction c_d of the modified Coulomb law: 0 below v0, 1 above v1, linear
    between (Ambrósio, 2002; the paper's eq. 9). Removes the sign jump at v_t = 0."""
    if slip_speed <= v0:
        return 0.0
    if slip_speed >= v1:
        return 1.0
    return (slip_speed - v0) / (v1 - v0)


@kernel
def friction_force(normal_force: float, slip: float, mu: float, v0: float, v1: float) -> float:
    """Friction along the slip direction: F_t = −μ c_d(|v_t|) F_n sign(v_t), in N."""
    if slip == 0.0:
        return 0.0
    mag = mu * coulomb_factor(abs(slip), v0, v1) * normal_force
    return -mag if slip > 0.0 else mag

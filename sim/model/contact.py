"""Contact force laws: stiffness from geometry and materials, the normal force of every
damping law (`sim.model.contact_laws`), Johnson's conformal stiffness, modified Coulomb
friction.

Symbols: δ penetration (m), δ̇ its rate (m/s), δ̇⁻ the rate at the onset of the
current contact, c_e the coefficient of restitution, K the contact stiffness,
n the force exponent (1.5 for Hertz), μ the friction coefficient, v_t the slip
velocity, v0 < v1 the friction tolerances of the modified Coulomb law.
"""

import math

from sim.jit import kernel
from sim.model.contact_laws import MEMORYLESS

JOHNSON_ITERATIONS = 60
"""Most Newton steps of Johnson's law; it converges to 1e-15 in fewer than ten."""


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
def normal_force(
    law: int,
    damping: float,
    elastic: float,
    delta: float,
    rate: float,
    onset_rate: float,
    exponent: float,
    min_impact_speed: float,
) -> float:
    """Normal force (N) of damping law `law` (its code in `sim.model.contact_laws.LAWS`) on
    the elastic force `elastic` (N) at penetration δ > 0 (m) and rate δ̇ (m/s), never negative.

    With memory: F = F_el [1 + χ δ̇ / max(δ̇⁻, v_min)], χ = `damping` (Lankarani–Nikravesh,
    J. Mech. Des. 112, 1990, and the laws of the same form). Guard: a resting or grazing
    contact has an onset rate near zero, where the damping coefficient grows without bound;
    below v_min (the scene's `contact.min_impact_speed`) the contact is treated as an impact
    at v_min, which bounds the damping and leaves real impacts untouched.

    Without memory: F = F_el + c δ^((n−1)/2) δ̇, c = `damping` (N s / m^((n+1)/2)); the onset
    rate and v_min are unused (Tsuji, Tanaka & Ishida, Powder Technol. 71, 1992)."""
    if MEMORYLESS[law]:
        return max(elastic + damping * delta ** (0.5 * (exponent - 1.0)) * rate, 0.0)
    v_ref = max(onset_rate, min_impact_speed)
    force = elastic * (1.0 + damping * rate / v_ref)
    return max(force, 0.0)


@kernel
def johnson_elastic(line_stiffness: float, clearance: float, delta: float) -> tuple[float, float]:
    """Elastic force F (N) and energy U (J) of Johnson's conformal cylinder law at
    penetration δ > 0 (m): δ = s [ln(4ΔR/s) − 1], s = F/(π L E*), ΔR the radial clearance (m),
    π L E* = `line_stiffness` (N/m); U = π L E* s² [ln(4ΔR/s)/2 − 3/4] (Johnson, Contact
    Mechanics, 1985, §5.6). Solved by Newton's method kept inside its bracket. The law holds
    up to s_lim = 4ΔR/e³, where dF/dδ = π L E*; deeper, F continues linearly with that slope."""
    s_lim = 4.0 * clearance * math.exp(-3.0)
    d_lim = 2.0 * s_lim
    if delta >= d_lim:
        u_lim = line_stiffness * s_lim * s_lim * 0.75
        extra = delta - d_lim
        force = line_stiffness * (s_lim + extra)
        return force, u_lim + line_stiffness * (s_lim * extra + 0.5 * extra * extra)
    lo = 0.0
    hi = s_lim
    s = 0.5 * s_lim
    for _ in range(JOHNSON_ITERATIONS):
        log_ratio = math.log(4.0 * clearance / s)
        residual = s * (log_ratio - 1.0) - delta
        if residual > 0.0:
            hi = s
        else:
            lo = s
        step = s - residual / (log_ratio - 2.0)
        s_next = step if lo < step < hi else 0.5 * (lo + hi)
        if abs(s_next - s) <= 1e-15 * s:
            s = s_next
            break
        s = s_next
    log_ratio = math.log(4.0 * clearance / s)
    return line_stiffness * s, line_stiffness * s * s * (0.5 * log_ratio - 0.75)


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

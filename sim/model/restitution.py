"""The restitution a damping law achieves: one free central impact of a point mass on a Hertz
half-space, driven by the engine's own compiled normal force (`sim.model.contact.normal_force`).

A mass m reaches the surface at speed v; its penetration δ obeys m δ̈ = −F(δ, δ̇, δ̇⁻ = v) with
the elastic force K δ^(3/2) and the law's damping (`sim.model.contact_laws`), from δ = 0,
δ̇ = v until δ returns to 0 at the rate −e_eff v. The laws with memory give e_eff as a function
of e and v / v_min alone (v_min the damping guard, `contact.min_impact_speed`); the law without
memory a function of e alone. m and K only set the impact's scales; the integration runs in
them (length (m v²/K)^(2/5), time that over v) with a tight tolerance.
"""

from scipy.integrate import solve_ivp

from sim.model.contact import normal_force
from sim.model.contact_laws import LAW_CODES, damping_coefficient
from sim.scene_keys import CONTACT, Field

HERTZ_EXPONENT = 1.5
MASS = 1.0
"""kg: the impacting mass (sets the scales only)."""
STIFFNESS = 1.0e10
"""N/m^1.5: the half-space's Hertz stiffness, a steel sphere of 10 mm radius (sets the scales
only)."""
MIN_IMPACT_SPEED: float = CONTACT["min_impact_speed"].default
"""m/s: the damping guard v_min, the scenes' default."""
NOMINAL = CONTACT["restitution"]
"""What a nominal restitution accepts: the scene key's range, 0 < e ≤ 1."""
SPEED = Field("number", 0.0, open_min=True, unit="m/s")
"""What an impact speed accepts: above 0."""


def effective_restitution(law: str, nominal: float, speed: float) -> float:
    """e_eff = −δ̇_out / v of one impact at speed v (m/s) under damping law `law` with
    nominal restitution e (`nominal`), by the engine's compiled normal force."""
    code = LAW_CODES[law]
    damping = damping_coefficient(law, nominal, HERTZ_EXPONENT, MASS, STIFFNESS)
    length = (MASS * speed**2 / STIFFNESS) ** (1.0 / (HERTZ_EXPONENT + 1.0))
    time = length / speed
    scale = time * time / (MASS * length)  # force (N) → dimensionless acceleration

    def rhs(_t: float, y: list[float]) -> list[float]:
        delta = y[0] * length
        if delta <= 0.0:
            return [y[1], 0.0]
        elastic = STIFFNESS * delta**HERTZ_EXPONENT
        force = normal_force(
            code,
            damping,
            elastic,
            delta,
            y[1] * speed,
            speed,
            HERTZ_EXPONENT,
            MIN_IMPACT_SPEED,
        )
        return [y[1], -force * scale]

    def leaves(_t: float, y: list[float]) -> float:
        return y[0]

    leaves.terminal, leaves.direction = True, -1.0
    sol = solve_ivp(rhs, (0.0, 1e3), [0.0, 1.0], "DOP853", events=leaves, rtol=1e-10, atol=1e-13)
    if not sol.t_events[0].size:
        return 0.0  # the mass came to rest inside the surface: no rebound
    return -float(sol.y_events[0][0][1])

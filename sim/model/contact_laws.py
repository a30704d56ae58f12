"""The contact laws a clearance joint can take, declared once: the damping laws (`LAWS`) and
the stiffness laws of a revolute clearance (`STIFFNESS_LAWS`), each with its code, the formula
and its source. The compiled force (`sim.model.contact.normal_force`) reads a joint's law code
and its damping coefficient from the joint's data (`sim.model.system.REVOLUTE_CLEARANCE`,
`TRANSLATIONAL_CLEARANCE`); the coefficient is computed once, at assembly, by the law's
`coefficient`.

Symbols: δ penetration (m), δ̇ its rate (m/s), δ̇⁻ the rate at the onset of the current contact
(m/s), v_min the damping guard (`contact.min_impact_speed`, m/s), e the nominal coefficient of
restitution, K the contact stiffness, n the force exponent, m* the contact's effective mass
(kg).

Every law with memory has the form F = max(0, K δⁿ [1 + χ(e) δ̇ / max(δ̇⁻, v_min)]) and differs
only in χ(e). The law without memory has the form F = max(0, K δⁿ + c δ^((n−1)/2) δ̇) with
c = ζ(e, n) √(m* K): scaling δ by the impact's own length and t by its time reduces the impact
to x'' = −max(0, xⁿ + ζ x^((n−1)/2) x'), x(0) = 0, x'(0) = 1, which holds no speed, so the
restitution depends on ζ and n alone (Kuwabara & Kono, Jpn. J. Appl. Phys. 26, 1987; Tsuji,
Tanaka & Ishida, Powder Technol. 71, 1992, for n = 3/2). ζ(e, n) is that dimensionless
problem's exact inverse, solved numerically (`memoryless_damping_ratio`).
"""

import math
from collections.abc import Callable
from functools import cache
from typing import NamedTuple


class Law(NamedTuple):
    """One damping law: its scene name, whether its damping remembers δ̇⁻, its coefficient
    from (e, n) (χ for a law with memory, ζ for one without), the formula and its source."""

    name: str
    memory: bool
    coefficient: Callable[[float, float], float]
    formula: str
    source: str
    validity: str


def _lankarani_nikravesh(e: float, n: float) -> float:
    """χ = 3(1 − e²)/4."""
    return 0.75 * (1.0 - e * e)


def _hunt_crossley(e: float, n: float) -> float:
    """χ = 3(1 − e)/2."""
    return 1.5 * (1.0 - e)


def _flores(e: float, n: float) -> float:
    """χ = 8(1 − e)/(5e)."""
    return 8.0 * (1.0 - e) / (5.0 * e)


def _gonthier_carvalho(e: float, n: float) -> float:
    """χ = 3(1 − e)(11 − e)/(2(1 + 9e)) for e > 1/3, (1 − e²)/e below; equal at e = 1/3."""
    if e > 1.0 / 3.0:
        return 1.5 * (1.0 - e) * (11.0 - e) / (1.0 + 9.0 * e)
    return (1.0 - e * e) / e


def _dimensionless_restitution(zeta: float, n: float) -> float:
    """Restitution of x'' = −max(0, xⁿ + ζ x^((n−1)/2) x') from x = 0, x' = 1 (the law
    without memory in its own units): −x' when x returns to 0."""

    def rhs(_t: float, y: list[float]) -> list[float]:
        x = max(y[0], 0.0)
        return [y[1], -max(0.0, x**n + zeta * x ** (0.5 * (n - 1.0)) * y[1])]

    def leaves(_t: float, y: list[float]) -> float:
        return y[0]

    # scipy is imported where a law without memory needs it, not with this module, which every
    # run imports: scipy.integrate and scipy.optimize take half a second of each `sim` start
    from scipy.integrate import solve_ivp

    leaves.terminal, leaves.direction = True, -1.0
    sol = solve_ivp(rhs, (0.0, 1e3), [0.0, 1.0], "DOP853", events=leaves, rtol=1e-11, atol=1e-13)
    return -float(sol.y_events[0][0][1])


@cache
def memoryless_damping_ratio(e: float, n: float) -> float:
    """ζ(e, n) of the law without memory: the dimensionless damping whose impact restitutes
    e (`_dimensionless_restitution`), 0 at e = 1."""
    if e >= 1.0:
        return 0.0
    from scipy.optimize import brentq  # here, as solve_ivp in `_dimensionless_restitution`

    hi = 1.0
    while _dimensionless_restitution(hi, n) > e:
        hi *= 4.0
    return brentq(lambda z: _dimensionless_restitution(z, n) - e, 0.0, hi, xtol=1e-12, rtol=1e-10)


def _tsuji(e: float, n: float) -> float:
    """ζ(e, n), the dimensionless damping of the law without memory."""
    return memoryless_damping_ratio(e, n)


MEMORY_FORM = "F = max(0, K δⁿ [1 + χ δ̇ / max(δ̇⁻, v_min)])"

#: The damping laws by code (a law's code is its index).
LAWS: tuple[Law, ...] = (
    Law(
        "lankarani-nikravesh",
        True,
        _lankarani_nikravesh,
        "χ = 3(1 − e²)/4",
        "Lankarani & Nikravesh, J. Mech. Des. 112 (1990) 369",
        "e close to 1 (energy balance of a slightly damped Hertz impact); the paper's law",
    ),
    Law(
        "hunt-crossley",
        True,
        _hunt_crossley,
        "χ = 3(1 − e)/2",
        "Hunt & Crossley, J. Appl. Mech. 42 (1975) 440",
        "e close to 1 (linearised in 1 − e)",
    ),
    Law(
        "flores",
        True,
        _flores,
        "χ = 8(1 − e)/(5e)",
        "Flores, Machado, Silva & Martins, Multibody Syst. Dyn. 25 (2011) 357",
        "the whole range 0 < e ≤ 1 (fitted to the exact impact), best at low and high e",
    ),
    Law(
        "gonthier-carvalho",
        True,
        _gonthier_carvalho,
        "χ = 3(1 − e)(11 − e)/(2(1 + 9e)) for e > 1/3; χ = (1 − e²)/e for e ≤ 1/3",
        "Carvalho & Martins, Mech. Mach. Theory 134 (2019) 14, above e = 1/3; Gonthier, McPhee, "
        "Lange & Piedbœuf, Multibody Syst. Dyn. 11 (2004) 209, below (Exudyn's impactModel 2)",
        "the whole range 0 < e ≤ 1",
    ),
    Law(
        "tsuji",
        False,
        _tsuji,
        "F = max(0, K δⁿ + ζ(e, n) √(m* K) δ^((n−1)/2) δ̇), no memory",
        "Tsuji, Tanaka & Ishida, Powder Technol. 71 (1992) 239 (n = 3/2: damping ∝ δ^(1/4) δ̇); "
        "Kuwabara & Kono, Jpn. J. Appl. Phys. 26 (1987) 1230",
        "0 < e ≤ 1 at every impact speed (ζ is the exact inverse); needs a power-law stiffness",
    ),
)
LAW_CODES: dict[str, int] = {law.name: code for code, law in enumerate(LAWS)}
LAW_NAMES: tuple[str, ...] = tuple(LAW_CODES)
DEFAULT_LAW = "lankarani-nikravesh"
#: per law code: True for a law without memory (compiled dispatch, `normal_force`)
MEMORYLESS: tuple[bool, ...] = tuple(not law.memory for law in LAWS)


def damping_coefficient(
    name: str, restitution: float, exponent: float, mass: float, stiffness: float
) -> float:
    """The damping coefficient a joint stores for law `name`: χ(e) for a law with memory,
    c = ζ(e, n) √(m* K) (N s / m^((n+1)/2)) for one without (mass m* in kg, stiffness K)."""
    law = LAWS[LAW_CODES[name]]
    value = law.coefficient(restitution, exponent)
    return value if law.memory else value * math.sqrt(mass * stiffness)


class StiffnessLaw(NamedTuple):
    """One stiffness law of a revolute clearance: its scene name, formula and source."""

    name: str
    formula: str
    source: str
    validity: str


#: The stiffness laws of a revolute clearance by code.
STIFFNESS_LAWS: tuple[StiffnessLaw, ...] = (
    StiffnessLaw(
        "hertz",
        "F = K δⁿ, K = (4/3) E* √(R_B R_J / (R_B − R_J))",
        "Lankarani & Nikravesh, J. Mech. Des. 112 (1990); the paper's eq. 6",
        "point contact of spheres of the joint's radii; the paper's law",
    ),
    StiffnessLaw(
        "johnson",
        "δ = (F / (π L E*)) [ln(4 π L E* ΔR / F) − 1], ΔR = R_B − R_J, solved for F",
        "Johnson, Contact Mechanics (1985) §5.6; in clearance joints: Pereira, Ramalho & "
        "Ambrósio, Nonlinear Dyn. 63 (2011) 681",
        "conformal line contact of cylinders of axial length L (`bearing_length`); the law "
        "holds while ln(4ΔR/s) > 3, s = F/(πLE*) (δ < 8ΔR/e³ ≈ 0.4 ΔR); beyond, the force "
        "continues linearly with the slope π L E* it has there",
    ),
)
STIFFNESS_CODES: dict[str, int] = {law.name: code for code, law in enumerate(STIFFNESS_LAWS)}
STIFFNESS_HERTZ, STIFFNESS_JOHNSON = STIFFNESS_CODES["hertz"], STIFFNESS_CODES["johnson"]
DEFAULT_STIFFNESS = "hertz"

"""The oil film of a lubricated revolute clearance joint: the hydrodynamic force of a
dynamically loaded journal bearing and its hand-over to the joint's dry contact law.

Symbols: R the journal radius, L the bearing length, D = 2R, c the radial clearance (m);
μ the oil's dynamic viscosity (Pa·s); e = r_J − r_B the eccentricity, ε = |e|/c, n = e/|e|,
t = k × n; ψ the angle around the bearing from n towards t, the film thickness
h = c H, H = 1 − ε cos ψ (thinnest at ψ = 0); ω_J, ω_B the journal's and the bearing's angular
velocities, ω̄ = (ω_J + ω_B)/2.

Squeeze and wedge in one: in the frame turning at ω̄ both surfaces slide at equal and
opposite speeds, so the wedge term of Reynolds' equation vanishes and the film sees a
pure squeeze at the relative velocity V = ė − ω̄ k × e; its radial part V_r = c ε̇ is the
squeeze term, its tangential part V_t = c ε (φ̇ − ω̄) carries the wedge term
(Frêne et al., Hydrodynamic Lubrication, Elsevier 1997, ch. 8; Flores, Ambrósio, Claro &
Lankarani, Mech. Mach. Theory 41, 2006, and Kinematics and Dynamics of Multibody Systems
with Imperfect Joints, Springer 2008, ch. 6). The angular velocities come from the bodies
(a beam node's from its slope). The film force F acts on the journal at its centre, −F on
the bearing at its centre, and each body takes the moment −(e × F)/2, that of the pressure's
Poiseuille shear on its surface (the two balance the couple of ±F): the film's power into
the bodies, F·ė − ω̄ (e × F)·k, is exactly F·V.

Cavitation: half-Sommerfeld (Gümbel), the film carries no negative pressure,
p = max(p_full, 0). With it F·V ≤ 0 in every model below: the film only dissipates; the
energy audit books −F·V as dissipated power. The viscous (Couette) shear torque of the
film, which is dissipative too, is neglected, as by Flores et al.

Models by L/D (`bearing_model`):
- short bearing (Ocvirk; Frêne et al. §8.3), L/D ≤ SHORT_MAX: p = 6μ (L²/4 − z²) (V·n_ψ)/h³;
  p > 0 on exactly the half circle facing V, so the Gümbel film is the π-film
  |ψ − α| < π/2, α the angle of V from n, integrated in closed form;
- long bearing (Sommerfeld; Pinkus & Sternlicht, Theory of Hydrodynamic Lubrication,
  McGraw-Hill 1961, ch. 4), L/D ≥ LONG_MIN: the full-film pressure of
  d/dψ (H³ dp/dψ) = −(12 μ R²/c³) (V_r cos ψ + V_t sin ψ), periodic, zero at the thickest
  film ψ = π (the oil supply), in closed form; its positive part integrated by the
  trapezoid rule on LONG_NODES points of the Sommerfeld angle γ, which gathers them where
  the film is thin;
- finite bearing, SHORT_MAX < L/D < LONG_MIN: Reynolds' equation in ψ and z with the
  pressure zero at the bearing's ends, solved once by finite volumes for a table of L/D, ε
  and the direction α of V (sim.model.finite_bearing, stored in finite_bearing.npz), its
  Gümbel force G interpolated: as a power of L/D between its neighbours when the system is
  built, in the kernel linearly in ln(1/(1 − ε)) and as a cos α + b sin α in α;
  F = −(12 μ R⁴/c³) |V| G.

The short and long bearings' integrals with the Sommerfeld substitution
cos γ = (cos ψ − ε)/(1 − ε cos ψ), which turns dψ/H³ into (1 + ε cos γ)² dγ/(1 − ε²)^(5/2)
and every integrand below into a trigonometric polynomial of γ.

Transition to contact (docs/model.md, "Lubricated revolute joints"): below the threshold
film thickness h_t the asperities carry a growing share of the load. The film force is
evaluated at ε_f = min(ε, ε_t), ε_t = 1 − h_t/c, and weighted by
w = s²(3 − 2s), s = clip(h/h_t, 0, 1), h = c(1 − ε): w = 1 above h_t, w = 0 at h = 0, where
the dry law, zero at zero penetration, acts alone. The force is continuous everywhere, and
w ≥ 0 times a dissipative force dissipates: no energy is created at the hand-over.
"""

import functools
import math
from pathlib import Path

import numpy as np

from sim.jit import kernel, kernel_inline
from sim.model.kinematics import apply_point_force_rotated, point_velocity_rotated
from sim.model.system import POINT_GROUND, POINT_NODE

BEARING_DRY, BEARING_SHORT, BEARING_LONG, BEARING_FINITE = 0, 1, 2, 3
SHORT_MAX = 0.5
"""Largest L/D of the short-bearing model: its force is within about 10 % of the finite
bearing's up to L/D = 0.5 at moderate ε, better below 0.25 (Frêne et al. §8.3)."""
LONG_MIN = 2.0
"""Smallest L/D of the long-bearing model (Pinkus & Sternlicht ch. 4: side leakage
negligible from about L/D = 2)."""
LONG_NODES = 128
"""Trapezoid points of the long bearing's force integral over the Sommerfeld angle: the
steady forces within 1e-4 of the closed form of Pinkus & Sternlicht (tests/model/
test_lubrication.py)."""

FINITE_RATIOS = tuple(SHORT_MAX * (LONG_MIN / SHORT_MAX) ** (k / 12) for k in range(13))
"""L/D of the finite bearing's table: 13, geometric from SHORT_MAX to LONG_MIN (steps of
12 %), between which the table is interpolated as a power of L/D."""
FINITE_ECCENTRICITY_MAX = 0.9995
"""Largest ε of the table: a film threshold of 5e-4 of the clearance."""
FINITE_ECCENTRICITIES = 77
"""ε of the table, uniform in u = ln(1/(1 − ε)) from 0 to that of FINITE_ECCENTRICITY_MAX
(steps of 0.1)."""
FINITE_ANGLES = 72
"""Angles α of V from n in the table, uniform from −π, every 5°."""
FINITE_STEP_U = -math.log(1.0 - FINITE_ECCENTRICITY_MAX) / (FINITE_ECCENTRICITIES - 1)
FINITE_STEP_ANGLE = 2.0 * math.pi / FINITE_ANGLES
FINITE_TABLE = Path(__file__).with_name("finite_bearing.npz")
"""The table, written by `python -m sim.model.finite_bearing`."""

FILM = np.dtype(
    [
        ("bearing", np.int64),  # BEARING_DRY, _SHORT, _LONG or _FINITE
        ("viscosity", np.float64),  # μ, Pa·s
        ("length", np.float64),  # L, m
        ("threshold", np.float64),  # h_t, m
    ],
    align=True,
)


def bearing_model(length: float, journal_radius: float) -> int:
    """BEARING_SHORT, BEARING_FINITE or BEARING_LONG for a bearing of length L (m) on a
    journal of radius R (m), by L/D."""
    ratio = length / (2.0 * journal_radius)
    if ratio <= SHORT_MAX:
        return BEARING_SHORT
    if ratio >= LONG_MIN:
        return BEARING_LONG
    return BEARING_FINITE


@functools.cache
def _finite_table() -> tuple[np.ndarray, np.ndarray]:
    """The stored table G (1 − ε²)² (L/D × ε × α × (n, t)) and its L/D; ValueError if its grid
    is not the one declared here."""
    stored = np.load(FINITE_TABLE)
    table = stored["table"]
    if table.shape[1:] != (FINITE_ECCENTRICITIES, FINITE_ANGLES, 2) or not np.allclose(
        stored["ratios"], FINITE_RATIOS
    ):
        raise ValueError(
            f"{FINITE_TABLE} does not match sim.model.lubrication's grid: "
            "regenerate it with `python -m sim.model.finite_bearing`"
        )
    return table, stored["ratios"]


def film_tables(films: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """The finite bearing's table at each joint's L/D (a power of L/D between the stored ones),
    for
    the joints' FILM rows `films` and journal radii (m); shape (joints, ε, α, 2), a single
    zero entry per joint when no joint is a finite bearing."""
    finite = films["bearing"] == BEARING_FINITE
    if not finite.any():
        return np.zeros((len(films), 1, 1, 2))
    table, ratios = _finite_table()
    out = np.zeros((len(films), *table.shape[1:]))
    for j in np.flatnonzero(finite):
        ratio = films["length"][j] / (2.0 * radii[j])
        k = min(int(np.searchsorted(ratios, ratio)), len(ratios) - 1)
        w = math.log(ratio / ratios[k - 1]) / math.log(ratios[k] / ratios[k - 1])
        low, high = table[k - 1], table[k]
        # a power of λ between neighbours (λ³ for a short bearing, λ for a long one);
        # linear where a component changes sign
        same = low * high > 0.0
        power = np.abs(low) ** (1.0 - w) * np.abs(high) ** w * np.sign(low)
        out[j] = np.where(same, power, (1.0 - w) * low + w * high)
    return out


def film_parameters(lubricant: dict | None, journal_radius: float) -> tuple:
    """The FILM row of a joint's `lubricant` block (sim.scene_keys.LUBRICANT); a dry row for
    None."""
    if lubricant is None:
        return (BEARING_DRY, 0.0, 0.0, 0.0)
    return (
        bearing_model(lubricant["length"], journal_radius),
        lubricant["viscosity"],
        lubricant["length"],
        lubricant["threshold"],
    )


@kernel_inline
def sommerfeld_angle(psi: float, eps: float) -> float:
    """γ(ψ) with tan(γ/2) = k tan(ψ/2), k = √((1 + ε)/(1 − ε)), continuous in ψ:
    γ = ψ + 2 atan((k − 1) sin ψ / ((k + 1) − (k − 1) cos ψ))."""
    k = math.sqrt((1.0 + eps) / (1.0 - eps))
    return psi + 2.0 * math.atan(
        (k - 1.0) * math.sin(psi) / ((k + 1.0) - (k - 1.0) * math.cos(psi))
    )


@kernel_inline
def short_bearing_force(
    eps: float, vr: float, vt: float, mu: float, radius: float, length: float, c: float
) -> tuple[float, float]:
    """Film force (F_n, F_t) (N) on the journal of a short bearing, π-film facing V:
    F = −(μ R L³/c³) ∫ n_ψ n_ψᵀ V dψ / H³ over |ψ − α| < π/2."""
    speed = math.hypot(vr, vt)
    if speed == 0.0:
        return 0.0, 0.0
    alpha = math.atan2(vt, vr)
    g1 = sommerfeld_angle(alpha - 0.5 * math.pi, eps)
    g2 = sommerfeld_angle(alpha + 0.5 * math.pi, eps)
    s = 1.0 - eps * eps
    # ∫ cos²ψ/H³, ∫ sin ψ cos ψ/H³, ∫ sin²ψ/H³ over the film, by their antiderivatives in γ
    cc = _cos2(g2, eps) - _cos2(g1, eps)
    sc = (0.5 * math.sin(g2) ** 2 - eps * math.cos(g2)) - (
        0.5 * math.sin(g1) ** 2 - eps * math.cos(g1)
    )
    ss = (0.5 * (g2 - g1) - 0.25 * (math.sin(2.0 * g2) - math.sin(2.0 * g1))) / s**1.5
    cc /= s**2.5
    sc /= s * s
    scale = mu * radius * length**3 / c**3
    return -scale * (cc * vr + sc * vt), -scale * (sc * vr + ss * vt)


@kernel_inline
def _cos2(g: float, eps: float) -> float:
    """∫ (cos γ + ε)² dγ."""
    return 0.5 * g + 0.25 * math.sin(2.0 * g) + 2.0 * eps * math.sin(g) + eps * eps * g


_GAMMA = -math.pi + (np.arange(LONG_NODES) + 0.5) * (2.0 * math.pi / LONG_NODES)
"""The long bearing's trapezoid points of the Sommerfeld angle γ, with their cos γ, sin γ and
sin 2γ, once: the kernel's integral then computes no trigonometric function."""
_COS_GAMMA = np.cos(_GAMMA)
_SIN_GAMMA = np.sin(_GAMMA)
_SIN_2GAMMA = np.sin(2.0 * _GAMMA)


@kernel_inline
def long_bearing_pressure(
    gamma: float, cg: float, sg: float, s2g: float, eps: float, vr: float, vt: float
) -> float:
    """Full-film pressure of the long bearing at Sommerfeld angle γ ∈ [−π, π] (cos γ, sin γ,
    sin 2γ given), in units of 12 μ R²/c³ (m/s): p(ψ) = ∫_π^ψ (−V_r sin ψ + V_t cos ψ + C)
    dψ/H³, C = −3 ε V_t/(2 + ε²) for periodicity."""
    s = 1.0 - eps * eps
    h = s / (1.0 + eps * cg)  # H at this γ
    cos_psi = (cg + eps) / (1.0 + eps * cg)
    # −V_r ∫ sin ψ/H³ = V_r [1/(2εH²)]_π^ψ, written without the division by ε
    squeeze = vr * (1.0 + cos_psi) * (1.0 + eps + h) / (2.0 * h * h * (1.0 + eps) ** 2)
    a = (1.0 + eps * eps) * sg + 1.5 * eps * (gamma - math.pi) + 0.25 * eps * s2g
    b = (1.0 + 0.5 * eps * eps) * (gamma - math.pi) + 2.0 * eps * sg + 0.25 * eps * eps * s2g
    return squeeze + vt * (a - 3.0 * eps / (2.0 + eps * eps) * b) / s**2.5


@kernel_inline
def long_bearing_force(
    eps: float, vr: float, vt: float, mu: float, radius: float, length: float, c: float
) -> tuple[float, float]:
    """Film force (F_n, F_t) (N) on the journal of a long bearing, half-Sommerfeld:
    F = −R L ∫ max(p, 0) n_ψ dψ, dψ = H dγ/√(1 − ε²), n_ψ = (cos ψ, sin ψ) =
    (cos γ + ε, √(1 − ε²) sin γ)/(1 + ε cos γ)."""
    s = 1.0 - eps * eps
    root = math.sqrt(s)
    fn = 0.0
    ft = 0.0
    for i in range(LONG_NODES):
        cg = _COS_GAMMA[i]
        sg = _SIN_GAMMA[i]
        p = long_bearing_pressure(_GAMMA[i], cg, sg, _SIN_2GAMMA[i], eps, vr, vt)
        if p <= 0.0:
            continue
        k = 1.0 + eps * cg
        weight = p * s / (k * k)  # p H/(1 + ε cos γ)
        fn += weight * (cg + eps)
        ft += weight * root * sg
    scale = -12.0 * mu * radius**3 * length / c**3 * (2.0 * math.pi / LONG_NODES) / root
    return scale * fn, scale * ft


@kernel_inline
def finite_bearing_force(
    table: np.ndarray, eps: float, vr: float, vt: float, mu: float, radius: float, c: float
) -> tuple[float, float]:
    """Film force (F_n, F_t) (N) on the journal of a finite bearing whose table
    G (1 − ε²)² (ε × α × (n, t), `film_tables`) is given: F = −(12 μ R⁴/c³) |V| G(ε, α),
    linear in u = ln(1/(1 − ε)), harmonic in α (`_bilinear`)."""
    speed = math.hypot(vr, vt)
    if speed == 0.0:
        return 0.0, 0.0
    x = min(-math.log(1.0 - eps) / FINITE_STEP_U, FINITE_ECCENTRICITIES - 1.0 - 1e-9)
    i = int(x)
    fx = x - i
    y = (math.atan2(vt, vr) + math.pi) / FINITE_STEP_ANGLE
    k = int(y) % FINITE_ANGLES
    fy = y - int(y)
    scale = -12.0 * mu * radius**4 / c**3 * speed / (1.0 - eps * eps) ** 2
    return (
        scale * _bilinear(table, i, k, fx, fy, 0),
        scale * _bilinear(table, i, k, fx, fy, 1),
    )


@kernel_inline
def _bilinear(table: np.ndarray, i: int, k: int, fx: float, fy: float, m: int) -> float:
    """Component m of `table` between ε rows i, i + 1 (linear, fraction fx) and angle columns
    k, k + 1 (periodic, fraction fy) as a cos α + b sin α through both columns: exact where the
    film's positive part keeps its place, since the pressure is linear in V."""
    k1 = (k + 1) % FINITE_ANGLES
    wk = math.sin((1.0 - fy) * FINITE_STEP_ANGLE) / math.sin(FINITE_STEP_ANGLE)
    wk1 = math.sin(fy * FINITE_STEP_ANGLE) / math.sin(FINITE_STEP_ANGLE)
    low = wk * table[i, k, m] + wk1 * table[i, k1, m]
    high = wk * table[i + 1, k, m] + wk1 * table[i + 1, k1, m]
    return (1.0 - fx) * low + fx * high


@kernel_inline
def film_weight(h: float, threshold: float) -> float:
    """Share w of the film in the load at minimum film thickness h (m): 1 above the threshold
    h_t, smoothstep s²(3 − 2s), s = h/h_t, below it, 0 at contact."""
    s = min(max(h / threshold, 0.0), 1.0)
    return s * s * (3.0 - 2.0 * s)


@kernel_inline
def film_force(sys, j: int, eps: float, vr: float, vt: float) -> tuple[float, float]:
    """The film force (F_n, F_t) (N) on the journal of lubricated revolute clearance j at
    eccentricity ratio ε and relative velocity (V_r, V_t) (m/s), with the hand-over to the
    dry law below the threshold (module docstring)."""
    film = sys.rj_film[j]
    c = sys.rj[j].clearance
    eps_f = min(eps, 1.0 - film.threshold / c)
    w = film_weight(c * (1.0 - eps), film.threshold)
    if w == 0.0:
        return 0.0, 0.0
    r = sys.rj[j].journal_radius
    if film.bearing == BEARING_SHORT:
        fn, ft = short_bearing_force(eps_f, vr, vt, film.viscosity, r, film.length, c)
    elif film.bearing == BEARING_LONG:
        fn, ft = long_bearing_force(eps_f, vr, vt, film.viscosity, r, film.length, c)
    else:
        fn, ft = finite_bearing_force(sys.rj_film_table[j], eps_f, vr, vt, film.viscosity, r, c)
    return w * fn, w * ft


@kernel_inline
def point_spin(sys, k: int, q: np.ndarray, qd: np.ndarray) -> float:
    """Angular velocity (rad/s) of the body at point k: its frame's for a rigid body or modal
    link, the slope's θ̇ = (r_x' ṙ_y' − r_y' ṙ_x')/|r'|² at a beam node, 0 on the ground."""
    kind = sys.pt_kind[k]
    o = sys.pt_off[k]
    if kind == POINT_GROUND:
        return 0.0
    if kind == POINT_NODE:
        sx = q[o + 2]
        sy = q[o + 3]
        return (sx * qd[o + 3] - sy * qd[o + 2]) / (sx * sx + sy * sy)
    return qd[o + 2]


@kernel_inline
def apply_point_torque(sys, k: int, q: np.ndarray, torque: float, gen: np.ndarray) -> None:
    """Add the generalized force of a torque (N·m) on the body at point k to `gen`: on its
    angle, or at a beam node on its slope through ∂θ/∂r' = (−r_y', r_x')/|r'|²."""
    kind = sys.pt_kind[k]
    o = sys.pt_off[k]
    if kind == POINT_GROUND:
        return
    if kind == POINT_NODE:
        sx = q[o + 2]
        sy = q[o + 3]
        scale = torque / (sx * sx + sy * sy)
        gen[o + 2] -= scale * sy
        gen[o + 3] += scale * sx
        return
    gen[o + 2] += torque


@kernel
def lubricated_joint(
    sys,
    j: int,
    q: np.ndarray,
    qd: np.ndarray,
    gen: np.ndarray,
    ex: float,
    ey: float,
    cb: float,
    sb: float,
    cj: float,
    sj: float,
) -> tuple[float, float, float]:
    """Apply the film force F of revolute clearance j at the journal's centre, −F at the
    bearing's, and the moment −(e × F)/2 on each body (module docstring); return the radial
    force on the journal towards the centre and the tangential force (N), and the power the
    film dissipates, −F·V (W). (ex, ey): the eccentricity (m); (c, s): the bearing's and the
    journal's cos θ, sin θ."""
    pb = sys.rj_pts[j, 0]
    pj = sys.rj_pts[j, 1]
    e = math.hypot(ex, ey)
    nx, ny = (ex / e, ey / e) if e > 0.0 else (1.0, 0.0)
    vjx, vjy = point_velocity_rotated(sys, pj, q, qd, 0.0, 0.0, cj, sj)
    vbx, vby = point_velocity_rotated(sys, pb, q, qd, 0.0, 0.0, cb, sb)
    spin = 0.5 * (point_spin(sys, pj, q, qd) + point_spin(sys, pb, q, qd))
    vx = vjx - vbx + spin * ey  # V = ė − ω̄ k × e
    vy = vjy - vby - spin * ex
    vr = vx * nx + vy * ny
    vt = -vx * ny + vy * nx
    fn, ft = film_force(sys, j, e / sys.rj[j].clearance, vr, vt)
    fx = fn * nx - ft * ny
    fy = fn * ny + ft * nx
    moment = -0.5 * (ex * fy - ey * fx)
    apply_point_force_rotated(sys, pj, q, fx, fy, 0.0, 0.0, gen, cj, sj)
    apply_point_force_rotated(sys, pb, q, -fx, -fy, 0.0, 0.0, gen, cb, sb)
    apply_point_torque(sys, pj, q, moment, gen)
    apply_point_torque(sys, pb, q, moment, gen)
    return -fn, ft, -(fx * vx + fy * vy)

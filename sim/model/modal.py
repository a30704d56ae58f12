"""Reduced flexible links (`bodies.<name>.kind: modal`): a floating frame of reference in
mean axes carrying a few free–free Euler–Bernoulli bending modes and, optionally, free–free
axial modes.

Coordinates of a modal link: (x, y, θ) of its frame, whose origin is the centre of mass and
whose x axis lies along the undeformed link, then k bending amplitudes q_1…q_k and a axial
amplitudes p_1…p_a (kg^½ m: the modes are mass-normalised). The material point at
body-frame (x̄, ȳ) is at

    r = R + A(θ) (x̄ − ȳ Σ ψ_k′(x̄) q_k + Σ χ_n(x̄) p_n,  ȳ + Σ ψ_k(x̄) q_k)

(the section stays normal to the deflected axis). The free–free bending modes of a uniform
beam,
ξ = x̄ + L/2 ∈ [0, L] measured from the link's start,

    φ_k(ξ) = cosh β_k ξ + cos β_k ξ − σ_k (sinh β_k ξ + sin β_k ξ),
    σ_k = (cosh β_k L − cos β_k L) / (sinh β_k L − sin β_k L),
    β_k L = 4.7300408, 7.8532046, 10.9956078, 14.1371655,   ω_k = β_k² √(EI/ρA),

scaled to ψ_k with ∫ ρA ψ_k ψ_l dx = δ_kl, satisfy the mean-axis (Tisserand/Buckens)
conditions ∫ ρA ψ_k dx = 0 and ∫ ρA x̄ ψ_k dx = 0 exactly (Blevins, Formulas for Natural
Frequency and Mode Shape, 1979, table 8-1; Shabana, Dynamics of Multibody Systems, 3rd ed.,
2005, ch. 5; Canavin & Likins, J. Spacecraft 14, 1977). So do the free–free axial modes of
a uniform rod, χ_n(x̄) = √(2/(ρA L)) cos(nπξ/L), ω_n = (nπ/L) √(EA/ρA) (Timoshenko, Young &
Weaver, Vibration Problems in Engineering, 4th ed., 1974, sect. 5.2), which are orthogonal
to the bending modes. The kinetic energy is then
T = ½ m |Ṙ|² + ½ (J₀ + Σ q_k²) θ̇² + ½ Σ q̇_k² + ½ Σ ṗ_n²; with Σ q_k² neglected against J₀
the mass matrix is the constant diag(m, m, J₀, 1, …, 1), gravity does no work on the modes,
the elastic forces are −ω_k² q_k (strain energy ½ Σ ω_k² q_k², axial modes alike) and the
stiffness-proportional damping −β ω_k² q̇_k. The neglected terms (docs/model.md, "Modal
links"): Σ q_k² in the inertia, the centrifugal and Coriolis couplings of frame and modes,
and the geometric stiffening by the axial load; without axial modes the link is axially
rigid.
"""

import math

import numpy as np

from sim.jit import kernel, kernel_inline

BETA_L = (4.7300408, 7.8532046, 10.9956078, 14.1371655)
"""β_k L of the first free–free bending modes of a uniform Euler–Bernoulli beam."""
MAX_AXIAL = 3
"""Free–free axial modes a modal link may carry (`bodies.<name>.axial_modes`)."""
MAX_MODES = len(BETA_L) + MAX_AXIAL
"""Modal coordinates of a link at most: its bending modes, then its axial ones."""

_QUADRATURE_POINTS = 64  # Gauss–Legendre points for the normalisation: exact to 1e-14 here


def _unit_shape(k: int, xi: np.ndarray, length: float, derivative: int = 0) -> np.ndarray:
    """φ_k (derivative 0, dimensionless) or dφ_k/dξ (derivative 1, 1/m) at ξ (m) from the start."""
    b = BETA_L[k] / length
    bl = BETA_L[k]
    sigma = (math.cosh(bl) - math.cos(bl)) / (math.sinh(bl) - math.sin(bl))
    s = b * np.asarray(xi, dtype=float)
    if derivative == 0:
        return np.cosh(s) + np.cos(s) - sigma * (np.sinh(s) + np.sin(s))
    return b * (np.sinh(s) - np.sin(s) - sigma * (np.cosh(s) + np.cos(s)))


def mode_scale(k: int, length: float, rho_a: float) -> float:
    """1 / √(∫ ρA φ_k² dx), which makes ψ_k = φ_k · scale mass-normalised (kg^-½)."""
    x, w = np.polynomial.legendre.leggauss(_QUADRATURE_POINTS)
    xi = 0.5 * length * (x + 1.0)
    return 1.0 / math.sqrt(rho_a * 0.5 * length * float(w @ _unit_shape(k, xi, length) ** 2))


def mode_shapes(
    x_bar: float, length: float, rho_a: float, modes: int, derivative: int = 0
) -> np.ndarray:
    """ψ_k(x̄) (kg^-½) or ψ_k′(x̄) (kg^-½/m), k < modes, at body-frame x̄ (m, from the centre)."""
    return np.array(
        [
            _unit_shape(k, x_bar + 0.5 * length, length, derivative) * mode_scale(k, length, rho_a)
            for k in range(modes)
        ]
    )


def frequencies(length: float, rho_a: float, ei: float, modes: int) -> np.ndarray:
    """Free–free angular frequencies ω_k = (β_k L / L)² √(EI/ρA) (rad/s)."""
    return np.array([(BETA_L[k] / length) ** 2 * math.sqrt(ei / rho_a) for k in range(modes)])


def axial_shapes(x_bar: float, length: float, rho_a: float, axial: int) -> np.ndarray:
    """χ_n(x̄) = √(2/(ρA L)) cos(nπξ/L) (kg^-½), n = 1…axial, the mass-normalised free–free
    axial modes of a uniform rod at body-frame x̄ (m, from the centre), ξ = x̄ + L/2."""
    n = np.arange(1, axial + 1)
    return math.sqrt(2.0 / (rho_a * length)) * np.cos(n * math.pi * (x_bar / length + 0.5))


def axial_frequencies(length: float, rho_a: float, ea: float, axial: int) -> np.ndarray:
    """Free–free axial angular frequencies ω_n = (nπ/L) √(EA/ρA) (rad/s), n = 1…axial."""
    return np.arange(1, axial + 1) * math.pi / length * math.sqrt(ea / rho_a)


def point_coefficients(
    u: tuple[float, float], length: float, rho_a: float, modes: int, axial: int = 0
) -> np.ndarray:
    """(2, MAX_MODES) ∂(local displacement)/∂q_k of the point at body-frame u = (x̄, ȳ) (m):
    for the `modes` bending modes row 0 −ȳ ψ_k′(x̄), row 1 ψ_k(x̄); for the `axial` axial modes
    after them row 0 χ_n(x̄), row 1 0; zero beyond."""
    out = np.zeros((2, MAX_MODES))
    out[0, :modes] = -u[1] * mode_shapes(u[0], length, rho_a, modes, derivative=1)
    out[1, :modes] = mode_shapes(u[0], length, rho_a, modes)
    out[0, modes : modes + axial] = axial_shapes(u[0], length, rho_a, axial)
    return out


@kernel_inline
def modal_forces(sys, q: np.ndarray, qd: np.ndarray, gen: np.ndarray):
    """Subtract the elastic forces ω_k² q_k and damping forces β ω_k² q̇_k of every modal link
    from `gen`; return the power they dissipate (W)."""
    p_diss = 0.0
    for b in range(sys.md_off.shape[0]):
        first = sys.md_off[b] + 3
        beta = sys.md_beta[b]
        for k in range(sys.md_modes[b]):
            w2 = sys.md_omega[b, k] * sys.md_omega[b, k]
            i = first + k
            damping = beta * w2 * qd[i]
            gen[i] -= w2 * q[i] + damping
            p_diss += damping * qd[i]
    return p_diss


@kernel_inline
def modal_strain_energy(sys, q: np.ndarray) -> float:
    """The strain energy Σ ω_k² q_k² / 2 of every modal link (J, the amplitudes mass-normalised)."""
    strain = 0.0
    for b in range(sys.md_off.shape[0]):
        first = sys.md_off[b] + 3
        for k in range(sys.md_modes[b]):
            w2 = sys.md_omega[b, k] * sys.md_omega[b, k]
            strain += 0.5 * w2 * q[first + k] * q[first + k]
    return strain


@kernel
def modal_damping_power(sys, qd: np.ndarray) -> float:
    """The power dissipated by the damping of every modal link, Σ β ω_k² q̇_k² (W)."""
    power = 0.0
    for b in range(sys.md_off.shape[0]):
        first = sys.md_off[b] + 3
        for k in range(sys.md_modes[b]):
            w = sys.md_omega[b, k] * qd[first + k]
            power += sys.md_beta[b] * w * w
    return power


@kernel
def add_modal_tangent(sys, mat: np.ndarray, c_c: float, c_k: float) -> None:
    """mat += c_K K + c_C C of every modal link's elastic and damping forces (diagonal)."""
    for b in range(sys.md_off.shape[0]):
        first = sys.md_off[b] + 3
        for k in range(sys.md_modes[b]):
            w2 = sys.md_omega[b, k] * sys.md_omega[b, k]
            mat[first + k, first + k] += (c_k + c_c * sys.md_beta[b]) * w2


@kernel
def modal_midspan_deflection(sys, b: int, q: np.ndarray) -> float:
    """Signed transverse deflection (m) of modal link b's mid-length point from the chord of its
    end points, positive to the left of the chord from start to end (the ANCF output's
    definition, `sim.model.ancf.beam_midspan_deflection`), in the link's frame."""
    first = sys.md_off[b] + 3
    v_start = 0.0
    v_mid = 0.0
    v_end = 0.0
    for k in range(sys.md_modes[b]):
        v_start += sys.md_shape[b, 0, k] * q[first + k]
        v_mid += sys.md_shape[b, 1, k] * q[first + k]
        v_end += sys.md_shape[b, 2, k] * q[first + k]
    half = 0.5 * sys.md_length[b]
    cx = 2.0 * half
    cy = v_end - v_start
    return (cx * (v_mid - v_start) - cy * half) / np.hypot(cx, cy)

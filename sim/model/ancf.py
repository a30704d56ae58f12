"""Planar ANCF beam: gradient-deficient two-node element with cubic Hermite interpolation.

A flexible link is a chain of ``n`` equal elements of undeformed length ``l = L / n`` (m) that
share nodes. Each node carries four absolute coordinates, its position r (m) and its slope
∂r/∂x (dimensionless), so a link has the coordinate vector

    q = [r_x, r_y, r'_x, r'_y]_node 0, ..., [r_x, r_y, r'_x, r'_y]_node n      (4(n+1) entries)

and element ``e`` uses the eight entries ``q[4e : 4e + 8]``. Here x (m) is the arc length along
the undeformed, straight beam and ξ = x/l ∈ [0, 1] the element coordinate. The position of a
material point is r(x) = S(ξ) q_e with the cubic Hermite shape functions

    S1 = 1 − 3ξ² + 2ξ³,   S2 = l(ξ − 2ξ² + ξ³),   S3 = 3ξ² − 2ξ³,   S4 = l(ξ³ − ξ²),

each multiplying the 2×2 identity (Shabana 1997; docs/model.md "Flexible links"); primes are
derivatives with respect to x.

Strain energy (Berzeri & Shabana 2000, their simple model of the elastic forces):

    U = ½ ∫ EA ε² dx + ½ qᵀ K_b q,   ε = (r'·r' − 1)/2,   K_b = ∫ EI S''ᵀ S'' dx,

with EA the axial stiffness (N), EI the bending stiffness (N m²), ε the axial Green strain of the
centre line and K_b the constant bending stiffness, which measures bending by |r''| instead of
the exact curvature (accurate while the axial strain is small). The bending force is K_b q. The
transverse slope and shear deformation of the fully parameterised element (Omar & Shabana 2001)
are left out on purpose: the links are slender.

Quadrature (Gauss–Legendre on each element, exact for every integral here, so no quadrature
error enters forces, Jacobians or energy):
- axial terms, 5 points (exact to degree 9): r' is of degree 2 in ξ, so ε is of degree 4 and
  the force integrand ε S'ᵀ r', the tangent integrand S'ᵀ(r' r'ᵀ + ε I₂)S' and ε² are of
  degree 8; the mass matrix integrand Sᵀ S (degree 6) uses the same rule;
- bending terms, 2 points (exact to degree 3): S'' is of degree 1, S''ᵀ S'' of degree 2. K_b is
  kept in this factored form, K_b = Σ_g EI l w_g S''(ξ_g)ᵀ S''(ξ_g), so that the bending energy
  ½ Σ_g EI l w_g |r''(ξ_g)|² is a sum of squares: never negative, and free of the round-off of
  the quadratic form qᵀ K_b q with its large cancelling entries (a rigidly rotated beam has
  exactly r'' = 0 up to the rounding of r'' itself). K_b q costs the same in either form.

Kernels for the integrator's hot loop are numba-compiled, allocation-free and write into arrays
the caller provides (float64, contiguous). The per-element constants they take come from
:func:`beam_constants`, computed once per link. All quantities are in SI units.

Sources:
    Shabana, A. A. (1997). Definition of the slopes and the finite element absolute nodal
    coordinate formulation. Multibody System Dynamics 1, 339–348.
    Berzeri, M., Shabana, A. A. (2000). Development of simple models for the elastic forces in
    the absolute nodal co-ordinate formulation. Journal of Sound and Vibration 235(4), 539–565.
    Omar, M. A., Shabana, A. A. (2001). A two-dimensional shear deformable beam for large rotation
    and deformation problems. Journal of Sound and Vibration 243(3), 565–576.
"""

from typing import NamedTuple

import numpy as np

from sim.jit import kernel

AXIAL_GAUSS_POINTS = 5
"""Gauss–Legendre points per element for the axial terms and the mass matrix (exact to degree 9)."""
BENDING_GAUSS_POINTS = 2
"""Gauss–Legendre points per element for the bending terms (exact to degree 3)."""


def _gauss_rule(points: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss–Legendre points ξ_g and weights w_g on [0, 1] (the weights sum to 1)."""
    x, w = np.polynomial.legendre.leggauss(points)
    return 0.5 * (x + 1.0), 0.5 * w


@kernel
def _hermite(xi: float, l: float, k: int, order: int) -> float:
    """Derivative of order 0, 1 or 2 with respect to x of the Hermite shape function S_{k+1}."""
    if order == 0:
        if k == 0:
            return 1.0 - 3.0 * xi**2 + 2.0 * xi**3
        if k == 1:
            return l * (xi - 2.0 * xi**2 + xi**3)
        if k == 2:
            return 3.0 * xi**2 - 2.0 * xi**3
        return l * (xi**3 - xi**2)
    if order == 1:
        if k == 0:
            return (-6.0 * xi + 6.0 * xi**2) / l
        if k == 1:
            return 1.0 - 4.0 * xi + 3.0 * xi**2
        if k == 2:
            return (6.0 * xi - 6.0 * xi**2) / l
        return 3.0 * xi**2 - 2.0 * xi
    if k == 0:
        return (-6.0 + 12.0 * xi) / l**2
    if k == 1:
        return (-4.0 + 6.0 * xi) / l
    if k == 2:
        return (6.0 - 12.0 * xi) / l**2
    return (6.0 * xi - 2.0) / l


def _shape_table(xi: np.ndarray, l: float, order: int) -> np.ndarray:
    """Shape function derivatives of the given order at the points ``xi``, shape (len(xi), 4)."""
    return np.array([[_hermite(x, l, k, order) for k in range(4)] for x in xi])


class BeamConstants(NamedTuple):
    """Per-element constants of a link's kernels, from :func:`beam_constants`.

    Pass them to a kernel unpacked, e.g. ``beam_elastic_forces(q, *constants, out)``.
    """

    dshape: np.ndarray
    """S_k' at the axial Gauss points, (AXIAL_GAUSS_POINTS, 4): 1/m for k = 0, 2; 1 for k = 1, 3."""
    axial_weight: np.ndarray
    """EA · l · w_g, axial stiffness times quadrature weight in x, (AXIAL_GAUSS_POINTS,), N m."""
    d2shape: np.ndarray
    """S_k'' at the bending Gauss points, (BENDING_GAUSS_POINTS, 4): 1/m² (k = 0, 2); 1/m."""
    bending_weight: np.ndarray
    """EI · l · w_g, bending stiffness times quadrature weight, (BENDING_GAUSS_POINTS,), N m³."""


def beam_constants(l: float, EA: float, EI: float) -> BeamConstants:
    """Constants of the kernels for elements of length ``l`` (m).

    ``EA`` is the axial stiffness (N) and ``EI`` the bending stiffness (N m²), uniform along the
    link. All elements of a link are equal, so the constants do not depend on their number; the
    kernels read it from the length of q.
    """
    axial_xi, axial_w = _gauss_rule(AXIAL_GAUSS_POINTS)
    bending_xi, bending_w = _gauss_rule(BENDING_GAUSS_POINTS)
    return BeamConstants(
        dshape=np.ascontiguousarray(_shape_table(axial_xi, l, 1)),
        axial_weight=EA * l * axial_w,
        d2shape=np.ascontiguousarray(_shape_table(bending_xi, l, 2)),
        bending_weight=EI * l * bending_w,
    )


def element_mass_matrix(rho_A: float, l: float) -> np.ndarray:
    """Consistent mass matrix ∫ ρA Sᵀ S dx of one element, shape (8, 8).

    ``rho_A`` is the mass per unit length (kg/m) and ``l`` the element length (m); the entries are
    in kg, kg m and kg m². Exact by Gauss quadrature (the integrand is of degree 6 in ξ).
    """
    xi, w = _gauss_rule(AXIAL_GAUSS_POINTS)
    shape = _shape_table(xi, l, 0)
    m4 = rho_A * l * np.einsum("g,gk,gm->km", w, shape, shape)
    return np.kron(m4, np.eye(2))


def beam_mass_matrix(rho_A: float, L: float, n: int) -> np.ndarray:
    """Mass matrix of a link of length ``L`` (m) meshed with ``n`` elements, (4(n+1), 4(n+1)).

    ``rho_A`` is the mass per unit length (kg/m). Constant: the ANCF has no velocity-dependent
    inertia terms (Shabana 1997).
    """
    me = element_mass_matrix(rho_A, L / n)
    m = np.zeros((4 * (n + 1), 4 * (n + 1)))
    for e in range(n):
        m[4 * e : 4 * e + 8, 4 * e : 4 * e + 8] += me
    return m


def straight_beam_coordinates(p0: np.ndarray, p1: np.ndarray, n: int) -> np.ndarray:
    """Coordinates q of a straight, unstressed link from point ``p0`` to point ``p1`` (m).

    Nodes are equally spaced and every slope is the unit vector from p0 to p1, so ε = 0 and
    r'' = 0. The undeformed length of the link is |p1 − p0|: use L = |p1 − p0| for its constants.
    """
    p0 = np.asarray(p0, dtype=float)
    p1 = np.asarray(p1, dtype=float)
    tangent = (p1 - p0) / np.linalg.norm(p1 - p0)
    q = np.empty(4 * (n + 1))
    for j in range(n + 1):
        q[4 * j : 4 * j + 2] = p0 + (j / n) * (p1 - p0)
        q[4 * j + 2 : 4 * j + 4] = tangent
    return q


# ---------------------------------------------------------------------------------------------
# Hot-loop kernels. The number of elements is n = len(q) // 4 − 1. At a Gauss point the slope
# r' = S' q_e and the second derivative r'' = S'' q_e are both "shape row times nodal values",
# so one set of helpers serves the axial (S') and the bending (S'') terms.


@kernel
def _interpolate(v: np.ndarray, base: int, shape: np.ndarray) -> tuple[float, float]:
    """Σ_k shape[k] v_e[k]: r' or r'' (v = q), or their rates (v = q̇), at one Gauss point."""
    x = 0.0
    y = 0.0
    for k in range(4):
        x += shape[k] * v[base + 2 * k]
        y += shape[k] * v[base + 2 * k + 1]
    return x, y


@kernel
def _add_gradient(
    out: np.ndarray, base: int, shape: np.ndarray, scale: float, ax: float, ay: float
) -> None:
    """out_e += scale · Bᵀ a for one Gauss point, B = [shape[k] I₂]_k (2×8)."""
    for k in range(4):
        out[base + 2 * k] += scale * shape[k] * ax
        out[base + 2 * k + 1] += scale * shape[k] * ay


@kernel
def _add_block(
    out: np.ndarray,
    base: int,
    shape: np.ndarray,
    scale: float,
    ax: float,
    ay: float,
    bx: float,
    by: float,
    c: float,
) -> None:
    """out_ee += scale · Bᵀ (a bᵀ + c I₂) B for one Gauss point, B = [shape[k] I₂]_k (2×8)."""
    a = (ax, ay)
    b = (bx, by)
    for k in range(4):
        for m in range(4):
            skm = scale * shape[k] * shape[m]
            for i in range(2):
                for j in range(2):
                    value = a[i] * b[j]
                    if i == j:
                        value += c
                    out[base + 2 * k + i, base + 2 * m + j] += skm * value


@kernel
def _add_bending_force(
    v: np.ndarray, d2shape: np.ndarray, bending_weight: np.ndarray, scale: float, out: np.ndarray
) -> None:
    """out += scale · K_b v, with K_b in its factored Gauss form."""
    for e in range(v.shape[0] // 4 - 1):
        base = 4 * e
        for g in range(bending_weight.shape[0]):
            cx, cy = _interpolate(v, base, d2shape[g])
            _add_gradient(out, base, d2shape[g], scale * bending_weight[g], cx, cy)


@kernel
def _add_bending_stiffness(
    d2shape: np.ndarray, bending_weight: np.ndarray, scale: float, out: np.ndarray
) -> None:
    """out += scale · K_b, assembled over the elements of the link."""
    for e in range(out.shape[0] // 4 - 1):
        for g in range(bending_weight.shape[0]):
            _add_block(out, 4 * e, d2shape[g], scale * bending_weight[g], 0.0, 0.0, 0.0, 0.0, 1.0)


@kernel
def beam_elastic_forces(
    q: np.ndarray,
    dshape: np.ndarray,
    axial_weight: np.ndarray,
    d2shape: np.ndarray,
    bending_weight: np.ndarray,
    out: np.ndarray,
) -> None:
    """Generalized elastic forces F = ∂U/∂q of a link (N on positions, N m on slopes).

    F = Σ_e ∫ EA ε S'ᵀ r' dx + K_b q (Berzeri & Shabana 2000). ``q`` holds the link's 4(n+1)
    coordinates, the next four arguments are the fields of :func:`beam_constants`, and ``out``
    (4(n+1),) is overwritten.
    """
    out[:] = 0.0
    for e in range(q.shape[0] // 4 - 1):
        base = 4 * e
        for g in range(axial_weight.shape[0]):
            rx, ry = _interpolate(q, base, dshape[g])
            strain = 0.5 * (rx * rx + ry * ry - 1.0)
            _add_gradient(out, base, dshape[g], axial_weight[g] * strain, rx, ry)
    _add_bending_force(q, d2shape, bending_weight, 1.0, out)


@kernel
def beam_elastic_jacobian(
    q: np.ndarray,
    dshape: np.ndarray,
    axial_weight: np.ndarray,
    d2shape: np.ndarray,
    bending_weight: np.ndarray,
    out: np.ndarray,
) -> None:
    """Tangent stiffness ∂F/∂q of a link, symmetric, (4(n+1), 4(n+1)), overwritten in ``out``.

    ∂F/∂q = Σ_e ∫ EA S'ᵀ (r' r'ᵀ + ε I₂) S' dx + K_b: the material (r' r'ᵀ) and geometric (ε I₂)
    parts of the axial stiffness, and the constant bending stiffness. Units N/m, N, N m.
    """
    out[:, :] = 0.0
    for e in range(q.shape[0] // 4 - 1):
        base = 4 * e
        for g in range(axial_weight.shape[0]):
            rx, ry = _interpolate(q, base, dshape[g])
            strain = 0.5 * (rx * rx + ry * ry - 1.0)
            _add_block(out, base, dshape[g], axial_weight[g], rx, ry, rx, ry, strain)
    _add_bending_stiffness(d2shape, bending_weight, 1.0, out)


@kernel
def beam_strain_energy(
    q: np.ndarray,
    dshape: np.ndarray,
    axial_weight: np.ndarray,
    d2shape: np.ndarray,
    bending_weight: np.ndarray,
) -> float:
    """Strain energy U = ½ ∫ EA ε² dx + ½ ∫ EI |r''|² dx (= ½ qᵀ K_b q) of a link (J)."""
    energy = 0.0
    for e in range(q.shape[0] // 4 - 1):
        base = 4 * e
        for g in range(axial_weight.shape[0]):
            rx, ry = _interpolate(q, base, dshape[g])
            strain = 0.5 * (rx * rx + ry * ry - 1.0)
            energy += 0.5 * axial_weight[g] * strain * strain
        for g in range(bending_weight.shape[0]):
            cx, cy = _interpolate(q, base, d2shape[g])
            energy += 0.5 * bending_weight[g] * (cx * cx + cy * cy)
    return energy


@kernel
def beam_damping_forces(
    q: np.ndarray,
    qdot: np.ndarray,
    dshape: np.ndarray,
    axial_weight: np.ndarray,
    d2shape: np.ndarray,
    bending_weight: np.ndarray,
    beta: float,
    out: np.ndarray,
) -> None:
    """Stiffness-proportional structural damping forces of a link (N, N m), overwritten in ``out``.

    F_d = β (∫ EA ε̇ S'ᵀ r' dx + K_b q̇), with ε̇ = r'·ṙ' the axial strain rate, q̇ (m/s, 1/s)
    the coordinate rates and ``beta`` (s) the stiffness-proportional (Rayleigh) coefficient.
    This is β times the material part of the tangent stiffness applied to q̇; the geometric part
    β ∫ EA ε S'ᵀ S' q̇ dx is left out. Why: F_d is then the q̇-gradient of the dissipation
    function D = ½ β ∫ (EA ε̇² + EI |ṙ''|²) dx of a Kelvin–Voigt material with retardation time
    β, so it vanishes for every rigid motion (also of a prestressed beam, where β (∂F/∂q) q̇ would
    not) and the dissipated power q̇ᵀF_d = 2D is never negative, which the energy audit relies
    on. At the straight unstressed state it equals β (∂F/∂q) q̇, so a mode of angular frequency
    ω_i gets the damping ratio ζ_i = β ω_i / 2.
    """
    out[:] = 0.0
    for e in range(q.shape[0] // 4 - 1):
        base = 4 * e
        for g in range(axial_weight.shape[0]):
            rx, ry = _interpolate(q, base, dshape[g])
            vx, vy = _interpolate(qdot, base, dshape[g])
            strain_rate = rx * vx + ry * vy
            _add_gradient(out, base, dshape[g], beta * axial_weight[g] * strain_rate, rx, ry)
    _add_bending_force(qdot, d2shape, bending_weight, beta, out)


@kernel
def beam_damping_jacobians(
    q: np.ndarray,
    qdot: np.ndarray,
    dshape: np.ndarray,
    axial_weight: np.ndarray,
    d2shape: np.ndarray,
    bending_weight: np.ndarray,
    beta: float,
    out_q: np.ndarray,
    out_qdot: np.ndarray,
) -> None:
    """Jacobians ∂F_d/∂q and ∂F_d/∂q̇ of :func:`beam_damping_forces`, both overwritten.

    ∂F_d/∂q = β ∫ EA S'ᵀ (r' ṙ'ᵀ + ε̇ I₂) S' dx (not symmetric; N/m, N, N m) and
    ∂F_d/∂q̇ = β (∫ EA S'ᵀ r' r'ᵀ S' dx + K_b) (N s/m, N s, N m s); both (4(n+1), 4(n+1)).
    """
    out_q[:, :] = 0.0
    out_qdot[:, :] = 0.0
    for e in range(q.shape[0] // 4 - 1):
        base = 4 * e
        for g in range(axial_weight.shape[0]):
            rx, ry = _interpolate(q, base, dshape[g])
            vx, vy = _interpolate(qdot, base, dshape[g])
            weight = beta * axial_weight[g]
            _add_block(out_q, base, dshape[g], weight, rx, ry, vx, vy, rx * vx + ry * vy)
            _add_block(out_qdot, base, dshape[g], weight, rx, ry, rx, ry, 0.0)
    _add_bending_stiffness(d2shape, bending_weight, beta, out_qdot)


# ---------------------------------------------------------------------------------------------
# Material points: joints, reference point, deflection output.


@kernel
def _locate(n: int, l: float, s: float) -> tuple[int, float]:
    """Element index and element coordinate ξ of the material point at arc length ``s`` (m)."""
    e = min(max(int(s / l), 0), n - 1)
    return e, s / l - e


@kernel
def _point(q: np.ndarray, n: int, l: float, s: float) -> tuple[float, float]:
    """Position (m) of the material point at arc length ``s`` (m)."""
    e, xi = _locate(n, l, s)
    x = 0.0
    y = 0.0
    for k in range(4):
        shape = _hermite(xi, l, k, 0)
        x += shape * q[4 * e + 2 * k]
        y += shape * q[4 * e + 2 * k + 1]
    return x, y


@kernel
def beam_point(q: np.ndarray, n: int, l: float, s: float, out: np.ndarray) -> None:
    """Position r(s) (m) of the material point at undeformed arc length s ∈ [0, n l] (m).

    ``n`` elements of length ``l`` (m); ``out`` (2,) is overwritten. A point s outside [0, n l]
    is extrapolated with the cubic of the nearest end element.
    """
    out[0], out[1] = _point(q, n, l, s)


@kernel
def beam_point_jacobian(n: int, l: float, s: float, shape_out: np.ndarray) -> int:
    """Sparse ∂r(s)/∂q of the material point at arc length ``s`` (m); returns the element index e.

    r(s) is linear in q and touches only element e, so the 2×4(n+1) Jacobian has the nonzero
    entries ∂r_i/∂q[4e + 2k + i] = shape_out[k] for i ∈ {0, 1} (x, y) and k = 0…3, where
    ``shape_out`` (4,) is overwritten with the shape function values S1…S4 at s (1, m, 1, m).
    The same values give r(s) = Σ_k shape_out[k] · q[4e + 2k : 4e + 2k + 2] and its velocity and
    acceleration from q̇ and q̈.
    """
    e, xi = _locate(n, l, s)
    for k in range(4):
        shape_out[k] = _hermite(xi, l, k, 0)
    return e


@kernel
def beam_midspan_deflection(q: np.ndarray, n: int, l: float) -> float:
    """Signed transverse deflection (m) of the mid-length material point from the end chord.

    Distance of r(n l / 2) from the straight line through the end nodes, positive to the left
    of the chord direction from node 0 to node n.
    """
    x0 = q[0]
    y0 = q[1]
    cx = q[4 * n] - x0
    cy = q[4 * n + 1] - y0
    px, py = _point(q, n, l, 0.5 * n * l)
    return (cx * (py - y0) - cy * (px - x0)) / np.hypot(cx, cy)

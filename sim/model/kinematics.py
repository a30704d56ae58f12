"""Positions, velocities and Jacobians of points attached to bodies.

For a point with body-frame vector u on a rigid body (R, θ):
    r = R + A(θ) u,  ṙ = Ṙ + θ̇ k × (A u),  r̈ = R̈ + θ̈ k × (A u) − θ̇² A u,
with A(θ) the planar rotation and k × v = (−v_y, v_x). A point on a beam node
is the node's position coordinates themselves; a ground point is fixed.
(Nikravesh, Computer-Aided Analysis of Mechanical Systems, 1988, ch. 6.)

A point of a modal link (`sim.model.modal`) has the body-frame vector
u = ū + Ψ q_m, linear in the modal amplitudes q_m (Ψ = pt_modal, 2 × k), so
    r = R + A u,  ṙ = Ṙ + θ̇ k × (A u) + A Ψ q̇_m,
    r̈ = R̈ + θ̈ k × (A u) + A Ψ q̈_m − θ̇² A u + 2 θ̇ k × (A Ψ q̇_m)
(Shabana, Dynamics of Multibody Systems, 3rd ed., 2005, ch. 5). A global offset
turns with the frame angle θ: the section's own small rotation Σ ψ_k′ q_k is
left out of a contact point's lever (docs/model.md, "Modal links").

`offset` arguments add a global vector to the body-frame point (a contact point
at a distance from the joint centre); for beam nodes the offset is ignored
because a node has no rotational coordinate to carry its moment.

The `*_rotated` forms take the owning body's (cos θ, sin θ) from `point_rotation`, or from
`body_rotation` where the tree of minimal coordinates has computed them already, so that a
caller that needs one point's position, velocity and force computes them once: a clearance
joint's contact force took them up to eight times an evaluation, and cos and sin take about a
fifth of the rigid core's integration time (perf; docs/performance.md).
"""

import numpy as np

from sim.jit import kernel_inline
from sim.model.system import POINT_GROUND, POINT_MODAL, POINT_NODE


@kernel_inline
def rotate(theta: float, ux: float, uy: float) -> tuple[float, float]:
    """A(θ) u."""
    c = np.cos(theta)
    s = np.sin(theta)
    return c * ux - s * uy, s * ux + c * uy


@kernel_inline
def _local(sys, k: int, q: np.ndarray) -> tuple[float, float]:
    """Body-frame vector u (m) of point k on a rigid body or modal link: ū + Ψ q_m."""
    ux = sys.pt_u[k, 0]
    uy = sys.pt_u[k, 1]
    o = sys.pt_off[k] + 3
    for m in range(sys.pt_modes[k]):
        ux += sys.pt_modal[k, 0, m] * q[o + m]
        uy += sys.pt_modal[k, 1, m] * q[o + m]
    return ux, uy


@kernel_inline
def point_rotation(sys, k: int, q: np.ndarray) -> tuple[float, float]:
    """(cos θ, sin θ) of the body that owns point k; (1, 0) for ground points and beam nodes,
    which have no angle."""
    kind = sys.pt_kind[k]
    if kind == POINT_GROUND or kind == POINT_NODE:
        return 1.0, 0.0
    theta = q[sys.pt_off[k] + 2]
    return np.cos(theta), np.sin(theta)


@kernel_inline
def frame_rotation(q: np.ndarray, o: int, rot: np.ndarray) -> tuple[float, float]:
    """(cos θ, sin θ) of the rigid body or modal link at offset o: read from `rot`, each
    body's at its offset, as the tree of minimal coordinates keeps them at every evaluation
    (sim.model.tree), or computed from q when `rot` is empty (absolute coordinates)."""
    if rot.shape[0] > 0:
        return rot[o, 0], rot[o, 1]
    return np.cos(q[o + 2]), np.sin(q[o + 2])


@kernel_inline
def body_rotation(sys, k: int, q: np.ndarray, rot: np.ndarray) -> tuple[float, float]:
    """`point_rotation` through `frame_rotation`: read from `rot` when it is given."""
    kind = sys.pt_kind[k]
    if kind == POINT_GROUND or kind == POINT_NODE:
        return 1.0, 0.0
    return frame_rotation(q, sys.pt_off[k], rot)


@kernel_inline
def _modal_velocity(sys, k: int, qd: np.ndarray, c: float, s: float) -> tuple[float, float]:
    """A Ψ q̇_m (m/s), A = A(θ) given by (c, s): the velocity of point k relative to its
    link's frame, zero for points of other bodies."""
    vx = 0.0
    vy = 0.0
    o = sys.pt_off[k] + 3
    for m in range(sys.pt_modes[k]):
        vx += sys.pt_modal[k, 0, m] * qd[o + m]
        vy += sys.pt_modal[k, 1, m] * qd[o + m]
    return c * vx - s * vy, s * vx + c * vy


@kernel_inline
def point_position(sys, k: int, q: np.ndarray) -> tuple[float, float]:
    """Global position (m) of point k."""
    c, s = point_rotation(sys, k, q)
    return point_position_rotated(sys, k, q, c, s)


@kernel_inline
def point_position_rotated(sys, k: int, q: np.ndarray, c: float, s: float) -> tuple[float, float]:
    """`point_position` with its body's (cos θ, sin θ) = (c, s) given."""
    kind = sys.pt_kind[k]
    if kind == POINT_GROUND:
        return sys.pt_u[k, 0], sys.pt_u[k, 1]
    o = sys.pt_off[k]
    if kind == POINT_NODE:
        return q[o], q[o + 1]
    ux, uy = _local(sys, k, q)
    return q[o] + c * ux - s * uy, q[o + 1] + s * ux + c * uy


@kernel_inline
def point_velocity(
    sys, k: int, q: np.ndarray, qd: np.ndarray, ox: float, oy: float
) -> tuple[float, float]:
    """Global velocity (m/s) of the material point at point k plus global offset (ox, oy)."""
    c, s = point_rotation(sys, k, q)
    return point_velocity_rotated(sys, k, q, qd, ox, oy, c, s)


@kernel_inline
def point_velocity_rotated(
    sys, k: int, q: np.ndarray, qd: np.ndarray, ox: float, oy: float, c: float, s: float
) -> tuple[float, float]:
    """`point_velocity` with its body's (cos θ, sin θ) = (c, s) given."""
    kind = sys.pt_kind[k]
    if kind == POINT_GROUND:
        return 0.0, 0.0
    o = sys.pt_off[k]
    if kind == POINT_NODE:
        return qd[o], qd[o + 1]
    ux, uy = _local(sys, k, q)
    ax = c * ux - s * uy
    ay = s * ux + c * uy
    w = qd[o + 2]
    vx = qd[o] - w * (ay + oy)
    vy = qd[o + 1] + w * (ax + ox)
    if kind == POINT_MODAL:
        mx, my = _modal_velocity(sys, k, qd, c, s)
        vx += mx
        vy += my
    return vx, vy


@kernel_inline
def point_quadratic_acceleration(sys, k: int, q: np.ndarray, qd: np.ndarray) -> tuple[float, float]:
    """The part of r̈ not proportional to q̈: −θ̇² A u for rigid points, plus
    2 θ̇ k × (A Ψ q̇_m) for modal points, zero otherwise."""
    kind = sys.pt_kind[k]
    if kind == POINT_GROUND or kind == POINT_NODE:
        return 0.0, 0.0
    o = sys.pt_off[k]
    ux, uy = _local(sys, k, q)
    ax, ay = rotate(q[o + 2], ux, uy)
    w = qd[o + 2]
    w2 = w * w
    if kind == POINT_MODAL:
        mx, my = _modal_velocity(sys, k, qd, np.cos(q[o + 2]), np.sin(q[o + 2]))
        return -w2 * ax - 2.0 * w * my, -w2 * ay + 2.0 * w * mx
    return -w2 * ax, -w2 * ay


@kernel_inline
def add_point_jacobian(sys, k: int, q: np.ndarray, sign: float, jac: np.ndarray, row: int) -> None:
    """Add sign·∂r_k/∂q into rows (row, row+1) of `jac`."""
    kind = sys.pt_kind[k]
    if kind == POINT_GROUND:
        return
    o = sys.pt_off[k]
    jac[row, o] += sign
    jac[row + 1, o + 1] += sign
    if kind == POINT_NODE:
        return
    ux, uy = _local(sys, k, q)
    ax, ay = rotate(q[o + 2], ux, uy)
    jac[row, o + 2] += -sign * ay
    jac[row + 1, o + 2] += sign * ax
    for m in range(sys.pt_modes[k]):
        px, py = rotate(q[o + 2], sys.pt_modal[k, 0, m], sys.pt_modal[k, 1, m])
        jac[row, o + 3 + m] += sign * px
        jac[row + 1, o + 3 + m] += sign * py


@kernel_inline
def apply_point_force(
    sys, k: int, q: np.ndarray, fx: float, fy: float, ox: float, oy: float, gen: np.ndarray
) -> None:
    """Add the generalized force of a global force (fx, fy) (N) acting at point k
    plus global offset (ox, oy) to `gen`: Q += (∂r/∂q)ᵀ f."""
    c, s = point_rotation(sys, k, q)
    apply_point_force_rotated(sys, k, q, fx, fy, ox, oy, gen, c, s)


@kernel_inline
def apply_point_force_rotated(
    sys,
    k: int,
    q: np.ndarray,
    fx: float,
    fy: float,
    ox: float,
    oy: float,
    gen: np.ndarray,
    c: float,
    s: float,
) -> None:
    """`apply_point_force` with its body's (cos θ, sin θ) = (c, s) given."""
    kind = sys.pt_kind[k]
    if kind == POINT_GROUND:
        return
    o = sys.pt_off[k]
    gen[o] += fx
    gen[o + 1] += fy
    if kind == POINT_NODE:
        return
    ux, uy = _local(sys, k, q)
    ax = c * ux - s * uy
    ay = s * ux + c * uy
    gen[o + 2] += (ax + ox) * fy - (ay + oy) * fx
    for m in range(sys.pt_modes[k]):
        px = c * sys.pt_modal[k, 0, m] - s * sys.pt_modal[k, 1, m]
        py = s * sys.pt_modal[k, 0, m] + c * sys.pt_modal[k, 1, m]
        gen[o + 3 + m] += px * fx + py * fy

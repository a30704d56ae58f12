"""Positions, velocities and Jacobians of points attached to bodies.

For a point with body-frame vector u on a rigid body (R, θ):
    r = R + A(θ) u,  ṙ = Ṙ + θ̇ k × (A u),  r̈ = R̈ + θ̈ k × (A u) − θ̇² A u,
with A(θ) the planar rotation and k × v = (−v_y, v_x). A point on a beam node
is the node's position coordinates themselves; a ground point is fixed.
(Nikravesh, Computer-Aided Analysis of Mechanical Systems, 1988, ch. 6.)

`offset` arguments add a global vector to the body-frame point (a contact point
at a distance from the joint centre); for beam nodes the offset is ignored
because a node has no rotational coordinate to carry its moment.
"""

import numpy as np

from sim.jit import kernel, kernel_inline
from sim.model.system import POINT_GROUND, POINT_RIGID


@kernel_inline
def rotate(theta: float, ux: float, uy: float) -> tuple[float, float]:
    """A(θ) u."""
    c = np.cos(theta)
    s = np.sin(theta)
    return c * ux - s * uy, s * ux + c * uy


@kernel
def point_position(sys, k: int, q: np.ndarray) -> tuple[float, float]:
    """Global position (m) of point k."""
    kind = sys.pt_kind[k]
    if kind == POINT_GROUND:
        return sys.pt_u[k, 0], sys.pt_u[k, 1]
    o = sys.pt_off[k]
    if kind == POINT_RIGID:
        ax, ay = rotate(q[o + 2], sys.pt_u[k, 0], sys.pt_u[k, 1])
        return q[o] + ax, q[o + 1] + ay
    return q[o], q[o + 1]


@kernel
def point_velocity(
    sys, k: int, q: np.ndarray, qd: np.ndarray, ox: float, oy: float
) -> tuple[float, float]:
    """Global velocity (m/s) of the material point at point k plus global offset (ox, oy)."""
    kind = sys.pt_kind[k]
    if kind == POINT_GROUND:
        return 0.0, 0.0
    o = sys.pt_off[k]
    if kind == POINT_RIGID:
        ax, ay = rotate(q[o + 2], sys.pt_u[k, 0], sys.pt_u[k, 1])
        w = qd[o + 2]
        return qd[o] - w * (ay + oy), qd[o + 1] + w * (ax + ox)
    return qd[o], qd[o + 1]


@kernel
def point_quadratic_acceleration(sys, k: int, q: np.ndarray, qd: np.ndarray) -> tuple[float, float]:
    """The part of r̈ not proportional to q̈: −θ̇² A u for rigid points, zero otherwise."""
    if sys.pt_kind[k] != POINT_RIGID:
        return 0.0, 0.0
    o = sys.pt_off[k]
    ax, ay = rotate(q[o + 2], sys.pt_u[k, 0], sys.pt_u[k, 1])
    w2 = qd[o + 2] * qd[o + 2]
    return -w2 * ax, -w2 * ay


@kernel
def add_point_jacobian(sys, k: int, q: np.ndarray, sign: float, jac: np.ndarray, row: int) -> None:
    """Add sign·∂r_k/∂q into rows (row, row+1) of `jac`."""
    kind = sys.pt_kind[k]
    if kind == POINT_GROUND:
        return
    o = sys.pt_off[k]
    jac[row, o] += sign
    jac[row + 1, o + 1] += sign
    if kind == POINT_RIGID:
        ax, ay = rotate(q[o + 2], sys.pt_u[k, 0], sys.pt_u[k, 1])
        jac[row, o + 2] += -sign * ay
        jac[row + 1, o + 2] += sign * ax


@kernel
def apply_point_force(
    sys, k: int, q: np.ndarray, fx: float, fy: float, ox: float, oy: float, gen: np.ndarray
) -> None:
    """Add the generalized force of a global force (fx, fy) (N) acting at point k
    plus global offset (ox, oy) to `gen`: Q += (∂r/∂q)ᵀ f."""
    kind = sys.pt_kind[k]
    if kind == POINT_GROUND:
        return
    o = sys.pt_off[k]
    gen[o] += fx
    gen[o + 1] += fy
    if kind == POINT_RIGID:
        ax, ay = rotate(q[o + 2], sys.pt_u[k, 0], sys.pt_u[k, 1])
        gen[o + 2] += (ax + ox) * fy - (ay + oy) * fx

"""Ideal joint constraints: Φ(q, t), the Jacobian Φ_q, the acceleration
right-hand side γ and the velocity right-hand side ν, such that

    Φ_q q̇ = ν,   Φ_q q̈ = γ,   with ν = −Φ_t and γ = −(Φ_q q̇)_q q̇ − 2Φ_qt q̇ − Φ_tt

(Nikravesh 1988, ch. 6; Haug, Computer Aided Kinematics and Dynamics of
Mechanical Systems, 1989). Constraint types are listed in `sim.model.system`.
"""

import numpy as np

from sim.jit import kernel_inline
from sim.model.kinematics import (
    add_point_jacobian,
    point_position,
    point_quadratic_acceleration,
    rotate,
)
from sim.model.system import (
    CON_CLAMP,
    CON_CLAMP_NODE,
    CON_DRIVE,
    CON_PRISMATIC,
    CON_REVOLUTE,
    CON_WELD,
    POINT_RIGID,
)


@kernel_inline
def _point_terms(sys, k, q, qd, sign, jac, row):
    """Position of point k, sign·∂r_k/∂q added into rows (row, row+1) of `jac`, and
    the quadratic acceleration term: the three of `sim.model.kinematics` with a
    rigid point's rotation A(θ) u evaluated once, not three times, in the same
    arithmetic."""
    if sys.pt_kind[k] != POINT_RIGID:
        x, y = point_position(sys, k, q)
        add_point_jacobian(sys, k, q, sign, jac, row)
        ax, ay = point_quadratic_acceleration(sys, k, q, qd)
        return x, y, ax, ay
    o = sys.pt_off[k]
    ax, ay = rotate(q[o + 2], sys.pt_u[k, 0], sys.pt_u[k, 1])
    jac[row, o] += sign
    jac[row + 1, o + 1] += sign
    jac[row, o + 2] += -sign * ay
    jac[row + 1, o + 2] += sign * ax
    w2 = qd[o + 2] * qd[o + 2]
    return q[o] + ax, q[o + 1] + ay, -w2 * ax, -w2 * ay


@kernel_inline
def _coincident_points(sys, c, row, q, qd, phi, jac, gamma):
    """Rows (row, row+1): point i1 minus point i0."""
    p0 = sys.con_i[c, 0]
    p1 = sys.con_i[c, 1]
    # Point i1's Jacobian is added first, as it always was.
    x1, y1, a1x, a1y = _point_terms(sys, p1, q, qd, 1.0, jac, row)
    x0, y0, a0x, a0y = _point_terms(sys, p0, q, qd, -1.0, jac, row)
    phi[row] = x1 - x0
    phi[row + 1] = y1 - y0
    gamma[row] = a0x - a1x
    gamma[row + 1] = a0y - a1y


@kernel_inline
def constraint_terms(
    sys,
    t: float,
    q: np.ndarray,
    qd: np.ndarray,
    phi: np.ndarray,
    jac: np.ndarray,
    gamma: np.ndarray,
    nu: np.ndarray,
) -> None:
    """Fill Φ, Φ_q (zeroed first), γ and ν for every ideal constraint at (q, q̇, t)."""
    jac[:, :] = 0.0
    gamma[:] = 0.0
    nu[:] = 0.0
    for c in range(sys.con_type.shape[0]):
        kind = sys.con_type[c]
        r = sys.con_row[c]
        o = sys.con_i[c, 0]
        f = sys.con_f[c]
        if kind == CON_REVOLUTE:
            _coincident_points(sys, c, r, q, qd, phi, jac, gamma)
        elif kind == CON_PRISMATIC:
            nx = -np.sin(f[2])
            ny = np.cos(f[2])
            phi[r] = q[o + 2] - f[2]
            phi[r + 1] = (q[o] - f[0]) * nx + (q[o + 1] - f[1]) * ny
            jac[r, o + 2] = 1.0
            jac[r + 1, o] = nx
            jac[r + 1, o + 1] = ny
        elif kind == CON_DRIVE:
            phi[r] = q[o] - f[0] - f[1] * t
            jac[r, o] = 1.0
            nu[r] = f[1]
        elif kind == CON_CLAMP:
            for k in range(3):
                phi[r + k] = q[o + k] - f[k]
                jac[r + k, o + k] = 1.0
        elif kind == CON_CLAMP_NODE:
            phi[r] = q[o] - f[0]
            phi[r + 1] = q[o + 1] - f[1]
            phi[r + 2] = q[o + 2] - np.cos(f[2])
            phi[r + 3] = q[o + 3] - np.sin(f[2])
            for k in range(4):
                jac[r + k, o + k] = 1.0
        elif kind == CON_WELD:
            _coincident_points(sys, c, r, q, qd, phi, jac, gamma)
            b0 = sys.con_i[c, 2]
            b1 = sys.con_i[c, 3]
            phi[r + 2] = q[b1 + 2] - q[b0 + 2] - f[0]
            jac[r + 2, b1 + 2] = 1.0
            jac[r + 2, b0 + 2] = -1.0

"""Minimal coordinates of a rigid mechanism whose ideal joints form a tree.

With clearance in some joints, the ideal revolute joints that remain often form a tree
rooted at the ground: on the six-bar with clearances in A and B, ground–O–crank (driven),
ground–C–rod3–D2–rod4, rod4–D1–rod2 and rod4–E–slider, no loop left to close. The motion is
then an ordinary differential equation in the absolute angles z of the undriven bodies (4
on that six-bar, against 15 absolute coordinates and 11 constraint rows). Each hinge places
its child from its parent (parent p, child c, body-frame hinge points u_p, u_c, rotation
A(θ); the ground's point is its fixed position):

    r_c = r_p + A(θ_p) u_p − A(θ_c) u_c
    ṙ_c = ṙ_p + θ̇_p B(θ_p) u_p − θ̇_c B(θ_c) u_c              B(θ) u = A(θ) (−u_y, u_x)
    r̈_c = J_c z̈ + r̈_p,b − θ̇_p² A(θ_p) u_p + θ̇_c² A(θ_c) u_c    (r̈_p,b: the parent's)

so that q̇ = J(q) ż (+ the drive's part) and q̈ = J z̈ + a_b, a_b the centripetal terms. The
driven body's angle is the drive's θ_d(t) = θ_0 + ω t; its column of J (the last one) gives
the drive torque (sim.solve.dae.tree_accelerations). Body-frame points are measured from
each body's centre of mass, as everywhere in `System` (sim.model.system).

The absolute coordinates stay the integrator's state, so every output, gap and analysis
reads them as before; they are slaves of (z, ż), rebuilt from the angles at every
evaluation, at the end of every step and at every start from a given state (Hairer, Lubich
& Wanner, Geometric Numerical Integration, 2006, IV.4: projection onto the manifold).
Kinematics after Nikravesh, Computer-Aided Analysis of Mechanical Systems, 1988, ch. 7
(relative coordinates) and the projection of the equations of motion after Kane & Levinson,
Dynamics, 1985.
"""

from collections import deque

import numpy as np

from sim.jit import kernel_inline
from sim.model.system import CON_DRIVE, CON_REVOLUTE, POINT_GROUND, POINT_RIGID

#: one hinge of the tree, in an order where every parent comes before its children
HINGE = np.dtype(
    [
        ("parent", np.int64),  # coordinate offset of the parent body, −1 for the ground
        ("child", np.int64),  # coordinate offset of the child body
        ("column", np.int64),  # the child's angle: its column of J (the drive's is the last)
        # scalar fields: a record's array field would be a view built at every access
        ("parent_ux", np.float64),  # m, parent's body-frame hinge point (ground: position)
        ("parent_uy", np.float64),
        ("child_ux", np.float64),  # m, child's body-frame hinge point
        ("child_uy", np.float64),
        ("angle0", np.float64),  # rad, driven body: θ_d at t = 0
        ("rate", np.float64),  # rad/s, driven body: ω
    ]
)


def spanning_tree(system) -> np.ndarray:
    """The hinges (`HINGE`) of `system` when its bodies are all rigid and its ideal
    constraints are revolute joints that join every body to the ground without a loop, plus
    one drive of a body's angle; an empty array otherwise (the system then keeps the
    multiplier form of sim.solve.dae)."""
    empty = np.zeros(0, dtype=HINGE)
    if system.beam_off.size or system.md_off.size or system.n % 3:
        return empty
    kinds = set(system.con_type.tolist())
    if not kinds <= {CON_REVOLUTE, CON_DRIVE} or system.con_type.tolist().count(CON_DRIVE) != 1:
        return empty
    drive = int(np.flatnonzero(system.con_type == CON_DRIVE)[0])
    driven = int(system.con_i[drive, 0]) - 2
    if driven % 3:
        return empty
    edges = []  # (body offset or −1, its point, other body offset or −1, its point)
    for c in np.flatnonzero(system.con_type == CON_REVOLUTE):
        ends = []
        for k in system.con_i[c, :2]:
            if system.pt_kind[k] == POINT_GROUND:
                ends.append((-1, tuple(system.pt_u[k])))
            elif system.pt_kind[k] == POINT_RIGID:
                ends.append((int(system.pt_off[k]), tuple(system.pt_u[k])))
            else:
                return empty
        edges.append(ends)
    placed, hinges, queue, free = {-1}, [], deque([-1]), 0
    while queue:
        parent = queue.popleft()
        for ends in edges:
            offsets = [o for o, _ in ends]
            if parent not in offsets or all(o in placed for o in offsets):
                continue
            (p_off, p_u), (c_off, c_u) = ends if offsets[0] == parent else ends[::-1]
            if c_off in placed:
                return empty  # the edge closes a loop
            placed.add(c_off)
            queue.append(c_off)
            hinges.append([p_off, c_off, p_u, c_u])
    if len(hinges) != len(edges) or len(placed) != system.n // 3 + 1 or driven not in placed:
        return empty  # a loop, or a body no ideal joint holds
    tree = np.zeros(len(hinges), dtype=HINGE)
    for h, (p_off, c_off, p_u, c_u) in enumerate(hinges):
        tree[h]["parent"], tree[h]["child"] = p_off, c_off
        tree[h]["parent_ux"], tree[h]["parent_uy"] = p_u
        tree[h]["child_ux"], tree[h]["child_uy"] = c_u
        if c_off == driven:
            tree[h]["column"] = len(hinges) - 1
            tree[h]["angle0"], tree[h]["rate"] = system.con_f[drive, :2]
        else:
            tree[h]["column"] = free
            free += 1
    return tree


@kernel_inline
def tree_kinematics(sys, t: float, y: np.ndarray, q, qd, jac, bias, rot) -> None:
    """Absolute q and q̇ (into q, qd), J = ∂q̇/∂ż with the driven angle's column last (into
    jac, n × hinges) and the centripetal accelerations a_b (into bias) of the tree `sys.tree`
    at time t, from the angles and angle rates that the state y holds (the driven body's
    from the drive). rot (n, 2) keeps each body's (cos θ, sin θ) at its offset."""
    n = sys.n
    jac[:, :] = 0.0
    for h in range(sys.tree.shape[0]):
        hinge = sys.tree[h]
        p = hinge.parent
        c = hinge.child
        col = hinge.column
        if col == sys.tree.shape[0] - 1:
            q[c + 2] = hinge.angle0 + hinge.rate * t
            qd[c + 2] = hinge.rate
        else:
            q[c + 2] = y[c + 2]
            qd[c + 2] = y[n + c + 2]
        w = qd[c + 2]
        cos_c = np.cos(q[c + 2])
        sin_c = np.sin(q[c + 2])
        rot[c, 0] = cos_c
        rot[c, 1] = sin_c
        ax = cos_c * hinge.child_ux - sin_c * hinge.child_uy  # A(θ_c) u_c
        ay = sin_c * hinge.child_ux + cos_c * hinge.child_uy
        if p < 0:
            x, yy = hinge.parent_ux, hinge.parent_uy
            vx = vy = bx = by = 0.0
        else:
            cos_p = rot[p, 0]
            sin_p = rot[p, 1]
            px = cos_p * hinge.parent_ux - sin_p * hinge.parent_uy  # A(θ_p) u_p
            py = sin_p * hinge.parent_ux + cos_p * hinge.parent_uy
            wp = qd[p + 2]
            x, yy = q[p] + px, q[p + 1] + py
            vx, vy = qd[p] - wp * py, qd[p + 1] + wp * px
            bx, by = bias[p] - wp * wp * px, bias[p + 1] - wp * wp * py
            for k in range(jac.shape[1]):
                jac[c, k] = jac[p, k] - jac[p + 2, k] * py
                jac[c + 1, k] = jac[p + 1, k] + jac[p + 2, k] * px
        q[c] = x - ax
        q[c + 1] = yy - ay
        qd[c] = vx + w * ay
        qd[c + 1] = vy - w * ax
        bias[c] = bx + w * w * ax
        bias[c + 1] = by + w * w * ay
        bias[c + 2] = 0.0
        jac[c, col] += ay
        jac[c + 1, col] -= ax
        jac[c + 2, col] = 1.0

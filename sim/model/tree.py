"""Minimal coordinates of a mechanism of rigid bodies and modal links whose ideal joints form
a tree.

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

A modal link (sim.model.modal) adds its modal amplitudes q_m to z, and its hinge points move
in its frame, u = ū + Ψ q_m. Then A(θ) u gains the velocity A Ψ q̇_m, which enters J through
the columns of q_m, and the acceleration terms 2 θ̇ k × (A Ψ q̇_m) enter a_b
(sim.model.kinematics, point_quadratic_acceleration). z holds the undriven angles, then the
modal amplitudes, then the driven angle: J has hinges + modes columns.

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
from sim.model.system import CON_DRIVE, CON_REVOLUTE, POINT_GROUND, POINT_MODAL, POINT_RIGID

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
        ("parent_point", np.int64),  # the hinge's point on the parent (its modal shapes)
        ("child_point", np.int64),  # the hinge's point on the child
        ("parent_modes", np.int64),  # the parent's modal amplitudes (0: rigid or ground)
        ("child_modes", np.int64),  # the child's modal amplitudes (0: a rigid body)
        ("modal_column", np.int64),  # the column of J of the first of them
    ]
)


def spanning_tree(system) -> np.ndarray:
    """The hinges (`HINGE`) of `system` when its bodies are rigid bodies and modal links, and
    its ideal constraints are revolute joints that join every body to the ground without a
    loop, plus one drive of a rigid body's angle; an empty array otherwise (the system then
    keeps the multiplier form of sim.solve.dae)."""
    empty = np.zeros(0, dtype=HINGE)
    if system.beam_off.size:
        return empty
    # each body is one mass block: (x, y, θ), then a modal link's amplitudes
    modes = dict(zip(system.md_off.tolist(), system.md_modes.tolist(), strict=True))
    bodies = system.blk_start.tolist()
    if any(
        end - start != 3 + modes.get(start, 0)
        for start, end in zip(bodies, system.blk_end, strict=True)
    ):
        return empty
    kinds = set(system.con_type.tolist())
    if not kinds <= {CON_REVOLUTE, CON_DRIVE} or system.con_type.tolist().count(CON_DRIVE) != 1:
        return empty
    drive = int(np.flatnonzero(system.con_type == CON_DRIVE)[0])
    driven = int(system.con_i[drive, 0]) - 2
    if driven not in bodies or driven in modes:
        return empty
    edges = []  # per joint: (body offset or −1, its point index) of both ends
    for c in np.flatnonzero(system.con_type == CON_REVOLUTE):
        ends = []
        for k in system.con_i[c, :2]:
            if system.pt_kind[k] == POINT_GROUND:
                ends.append((-1, int(k)))
            elif system.pt_kind[k] in (POINT_RIGID, POINT_MODAL):
                ends.append((int(system.pt_off[k]), int(k)))
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
            (p_off, p_k), (c_off, c_k) = ends if offsets[0] == parent else ends[::-1]
            if c_off in placed:
                return empty  # the edge closes a loop
            placed.add(c_off)
            queue.append(c_off)
            hinges.append([p_off, c_off, p_k, c_k])
    if len(hinges) != len(edges) or len(placed) != len(bodies) + 1 or driven not in placed:
        return empty  # a loop, or a body no ideal joint holds
    tree = np.zeros(len(hinges), dtype=HINGE)
    modal_column = len(hinges) - 1  # after the undriven angles
    for h, (p_off, c_off, p_k, c_k) in enumerate(hinges):
        tree[h]["parent"], tree[h]["child"] = p_off, c_off
        tree[h]["parent_point"], tree[h]["child_point"] = p_k, c_k
        tree[h]["parent_ux"], tree[h]["parent_uy"] = system.pt_u[p_k]
        tree[h]["child_ux"], tree[h]["child_uy"] = system.pt_u[c_k]
        tree[h]["parent_modes"] = modes.get(p_off, 0)
        tree[h]["child_modes"] = modes.get(c_off, 0)
        tree[h]["modal_column"] = modal_column
        modal_column += modes.get(c_off, 0)
        if c_off != driven:
            tree[h]["column"] = free
            free += 1
    last = np.flatnonzero(tree["child"] == driven)[0]
    tree["column"][last] = modal_column  # the last column
    tree["angle0"][last], tree["rate"][last] = system.con_f[drive, :2]
    return tree


def tree_columns(tree: np.ndarray) -> int:
    """Columns of J: the tree's angles and its modal links' amplitudes (0 without a tree)."""
    return int(tree.size + tree["child_modes"].sum())


def tree_pattern(tree: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """The columns of J where each of its n rows can be nonzero, ascending (n, columns), and
    how many (n,): the pattern `tree_kinematics` fills. A body's x and y rows hold its
    ancestors' columns (their rows' pattern) and its own angle's and amplitudes'; its angle
    row the angle's column alone; an amplitude's row its own column. The projected mass
    matrix and the accelerations sum over these columns only (sim.solve.dae)."""
    columns = tree_columns(tree)
    pattern: list[set[int]] = [set() for _ in range(n if columns else 0)]
    for hinge in tree:
        p, c, modes = int(hinge["parent"]), int(hinge["child"]), int(hinge["child_modes"])
        own = {int(hinge["modal_column"]) + m for m in range(modes)}
        for m in range(modes):
            pattern[c + 3 + m] = {int(hinge["modal_column"]) + m}
        position = {int(hinge["column"])} | own
        if p >= 0:
            for i in range(p, p + 3 + int(hinge["parent_modes"])):
                position |= pattern[i]
        pattern[c] = pattern[c + 1] = position
        pattern[c + 2] = {int(hinge["column"])}
    cols = np.zeros((len(pattern), columns), dtype=np.int64)
    ncols = np.array([len(row) for row in pattern], dtype=np.int64)
    for i, row in enumerate(pattern):
        cols[i, : len(row)] = sorted(row)
    return cols, ncols


@kernel_inline
def _hinge_point(sys, k: int, o: int, modes: int, ux: float, uy: float, q, qd, cos_t, sin_t):
    """A(θ) u and A(θ) Ψ q̇_m of hinge point k (body-frame ū = (ux, uy)) on the body at offset
    o with `modes` modal amplitudes in q and qd (none for a rigid body or the ground). The
    same sums as sim.model.kinematics' `_local` and `_modal_velocity`, from the hinge's own
    fields: built on those two and on `sys.pt_u`, the rigid flagship ran 5 % slower (paired,
    eight runs each, at f71f65d)."""
    vx = 0.0
    vy = 0.0
    for m in range(modes):
        ux += sys.pt_modal[k, 0, m] * q[o + 3 + m]
        uy += sys.pt_modal[k, 1, m] * q[o + 3 + m]
        vx += sys.pt_modal[k, 0, m] * qd[o + 3 + m]
        vy += sys.pt_modal[k, 1, m] * qd[o + 3 + m]
    return (
        cos_t * ux - sin_t * uy,
        sin_t * ux + cos_t * uy,
        cos_t * vx - sin_t * vy,
        sin_t * vx + cos_t * vy,
    )


@kernel_inline
def tree_kinematics(sys, t: float, y: np.ndarray, q, qd, jac, bias, rot) -> None:
    """Absolute q and q̇ (into q, qd), J = ∂q̇/∂ż with the driven angle's column last (into
    jac, n × columns) and the centripetal and Coriolis accelerations a_b (into bias) of the
    tree `sys.tree` at time t, from the angles, modal amplitudes and their rates that the
    state y holds (the driven body's angle from the drive). rot (n, 2) keeps each body's
    (cos θ, sin θ) at its offset."""
    n = sys.n
    last = jac.shape[1] - 1
    jac[:, :] = 0.0
    for h in range(sys.tree.shape[0]):
        hinge = sys.tree[h]
        p = hinge.parent
        c = hinge.child
        col = hinge.column
        if col == last:
            q[c + 2] = hinge.angle0 + hinge.rate * t
            qd[c + 2] = hinge.rate
        else:
            q[c + 2] = y[c + 2]
            qd[c + 2] = y[n + c + 2]
        for m in range(hinge.child_modes):  # the child's amplitudes are free coordinates
            i = c + 3 + m
            q[i] = y[i]
            qd[i] = y[n + i]
            bias[i] = 0.0
            jac[i, hinge.modal_column + m] = 1.0
        w = qd[c + 2]
        cos_c = np.cos(q[c + 2])
        sin_c = np.sin(q[c + 2])
        rot[c, 0] = cos_c
        rot[c, 1] = sin_c
        # A(θ_c) u_c and A(θ_c) Ψ_c q̇_m of the child's hinge point
        modes = hinge.child_modes
        ax, ay, mx, my = _hinge_point(
            sys, hinge.child_point, c, modes, hinge.child_ux, hinge.child_uy, q, qd, cos_c, sin_c
        )
        if p < 0:
            x, yy = hinge.parent_ux, hinge.parent_uy
            vx = vy = bx = by = 0.0
        else:
            cos_p = rot[p, 0]
            sin_p = rot[p, 1]
            k = hinge.parent_point
            px, py, pmx, pmy = _hinge_point(
                sys, k, p, hinge.parent_modes, hinge.parent_ux, hinge.parent_uy, q, qd, cos_p, sin_p
            )
            wp = qd[p + 2]
            x, yy = q[p] + px, q[p + 1] + py
            vx, vy = qd[p] - wp * py + pmx, qd[p + 1] + wp * px + pmy
            bx = bias[p] - wp * wp * px - 2.0 * wp * pmy
            by = bias[p + 1] - wp * wp * py + 2.0 * wp * pmx
            for a in range(jac.shape[1]):
                jac[c, a] = jac[p, a] - jac[p + 2, a] * py
                jac[c + 1, a] = jac[p + 1, a] + jac[p + 2, a] * px
            for m in range(hinge.parent_modes):
                ex = cos_p * sys.pt_modal[k, 0, m] - sin_p * sys.pt_modal[k, 1, m]
                ey = sin_p * sys.pt_modal[k, 0, m] + cos_p * sys.pt_modal[k, 1, m]
                for a in range(jac.shape[1]):
                    jac[c, a] += ex * jac[p + 3 + m, a]
                    jac[c + 1, a] += ey * jac[p + 3 + m, a]
        q[c] = x - ax
        q[c + 1] = yy - ay
        qd[c] = vx + w * ay - mx
        qd[c + 1] = vy - w * ax - my
        bias[c] = bx + w * w * ax + 2.0 * w * my
        bias[c + 1] = by + w * w * ay - 2.0 * w * mx
        bias[c + 2] = 0.0
        jac[c, col] += ay
        jac[c + 1, col] -= ax
        jac[c + 2, col] = 1.0
        k = hinge.child_point
        for m in range(modes):
            jac[c, hinge.modal_column + m] -= (
                cos_c * sys.pt_modal[k, 0, m] - sin_c * sys.pt_modal[k, 1, m]
            )
            jac[c + 1, hinge.modal_column + m] -= (
                sin_c * sys.pt_modal[k, 0, m] + cos_c * sys.pt_modal[k, 1, m]
            )

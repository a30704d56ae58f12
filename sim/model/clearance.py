"""Clearance joints: the gaps they monitor and the contact forces they apply.

Revolute clearance (bearing point B on one body, journal point J on the other):
    e = r_J − r_B, δ = |e| − c, n = e/|e|, t = k × n;
contact points Q_J = r_J + R_J n and Q_B = r_B + R_B n; δ̇ = n·ė; slip v_t is the
tangential relative velocity of the material points at Q_J and Q_B. The force
−F_n n + F_t t acts on the journal at Q_J and its opposite on the bearing at Q_B
(Flores & Ambrósio, Comput. Struct. 82, 2004). A lubricated one adds its oil film's force
(sim.model.lubrication); its outputs `normal_force` and `friction_force` are then the radial
(towards the centre) and tangential forces of film and contact together.

Translational clearance (rigid slider of length L and width W in a ground guide
of width H through point p with direction t_g and normal n_g): each corner i is
checked against both walls, δ_i± = ±(r_i − p)·n_g − H/2. When the two corners of
one edge both penetrate the same wall the face law F = K_face δ̄ acts at the
centroid of the penetrated (trapezoidal) area, δ̄ the mean depth of the edge;
otherwise every penetrating corner gets a Hertz force with the joint's damping law
(`sim.model.contact_laws`) and its own onset memory (Flores et al., Multibody Syst.
Dyn. 16, 2006; the paper's eqs. 10–18). Friction acts along the guide at each force's point.

The gaps (one per revolute clearance, one per slider corner and wall) and their
contact memory are numbered and laid out in `sim.model.gaps`: the in-contact flag and
the onset rate δ̇⁻ are written by the integrator at the located crossing. A stage that
sees δ > 0 before the crossing was located uses its own δ̇ as δ̇⁻: the same value it
tends to at the crossing.
"""

import numpy as np

from sim.jit import kernel, kernel_inline
from sim.model.contact import friction_force, johnson_elastic, normal_force
from sim.model.contact_laws import STIFFNESS_JOHNSON
from sim.model.gaps import (
    CORNERS_PER_SLIDER,
    GAP_REVOLUTE,
    MEM_GRAZED,
    MEM_IN_CONTACT,
    MEM_ONSET_RATE,
    gap_owner,
    slider_gap,
)
from sim.model.kinematics import (
    apply_point_force_rotated,
    body_rotation,
    frame_rotation,
    point_position_rotated,
    point_rotation,
    point_velocity_rotated,
)
from sim.model.lubrication import BEARING_DRY, lubricated_joint
from sim.model.system import (
    OUT_FRICTION_FORCE,
    OUT_NORMAL_FORCE,
    OUT_PENETRATION,
    OUT_RATE,
    OUT_STATE,
    SLIDER_LAW_WINKLER,
)

# Corner signs in the slider frame (x along the slider's length, y across), in
# order around the block so that corners i and i+1 (mod 4) share an edge.
CORNER_SX = (1.0, -1.0, -1.0, 1.0)
CORNER_SY = (1.0, 1.0, -1.0, -1.0)


@kernel_inline
def eccentricity(sys, j: int, q: np.ndarray) -> tuple[float, float]:
    """Eccentricity vector e = r_J − r_B (m) of revolute clearance j."""
    cb, sb = point_rotation(sys, sys.rj_pts[j, 0], q)
    cj, sj = point_rotation(sys, sys.rj_pts[j, 1], q)
    return _eccentricity(sys, j, q, cb, sb, cj, sj)


@kernel_inline
def _eccentricity(sys, j: int, q: np.ndarray, cb: float, sb: float, cj: float, sj: float):
    """`eccentricity` with the bearing's and the journal's (cos θ, sin θ) given."""
    bx, by = point_position_rotated(sys, sys.rj_pts[j, 0], q, cb, sb)
    jx, jy = point_position_rotated(sys, sys.rj_pts[j, 1], q, cj, sj)
    return jx - bx, jy - by


@kernel_inline
def eccentricity_rate(sys, j: int, q: np.ndarray, qd: np.ndarray) -> tuple[float, float]:
    """ė (m/s) of revolute clearance j."""
    cb, sb = point_rotation(sys, sys.rj_pts[j, 0], q)
    cj, sj = point_rotation(sys, sys.rj_pts[j, 1], q)
    return _eccentricity_rate(sys, j, q, qd, cb, sb, cj, sj)


@kernel_inline
def _eccentricity_rate(sys, j: int, q, qd, cb: float, sb: float, cj: float, sj: float):
    """`eccentricity_rate` with the bearing's and the journal's (cos θ, sin θ) given."""
    bx, by = point_velocity_rotated(sys, sys.rj_pts[j, 0], q, qd, 0.0, 0.0, cb, sb)
    jx, jy = point_velocity_rotated(sys, sys.rj_pts[j, 1], q, qd, 0.0, 0.0, cj, sj)
    return jx - bx, jy - by


@kernel_inline
def guide_frame(sys, j: int) -> tuple[float, float, float, float]:
    """Tangent and normal (t_x, t_y, n_x, n_y) of the guide of translational clearance j."""
    c = sys.tj[j].cos_angle
    s = sys.tj[j].sin_angle
    return c, s, -s, c


@kernel_inline
def slider_point_velocity(sys, j: int, qd: np.ndarray, ax: float, ay: float) -> tuple[float, float]:
    """Velocity (m/s) of the slider's material point at offset (ax, ay) from its centre."""
    o = sys.tj_off[j]
    w = qd[o + 2]
    return qd[o] - w * ay, qd[o + 1] + w * ax


@kernel_inline
def slider_pose(sys, j: int, q: np.ndarray) -> tuple[float, float, float, float]:
    """cos θ and sin θ of slider j, and the normal (n_x, n_y) of its guide: the
    trigonometry every corner of one evaluation shares."""
    o = sys.tj_off[j]
    _, _, nx, ny = guide_frame(sys, j)
    return np.cos(q[o + 2]), np.sin(q[o + 2]), nx, ny


@kernel_inline
def corner_depth(
    sys, j: int, i: int, side: float, q, c: float, s: float, nx: float, ny: float
) -> tuple[float, float, float]:
    """Penetration δ (m) and the corner's offset (a_x, a_y) from the slider centre, for
    corner i of slider j against wall `side`, from its pose (`slider_pose`)."""
    o = sys.tj_off[j]
    ux = 0.5 * CORNER_SX[i] * sys.tj[j].length
    uy = 0.5 * CORNER_SY[i] * sys.tj[j].width
    ax = c * ux - s * uy
    ay = s * ux + c * uy
    lateral = (q[o] + ax - sys.tj[j].px) * nx + (q[o + 1] + ay - sys.tj[j].py) * ny
    return side * lateral - 0.5 * sys.tj[j].gap_width, ax, ay


@kernel_inline
def corner_gap(
    sys, j: int, i: int, side: float, q, qd, c: float, s: float, nx: float, ny: float
) -> tuple[float, float, float, float]:
    """`corner_depth` and the penetration's rate (m/s): (δ, δ̇, a_x, a_y)."""
    delta, ax, ay = corner_depth(sys, j, i, side, q, c, s, nx, ny)
    vx, vy = slider_point_velocity(sys, j, qd, ax, ay)
    return delta, side * (vx * nx + vy * ny), ax, ay


@kernel_inline
def gap(sys, g: int, q: np.ndarray, qd: np.ndarray) -> tuple[float, float]:
    """Penetration δ (m, negative while apart) and its rate δ̇ (m/s) of gap g."""
    kind, j, i, w = gap_owner(sys, g)
    if kind == GAP_REVOLUTE:
        ex, ey = eccentricity(sys, j, q)
        vx, vy = eccentricity_rate(sys, j, q, qd)
        e = np.hypot(ex, ey)
        rate = (ex * vx + ey * vy) / e if e > 0.0 else 0.0
        return e - sys.rj[j].clearance, rate
    c, s, nx, ny = slider_pose(sys, j, q)
    delta, rate, _, _ = corner_gap(sys, j, i, 1.0 if w == 0 else -1.0, q, qd, c, s, nx, ny)
    return delta, rate


@kernel_inline
def gap_depths(sys, q: np.ndarray, out: np.ndarray) -> None:
    """δ (m) of every gap at q into `out`: `gap`'s penetrations without their rates, each
    joint's trigonometry computed once (the scan of every gap at each step's end)."""
    nr = sys.rj_pts.shape[0]
    for j in range(nr):
        ex, ey = eccentricity(sys, j, q)
        out[j] = np.hypot(ex, ey) - sys.rj[j].clearance
    for j in range(sys.tj_off.shape[0]):
        c, s, nx, ny = slider_pose(sys, j, q)
        for i in range(CORNERS_PER_SLIDER):
            for w in range(2):
                side = 1.0 if w == 0 else -1.0
                delta, _, _ = corner_depth(sys, j, i, side, q, c, s, nx, ny)
                out[slider_gap(sys, j, i, w)] = delta


@kernel_inline
def _flagged_edge(sys, mem: np.ndarray, j: int, w: int) -> int:
    """First corner i of an edge (i, i+1) of slider j whose two corners are both flagged
    in contact with wall w, or -1. The contact mode (face or corners) follows the
    flags, which change only at located crossings, so a stage can never switch
    laws before the integrator has found the switch."""
    for i in range(CORNERS_PER_SLIDER):
        nxt = (i + 1) % CORNERS_PER_SLIDER
        if (
            mem[slider_gap(sys, j, i, w), MEM_IN_CONTACT] > 0.0
            and mem[slider_gap(sys, j, nxt, w), MEM_IN_CONTACT] > 0.0
        ):
            return i
    return -1


@kernel_inline
def face_energy(sys, j: int, da: float, db: float) -> float:
    """Elastic energy (J) of slider j's face pressed in to end depths da, db (m)."""
    return sys.tj[j].k_face * (da * da + da * db + db * db) / 6.0


@kernel_inline
def corner_energy(sys, j: int, delta: float) -> float:
    """Elastic energy (J) of one corner of slider j pressed in to depth δ (m)."""
    p = sys.contact.exponent
    return sys.tj[j].k_corner * delta ** (p + 1.0) / (p + 1.0)


@kernel
def face_switch_energy(sys, mem: np.ndarray, g: int, q: np.ndarray, qd: np.ndarray) -> float:
    """Jump (J) of the stored contact energy when gap g's corner reaches its wall
    while the neighbouring corner on the same edge is in contact with it: the
    paper's laws switch there from one Hertz corner to the face law, whose
    energy K_face δa²/6 differs from the corner's K δa^(n+1)/(n+1). The jump is
    released as motion; the energy audit books it (negative: created)."""
    kind, j, i, w = gap_owner(sys, g)
    if kind == GAP_REVOLUTE or sys.contact.slider_law == SLIDER_LAW_WINKLER:
        return 0.0
    for nb in ((i + 1) % CORNERS_PER_SLIDER, (i + CORNERS_PER_SLIDER - 1) % CORNERS_PER_SLIDER):
        neighbour = slider_gap(sys, j, nb, w)
        if mem[neighbour, MEM_IN_CONTACT] > 0.0:
            da, _ = gap(sys, neighbour, q, qd)
            da = max(da, 0.0)
            return face_energy(sys, j, da, 0.0) - corner_energy(sys, j, da)
    return 0.0


@kernel
def _onset_rate(mem: np.ndarray, g: int, rate: float) -> float:
    """δ̇⁻ of gap g: the memory captured at the crossing, or, before the crossing
    was located, the current rate. The latter case is marked MEM_GRAZED so the
    integrator can tell a contact that came and went inside one step (a graze
    its events would miss) from one that it will locate."""
    if mem[g, MEM_IN_CONTACT] > 0.0:
        return mem[g, MEM_ONSET_RATE]
    mem[g, MEM_GRAZED] = 1.0
    return rate


@kernel_inline
def revolute_elastic(sys, j: int, delta: float) -> tuple[float, float]:
    """Elastic force (N) and stored energy (J) of revolute clearance j at penetration
    δ > 0 (m), by its stiffness law: Hertz K δⁿ with energy K δⁿ⁺¹/(n + 1), or Johnson's
    conformal law (`sim.model.contact.johnson_elastic`)."""
    if sys.rj[j].stiffness_law == STIFFNESS_JOHNSON:
        return johnson_elastic(sys.rj[j].stiffness, sys.rj[j].clearance, delta)
    n = sys.contact.exponent
    elastic = sys.rj[j].stiffness * delta**n
    return elastic, elastic * delta / (n + 1.0)


@kernel_inline
def revolute_clearance_forces(
    sys,
    q: np.ndarray,
    qd: np.ndarray,
    mem: np.ndarray,
    gen: np.ndarray,
    jout: np.ndarray,
    rot: np.ndarray,
) -> tuple[float, float]:
    """Add the contact forces of every revolute clearance to `gen`; write the
    per-joint outputs; return (dissipated power W, stored contact energy J). The bodies'
    rotations are read from `rot` when it is given (sim.model.kinematics.frame_rotation)."""
    ce = sys.contact
    p_diss = 0.0
    u_contact = 0.0
    for j in range(sys.rj_pts.shape[0]):
        pb = sys.rj_pts[j, 0]
        pj = sys.rj_pts[j, 1]
        # each body's rotation once for all the points' kinematics below
        cb, sb = body_rotation(sys, pb, q, rot)
        cj, sj = body_rotation(sys, pj, q, rot)
        ex, ey = _eccentricity(sys, j, q, cb, sb, cj, sj)
        e = np.hypot(ex, ey)
        delta = e - sys.rj[j].clearance
        vx, vy = _eccentricity_rate(sys, j, q, qd, cb, sb, cj, sj)
        rate = (ex * vx + ey * vy) / e if e > 0.0 else 0.0
        jout[j, OUT_PENETRATION] = max(delta, 0.0)
        jout[j, OUT_RATE] = rate
        jout[j, OUT_NORMAL_FORCE] = 0.0
        jout[j, OUT_FRICTION_FORCE] = 0.0
        jout[j, OUT_STATE] = 0.0
        if sys.rj_film[j].bearing != BEARING_DRY:
            film_n, film_t, p_film = lubricated_joint(sys, j, q, qd, gen, ex, ey, cb, sb, cj, sj)
            p_diss += p_film
            jout[j, OUT_NORMAL_FORCE] = film_n
            jout[j, OUT_FRICTION_FORCE] = film_t
        if delta <= 0.0:
            continue
        fel, energy = revolute_elastic(sys, j, delta)
        fn = normal_force(
            sys.rj[j].law,
            sys.rj[j].damping,
            fel,
            delta,
            rate,
            _onset_rate(mem, j, rate),
            ce.exponent,
            ce.min_impact_speed,
        )
        nx = ex / e
        ny = ey / e
        rj = sys.rj[j].journal_radius
        rb = sys.rj[j].bearing_radius
        vjx, vjy = point_velocity_rotated(sys, pj, q, qd, rj * nx, rj * ny, cj, sj)
        vbx, vby = point_velocity_rotated(sys, pb, q, qd, rb * nx, rb * ny, cb, sb)
        slip = -ny * (vjx - vbx) + nx * (vjy - vby)
        ft = friction_force(fn, slip, ce.friction, ce.v0, ce.v1)
        fx = -fn * nx - ft * ny
        fy = -fn * ny + ft * nx
        apply_point_force_rotated(sys, pj, q, fx, fy, rj * nx, rj * ny, gen, cj, sj)
        apply_point_force_rotated(sys, pb, q, -fx, -fy, rb * nx, rb * ny, gen, cb, sb)
        p_diss += (fn - fel) * rate - ft * slip
        u_contact += energy
        jout[j, OUT_NORMAL_FORCE] += fn
        jout[j, OUT_FRICTION_FORCE] += ft
        jout[j, OUT_STATE] = 1.0
    return p_diss, u_contact


@kernel_inline
def _slider_force(
    sys,
    j: int,
    q: np.ndarray,
    qd: np.ndarray,
    side: float,
    fn: float,
    ax: float,
    ay: float,
    gen: np.ndarray,
) -> tuple[float, float]:
    """Apply a wall's normal force fn (pushing the slider away from wall `side`)
    and the friction along the guide at slider offset (ax, ay); return the
    friction force (N, along t_g) and its dissipated power (W)."""
    tx, ty, nx, ny = guide_frame(sys, j)
    vx, vy = slider_point_velocity(sys, j, qd, ax, ay)
    slip = vx * tx + vy * ty
    ce = sys.contact
    ft = friction_force(fn, slip, ce.friction, ce.v0, ce.v1)
    fx = -side * fn * nx + ft * tx
    fy = -side * fn * ny + ft * ty
    o = sys.tj_off[j]
    gen[o] += fx
    gen[o + 1] += fy
    gen[o + 2] += ax * fy - ay * fx
    return ft, -ft * slip


@kernel
def _winkler_edge(sys, j, w, q, qd, mem, gen, c, s, nx, ny):
    """The long edge of slider j that faces wall w, pressed into an elastic
    foundation of stiffness k' = K_face / L per unit length (Winkler).

    With end depths δa, δb (m, negative where apart) the penetrated part is the
    whole edge (a trapezoid) or, for one corner in, a triangle of length
    ℓ = L δa / (δa − δb); the elastic force k'·area acts at the area's centroid
    and derives from U = k' ∫ δ² / 2 ds. Both corners in, this is the paper's face
    law; one corner in, its wedge limit, continuous with it. Damping by the joint's law
    (`sim.model.contact.normal_force`, exponent 1 and the face's coefficient), with the rate
    at the force's point and the onset rate of the edge's first corner. (c, s, n_x, n_y): the
    slider's pose (`slider_pose`).

    Returns (normal force N, friction N, dissipated power W, elastic energy J,
    deepest penetration m)."""
    # Which long edge faces wall w: the one whose outward normal (body +y for
    # corners 0, 1, that is (−sin θ, cos θ)) points along side·n_g.
    side = 1.0 if w == 0 else -1.0
    a = 0 if side * (-s * nx + c * ny) > 0.0 else 2
    b = a + 1
    ga = slider_gap(sys, j, a, w)
    gb = slider_gap(sys, j, b, w)
    da, ra, aax, aay = corner_gap(sys, j, a, side, q, qd, c, s, nx, ny)
    db, rb, abx, aby = corner_gap(sys, j, b, side, q, qd, c, s, nx, ny)
    if da <= 0.0 and db <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0
    k_face = sys.tj[j].k_face
    if da > 0.0 and db > 0.0:
        frac = (da + 2.0 * db) / (3.0 * (da + db))
        f_el = 0.5 * k_face * (da + db)
        u_el = k_face * (da * da + da * db + db * db) / 6.0
    elif da > 0.0:
        share = da / (da - db)  # ℓ / L
        frac = share / 3.0
        f_el = 0.5 * k_face * share * da
        u_el = k_face * share * da * da / 6.0
    else:
        share = db / (db - da)
        frac = 1.0 - share / 3.0
        f_el = 0.5 * k_face * share * db
        u_el = k_face * share * db * db / 6.0
    rate = ra + frac * (rb - ra)
    in_a = mem[ga, MEM_IN_CONTACT] > 0.0
    in_b = mem[gb, MEM_IN_CONTACT] > 0.0
    if in_a or in_b:
        onset = max(
            mem[ga, MEM_ONSET_RATE] if in_a else 0.0, mem[gb, MEM_ONSET_RATE] if in_b else 0.0
        )
    else:
        onset = _onset_rate(mem, ga if da > 0.0 else gb, rate)
    ce = sys.contact
    fn = normal_force(
        sys.tj[j].law,
        sys.tj[j].face_damping,
        f_el,
        max(da, db),
        rate,
        onset,
        1.0,
        ce.min_impact_speed,
    )
    cx = aax + frac * (abx - aax)
    cy = aay + frac * (aby - aay)
    ft, pf = _slider_force(sys, j, q, qd, side, fn, cx, cy, gen)
    return fn, ft, pf + (fn - f_el) * rate, u_el, max(da, db)


@kernel_inline
def translational_clearance_forces(
    sys,
    q: np.ndarray,
    qd: np.ndarray,
    mem: np.ndarray,
    gen: np.ndarray,
    jout: np.ndarray,
    rot: np.ndarray,
) -> tuple[float, float]:
    """Add the contact forces of every translational clearance to `gen`; write the
    per-joint outputs; return (dissipated power W, stored contact energy J). The sliders'
    rotations are read from `rot` when it is given (sim.model.kinematics.frame_rotation).

    The face law is an elastic (Winkler) foundation along the edge: pressure
    k' δ(s) with k' = K_face / L gives the total force K_face δ̄ at the centroid
    of the penetrated area, exactly the paper's law, and derives from the
    potential U = K_face (δa² + δa δb + δb²) / 6 of the edge's end depths."""
    ce = sys.contact
    nr = sys.rj_pts.shape[0]
    p_diss = 0.0
    u_contact = 0.0
    for j in range(sys.tj_off.shape[0]):
        row = nr + j
        total_fn = 0.0
        total_ft = 0.0
        deepest = 0.0
        state = 0.0
        c, s = frame_rotation(q, sys.tj_off[j], rot)
        _, _, nx, ny = guide_frame(sys, j)
        for w in range(2):
            side = 1.0 if w == 0 else -1.0
            if ce.slider_law == SLIDER_LAW_WINKLER:
                fn, ft, pd, ue, depth = _winkler_edge(sys, j, w, q, qd, mem, gen, c, s, nx, ny)
                if fn > 0.0 or depth > 0.0:
                    state = max(state, 2.0 if depth > 0.0 and fn > 0.0 else 1.0)
                p_diss += pd
                u_contact += ue
                total_fn += fn
                total_ft += ft
                deepest = max(deepest, depth)
                continue
            first = _flagged_edge(sys, mem, j, w)
            if first >= 0:
                second = (first + 1) % CORNERS_PER_SLIDER
                da, _, aax, aay = corner_gap(sys, j, first, side, q, qd, c, s, nx, ny)
                db, _, abx, aby = corner_gap(sys, j, second, side, q, qd, c, s, nx, ny)
                # At a located crossing one depth may be a hair below zero.
                da = max(da, 0.0)
                db = max(db, 0.0)
                deepest = max(deepest, da, db)
                state = 2.0
                if da + db <= 0.0:
                    continue
                frac = (da + 2.0 * db) / (3.0 * (da + db))
                cx = aax + frac * (abx - aax)
                cy = aay + frac * (aby - aay)
                fn = sys.tj[j].k_face * 0.5 * (da + db)
                ft, pf = _slider_force(sys, j, q, qd, side, fn, cx, cy, gen)
                p_diss += pf
                u_contact += face_energy(sys, j, da, db)
                total_fn += fn
                total_ft += ft
                continue
            for i in range(CORNERS_PER_SLIDER):
                g = slider_gap(sys, j, i, w)
                delta, rate, ax, ay = corner_gap(sys, j, i, side, q, qd, c, s, nx, ny)
                if delta <= 0.0:
                    continue
                deepest = max(deepest, delta)
                fel = sys.tj[j].k_corner * delta**ce.exponent
                fn = normal_force(
                    sys.tj[j].law,
                    sys.tj[j].damping,
                    fel,
                    delta,
                    rate,
                    _onset_rate(mem, g, rate),
                    ce.exponent,
                    ce.min_impact_speed,
                )
                ft, pf = _slider_force(sys, j, q, qd, side, fn, ax, ay, gen)
                p_diss += pf + (fn - fel) * rate
                u_contact += corner_energy(sys, j, delta)
                total_fn += fn
                total_ft += ft
                state = max(state, 1.0)
        jout[row, OUT_PENETRATION] = deepest
        jout[row, OUT_NORMAL_FORCE] = total_fn
        jout[row, OUT_FRICTION_FORCE] = total_ft
        jout[row, OUT_STATE] = state
        o = sys.tj_off[j]
        jout[row, OUT_RATE] = qd[o] * nx + qd[o + 1] * ny
    return p_diss, u_contact

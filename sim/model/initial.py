"""Initial position and velocity analysis.

Positions: Newton–Raphson on Φ(q, t0) = 0 from the scene's hints, with the minimum-norm
correction Δq = −Φ_q⁺ Φ so that free coordinates stay near their hints (Nikravesh 1988,
ch. 4; Haug 1989, ch. 3); bodies without a hint are found by a search from several guesses,
which reports the assembly branch it takes (`assemble`). Velocities: the minimum-norm
solution of Φ_q q̇ = ν; accelerations likewise from Φ_q q̈ = γ. Solved on the all-ideal,
all-rigid mechanism, so every clearance joint starts centred (zero eccentricity), as
docs/model.md says; beams are then laid along their rigid pose and, by default, deformed to
carry its loads (`quasi_static_beams`).
"""

import math
from collections.abc import Callable, Iterator
from typing import NamedTuple

import numpy as np

from sim.model import ancf, modal
from sim.model.assembly import AssemblyError, Layout, build_system, local_points
from sim.model.constraints import constraint_terms
from sim.model.system import System
from sim.scene import GROUND


def constraint_values(system: System, q: np.ndarray, qd: np.ndarray, t: float):
    """Φ, Φ_q and ν at (q, q̇, t) as fresh arrays (setup code, not the hot loop)."""
    phi = np.zeros(system.m)
    jac = np.zeros((system.m, system.n))
    gamma = np.zeros(system.m)
    nu = np.zeros(system.m)
    constraint_terms(system, t, q, qd, phi, jac, gamma, nu)
    return phi, jac, nu


def minimum_norm_newton(
    linearize: Callable[[np.ndarray], tuple[np.ndarray, np.ndarray]],
    x0: np.ndarray,
    tolerance: float,
    iterations: int,
) -> tuple[np.ndarray, bool]:
    """Solve r(x) = 0 from x0 by Newton with minimum-norm corrections Δx = −r_x⁺ r, which
    leave the directions r does not constrain at their start values (Nikravesh 1988, ch. 4).
    `linearize(x)` returns (r, r_x); converged when max |r| < `tolerance` (units of r).
    Returns the last iterate and whether it converged within `iterations` corrections."""
    x = x0.copy()
    for _ in range(iterations):
        r, r_x = linearize(x)
        if np.max(np.abs(r), initial=0.0) < tolerance:
            return x, True
        x -= np.linalg.lstsq(r_x, r, rcond=None)[0]
    return x, bool(np.max(np.abs(linearize(x)[0]), initial=0.0) < tolerance)


# At the least-squares closest approach a joint whose gap is below this share of the largest
# closes: the tight tolerances below leave closed joints near 1e-11 m against gaps of mm.
_OPEN_SHARE = 1e-3
# Starts of the branch search when some bodies have no hint (each closes the loops from other
# angles of those bodies); a four-bar has two branches, a six-bar four.
_STARTS = 12
# Two assemblies whose angles differ by less than this (rad) are one branch.
_SAME_BRANCH = 1e-6


def _close(linearize: Callable, q0: np.ndarray) -> tuple[np.ndarray, bool]:
    """Close every loop from q0: Newton, and when it fails (from a far guess its iterates can
    wander for 50 iterations) Newton again from the least-squares closest approach, which
    converges when that approach is an assembly. Returns the closest approach and False when
    no assembly is near."""
    q, converged = minimum_norm_newton(linearize, q0, 1e-13, 50)
    if converged:
        return q, True
    # imported here: Newton closes the loops of almost every start, and scipy.optimize takes
    # a quarter of a second of each `sim` start to import
    from scipy.optimize import least_squares

    closest = least_squares(
        lambda x: linearize(x)[0], q0, jac=lambda x: linearize(x)[1], xtol=1e-15, ftol=1e-15
    ).x
    q, converged = minimum_norm_newton(linearize, closest, 1e-13, 50)
    return (q, True) if converged else (closest, False)


def solve_positions(system: System, layout: Layout, q0: np.ndarray, t: float = 0.0) -> np.ndarray:
    """Close every loop from the guess q0; AssemblyError names the loop that cannot close."""
    linearize = _linearization(system, t)
    q, closed = _close(linearize, q0)
    if closed:
        return q
    raise AssemblyError(_open_loop(linearize, layout, q))


def _linearization(system: System, t: float) -> Callable:
    """x ↦ (Φ(x, t), Φ_q(x, t)) of the position analysis."""
    zero = np.zeros(system.n)

    def linearize(q):
        phi, jac, _ = constraint_values(system, q, zero, t)
        return phi, jac

    return linearize


def _open_loop(linearize: Callable, layout: Layout, closest: np.ndarray) -> str:
    """Why the loops do not close, for the message, from the least-squares closest approach
    (Newton's last iterate is arbitrary when no assembly exists): the joints still open there
    form the loop that cannot close, each with its gap (m; angles of welds and guides in rad).
    The drive's row, an angle, is left out of the account."""
    residual = linearize(closest)[0]
    gaps = {
        name: float(np.linalg.norm(residual[first : first + count]))
        for name, first, count in layout.constraint_rows
        if name != "drive"
    }
    worst = max(gaps, key=gaps.get)
    loop = [name for name, gap in gaps.items() if gap > _OPEN_SHARE * gaps[worst]]
    return (
        f"the linkage cannot close: the loop through joints {', '.join(loop)} cannot close; "
        f"closest approach (least squares from the scene's hints): joint '{worst}' misses by "
        f"{gaps[worst]:.3g} m, the loop's gaps sum to {sum(gaps[n] for n in loop):.3g} m. A "
        "link of that loop is too short or too long for the others, or the hints point to no "
        "assembly branch: check the lengths, ground points and bodies.<name>.hint."
    )


def solve_velocities(system: System, q: np.ndarray, t: float = 0.0) -> np.ndarray:
    """Minimum-norm q̇ with Φ_q q̇ = ν."""
    _, jac, nu = constraint_values(system, q, np.zeros_like(q), t)
    return np.linalg.lstsq(jac, nu, rcond=None)[0]


#: Assembly.branch when every body has a hint
HINTED = "from the scene's hints"


class Assembly(NamedTuple):
    """The all-ideal, all-rigid mechanism assembled at t = 0: positions, velocities, its
    system and layout, and which assembly branch was taken (for the log and the output)."""

    q: np.ndarray
    qd: np.ndarray
    system: System
    layout: Layout
    branch: str


def _guesses(scene: dict, layout: Layout) -> Iterator[np.ndarray]:
    """Guesses of the rigid coordinates: bodies with a hint at it; the others placed joint by
    joint from the ground (a pinned body's point on its partner's, a guided body on its
    guide) at angles spread over the circle, differently at each of `_STARTS` starts (one
    start when every body has a hint)."""
    bodies = scene["bodies"]
    free = [b for b in layout.bodies if bodies[b]["hint"] is None]
    golden = (math.sqrt(5.0) - 1.0) / 2.0
    for start in range(_STARTS if free else 1):
        pose = {
            b: (
                np.array(bodies[b]["hint"]["position"]),
                math.radians(bodies[b]["hint"]["angle_deg"]),
            )
            for b in layout.bodies
            if b not in free
        }
        angles = {
            b: 2.0 * math.pi * ((start + 1) * golden * (i + 1) % 1.0) for i, b in enumerate(free)
        }
        for _ in free:
            for joint in scene["joints"].values():
                _place(scene, joint, pose, angles)
        guess = np.zeros(3 * len(layout.bodies))
        for b in layout.bodies:
            position, angle = pose.get(b, (np.zeros(2), angles.get(b, 0.0)))
            o = layout.offset[b]
            guess[o : o + 3] = (*position, angle)
        yield guess


def _place(scene: dict, joint: dict, pose: dict, angles: dict) -> None:
    """Place a body of `joint` that has no pose yet from its partner's (see `_guesses`)."""
    pair = joint["bodies"]
    if joint["type"] == "translational":
        if pair[1] in angles and pair[1] not in pose:
            pose[pair[1]] = (np.array(joint["guide_point"]), math.radians(joint["guide_angle_deg"]))
        return
    ends = list(zip(pair, joint["points"], strict=True))
    for (a, pa), (b, pb) in (ends, ends[::-1]):
        if b in angles and b not in pose and (a == GROUND or a in pose):
            local = local_points(scene["bodies"][b])[pb]
            pose[b] = (_world(scene, a, pa, pose) - _rotated(angles[b], local), angles[b])


def _rotated(theta: float, point: tuple[float, float]) -> np.ndarray:
    """`point` (m) turned by theta (rad)."""
    c, s = math.cos(theta), math.sin(theta)
    return np.array([c * point[0] - s * point[1], s * point[0] + c * point[1]])


def _world(scene: dict, body: str, point: str, pose: dict) -> np.ndarray:
    """Global position (m) of a body's named point at its pose (a ground point's own)."""
    if body == GROUND:
        return np.array(scene["ground"][point], dtype=float)
    position, theta = pose[body]
    return position + _rotated(theta, local_points(scene["bodies"][body])[point])


def assemble(scene: dict) -> Assembly:
    """The all-ideal, all-rigid mechanism assembled at t = 0 from the scene's hints. Bodies
    without a hint are found by a search from `_STARTS` guesses (`_guesses`); of the distinct
    assemblies it finds (the branches), the first is taken and `Assembly.branch` says which,
    with the others, as the body angles. AssemblyError names the loop that cannot close."""
    system, layout = build_system(scene, ideal=True, rigid=True)
    linearize = _linearization(system, 0.0)
    free = [b for b in layout.bodies if scene["bodies"][b]["hint"] is None]
    branches, first_miss = [], None
    for guess in _guesses(scene, layout):
        q, closed = _close(linearize, guess)
        if not closed:
            first_miss = q if first_miss is None else first_miss
            continue
        angles = np.array([q[layout.offset[b] + 2] for b in free])
        if all(
            np.abs(np.angle(np.exp(1j * (angles - other[1])))).max(initial=0.0) > _SAME_BRANCH
            for other in branches
        ):
            branches.append((q, angles))
    if not branches:
        raise AssemblyError(_open_loop(linearize, layout, first_miss))
    q = branches[0][0]
    branch = HINTED
    if free:

        def described(angles):
            return ", ".join(
                f"{b} {math.degrees(a) % 360.0:.2f}°" for b, a in zip(free, angles, strict=True)
            )

        branch = (
            f"bodies without a hint assembled at angles {described(branches[0][1])}, the first "
            f"of {len(branches)} assembly branches found from {_STARTS} starts"
            + "".join(f"; another: {described(a)}" for _, a in branches[1:])
            + " (give bodies.<name>.hint to choose one)"
        )
    return Assembly(q, solve_velocities(system, q), system, layout, branch)


def solve_accelerations(system: System, q: np.ndarray, qd: np.ndarray, t: float = 0.0):
    """q̈ with Φ_q q̈ = γ (minimum norm): the acceleration analysis of a driven
    mechanism with no free degree of freedom."""
    jac = np.zeros((system.m, system.n))
    gamma = np.zeros(system.m)
    constraint_terms(system, t, q, qd, np.zeros(system.m), jac, gamma, np.zeros(system.m))
    return np.linalg.lstsq(jac, gamma, rcond=None)[0]


def _rigid_motion(
    scene: dict, layout: Layout, assembly: Assembly
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """q, q̇ and q̈ of the all-ideal, all-rigid mechanism at t = 0 in the
    coordinates of `layout`, from the rigid `assembly`: each beam laid straight along its
    rigid pose, its nodes moving with the rigid link (r = R + u e, r' = e with e = (cos θ, sin θ),
    so ṙ = Ṙ + u θ̇ e⊥, r̈ = R̈ + u (θ̈ e⊥ − θ̇² e), and likewise r', e⊥ = (−sin θ, cos θ))."""
    q_r, qd_r, system_r, rigid_layout, _ = assembly
    qdd_r = solve_accelerations(system_r, q_r, qd_r)
    n = sum(
        4 * (layout.elements[b] + 1) if layout.is_beam[b] else 3 + layout.modes.get(b, 0)
        for b in layout.bodies
    )
    # A modal link's frame takes the rigid pose and its modes start at rest at zero.
    q, qd, qdd = np.zeros(n), np.zeros(n), np.zeros(n)
    for name in layout.bodies:
        r = rigid_layout.offset[name]
        o = layout.offset[name]
        if not layout.is_beam[name]:
            q[o : o + 3] = q_r[r : r + 3]
            qd[o : o + 3] = qd_r[r : r + 3]
            qdd[o : o + 3] = qdd_r[r : r + 3]
            continue
        x, y, theta = q_r[r : r + 3]
        vx, vy, w = qd_r[r : r + 3]
        ax, ay, alpha = qdd_r[r : r + 3]
        e = np.array([math.cos(theta), math.sin(theta)])
        e_perp = np.array([-e[1], e[0]])
        length = scene["bodies"][name]["length"]
        ne = layout.elements[name]
        for i in range(ne + 1):
            u = -0.5 * length + i * length / ne
            k = o + 4 * i
            q[k : k + 4] = (*(np.array([x, y]) + u * e), *e)
            qd[k : k + 4] = (*(np.array([vx, vy]) + u * w * e_perp), *(w * e_perp))
            turn = alpha * e_perp - w * w * e
            qdd[k : k + 4] = (*(np.array([ax, ay]) + u * turn), *turn)
    return q, qd, qdd


def _beam_elastic(system: System, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Elastic forces F (n,) and their Jacobian K (n, n) of every beam and modal link at q."""
    force = np.zeros(system.n)
    stiffness = np.zeros((system.n, system.n))
    modal.add_modal_tangent(system, stiffness, 0.0, 1.0)
    force += stiffness @ q
    for b, o in enumerate(system.beam_off):
        size = 4 * (system.beam_nel[b] + 1)
        block = slice(o, o + size)
        consts = (
            system.beam_dshape[b],
            system.beam_axial_w[b],
            system.beam_d2shape[b],
            system.beam_bending_w[b],
        )
        ancf.beam_elastic_forces(q[block], *consts, force[block])
        k = np.zeros((size, size))
        ancf.beam_elastic_jacobian(q[block], *consts, k)
        stiffness[block, block] = k
    return force, stiffness


def quasi_static_beams(
    scene: dict, q: np.ndarray, qd: np.ndarray, qdd: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Beams deformed so that they carry the rigid mechanism's loads at t = 0.

    Solves, on the mechanism with every joint ideal, for the coordinates q and
    multipliers λ with
        F(q) + Φ_q(q)ᵀ λ = Q_g − M q̈_rigid,   Φ(q, 0) = 0,
    the elastic forces F balancing gravity, the inertia of the prescribed rigid
    motion and the joint reactions (docs/model.md, "Beams need care"); Newton with the
    matrix [K, Φ_qᵀ; Φ_q, 0], K = ∂F/∂q. Velocities are the rigid field made
    consistent with the deformed pose (minimum-norm correction of Φ_q q̇ = ν).
    The flexible model then starts with the rigid model's accelerations, to
    within the static deflections."""
    system, _ = build_system(scene, ideal=True)
    load = system.gravity_force - system.mass @ qdd
    q = q.copy()
    lam = np.zeros(system.m)
    n = system.n
    for _ in range(50):
        phi, jac, _ = constraint_values(system, q, np.zeros(n), 0.0)
        force, stiffness = _beam_elastic(system, q)
        residual = np.concatenate([force + jac.T @ lam - load, phi])
        matrix = np.block([[stiffness, jac.T], [jac, np.zeros((system.m, system.m))]])
        step = np.linalg.solve(matrix, -residual)
        q += step[:n]
        lam += step[n:]
        # Converged when the correction reaches round-off of the coordinates
        # (the residual itself stalls near EA·1e-16, about 1e-7 N here).
        if np.abs(step[:n]).max() < 1e-13:
            break
    else:
        raise AssemblyError(
            "the quasi-static beam deformation at the initial crank angle did not converge "
            "in 50 Newton iterations; start the beams straight (simulation.beam_start: "
            "straight) or check the beams' stiffness"
        )
    _, jac, nu = constraint_values(system, q, qd, 0.0)
    qd = qd - np.linalg.lstsq(jac, jac @ qd - nu, rcond=None)[0]
    return q, qd


# A singular value of Φ_q M^(-1/2) at or below this share of the largest counts as zero: the
# integrator refuses a Schur-complement (Φ_q M⁻¹ Φ_qᵀ) pivot below 1e-13 of its diagonal
# (sim/solve/linalg.py), and the Schur complement's eigenvalues are those singular values
# squared, so this is about the integrator's own limit.
_RANK_SHARE = math.sqrt(1e-13)


def check_independent(system: System, layout: Layout, q: np.ndarray) -> None:
    """AssemblyError naming the joints whose constraint rows depend on each other at q (t = 0):
    the rows that carry weight in the left null space of the mass-scaled Φ_q, which the
    integrator could not invert."""
    if system.m == 0:
        return
    _, jac, _ = constraint_values(system, q, np.zeros_like(q), 0.0)
    # Φ_q L⁻ᵀ with M = L Lᵀ: its Gram matrix is the integrator's Φ_q M⁻¹ Φ_qᵀ.
    scaled = np.linalg.solve(np.linalg.cholesky(system.mass), jac.T).T
    left, singular, _ = np.linalg.svd(scaled)
    rank = int(np.sum(singular > _RANK_SHARE * singular[0]))
    weight = np.linalg.norm(left[:, rank:], axis=1)
    owners = dict.fromkeys(layout.joint_of_row(r) for r in np.flatnonzero(weight > 1e-6))
    if not owners:
        return
    joints = [f"'{o}'" for o in owners if o != "drive"]
    named = ", ".join(joints) + (" and the drive" if "drive" in owners else "")
    raise AssemblyError(
        f"the constraints are redundant at t = 0: the rows of joints {named} depend on each "
        "other (they fix the same motion more than once, or the linkage starts in a locked, "
        f"singular position). Remove one of those joints (e.g. {joints[-1]}, defined last) or "
        "give it a clearance (joints.<name>.clearance > 0); if the position is locked, change "
        "drive.initial_angle_deg or the bodies' hints."
    )


def initial_state(
    scene: dict, system: System, layout: Layout, assembly: Assembly
) -> tuple[np.ndarray, np.ndarray]:
    """q and q̇ at t = 0 for `system`: the rigid `assembly` (`assemble`) with every clearance
    joint centred; beams pre-deformed to the quasi-static solution
    (`simulation.beam_start: quasi-static`) or straight along their rigid pose
    (`straight`), moving with it. AssemblyError when the constraints are redundant."""
    q, qd, qdd = _rigid_motion(scene, layout, assembly)
    check_independent(system, layout, q)
    flexible = any(layout.is_beam.values()) or any(layout.modes.values())
    if flexible and scene["simulation"]["beam_start"] == "quasi-static":
        q, qd = quasi_static_beams(scene, q, qd, qdd)
    return q, qd

"""Initial position and velocity analysis.

Positions: Newton–Raphson on Φ(q, t0) = 0 from the scene's hints, with the
minimum-norm correction Δq = −Φ_q⁺ Φ so that free coordinates stay near their
hints (Nikravesh 1988, ch. 4; Haug 1989, ch. 3). Velocities: the minimum-norm
solution of Φ_q q̇ = ν. Solved on the all-ideal, all-rigid mechanism, so every
clearance joint starts centred (zero eccentricity), as MODEL.md says; beams are
then laid straight along their rigid pose.
"""

import math

import numpy as np

from sim.model.assembly import AssemblyError, Layout, build_system
from sim.model.constraints import constraint_terms
from sim.model.system import System


def constraint_values(system: System, q: np.ndarray, qd: np.ndarray, t: float):
    """Φ, Φ_q and ν at (q, q̇, t) as fresh arrays (setup code, not the hot loop)."""
    phi = np.zeros(system.m)
    jac = np.zeros((system.m, system.n))
    gamma = np.zeros(system.m)
    nu = np.zeros(system.m)
    constraint_terms(system, t, q, qd, phi, jac, gamma, nu)
    return phi, jac, nu


def solve_positions(system: System, layout: Layout, q0: np.ndarray, t: float = 0.0) -> np.ndarray:
    """Close every loop from the guess q0; AssemblyError names the worst joint."""
    q = q0.copy()
    zero = np.zeros_like(q)
    for _ in range(50):
        phi, jac, _ = constraint_values(system, q, zero, t)
        if np.max(np.abs(phi), initial=0.0) < 1e-13:
            return q
        q -= np.linalg.lstsq(jac, phi, rcond=None)[0]
    phi, _, _ = constraint_values(system, q, zero, t)
    worst = int(np.argmax(np.abs(phi)))
    joint = layout.joint_of_row(worst)
    raise AssemblyError(
        f"the linkage cannot close: joint '{joint}' misses by {abs(phi[worst]):.3g} m "
        f"(largest residual after 50 Newton iterations from the scene's hints). The loop "
        f"through '{joint}' is too short or too long for its links, or the hints point to "
        "no assembly branch: check the lengths, ground points and bodies.<name>.hint."
    )


def solve_velocities(system: System, q: np.ndarray, t: float = 0.0) -> np.ndarray:
    """Minimum-norm q̇ with Φ_q q̇ = ν."""
    _, jac, nu = constraint_values(system, q, np.zeros_like(q), t)
    return np.linalg.lstsq(jac, nu, rcond=None)[0]


def rigid_initial_state(scene: dict) -> tuple[np.ndarray, np.ndarray, System, Layout]:
    """Positions and velocities of the all-ideal, all-rigid mechanism at t = 0."""
    system, layout = build_system(scene, ideal=True, rigid=True)
    guess = np.zeros(system.n)
    for name in layout.bodies:
        hint = scene["bodies"][name]["hint"]
        o = layout.offset[name]
        guess[o : o + 2] = hint["position"]
        guess[o + 2] = math.radians(hint["angle_deg"])
    q = solve_positions(system, layout, guess)
    return q, solve_velocities(system, q), system, layout


def initial_state(scene: dict, system: System, layout: Layout) -> tuple[np.ndarray, np.ndarray]:
    """q and q̇ at t = 0 for `system`: the rigid assembly, with every beam laid
    straight along its rigid pose and moving with it."""
    q_r, qd_r, _, rigid_layout = rigid_initial_state(scene)
    q = np.zeros(system.n)
    qd = np.zeros(system.n)
    for name in layout.bodies:
        r = rigid_layout.offset[name]
        x, y, theta = q_r[r : r + 3]
        vx, vy, w = qd_r[r : r + 3]
        o = layout.offset[name]
        if not layout.is_beam[name]:
            q[o : o + 3] = (x, y, theta)
            qd[o : o + 3] = (vx, vy, w)
            continue
        length = scene["bodies"][name]["length"]
        ne = layout.elements[name]
        c, s = math.cos(theta), math.sin(theta)
        for i in range(ne + 1):
            u = -0.5 * length + i * length / ne
            k = o + 4 * i
            q[k : k + 4] = (x + c * u, y + s * u, c, s)
            qd[k : k + 4] = (vx - w * s * u, vy + w * c * u, -w * s, w * c)
    return q, qd

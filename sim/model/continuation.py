"""Continuation: the final state of one run carried over as the start of a neighbouring scene.

A bifurcation sweep can start each parameter value from the previous value's settled motion
instead of the assembled, centred state, so that less of each run is transient. The previous
state is not admissible as it stands: a smaller clearance puts the journal inside its bearing
wall, a new crank speed breaks the drive constraint's velocity. It is therefore projected onto
the new scene, keeping the motion's shape:

- time restarts at 0 after a whole number of revolutions, so every body angle is brought back
  by whole turns (the crank to its drive angle at t = 0);
- velocities scale with the crank speed, s = ω'/ω: the ideal joints are scleronomic and the
  drive is θ = θ₀ + ωt, so s·q̇ satisfies Φ_q q̇ = ν of the new speed exactly;
- the clearance coordinates c of each clearance joint (the eccentricity e = r_J − r_B of a
  revolute; the lateral offset and the tilt of a slider in its guide) and their rates scale
  with the joint's clearance, k = c'/c, so a journal touching its wall still touches it;
- positions then solve Φ(q, 0) = 0 and c(q) = k·c_prev by Newton with minimum-norm
  corrections from the previous coordinates (as the assembly does, Nikravesh 1988, ch. 4);
  velocities solve Φ_q q̇ = ν and c_q q̇ = k·s·ċ_prev likewise from s·q̇_prev;
- the contact memory (onset rate δ̇⁻) of a gap that still penetrates is kept, scaled by k·s;
  every other gap starts open.

Continuation needs the same coordinates (bodies, link models, element counts) and the same
clearance joints; a clearance of 0 makes a joint ideal and so changes the model: such a value
starts from its assembled state (`ContinuationError` says why).
"""

import math
from dataclasses import dataclass

import numpy as np

from sim.model.assembly import Layout
from sim.model.clearance import eccentricity, gap, guide_frame
from sim.model.gaps import (
    GAP_REVOLUTE,
    MEM_IN_CONTACT,
    MEM_ONSET_RATE,
    contact_memory,
    gap_owner,
)
from sim.model.initial import constraint_values, minimum_norm_newton
from sim.model.system import System

NEWTON_TOL = 1e-12  # m (and rad): residual of Φ and of the clearance coordinates
FD_STEP = 1e-7  # m or rad: central differences of the clearance coordinates


class ContinuationError(RuntimeError):
    """The previous run's state cannot start this scene (another model, or no convergence)."""


@dataclass(frozen=True)
class State:
    """The state at the end of a run: coordinates q, velocities q̇, contact memory (one row
    per gap), the number of crank revolutions simulated and the crank speed ω (rad/s), with
    the system and layout they belong to."""

    q: np.ndarray
    qd: np.ndarray
    mem: np.ndarray
    revolutions: float
    omega: float
    system: System
    layout: Layout


def clearance_coordinates(system: System, q: np.ndarray) -> np.ndarray:
    """c(q): (e_x, e_y) in m of every revolute clearance, then the lateral offset (m) of every
    slider's centre from its guide's centre line and its tilt (rad) against the guide."""
    c = []
    for j in range(system.rj_pts.shape[0]):
        c += eccentricity(system, j, q)
    for j in range(system.tj_off.shape[0]):
        o = system.tj_off[j]
        _, _, nx, ny = guide_frame(system, j)
        f = system.tj[j]
        lateral = (q[o] - f["px"]) * nx + (q[o + 1] - f["py"]) * ny
        c += [lateral, math.remainder(q[o + 2] - f["angle"], 2.0 * math.pi)]
    return np.array(c)


def clearance_jacobian(system: System, q: np.ndarray) -> np.ndarray:
    """∂c/∂q by central differences (setup code, a few coordinates per joint)."""
    jac = np.zeros((2 * (system.rj_pts.shape[0] + system.tj_off.shape[0]), q.size))
    for i in range(q.size):
        step = np.zeros_like(q)
        step[i] = FD_STEP
        jac[:, i] = clearance_coordinates(system, q + step) - clearance_coordinates(
            system, q - step
        )
    return jac / (2.0 * FD_STEP)


def clearance_sizes(system: System) -> np.ndarray:
    """The free play of each clearance joint (m): the radial clearance of a revolute, half the
    guide width less the slider width of a translational joint."""
    slider = 0.5 * (system.tj["gap_width"] - system.tj["width"])
    return np.concatenate([system.rj["clearance"], slider])


def _link_models(layout: Layout) -> list[tuple]:
    """Each body's link model: (name, beam?, elements, modal coordinates, axial modes)."""
    return [
        (
            b,
            layout.is_beam[b],
            layout.elements.get(b),
            layout.modes.get(b, 0),
            layout.axial_modes.get(b, 0),
        )
        for b in layout.bodies
    ]


def _check_same_model(previous: State, system: System, layout: Layout) -> None:
    old, new = previous.layout, layout
    if _link_models(old) != _link_models(new):
        raise ContinuationError(
            "the previous run has other bodies or link models "
            "(rigid, beam, elements, modal, modes, axial modes)"
        )
    if old.clearance_joints != new.clearance_joints:
        raise ContinuationError(
            f"the previous run has clearance joints {old.clearance_joints}, this scene "
            f"{new.clearance_joints} (a clearance of 0 makes a joint ideal)"
        )
    turns = previous.revolutions
    if abs(turns - round(turns)) > 1e-9:
        raise ContinuationError(f"the previous run ended after {turns:g} revolutions, not whole")


def continued_state(
    previous: State, system: System, layout: Layout, q_assembled: np.ndarray, omega: float
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """q, q̇ and the contact memory that start `system` (crank speed ω, rad/s) from the end of
    the previous run, projected as the module docstring says. `q_assembled` is the scene's own
    assembled start: the reference for bringing angles back by whole turns."""
    _check_same_model(previous, system, layout)
    s = omega / previous.omega
    k = np.repeat(clearance_sizes(system) / clearance_sizes(previous.system), 2)
    q = previous.q.copy()
    for body in layout.bodies:
        if not layout.is_beam[body]:
            i = layout.offset[body] + 2
            q[i] -= 2.0 * math.pi * round((q[i] - q_assembled[i]) / (2.0 * math.pi))
    c_target = k * clearance_coordinates(previous.system, q)
    zero = np.zeros_like(q)

    def linearize(x):
        phi, phi_q, _ = constraint_values(system, x, zero, 0.0)
        residual = np.concatenate([phi, clearance_coordinates(system, x) - c_target])
        return residual, np.vstack([phi_q, clearance_jacobian(system, x)])

    q, converged = minimum_norm_newton(linearize, q, NEWTON_TOL, 30)
    if not converged:
        raise ContinuationError(
            "the loops with the scaled clearances do not close: residual "
            f"{np.max(np.abs(linearize(q)[0])):.3g} after 30 Newton iterations"
        )
    _, phi_q, nu = constraint_values(system, q, zero, 0.0)
    a = np.vstack([phi_q, clearance_jacobian(system, q)])
    c_rate = k * s * (clearance_jacobian(previous.system, previous.q) @ previous.qd)
    b = np.concatenate([nu, c_rate])
    qd = s * previous.qd
    qd -= np.linalg.lstsq(a, a @ qd - b, rcond=None)[0]
    mem = contact_memory(system)
    nr = system.rj_pts.shape[0]
    for g in range(mem.shape[0]):
        kind, j, _, _ = gap_owner(system, g)
        joint = j if kind == GAP_REVOLUTE else nr + j  # revolute clearances first
        if previous.mem[g, MEM_IN_CONTACT] > 0.0 and gap(system, g, q, qd)[0] > 0.0:
            mem[g] = previous.mem[g]
            mem[g, MEM_ONSET_RATE] *= k[2 * joint] * s
    return q, qd, mem

"""Can the ideal linkage be driven through a full crank turn on its assembled branch?

A linkage whose crank cannot turn fully (a four-bar that is not Grashof with the crank the
shortest link, a six-bar whose loops do not close somewhere in the turn) would otherwise be
integrated until its clearance contacts fail far from the cause. Before integrating, the
position analysis is continued in crank-angle steps (Nikravesh 1988, ch. 5, kinematic
analysis by Newton's method from the previous position with a first-order predictor),
halving a step whose Newton iteration fails; when the step falls below `_FINEST` of a turn
the linkage locks there: the message names the crank angle and the loop whose constraint
Jacobian turns singular (a dead point, where two links of the loop line up).
"""

import json

import numpy as np

from sim.model.assembly import AssemblyError, Layout, crank_period
from sim.model.initial import (
    Assembly,
    assemble,
    constraint_values,
    minimum_norm_newton,
    solve_velocities,
)
from sim.model.system import System

_STEPS = 72  # crank-angle steps per turn when nothing locks (5°: a few Newton iterations each)
_FINEST = 1e-5  # the smallest step, in turns (0.0036°): how closely a lock is located
_TOLERANCE = 1e-11  # m (rad for angles): Newton's tolerance on the constraints
_ITERATIONS = 8
# A row of Φ_q whose weight in the near-null left singular vector exceeds this belongs to the
# loop that locks (the other rows' weights are round-off there).
_LOOP_WEIGHT = 1e-3


#: scene keys that the ideal, rigid linkage's kinematics do not read: a scene differing from
#: a checked one only in these needs no check of its own (anything else counts, so a key added
#: later costs at most a check too many)
_NOT_KINEMATIC = {
    "scene": (
        "name",
        "description",
        "assumptions",
        "materials",
        "gravity",
        "contact",
        "simulation",
        "solver",
        "output",
    ),
    "body": ("kind", "material", "mass", "inertia", "elements", "modes", "axial_modes", "damping"),
    "joint": ("clearance", "bearing_radius"),
    "drive": ("speed_rpm",),
}


def kinematic_key(scene: dict) -> str:
    """What the full-turn check of a resolved scene depends on, as text: two scenes with the
    same key assemble and turn alike (clearances, link models, speed and solver do not
    enter: the check drives the ideal, rigid linkage through a turn of the crank angle)."""

    def kept(mapping: dict, part: str) -> dict:
        return {k: v for k, v in mapping.items() if k not in _NOT_KINEMATIC[part]}

    key = kept(scene, "scene")
    key["bodies"] = {name: kept(body, "body") for name, body in scene["bodies"].items()}
    key["joints"] = {name: kept(joint, "joint") for name, joint in scene["joints"].items()}
    key["drive"] = kept(scene["drive"], "drive")
    return json.dumps(key, sort_keys=True)


def drive_through_turn(scene: dict) -> Assembly:
    """The ideal, rigid linkage of a validated scene assembled at t = 0
    (:func:`sim.model.initial.assemble`) and driven through a full crank turn
    (:func:`check_full_turn`); AssemblyError naming the loop that cannot close, or the crank
    angle and the loop where it locks."""
    assembly = assemble(scene)
    check_full_turn(
        assembly.system,
        assembly.layout,
        assembly.q,
        crank_period(scene),
        scene["drive"]["initial_angle_deg"],
    )
    return assembly


def check_full_turn(
    system: System, layout: Layout, q: np.ndarray, period: float, initial_angle_deg: float
) -> None:
    """AssemblyError naming the crank angle (deg) and the loop where the ideal, rigid `system`
    (assembled at q, t = 0, crank at `initial_angle_deg`) cannot be driven further within one
    crank `period` (s)."""
    t, dt = 0.0, period / _STEPS
    qd = solve_velocities(system, q, t)
    zero = np.zeros_like(q)
    while t < period:
        dt = min(dt, period - t)
        step = t + dt

        def linearize(x, time=step):
            phi, jac, _ = constraint_values(system, x, zero, time)
            return phi, jac

        moved, converged = minimum_norm_newton(linearize, q + qd * dt, _TOLERANCE, _ITERATIONS)
        if converged:
            q, t = moved, step
            qd = solve_velocities(system, q, t)
            dt = min(2.0 * dt, period / _STEPS)
        elif dt > _FINEST * period:
            dt /= 2.0
        else:
            raise AssemblyError(
                _locked(system, layout, q, t, 360.0 * t / period + initial_angle_deg)
            )


def _locked(system: System, layout: Layout, q: np.ndarray, t: float, angle: float) -> str:
    """The message for a linkage that locks at time t (s) and crank angle `angle` (deg), last
    assembled at q."""
    _, jac, _ = constraint_values(system, q, np.zeros_like(q), t)
    left, _, _ = np.linalg.svd(jac)
    weight = np.abs(left[:, -1])
    loop = list(
        dict.fromkeys(
            layout.joint_of_row(r) for r in np.flatnonzero(weight > _LOOP_WEIGHT * weight.max())
        )
    )
    joints = ", ".join(j for j in loop if j != "drive")
    return (
        f"the linkage cannot be driven through a full crank turn on its assembled branch: it "
        f"locks at crank angle {angle:.2f}° (t = {t:.4g} s), where the loop "
        f"through joints {joints} reaches a dead point (two of its links line up and its "
        "constraint Jacobian turns singular). Check the link lengths (a four-bar's crank turns "
        "fully when shortest + longest ≤ the sum of the other two and the crank is the "
        "shortest: Grashof), the ground points and drive.body."
    )

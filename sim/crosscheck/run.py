"""Run a scene in Exudyn from our initial state; the output Dataset uses our variable names.

`simulate_exudyn` is the counterpart of `sim.run.simulate`: same scene, same start (our
`prepare(...).y`), same output times and Poincaré sections, and a Dataset with the variables
position, velocity, acceleration (time, body, axis), angle, crank_angle, drive_torque,
eccentricity and eccentricity_rate (time, joint, axis), section_* (revolution, ...) and
peak_acceleration, peak_drive_torque. Energies are not recorded, nor contact forces, except
`normal_force` (time, joint) of the joints given Exudyn's own contact (`builtin_contact`; NaN
for the others).

Exudyn integrates with fixed steps, an integer number per output sample, so that its sensors
are read exactly at our output times (`sim.crosscheck.model.Recorder`; where Exudyn halves a
step whose Newton iteration failed, samples are interpolated and counted in the attribute
`solver_interpolated_samples`):
- `trapezoidal_index2`: Newmark β = 1/4, γ = 1/2 with the constraints on velocity level
  (Exudyn's TrapezoidalIndex2); no numerical damping, like our explicit DOPRI5, so undamped
  beam vibration keeps its amplitude in both codes;
- `generalized_alpha`: index 3 (Arnold & Brüls, Multibody Syst. Dyn. 18, 2007) with spectral
  radius ρ∞ < 1, which damps the highest frequencies and, with index 3, starts with decaying
  oscillations of the accelerations and multipliers.
"""

import datetime
import json
import time
from dataclasses import asdict, dataclass

import exudyn as exu
import numpy as np
import xarray as xr

from sim import __version__
from sim.crosscheck.model import CrossCheckError, ExudynModel, build_model
from sim.model.assembly import crank_period
from sim.quantities import AXES
from sim.results import annotate
from sim.run import prepare, simulate

SOLVERS = ("trapezoidal_index2", "generalized_alpha")


@dataclass(frozen=True)
class ExudynSettings:
    """Exudyn's time integration: method (SOLVERS), steps per output sample (the step is
    the output interval over this), ρ∞ of generalized-α and Newton's relative tolerance; and
    whether revolute clearances take Exudyn's own contact object (`builtin_contact`,
    sim.crosscheck.model) rather than our laws through a user function, and the error goal of
    Exudyn's iteration on that contact's state (`contact_tolerance`: |gap| K, K the contact
    stiffness; Exudyn's default 1 asks |gap| < 1e-11 m of a K = 1e11 N/m^1.5 joint, which its
    step reduction at a contact onset cannot reach above its 1e-8 s minimum step)."""

    solver: str = "trapezoidal_index2"
    steps_per_sample: int = 10
    spectral_radius: float = 0.9
    newton_relative_tolerance: float = 1e-10
    builtin_contact: bool = False
    contact_tolerance: float = 1.0

    def __post_init__(self) -> None:
        checks = {
            "solver": (self.solver in SOLVERS, f"one of {', '.join(SOLVERS)}"),
            "steps_per_sample": (
                isinstance(self.steps_per_sample, int) and self.steps_per_sample >= 1,
                "an integer >= 1",
            ),
            "spectral_radius": (0.0 <= self.spectral_radius <= 1.0, "in [0, 1]"),
            "newton_relative_tolerance": (
                0.0 < self.newton_relative_tolerance < 1e-2,
                "in (0, 1e-2)",
            ),
            "builtin_contact": (isinstance(self.builtin_contact, bool), "true or false"),
            "contact_tolerance": (self.contact_tolerance > 0.0, "> 0"),
        }
        for key, (ok, accepted) in checks.items():
            if not ok:
                raise CrossCheckError(f"exudyn.{key} = {getattr(self, key)!r}: must be {accepted}")


def _simulation_settings(settings: ExudynSettings, steps: int, t_end: float):
    s = exu.SimulationSettings()
    ti = s.timeIntegration
    ti.numberOfSteps = steps
    ti.endTime = t_end
    ti.verboseMode = 0
    ti.newton.relativeTolerance = settings.newton_relative_tolerance
    ti.discontinuous.iterationTolerance = settings.contact_tolerance
    alpha = ti.generalizedAlpha
    if settings.solver == "trapezoidal_index2":
        alpha.useIndex2Constraints = True
        alpha.useNewmark = True
    else:
        alpha.spectralRadius = settings.spectral_radius
    s.solution.file.write = False
    s.solution.sensors.active = False
    return s


def _stored(model: ExudynModel, sensor, columns) -> np.ndarray:
    return model.recorder.series(sensor)[:, columns]


def _point_series(model: ExudynModel, point, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Position and velocity (n, 2) of a clearance joint point."""
    if point.ground is not None:
        return np.tile(point.ground, (n, 1)), np.zeros((n, 2))
    return _stored(model, point.position, slice(0, 2)), _stored(model, point.velocity, slice(0, 2))


def _eccentricities(model: ExudynModel, scene: dict, position: np.ndarray, velocity: np.ndarray):
    """Eccentricity and its rate (time, joint, axis): journal minus bearing centre, and for a
    slider its centre from the guide point, across (x) and along (y) the guide."""
    n = position.shape[0]
    joints = model.layout.clearance_joints
    ecc = np.zeros((n, len(joints), 2))
    rate = np.zeros_like(ecc)
    for j, name in enumerate(joints):
        joint = scene["joints"][name]
        if joint["type"] == "revolute":
            (pb, vb), (pj, vj) = (_point_series(model, p, n) for p in model.joint_points[name])
            ecc[:, j], rate[:, j] = pj - pb, vj - vb
            continue
        b = model.layout.bodies.index(joint["bodies"][1])
        angle = np.radians(joint["guide_angle_deg"])
        frame = np.array([[-np.sin(angle), np.cos(angle)], [np.cos(angle), np.sin(angle)]])
        ecc[:, j] = (position[:, b] - np.asarray(joint["guide_point"])) @ frame.T
        rate[:, j] = velocity[:, b] @ frame.T
    return ecc, rate


def simulate_exudyn(
    scene: dict,
    *,
    ideal: bool = False,
    rigid: bool = False,
    revolutions: float | None = None,
    settings: ExudynSettings | None = None,
) -> xr.Dataset:
    """Simulate a validated scene in Exudyn from our initial state; our output layout.

    ideal / rigid / revolutions as in `sim.run.simulate`. Raises CrossCheckError for what the
    Exudyn model does not build and exudyn.SolverError when Exudyn's solver stops."""
    settings = settings or ExudynSettings()
    start = prepare(scene, ideal=ideal, rigid=rigid, revolutions=revolutions)
    model = build_model(scene, start.system, start.layout, start.y, settings.builtin_contact)
    out_t = start.out_t
    sample = out_t[1] - out_t[0]
    steps = (out_t.size - 1) * settings.steps_per_sample
    sim_settings = _simulation_settings(settings, steps, out_t[-1])
    model.recorder.times, model.recorder.step = out_t, out_t[-1] / steps
    wall0 = time.perf_counter()
    model.mbs.SolveDynamic(sim_settings)
    wall = time.perf_counter() - wall0
    model.recorder.take(model.mbs, model.mbs.systemData.GetTime(), np.inf)
    solver = model.mbs.sys["dynamicSolver"]

    bodies = model.layout.bodies
    series = {
        var: np.stack(
            [_stored(model, model.reference_point[b][var], slice(0, 2)) for b in bodies], axis=1
        )
        for var in ("Position", "Velocity", "Acceleration")
    }
    if len(model.recorder.values) != out_t.size:
        raise CrossCheckError(
            f"Exudyn's steps met {len(model.recorder.values)} of our {out_t.size} output times"
        )
    angle = np.stack([_angle(model, b) for b in bodies], axis=1)
    torque = -_stored(model, model.drive, 0)
    ecc, ecc_rate = _eccentricities(model, scene, series["Position"], series["Velocity"])
    normal = _normal_forces(model, ecc)
    sections = np.rint(start.sec_t / sample).astype(int)
    drive_body = bodies.index(scene["drive"]["body"])
    nb = len(bodies)
    peak_acc = np.maximum(
        model.peaks[: 2 * nb].reshape(nb, 2), np.abs(series["Acceleration"]).max(0)
    )

    ds = xr.Dataset(
        {
            "crank_angle": ("time", angle[:, drive_body]),
            "position": (("time", "body", "axis"), series["Position"]),
            "velocity": (("time", "body", "axis"), series["Velocity"]),
            "acceleration": (("time", "body", "axis"), series["Acceleration"]),
            "angle": (("time", "body"), angle),
            "drive_torque": ("time", torque),
            "eccentricity": (("time", "joint", "axis"), ecc),
            "eccentricity_rate": (("time", "joint", "axis"), ecc_rate),
            "normal_force": (("time", "joint"), normal),
            "section_position": (("revolution", "body", "axis"), series["Position"][sections]),
            "section_velocity": (("revolution", "body", "axis"), series["Velocity"][sections]),
            "section_eccentricity": (("revolution", "joint", "axis"), ecc[sections]),
            "section_eccentricity_rate": (("revolution", "joint", "axis"), ecc_rate[sections]),
            "peak_acceleration": (("body", "axis"), peak_acc),
            "peak_drive_torque": ((), max(model.peaks[2 * nb], float(np.abs(torque).max()))),
        },
        coords={
            "time": out_t,
            "body": bodies,
            "axis": AXES,
            "joint": model.layout.clearance_joints,
            "revolution": np.arange(sections.size),
        },
    )
    annotate(ds, "point")  # Exudyn's sensors read the state at the output times
    t_end = float(out_t[-1])
    ds.attrs.update(
        Conventions="CF-1.8",
        title=f"Exudyn run of scene '{scene['name']}' (sim cross-check)",
        source=f"exudyn {exu.__version__} via sim {__version__} (sim.crosscheck)",
        history=f"{datetime.datetime.now(datetime.UTC).isoformat()} sim.crosscheck",
        scene=json.dumps(scene),
        assumptions=json.dumps(scene["assumptions"]),
        sim_version=__version__,
        exudyn_version=exu.__version__,
        exudyn_settings=json.dumps(asdict(settings)),
        crank_period=crank_period(scene),
        model_ideal=int(ideal),
        model_rigid=int(rigid),
        solver_method=f"exudyn {settings.solver}",
        solver_step_s=t_end / steps,
        solver_accepted_steps=int(solver.it.currentStepIndex) - 1,
        solver_newton_iterations=int(solver.it.newtonStepsCount),
        solver_jacobians=int(solver.it.newtonJacobiCount),
        solver_interpolated_samples=model.recorder.interpolated,
        solver_wall_time_s=wall,
        real_time_factor=t_end / wall if wall > 0 else float("inf"),
        simulated_time_s=t_end,
    )
    return ds


def _normal_forces(model: ExudynModel, ecc: np.ndarray) -> np.ndarray:
    """Normal contact force (N, time × joint) of each joint with Exudyn's own contact: its
    force on the bearing against e/|e| (Exudyn's sensor `Force` of the contact, which, for a
    hollow sphere 1, is the force on marker 0, the journal: measured on a single impact), positive
    pressing the surfaces together; NaN for the
    other joints, whose force Exudyn does not compute itself."""
    out = np.full(ecc.shape[:2], np.nan)
    for name, sensor in model.builtin.items():
        j = model.layout.clearance_joints.index(name)
        e = ecc[:, j]
        along = -np.sum(_stored(model, sensor, slice(0, 2)) * e, axis=1)
        length = np.hypot(e[:, 0], e[:, 1])
        out[:, j] = np.divide(along, length, out=np.zeros_like(along), where=length > 0.0)
    return out


def _angle(model: ExudynModel, body: str) -> np.ndarray:
    """Body angle (rad): θ of a rigid body, the chord angle between a beam's end nodes."""
    sensors = model.angle[body]
    if len(sensors) == 1:
        return _stored(model, sensors[0], 2)
    p0, p1 = (_stored(model, s, slice(0, 2)) for s in sensors)
    return np.arctan2(p1[:, 1] - p0[:, 1], p1[:, 0] - p0[:, 0])


def run_both(scene: dict, settings: ExudynSettings | None = None) -> tuple[xr.Dataset, xr.Dataset]:
    """Our run and Exudyn's of the same scene, one after the other in this process, so that
    their wall times compare. Our kernels are compiled (numba, on first call) by a run of two
    output samples first, outside the timed runs. Ours records point samples, as Exudyn's
    sensors do, so that the two compare sample for sample."""
    ours = {**scene, "simulation": {**scene["simulation"], "sampling": "point"}}
    simulate(ours, revolutions=2.0 / scene["simulation"]["output_per_revolution"])
    return simulate(ours), simulate_exudyn(scene, settings=settings)

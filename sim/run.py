"""Run one scene: assemble, integrate, collect the output Dataset.

`simulate` is the library entry point (`sim run` and the workflow call it).
"""

import datetime
import math
import sys
import time
from dataclasses import dataclass
from typing import Any

import numpy as np
import xarray as xr

from sim.ensemble import Member, perturbed
from sim.kernel_cache import compile_integrator
from sim.model.assembly import Layout, build_system, crank_period, omega
from sim.model.continuation import State, continued_state
from sim.model.gaps import contact_memory
from sim.model.initial import HINTED, initial_state
from sim.model.mobility import drive_through_turn
from sim.model.system import (
    OUT_NORMAL_FORCE,
    SLIDER_LAW_PAPER,
    System,
)
from sim.results import build_dataset, decode_rows, energy_balance, energy_error_relative
from sim.solve import lockstep, stepping
from sim.solve.control import ERR_OLD_MIN
from sim.solve.means import make_means
from sim.solve.methods import Dopri5, make_carry, method_of
from sim.solve.record import peak_slots, peak_width, row_width
from sim.solve.state import CLOCK, TALLY, Buffers, Options, Trajectory
from sim.solve.status import (
    MAX_STEPS,
    NONFINITE,
    OK,
    PENETRATION,
    SINGULAR,
    STEP_COLLAPSE,
    VIOLATION,
)
from sim.solve.work import Work, make_work, state_size


class SimulationError(RuntimeError):
    """A run that cannot go on: the message names the time, the joint and a diagnosis."""


class Interrupted(KeyboardInterrupt):
    """Ctrl-C during a computation: ``where`` says what was interrupted and where (the
    simulated time reached, the sweep point), ``kept`` what was written before it. A
    KeyboardInterrupt still, so that nothing catching Exception swallows it."""

    def __init__(self, where: str, kept: str = "nothing written"):
        super().__init__(where)
        self.where, self.kept = where, kept


# Sane bounds, as fractions of the joint's own size: a penetration beyond them
# means a contact far too soft or a step far too large, not a physical state.
PENETRATION_BOUND = 0.02  # of the journal radius or the slider width
VIOLATION_BOUND = 0.01  # of the shortest body dimension, m
# Energy audit (T + V + U + U_c − W + D drift over the energy scale) that stops a run: far
# beyond any sound run's (DOPRI5 ≤ 1e-3; generalized-α's numerical damping at ρ∞ = 0.5,
# 3.4e-2 in 10 revolutions), so reaching it means a step created or lost energy, e.g. a
# contact force from a wrong velocity.
ENERGY_BOUND = 0.5
# The energy audit of a sound run (docs/fidelity.md, criterion 2 of the default fidelity): a run
# above it finishes, but says so (summary of `sim run`, attribute energy_audit_exceeded).
ENERGY_AUDIT_BOUND = 1e-3


@dataclass(frozen=True)
class Snapshot:
    """A restart point of an integration: copies of its trajectory (state, contact memory,
    clock) and, unless None, of the step data carried to the next step. Restored with the
    carried data (Newton factors included), an integration continues bit for bit as if never
    interrupted; without, it re-evaluates the derivative and the generalized-α start data at
    the restart (needed after the state was changed, as by a renormalisation) and keeps the
    Newton factors it holds (they only speed Newton up)."""

    trajectory: Trajectory
    carry: tuple | None  # the method's Carry (sim.solve.methods.make_carry)


def _copied(structure):
    """A NamedTuple of arrays with every array copied."""
    return type(structure)(*(np.copy(a) for a in structure))


@dataclass
class Integration:
    """Everything the compiled integrator reads and writes for one run."""

    system: System
    layout: Layout
    work: Work
    carry: tuple  # the method's Carry (sim.solve.methods.make_carry)
    trajectory: Trajectory
    options: Options
    buffers: Buffers
    tally: np.ndarray  # (1,) TALLY
    assembly_branch: str  # which assembly branch the initial state is on (Assembly.branch)

    @property
    def y(self) -> np.ndarray:
        """The state (q, q̇, W_drive, E_dissipated)."""
        return self.trajectory.y

    @property
    def mem(self) -> np.ndarray:
        """The contact memory, one row per gap."""
        return self.trajectory.mem

    @property
    def out_t(self) -> np.ndarray:
        """The output sample times (s)."""
        return self.buffers.out_t

    @property
    def sec_t(self) -> np.ndarray:
        """The Poincaré section times (s), one per crank revolution from t = 0."""
        return self.buffers.sec_t

    @property
    def t(self) -> float:
        """The time reached (s)."""
        return float(self.trajectory.clock[0]["t"])

    def count(self, name: str) -> int:
        """A counter of the run (a field of sim.solve.state.TALLY)."""
        return int(self.tally[0][name])

    def arguments(self, t_end: float) -> tuple:
        """The arguments of the compiled integrator (`stepping.integrate`) up to t_end (s)."""
        return (
            self.system,
            self.work,
            self.carry,
            self.trajectory,
            float(t_end),
            self.options,
            self.buffers,
            self.tally,
        )

    def advance(self, t_end: float) -> int:
        """Integrate up to t_end; the status code (sim.solve.status) of the compiled integrator."""
        return stepping.integrate(*self.arguments(t_end))

    def clear_step_log(self) -> None:
        """Start a new log of accepted step ends (the run keeps one if prepared with
        `step_log`)."""
        self.tally[0]["logged"] = 0

    def follow(self, leader: "Integration") -> int:
        """Advance through the step ends `leader` logged since its log was cleared, with this
        integration's own state and contact events (sim.solve.lockstep.follow); the status
        code. ValueError when the leader took more steps than its log holds."""
        n = leader.count("logged")
        if n > leader.buffers.step_ends.size:
            raise ValueError(
                f"the leading trajectory took {n} steps, more than its log of "
                f"{leader.buffers.step_ends.size} holds: shorten the interval"
            )
        return lockstep.follow(*self.follow_arguments(leader.buffers.step_ends, n))

    def follow_arguments(self, step_ends: np.ndarray, n: int) -> tuple:
        """The arguments of the compiled follower (`lockstep.follow`) through the first n of
        a leader's logged step ends."""
        return (
            self.system,
            self.work,
            self.carry,
            self.trajectory,
            step_ends,
            int(n),
            self.options,
            self.buffers,
            self.tally,
        )

    def snapshot(self, carried: bool = True) -> Snapshot:
        """A restart point at the time reached; with `carried`, one that resumes exactly."""
        return Snapshot(_copied(self.trajectory), _copied(self.carry) if carried else None)

    def restore(self, snapshot: Snapshot) -> None:
        """Return to a restart point (see Snapshot). Counters and buffers are not rewound."""
        for mine, saved in zip(self.trajectory, snapshot.trajectory, strict=True):
            mine[...] = saved
        if snapshot.carry is None:
            self.trajectory.clock[0]["started"] = False
        else:
            for mine, saved in zip(self.carry, snapshot.carry, strict=True):
                mine[...] = saved


def _shortest_dimension(scene: dict) -> float:
    sizes = []
    for body in scene["bodies"].values():
        sizes += [body["length"]] if body["shape"] == "bar" else body["size"][:2]
    return min(sizes)


def solver_options(scene: dict, system: System) -> Options:
    """The compiled integrator's options for a validated scene and its system: the solver
    section's method and tolerances, the step bounds as fractions of the crank period, and
    the failure bounds (constraint violation, penetration per clearance joint)."""
    period = crank_period(scene)
    solver = scene["solver"]
    return Options(
        method=method_of(solver),
        rtol=float(solver["rtol"]),
        atol=float(solver["atol"]),
        hmax=solver["max_step_fraction"] * period,
        hmin=1e-14 * period,
        violation_bound=VIOLATION_BOUND * _shortest_dimension(scene),
        max_steps=int(solver["max_steps"]),
        pen_bound=np.concatenate(
            [
                PENETRATION_BOUND * system.rj["journal_radius"],
                PENETRATION_BOUND * system.tj["width"],
            ]
        ),
    )


def prepare(
    scene: dict,
    *,
    ideal: bool = False,
    rigid: bool = False,
    revolutions: float | None = None,
    start: State | None = None,
    step_log: int = 0,
) -> Integration:
    """Assemble the system, its initial state and the output buffers. The initial state is
    the assembled one, or with `start` the end of a previous run projected onto this scene
    (sim.model.continuation; ContinuationError when it cannot be). `step_log` > 0 keeps a log of
    that many accepted step ends for a lockstep follower (sim.solve.lockstep)."""
    system, layout = build_system(scene, ideal=ideal, rigid=rigid)
    assembly = drive_through_turn(scene)
    period = crank_period(scene)
    q0, qd0 = initial_state(scene, system, layout, assembly)
    mem = contact_memory(system)
    if start is not None:
        q0, qd0, mem = continued_state(start, system, layout, q0, omega(scene))
    y = np.concatenate([q0, qd0, [0.0, 0.0]])
    n_rev = scene["simulation"]["revolutions"] if revolutions is None else revolutions
    per_rev = scene["simulation"]["output_per_revolution"]
    n_out = math.floor(n_rev * per_rev + 1e-9) + 1
    out_t = np.arange(n_out) * (period / per_rev)
    sec_t = np.arange(math.floor(n_rev + 1e-9) + 1) * period
    width = row_width(len(layout.bodies), len(layout.clearance_joints))
    n_peaks = peak_width(len(layout.bodies), len(layout.clearance_joints))
    options = solver_options(scene, system)
    clock = np.zeros(1, dtype=CLOCK)
    clock[0]["h"] = min(1e-5 * period, options.hmax)
    clock[0]["facold"] = ERR_OLD_MIN
    # The integrator samples times in (t, t + h], and t = 0 on its first call.
    assert state_size(system) == y.size
    work = make_work(system)
    out_rows = np.zeros((n_out, width))
    sec_rows = np.zeros((sec_t.size, width))
    n_bodies, n_joints = len(layout.bodies), len(layout.clearance_joints)
    sampling = scene["simulation"]["sampling"]
    buffers = Buffers(
        out_t=out_t,
        out_rows=out_rows,
        sec_t=sec_t,
        sec_rows=sec_rows,
        peaks=np.zeros(n_peaks),
        peak_slots=peak_slots(n_bodies, n_joints),
        # one row per revolution (ending at each section), one more for what follows the last
        rev_peaks=np.zeros((sec_t.size + 1, n_peaks)),
        rev_events=np.zeros(sec_t.size + 1, dtype=np.int64),
        gap_onsets=np.zeros(mem.shape[0], dtype=np.int64),
        means=make_means(
            width,
            n_bodies,
            n_joints,
            windows=sampling == "mean",
            balance=not isinstance(options.method, Dopri5),
        ),
        step_ends=np.zeros(step_log),
    )
    tally = np.zeros(1, dtype=TALLY)
    return Integration(
        system=system,
        layout=layout,
        work=work,
        carry=make_carry(options.method, system.n, system.m),
        trajectory=Trajectory(y=y, mem=mem, clock=clock),
        options=options,
        buffers=buffers,
        tally=tally,
        assembly_branch=assembly.branch,
    )


def _busiest_joint(integ: Integration) -> str | None:
    """The clearance joint with the largest contact force at the last evaluation."""
    joints = integ.layout.clearance_joints
    return joints[int(np.argmax(integ.work.jout[:, OUT_NORMAL_FORCE]))] if joints else None


class EnergyWatch:
    """The energy audit of a run, followed as it is recorded: each sample is read once, and
    only the samples that set the audit so far are kept (the first, and those holding the
    largest kinetic energy, the potential energy's extremes, the largest drive work and the
    largest imbalance), so the audit over them equals the audit over every sample."""

    def __init__(self, integ: Integration, method: str):
        self.integ = integ
        self.method = method  # solver.method, for the advice when the audit drifts
        self.done = 0
        self.kept = integ.buffers.out_rows[:0]

    def audit(self) -> float:
        """The energy audit (share of the energy scale) of every sample recorded so far."""
        integ = self.integ
        upto = integ.count("outputs")
        rows = np.concatenate([self.kept, integ.buffers.out_rows[self.done : upto]])
        self.done = upto
        data = decode_rows(rows, integ.layout.bodies, integ.layout.clearance_joints)
        setting = {
            0,
            int(np.argmax(data["kinetic_energy"])),
            int(np.argmin(data["potential_energy"])),
            int(np.argmax(data["potential_energy"])),
            int(np.argmax(np.abs(data["drive_work"]))),
            int(np.argmax(np.abs(energy_balance(data)))),
        }
        self.kept = rows[sorted(setting)]
        return energy_error_relative(data)

    def drift(self) -> str | None:
        """None while the audit is within ENERGY_BOUND; otherwise the diagnosis: the time
        reached and the joint with the largest contact force."""
        audit = self.audit()
        if audit <= ENERGY_BOUND:
            return None
        integ = self.integ
        busiest = _busiest_joint(integ)
        where = f" (largest contact force at joint '{busiest}')" if busiest else ""
        return (
            f"by t = {integ.buffers.out_t[self.done - 1]:.6g} s the energy audit is off by "
            f"{audit:.3g} of the energy scale (bound {ENERGY_BOUND}){where}: a step created or "
            f"lost energy; {audit_advice(self.method, integ.system.beam_off.size > 0)}"
        )


def audit_advice(method: str, beams: bool) -> str:
    """What to change when a run's energy audit fails, for its integrator (`solver.method`)
    and whether it has ANCF beams: its tolerance, or, under generalized-α without beams, the
    integrator. Generalized-α's index-3 form loses or creates energy at the contact events of
    a rattling clearance joint, which no tolerance or ρ∞ repairs (docs/fidelity.md, "Modal
    links"); DOPRI5 closes the same runs' audits near 1e-5, for rigid and modal links at
    1.6–3.7 × the CPU time, but with beams its steps are bound by their axial modes."""
    if method == "dopri5" or beams:
        return "tighten solver.rtol"
    return (
        "use solver.method=dopri5: generalized-alpha loses or creates energy at the contact "
        "events of a rattling clearance joint, which no tolerance or rho_inf repairs"
    )


def diagnose(integ: Integration, status: int) -> str:
    """A failure message: the time, the joint and the likely cause."""
    tally = integ.tally[0]
    t = tally["failure_time"]
    joints = integ.layout.clearance_joints
    jout = integ.work.jout
    busiest = _busiest_joint(integ)
    at = f"at t = {t:.6g} s"
    if status == PENETRATION:
        j = int(tally["culprit"])
        hint = ""
        is_slider = j >= integ.system.rj_pts.shape[0]
        if is_slider and integ.system.contact.slider_law == SLIDER_LAW_PAPER:
            hint = (
                "; the paper's slider law switches from a corner to the face law with a jump "
                "in stored energy that feeds the slider's rattle: contact.slider_law=winkler "
                "is the continuous, energy-consistent form of the same face law"
            )
        return (
            f"{at}: joint '{joints[j]}' penetrates {jout[j, 0]:.3g} m, beyond the sane bound "
            f"{integ.options.pen_bound[j]:.3g} m ({PENETRATION_BOUND:.0%} of its size): the "
            f"contact is too soft for the load, or the clearance law met a velocity it cannot "
            f"stop{hint}"
        )
    if status == VIOLATION:
        return (
            f"{at}: ideal constraints drifted beyond {integ.options.violation_bound:.3g} m; "
            "the mechanism may pass a singular (locked) position; raise solver.baumgarte_* or "
            "tighten solver.rtol"
        )
    if status == STEP_COLLAPSE:
        where = f"; the largest contact force is at joint '{busiest}'" if busiest else ""
        if isinstance(integ.options.method, Dopri5):
            cause = "a force discontinuity or stiffness the explicit method cannot pass"
        else:
            failures = int(tally["newton_failures"])
            cause = (
                f"Newton failed {failures} times in the run: a force law the implicit "
                "method cannot converge on (try solver.method=dopri5 or a smaller solver.rtol)"
            )
        return f"{at}: the step size collapsed below {integ.options.hmin:.3g} s{where}: " + cause
    if status == SINGULAR:
        return (
            f"{at}: the constraint Jacobian lost rank: redundant joints or a locked "
            "(singular) position of the linkage"
        )
    if status == NONFINITE:
        where = f" (largest contact force at joint '{busiest}')" if busiest else ""
        return f"{at}: the state became non-finite{where}: the step outran a stiff force"
    if status == MAX_STEPS:
        return f"{at}: solver.max_steps = {integ.options.max_steps} reached"
    return f"{at}: integrator status {status}"


class Progress:
    """One status line on stderr: simulated time, share done, time left."""

    def __init__(self, t_end: float, enabled: bool):
        self.t_end = t_end
        # A carriage-return status line only makes sense on a terminal.
        self.enabled = enabled and sys.stderr.isatty()
        self.start = time.perf_counter()

    def update(self, t: float) -> None:
        if not self.enabled:
            return
        wall = time.perf_counter() - self.start
        share = t / self.t_end if self.t_end > 0 else 1.0
        left = wall * (1.0 - share) / share if share > 0 else float("nan")
        sys.stderr.write(
            f"\r  t = {t:9.4f} s of {self.t_end:.4f} s  {100 * share:5.1f} %  "
            f"elapsed {wall:6.1f} s  left ~{left:6.1f} s "
        )
        sys.stderr.flush()

    def close(self) -> None:
        if self.enabled:
            sys.stderr.write("\n")


def simulate(
    scene: dict,
    *,
    progress: bool = False,
    ideal: bool = False,
    rigid: bool = False,
    revolutions: float | None = None,
    member: Member | None = None,
) -> xr.Dataset:
    """Simulate a validated scene from its assembled state and return its output Dataset.

    ideal / rigid replace every clearance joint by an ideal one / every beam by a
    rigid link (the reference mechanism); `revolutions` overrides the duration; `member`
    starts from an ensemble member's perturbed state (sim.ensemble; default the nominal)."""
    return simulate_from(
        scene,
        None,
        progress=progress,
        ideal=ideal,
        rigid=rigid,
        revolutions=revolutions,
        member=member,
    )[0]


def simulate_from(scene: dict, start: State | None, **options: Any) -> tuple[xr.Dataset, State]:
    """`simulate`, started from the end of a previous run (`start`, projected onto this
    scene by sim.model.continuation) or, with None, from the assembled state; returns the
    output Dataset and the final state, from which a neighbouring scene can continue.
    `options`: those of `Run` (progress, ideal, rigid, revolutions, and `member`, the
    ensemble member of sim.ensemble whose perturbation applies; its index, seed and
    perturbation are recorded in the Dataset's attributes)."""
    return Run(scene, start, **options).finish()


class Run:
    """A run in progress (the arguments are those of `simulate`, and `start` as for
    `simulate_from`; `announce_assembly`: with `progress`, say which assembly branch was
    taken): `advance_to` integrates it in pieces of at most a quarter revolution,
    each checked (integrator status, energy audit), so a caller may pause it where it needs
    the state (as the model exponent does, sim.studies.model_lyapunov.run_with_exponent);
    `finish` integrates to the end and returns the output Dataset and the final state.
    Without pauses the pieces are those of an uninterrupted run, so it is reproduced bit for
    bit. Ctrl-C raises `Interrupted` with the simulated time reached."""

    def __init__(
        self,
        scene: dict,
        start: State | None,
        *,
        progress: bool = False,
        ideal: bool = False,
        rigid: bool = False,
        revolutions: float | None = None,
        member: Member | None = None,
        step_log: int = 0,
        announce_assembly: bool = True,
    ):
        self.member = Member() if member is None else member
        self.scene = perturbed(scene, self.member)
        self.start, self.ideal, self.rigid = start, ideal, rigid
        self.integ = prepare(
            self.scene,
            ideal=ideal,
            rigid=rigid,
            revolutions=revolutions,
            start=start,
            step_log=step_log,
        )
        if progress and announce_assembly and self.integ.assembly_branch != HINTED:
            print(f"assembly: {self.integ.assembly_branch}", file=sys.stderr)
        # compiled before the clock starts: wall time and real-time factor are the integration's
        self.compile_time = compile_integrator(
            self.integ.arguments(0.0), self.scene["solver"]["method"]
        )
        self.period = crank_period(self.scene)
        self.revolutions = (
            self.scene["simulation"]["revolutions"] if revolutions is None else revolutions
        )
        self.t_end = self.revolutions * self.period
        self.t = 0.0
        self.wall = 0.0  # s spent integrating this run alone
        self.cpu = 0.0  # s of this process's CPU time spent integrating it
        self.bar = Progress(self.t_end, progress)
        self.watch = EnergyWatch(self.integ, self.scene["solver"]["method"])
        self.next_audit = self.period / 4.0  # s: when the energy watch next audits
        # the integrator's first call records the samples at t = 0 (and takes no step)
        self._check(self.integ.advance(0.0))

    def advance_to(self, t_stop: float) -> None:
        """Integrate up to min(t_stop, the run's end) (s); SimulationError on a failure."""
        t_stop = min(t_stop, self.t_end)
        wall0, cpu0 = time.perf_counter(), time.process_time()
        while self.t < t_stop:
            self.t = min(self.t + self.period / 4.0, t_stop)
            try:
                status = self.integ.advance(self.t)
            except KeyboardInterrupt:
                # numba's compiled loop does not see signals: Python raises on its return
                self.bar.close()
                raise Interrupted(
                    f"at t = {self.integ.t:.4g} s of {self.t_end:.4g} s, crank revolution "
                    f"{self.integ.t / self.period:.1f} of {self.revolutions:g}"
                ) from None
            self._check(status)
            if self.t >= min(self.next_audit, self.t_end):
                # the audit every quarter revolution, however often the caller pauses the run
                # (the model exponent pauses it 32 times a revolution)
                self.next_audit = self.t + self.period / 4.0
                self._fail_on(self.watch.drift())
            self.bar.update(self.t)
        self.wall += time.perf_counter() - wall0
        self.cpu += time.process_time() - cpu0

    def _check(self, status: int) -> None:
        """SimulationError with the diagnosis unless the integrator's status is OK."""
        if status != OK:
            self._fail_on(diagnose(self.integ, status))

    def _fail_on(self, failure: str | None) -> None:
        """SimulationError with this failure's diagnosis, if any."""
        if failure is not None:
            self.bar.close()
            raise SimulationError(f"scene '{self.scene['name']}': " + failure)

    def finish(self) -> tuple[xr.Dataset, State]:
        """Integrate to the end; the output Dataset and the final state."""
        self.advance_to(self.t_end)
        self.bar.close()
        integ, scene = self.integ, self.scene
        buffers = integ.buffers
        recorded = (integ.count("outputs"), integ.count("sections"))
        if recorded != (buffers.out_t.size, buffers.sec_t.size):
            raise SimulationError(
                f"scene '{scene['name']}': the integrator recorded {recorded} of "
                f"{(buffers.out_t.size, buffers.sec_t.size)} samples and sections"
            )
        provenance = {
            "history": f"{datetime.datetime.now(datetime.UTC).isoformat()} sim simulate",
            "crank_period": self.period,
            "model_ideal": int(self.ideal),
            "model_rigid": int(self.rigid),
            "solver_method": scene["solver"]["method"],
            "solver_accepted_steps": integ.count("accepted"),
            "solver_rejected_steps": integ.count("rejected"),
            "solver_function_evaluations": integ.count("evaluations"),
            "solver_contact_events": integ.count("events"),
            "solver_iteration_matrices": integ.count("jacobians"),
            "solver_newton_failures": integ.count("newton_failures"),
            "solver_wall_time_s": self.wall,
            "solver_cpu_time_s": self.cpu,
            "solver_compile_time_s": self.compile_time,
            "real_time_factor": self.t_end / self.wall if self.wall > 0 else float("inf"),
            "simulated_time_s": self.t_end,
            "initial_state": "assembled" if self.start is None else "continued",
            "assembly_branch": integ.assembly_branch,
            **self.member.attrs(),
        }
        n = integ.system.n
        final = State(
            q=integ.y[:n].copy(),
            qd=integ.y[n : 2 * n].copy(),
            mem=integ.mem.copy(),
            revolutions=self.revolutions,
            omega=omega(scene),
            system=integ.system,
            layout=integ.layout,
        )
        dataset = build_dataset(
            times=buffers.out_t,
            rows=buffers.out_rows,
            section_rows=buffers.sec_rows,
            peaks=buffers.peaks,
            rev_peaks=buffers.rev_peaks,
            rev_events=buffers.rev_events,
            bodies=integ.layout.bodies,
            joints=integ.layout.clearance_joints,
            scene=scene,
            provenance=provenance,
        )
        dataset.attrs["energy_audit_bound"] = ENERGY_AUDIT_BOUND
        dataset.attrs["energy_audit_exceeded"] = int(
            dataset.attrs["energy_error_relative"] > ENERGY_AUDIT_BOUND
        )
        return dataset, final

"""Largest Lyapunov exponent of a linkage from the model itself (Benettin on the run's integrator).

The two trajectories of :func:`sim.analysis.lyapunov.benettin` are advanced by the compiled
integrator of :mod:`sim.run` (the same step code, contact events and force laws as ``sim run``),
so the exponent belongs to exactly the dynamics the run file holds, and the perturbed
trajectory costs what a second run costs.
"""

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import NamedTuple

import numpy as np
import xarray as xr

from sim.analysis.lyapunov import BenettinResult, Rescale, benettin, interval_stretch
from sim.model.assembly import crank_period, omega
from sim.model.continuation import State
from sim.model.gaps import MEM_COLUMNS, MEM_IN_CONTACT, MEM_ONSET_RATE, gap_joints
from sim.run import Integration, Run, SimulationError, Snapshot, diagnose, prepare
from sim.solve.state import CLOCK, Trajectory
from sim.solve.status import OK

#: default separation d0 of the two trajectories (m, in the metric of :class:`LinkagePropagator`)
DEFAULT_D0 = 1e-6
#: default renormalisation interval, in crank revolutions
DEFAULT_INTERVAL_REVOLUTIONS = 1 / 32
#: default revolutions of :func:`run_with_exponent`'s perturbed trajectory before recording
DEFAULT_ALIGNMENT_REVOLUTIONS = 2.0
#: default integration tolerances (rtol, atol) of both trajectories per integrator, unless the
#: scene's are tighter: the loosest whose exponent a tighter one does not move
#: (see :func:`linkage_lyapunov`)
DEFAULT_TOLERANCES = {"dopri5": (1e-6, 1e-8), "generalized_alpha": (1e-8, 1e-10)}
#: the fields of the integration's clock (sim.solve.state.CLOCK) packed with a trajectory
CONTROLLER = ("t", "h", "facold")
#: the reference's log of step ends: room for the accepted steps of one renormalisation
#: interval (8 MiB; the flexible flagship's ANCF beams under DOPRI5 take ~10^4 in 1/16 revolution)
STEP_LOG = 1 << 20


def _pack(integ: Integration) -> np.ndarray:
    """An integration's current trajectory (:class:`sim.solve.state.Trajectory`) as one array."""
    clock = integ.trajectory.clock[0]
    return np.concatenate([integ.y, integ.mem.ravel(), [clock[k] for k in CONTROLLER]])


def _check(integ: Integration, status: int, scene_name: str, which: str) -> None:
    if status != OK:
        raise SimulationError(f"scene '{scene_name}' ({which}): {diagnose(integ, status)}")


@dataclass(eq=False)
class OnsetLog:
    """The contact onsets of every clearance joint in each renormalisation interval, of the
    reference and of the perturbed trajectory, in the order the intervals ran (the transient's
    first): one (joints,) count per interval (sim.solve.state.Buffers.gap_onsets, summed over
    each joint's gaps)."""

    joints: np.ndarray  # (gaps,) the joint of each gap (sim.model.gaps.gap_joints)
    n_joints: int
    reference: list[np.ndarray] = field(default_factory=list)
    perturbed: list[np.ndarray] = field(default_factory=list)

    def counted(self, integ: Integration, log: list, advance: Callable[[], np.ndarray]):
        """``advance()``'s result, with the onsets of each joint it made ``integ`` take
        appended to ``log``."""
        before = integ.buffers.gap_onsets.copy()
        out = advance()
        new = integ.buffers.gap_onsets - before
        log.append(np.bincount(self.joints, weights=new, minlength=self.n_joints))
        return out


class OnsetShares(NamedTuple):
    """Where the model exponent's stretch is made: per clearance joint, the share of the
    recorded stretch ln(d / d0) accumulated in the renormalisation intervals in which the joint
    had a contact onset in either trajectory (the window after an onset is the interval it
    falls in), beside the share of the recorded intervals those are. A joint whose stretch share
    far exceeds its interval share makes the chaos in bursts after its impacts."""

    joints: tuple[str, ...]
    stretch: np.ndarray  # (joints,)
    intervals: np.ndarray  # (joints,)


def onset_shares(result: BenettinResult, propagator: "LinkagePropagator") -> OnsetShares:
    """The :class:`OnsetShares` of an exponent computed with ``propagator``."""
    stretch = interval_stretch(result)
    n = stretch.size
    log = propagator.onsets
    hit = (np.array(log.reference[-n:]) > 0) | (np.array(log.perturbed[-n:]) > 0)
    return OnsetShares(
        tuple(propagator.integration.layout.clearance_joints),
        (stretch[:, None] * hit).sum(axis=0) / stretch.sum(),
        hit.mean(axis=0),
    )


@dataclass(frozen=True, eq=False)
class LinkagePropagator:
    """The two trajectories of :func:`~sim.analysis.lyapunov.benettin` on a linkage, in lockstep.

    The reference (``leader``) is integrated by its own step control and logs the end of every
    accepted step; ``advance`` takes the perturbed trajectory through those same step ends
    (:mod:`sim.solve.lockstep`), splitting a step only at its own contact events. The two are
    then orbits of one discrete map, and their separation is free of the integration noise that
    two independent step sequences add (which made the exponent depend on the tolerance).

    The packed state of a trajectory is everything its future depends on:
    ``(q, q̇, W_drive, E_dissipated)`` (the integrator's ``y``), the contact memory of every gap
    (in-contact flag, onset rate δ̇⁻, graze mark) and the step-size controller's state (t, h,
    previous error). Only q and q̇ are continuous (``mask``); the contact memory travels with
    its trajectory unchanged, the energy quadratures do not enter the distance.

    Distance (see :meth:`distance`): the Euclidean norm of (Δq, Δq̇ / ω), ω the crank speed, so
    that positions (m; rad and dimensionless slopes count as they are) and velocities weigh
    alike over one radian of crank motion. Any norm gives the same exponent; this one keeps the
    separation's components of comparable size, which shortens the transient.

    Attributes:
        integration: the perturbed trajectory's integration (:func:`sim.run.prepare`).
        leader: the reference's integration, prepared with a step log.
        scene_name: for error messages.
        onsets: each joint's contact onsets per interval in both (:class:`OnsetLog`; made
            empty when not given).
    """

    integration: Integration
    leader: Integration
    scene_name: str
    onsets: OnsetLog | None = None

    def __post_init__(self) -> None:
        if self.onsets is None:
            system = self.integration.system
            log = OnsetLog(gap_joints(system), len(self.integration.layout.clearance_joints))
            object.__setattr__(self, "onsets", log)

    def pack(self) -> np.ndarray:
        """The reference's current trajectory as one array."""
        return _pack(self.leader)

    def mask(self) -> np.ndarray:
        """True for the entries of a packed state that are continuous in every state: q, q̇."""
        integ = self.integration
        mask = np.zeros(integ.y.size + integ.mem.size + len(CONTROLLER), dtype=bool)
        mask[: 2 * integ.system.n] = True
        return mask

    def _memory(self, column: int) -> slice:
        """The packed entries of one column of the contact memory, a gap a row."""
        n_y, n_mem = self.integration.y.size, self.integration.mem.size
        return slice(n_y + column, n_y + n_mem, MEM_COLUMNS)

    def _continuous(self, a: np.ndarray, b: np.ndarray) -> np.ndarray:
        """True for the entries in which two packed states differ continuously: q, q̇ and the
        onset rate δ̇⁻ of every gap in contact in both (it was taken from q̇ at the onset, and
        the Lankarani–Nikravesh force depends on it as on the state)."""
        continuous = self.mask()
        closed = (a[self._memory(MEM_IN_CONTACT)] > 0.0) & (b[self._memory(MEM_IN_CONTACT)] > 0.0)
        continuous[self._memory(MEM_ONSET_RATE)] = closed
        return continuous

    def distance(self, scene: dict) -> Callable[[np.ndarray, np.ndarray], float]:
        """The distance between two packed states: the norm of (Δq, Δq̇ / ω, Δδ̇⁻ / ω) over
        their continuous entries (class docstring, :meth:`_continuous`)."""
        weights = np.zeros(self.mask().size)
        n = self.integration.system.n
        weights[:n] = 1.0
        weights[n : 2 * n] = 1.0 / omega(scene)
        weights[self._memory(MEM_ONSET_RATE)] = 1.0 / omega(scene)

        def distance(a: np.ndarray, b: np.ndarray) -> float:
            return float(np.linalg.norm((weights * (a - b))[self._continuous(a, b)]))

        return distance

    def rescale(self, distance: Callable[[np.ndarray, np.ndarray], float]) -> Rescale:
        """Renormalisation: the perturbed state pulled radially towards the reference's, to
        distance d0, over the continuous entries (the onset rates of the gaps in contact in
        both included, so that the perturbed trajectory's contact law stays consistent with
        its rescaled state); its flags and the rest stay its own."""

        def rescale(y_ref: np.ndarray, y_pert: np.ndarray, d0: float) -> np.ndarray:
            continuous = self._continuous(y_ref, y_pert)
            factor = d0 / distance(y_ref, y_pert)
            rescaled = y_pert.copy()
            rescaled[continuous] = y_ref[continuous] + factor * (
                y_pert[continuous] - y_ref[continuous]
            )
            return rescaled

        return rescale

    def advance_leader(self, state: np.ndarray, t: float, dt: float) -> np.ndarray:
        """The reference's packed state at t + dt; it must be at t (``state`` is its packing)."""
        leader = self.leader
        if not np.isclose(leader.t, t, rtol=0.0, atol=1e-9 * max(1.0, abs(t))):
            raise ValueError(f"the reference is at t = {leader.t} s, not at t = {t} s")
        leader.clear_step_log()

        def advance() -> np.ndarray:
            _check(leader, leader.advance(t + dt), self.scene_name, "Lyapunov reference")
            return _pack(leader)

        return self.onsets.counted(leader, self.onsets.reference, advance)

    def advance(self, state: np.ndarray, t: float, dt: float) -> np.ndarray:
        """The perturbed packed state at t + dt from the packed ``state`` at t (``state`` is not
        changed), through the step ends the reference logged over the same interval: advance
        the reference first."""
        integ = self.integration
        n_y, n_mem = integ.y.size, integ.mem.size
        clock = np.zeros(1, dtype=CLOCK)
        for k, value in zip(CONTROLLER, state[n_y + n_mem :], strict=True):
            clock[0][k] = value
        if not np.isclose(clock[0]["t"], t, rtol=0.0, atol=1e-9 * max(1.0, abs(t))):
            raise ValueError(f"state is at t = {clock[0]['t']} s, not at t = {t} s")
        trajectory = Trajectory(
            y=state[:n_y], mem=state[n_y : n_y + n_mem].reshape(integ.mem.shape), clock=clock
        )
        # the carried step data belong to the state before its renormalisation: restored
        # without them, the integrator re-evaluates them
        integ.restore(Snapshot(trajectory, carry=None))

        def advance() -> np.ndarray:
            _check(integ, integ.follow(self.leader), self.scene_name, "Lyapunov trajectory")
            return _pack(integ)

        return self.onsets.counted(integ, self.onsets.perturbed, advance)


def linkage_propagator(
    scene: dict, *, ideal: bool = False, rigid: bool = False
) -> LinkagePropagator:
    """A propagator of ``scene``, both trajectories at its assembled initial state (t = 0).

    No output samples are recorded (runs of zero revolutions are prepared), so the propagator
    costs the integrations alone.
    """
    return LinkagePropagator(
        prepare(scene, ideal=ideal, rigid=rigid, revolutions=0),
        prepare(scene, ideal=ideal, rigid=rigid, revolutions=0, step_log=STEP_LOG),
        scene["name"],
    )


def default_tolerances(scene: dict) -> tuple[float, float]:
    """The exponent's default (rtol, atol) for the scene's integrator (DEFAULT_TOLERANCES)."""
    return DEFAULT_TOLERANCES[scene["solver"]["method"]]


def exponent_tolerances(
    scene: dict, tolerances: tuple[float, float] | None = None
) -> tuple[float, float]:
    """The (rtol, atol) both trajectories of :func:`linkage_lyapunov` take for ``scene`` given
    its ``tolerances`` argument: the scene's own, bounded by ``tolerances`` or, when None, by
    :func:`default_tolerances`."""
    solver = with_tolerances(scene, tolerances or default_tolerances(scene))["solver"]
    return solver["rtol"], solver["atol"]


def with_tolerances(scene: dict, tolerances: tuple[float, float]) -> dict:
    """A copy of ``scene`` whose solver rtol and atol are at most ``tolerances``."""
    rtol, atol = tolerances
    solver = scene["solver"]
    return {
        **scene,
        "solver": {**solver, "rtol": min(solver["rtol"], rtol), "atol": min(solver["atol"], atol)},
    }


def with_modal_links(scene: dict) -> dict:
    """A copy of ``scene`` whose beams are modal links (with the scene's default modes, and
    no axial modes: the explicit method resolves them), the link model whose exponent the
    chaos studies take (docs/exponent.md, "Model convergence")."""
    bodies = {
        name: {**body, "kind": "modal", "axial_modes": 0} if body["kind"] == "beam" else body
        for name, body in scene["bodies"].items()
    }
    return {**scene, "bodies": bodies, "solver": dict(scene["solver"])}


def linkage_lyapunov(
    scene: dict,
    *,
    revolutions: float,
    transient_revolutions: float,
    d0: float = DEFAULT_D0,
    interval_revolutions: float = DEFAULT_INTERVAL_REVOLUTIONS,
    tolerances: tuple[float, float] | None = None,
    ideal: bool = False,
    rigid: bool = False,
) -> BenettinResult:
    """Largest Lyapunov exponent (1/s) of a linkage scene by two nearby trajectories.

    Explanation of the method:
        :func:`sim.analysis.lyapunov.benettin` on the full state of the mechanism: the
        reference trajectory starts at the scene's assembled initial state, the perturbed one
        d0 away in a fixed random direction of (q, q̇); the reference is integrated by the
        run's own compiled integrator, the perturbed one through the reference's own steps
        (:mod:`sim.solve.lockstep`), each with its own contact events and memory, and the
        separation is renormalised to d0 every ``interval_revolutions``, the onset rates of
        the contacts both trajectories share included (:class:`LinkagePropagator`). The
        perturbation leaves the ideal constraints by d0. In minimal coordinates (a tree
        mechanism, :mod:`sim.model.tree`) the first step's projection drops that component;
        in absolute coordinates Baumgarte stabilisation pulls it back at its rates
        (−α ± √(α² − β²)), so it fades within the transient unless the motion is more stable
        than the stabilisation itself (then the exponent found is the stabilisation's,
        −α + Re √(α² − β²): the all-ideal mechanism has no other dynamics).

        Two things make the exponent the dynamics' and not the integrator's (docs/exponent.md
        has the measurements). The perturbed trajectory takes the reference's steps, so the
        two do not differ by their local integration errors. And the onset rate δ̇⁻ that each
        impact's Lankarani–Nikravesh force remembers is renormalised with the state: left as
        it was, the perturbed trajectory's force kept a difference e^(λ · interval) times too
        large after every renormalisation in contact, which doubled the rigid flagship's
        exponent and made it depend on the interval.

    Choosing the parameters:
        tolerances: the exponent of the discrete map approaches the flow's as the steps
            resolve the motion; on the flagship (A and B 0.5 mm, 150 rpm, d0 = 1e-6 m,
            interval 1/32 revolution, 20 recorded revolutions) under DOPRI5, rtol 1e-6 and 1e-8
            agree within their standard errors (rigid links 57.3 ± 2.2 and 57.8 ± 5.2 1/s,
            modal links 270.7 ± 5.7 and 269.2 ± 6.2), while rtol 1e-5 reads 70 ± 6 and 295 ± 8.
            Generalized-α needs 1e-8: modal links read 310 ± 6 at rtol 1e-6 and 274 ± 4 at
            1e-8 (DOPRI5's value), and with an axial mode 342 ± 4, 298 ± 5 and 295 ± 7 at 1e-6,
            1e-8 and 1e-9, its 1e-6 value moving with the interval and d0 too (411 and 454).
            Hence the defaults per integrator (DEFAULT_TOLERANCES: (1e-6, 1e-8) and (1e-8,
            1e-10)), applied where the scene's own tolerances are looser.
        d0: inside the linear regime and above the integration noise. The noise floor scales
            with the tolerance, about rtol metres: at rtol 1e-6 the rigid flagship reads
            58.0 ± 2.8, 57.3 ± 2.2, 67.0 ± 2.6 and 87.2 ± 4.3 1/s for d0 = 1e-5 … 1e-8 m; at
            rtol 1e-8, 57.8, 59.3 and 63.2 (± 5–6) for 1e-6 … 1e-8. Impacts make the motion
            non-linear on the scale of the Hertz penetration (flagship: 1–2 µm median while in
            contact, 18 µm at the peak), so d0 · e^(λ · interval) should not much exceed it.
            The default 1e-6 m keeps a decade to the floor at the default tolerances.
        interval_revolutions: short enough that the separation grows by little more than one
            e-fold (λ · interval ≲ 1.5); the default 1/32 revolution (12.5 ms at 150 rpm)
            suits exponents up to ~120 1/s, and 1/16 … 1/512 read the same on the flagship
            (rigid 56.9, 57.3, 58.3, 60.4, 62.8; modal 270.7 and 269.9 at 1/32 and 1/128,
            ± 2–6 1/s). Not at the harder points: at 0.1 mm the default reads 10–20 % low,
            and at 30 rpm the exponent rises with shorter intervals without settling
            (docs/exponent.md, "The harder points").
        transient_revolutions: let the reference settle on its attractor and the separation
            align with the most unstable direction; as for the run's analyses (20 by default).
        Check with a second setting (d0 · 10, interval / 2) that the exponent does not move
        beyond its standard error: tests/analysis/test_model_lyapunov.py does on the flagship.

    Minimum data length:
        The standard error falls like 1 / sqrt(recorded time): ±2–6 1/s from 20 recorded
        revolutions of the flagship; at least 2 · N_BLOCKS renormalisation intervals.

    Cost:
        Two integrations of the scene over ``revolutions`` at ``tolerances``, without output
        sampling: about twice one run of the same length and tolerances (the perturbed one
        rejects no step).

    References:
        G. Benettin, L. Galgani, A. Giorgilli, J.-M. Strelcyn, Meccanica 15 (1980) 9–20.
        T. S. Parker, L. O. Chua, "Practical Numerical Algorithms for Chaotic Systems",
        Springer (1989), section 5.2 (exponents from nearby orbits; integration noise).

    Args:
        scene: a validated scene (:func:`sim.scene.load_scene`, or ``scene_of(run)``).
        revolutions: crank revolutions in all, the transient included.
        transient_revolutions: revolutions run (with renormalisation) before recording.
        d0: separation after every renormalisation, in the metric of
            :class:`LinkagePropagator` (m).
        interval_revolutions: renormalisation interval in crank revolutions.
        tolerances: upper bounds on the solver's (rtol, atol) for both trajectories; None:
            :func:`default_tolerances` of the scene.
        ideal, rigid: the reference mechanism, as for :func:`sim.run.simulate`.

    Returns:
        A :class:`~sim.analysis.lyapunov.BenettinResult` in seconds (``time``, ``interval``) and
        1/s (``exponent``, ``stderr``, ``running``).
    """
    return linkage_exponent(
        scene,
        revolutions=revolutions,
        transient_revolutions=transient_revolutions,
        d0=d0,
        interval_revolutions=interval_revolutions,
        tolerances=tolerances,
        ideal=ideal,
        rigid=rigid,
    )[0]


def linkage_exponent(
    scene: dict,
    *,
    revolutions: float,
    transient_revolutions: float,
    d0: float = DEFAULT_D0,
    interval_revolutions: float = DEFAULT_INTERVAL_REVOLUTIONS,
    tolerances: tuple[float, float] | None = None,
    ideal: bool = False,
    rigid: bool = False,
) -> tuple[BenettinResult, OnsetShares]:
    """:func:`linkage_lyapunov`'s exponent (the arguments as there) and where its stretch is
    made: each clearance joint's share of it in the intervals of its contact onsets
    (:class:`OnsetShares`)."""
    _check_schedule(revolutions, transient_revolutions, interval_revolutions)
    scene = with_tolerances(scene, exponent_tolerances(scene, tolerances))
    propagator = linkage_propagator(scene, ideal=ideal, rigid=rigid)
    result = propagator_lyapunov(
        propagator,
        scene,
        revolutions=revolutions,
        transient_revolutions=transient_revolutions,
        d0=d0,
        interval_revolutions=interval_revolutions,
    )
    return result, onset_shares(result, propagator)


def _check_schedule(revolutions: float, transient_revolutions: float, interval: float) -> None:
    """ValueError unless 0 <= transient < revolutions and the renormalisation interval (all in
    crank revolutions) is positive: checked before a propagator is built."""
    if not 0 <= transient_revolutions < revolutions:
        raise ValueError(
            f"transient_revolutions = {transient_revolutions} must lie in [0, {revolutions})"
        )
    if interval <= 0:
        raise ValueError(f"interval_revolutions = {interval} must be positive")


def propagator_lyapunov(
    propagator: LinkagePropagator,
    scene: dict,
    *,
    revolutions: float,
    transient_revolutions: float,
    d0: float = DEFAULT_D0,
    interval_revolutions: float = DEFAULT_INTERVAL_REVOLUTIONS,
) -> BenettinResult:
    """The exponent of :func:`linkage_lyapunov` (1/s) on a propagator already built from
    ``scene`` at t = 0 (:func:`linkage_propagator`, or a subclass of :class:`LinkagePropagator`
    that records what its trajectories step through); the arguments as there.
    """
    _check_schedule(revolutions, transient_revolutions, interval_revolutions)
    interval = interval_revolutions * crank_period(scene)
    distance = propagator.distance(scene)
    return benettin(
        propagator.advance,
        propagator.pack(),
        0.0,
        interval=interval,
        n_intervals=round((revolutions - transient_revolutions) / interval_revolutions),
        d0=d0,
        distance=distance,
        rescale=propagator.rescale(distance),
        mask=propagator.mask(),
        transient_intervals=round(transient_revolutions / interval_revolutions),
        advance_reference=propagator.advance_leader,
    )


def run_with_exponent(
    scene: dict,
    start: State | None,
    *,
    transient_revolutions: float,
    alignment_revolutions: float = DEFAULT_ALIGNMENT_REVOLUTIONS,
    d0: float = DEFAULT_D0,
    interval_revolutions: float = DEFAULT_INTERVAL_REVOLUTIONS,
    progress: bool = False,
    announce_assembly: bool = True,
) -> tuple[xr.Dataset, State, BenettinResult]:
    """A run of ``scene`` (:func:`sim.run.simulate_from`) and the largest Lyapunov exponent
    (1/s) of its revolutions after ``transient_revolutions``, the run itself being the
    reference trajectory.

    Explanation of the method:
        :func:`sim.analysis.lyapunov.benettin` as in :func:`linkage_lyapunov`, but the
        reference is the run, paused at every renormalisation (:class:`sim.run.Run`), so only
        the perturbed trajectory costs extra. It starts ``alignment_revolutions`` before the
        transient ends, d0 away from the run in a fixed random direction of (q, q̇), and is
        renormalised through the alignment (not recorded) and then through every recorded
        revolution: the exponent covers the same revolutions as the run's Poincaré points.
        Both trajectories are integrated at the scene's own tolerances; the run's pauses end
        its steps at the renormalisation times (32 per revolution against thousands of steps),
        so its file differs from an uninterrupted run's by integration error only, which the
        chaotic motion then amplifies like any other.

    Choosing the parameters:
        alignment_revolutions: long enough for the separation to turn into the most unstable
            direction and for its component off the ideal constraints to fade (Baumgarte, see
            :func:`linkage_lyapunov`); at most the transient. On three points of the clearance
            sweep, 1, 2 and 4 revolutions gave exponents within two standard errors of one
            another; the default is 2 (64 renormalisations).
        d0, interval_revolutions: as for :func:`linkage_lyapunov`.
        The scene's tolerances: both trajectories take the run's steps. Give the scene rtol
            1e-6 or tighter: at 1e-5 the discrete map's exponent reads 20–25 % high
            (:func:`linkage_lyapunov`).

    Cost:
        One run plus one trajectory over the recorded and alignment revolutions without
        output sampling: (revolutions + recorded + alignment) / revolutions runs, 1.77 for
        the dense sweeps' 35 revolutions with 10 transient (1.8–2.0 measured), against 3 for
        a run followed by :func:`linkage_lyapunov` at the same tolerances.

    References:
        As :func:`linkage_lyapunov`.

    Args:
        scene: a validated scene.
        start: None for the assembled state, or a previous run's final state to continue
            from (:func:`sim.run.simulate_from`).
        transient_revolutions: revolutions before the recorded window, the alignment included.
        alignment_revolutions: revolutions of the perturbed trajectory before recording.
        d0: separation after every renormalisation (m, metric of :class:`LinkagePropagator`).
        interval_revolutions: renormalisation interval in crank revolutions.
        progress: show the run's progress line.
        announce_assembly: with ``progress``, say which assembly branch was taken.

    Returns:
        The run's output Dataset and final state (as :func:`sim.run.simulate_from`) and the
        :class:`~sim.analysis.lyapunov.BenettinResult`.
    """
    if not 0 < alignment_revolutions <= transient_revolutions:
        raise ValueError(
            f"alignment_revolutions = {alignment_revolutions} must lie in "
            f"(0, transient_revolutions = {transient_revolutions}]"
        )
    run = Run(
        scene, start, progress=progress, step_log=STEP_LOG, announce_assembly=announce_assembly
    )
    if not transient_revolutions < run.revolutions:
        raise ValueError(
            f"transient_revolutions = {transient_revolutions} must be below the run's "
            f"{run.revolutions} revolutions"
        )
    perturbed = LinkagePropagator(prepare(run.scene, revolutions=0), run.integ, scene["name"])
    t_align = (transient_revolutions - alignment_revolutions) * run.period
    run.advance_to(t_align)
    distance = perturbed.distance(run.scene)

    def advance_reference(state: np.ndarray, t: float, dt: float) -> np.ndarray:
        run.integ.clear_step_log()

        def advance() -> np.ndarray:
            run.advance_to(t + dt)
            return perturbed.pack()

        return perturbed.onsets.counted(run.integ, perturbed.onsets.reference, advance)

    result = benettin(
        perturbed.advance,
        perturbed.pack(),
        t_align,
        interval=interval_revolutions * run.period,
        n_intervals=round((run.revolutions - transient_revolutions) / interval_revolutions),
        d0=d0,
        distance=distance,
        rescale=perturbed.rescale(distance),
        mask=perturbed.mask(),
        transient_intervals=round(alignment_revolutions / interval_revolutions),
        advance_reference=advance_reference,
    )
    dataset, final = run.finish()
    return dataset, final, result


def model_lyapunov_dataset(
    result: BenettinResult, tolerances: tuple[float, float], shares: OnsetShares | None = None
) -> xr.Dataset:
    """The exponent, its standard error and its convergence curve as CF-annotated variables,
    with the settings (d0, interval, transient, the solver's rtol and atol) as attributes; with
    ``shares``, each clearance joint's share of the stretch after its contact onsets and of the
    intervals (:class:`OnsetShares`)."""
    dataset = xr.Dataset(
        {
            "model_lyapunov_exponent": (
                (),
                result.exponent,
                {"units": "s-1", "long_name": "largest Lyapunov exponent of the model (Benettin)"},
            ),
            "model_lyapunov_stderr": (
                (),
                result.stderr,
                {"units": "s-1", "long_name": "standard error of the model exponent over blocks"},
            ),
            "model_lyapunov_running": (
                "renormalisation_time",
                result.running,
                {"units": "s-1", "long_name": "running estimate of the model exponent"},
            ),
        },
        coords={
            "renormalisation_time": (
                "renormalisation_time",
                result.time,
                {"units": "s", "long_name": "end of each recorded renormalisation interval"},
            )
        },
        attrs={
            "model_lyapunov_d0": result.d0,
            "model_lyapunov_interval_s": result.interval,
            "model_lyapunov_transient_intervals": result.transient_intervals,
            "model_lyapunov_rtol": tolerances[0],
            "model_lyapunov_atol": tolerances[1],
        },
    )
    if shares is None:
        return dataset
    return dataset.assign(
        model_lyapunov_onset_stretch_share=(
            "joint",
            shares.stretch,
            {
                "units": "1",
                "long_name": "share of the exponent's stretch in the renormalisation intervals "
                "with a contact onset of the joint",
            },
        ),
        model_lyapunov_onset_interval_share=(
            "joint",
            shares.intervals,
            {
                "units": "1",
                "long_name": "share of the renormalisation intervals with a contact onset of "
                "the joint",
            },
        ),
    ).assign_coords(joint=list(shares.joints))

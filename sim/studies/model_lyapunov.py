"""Largest Lyapunov exponent of a linkage from the model itself (Benettin on the run's integrator).

The two trajectories of :func:`sim.analysis.lyapunov.benettin` are advanced by the compiled
integrator of :mod:`sim.run` (the same step code, contact events and force laws as ``sim run``),
so the exponent belongs to exactly the dynamics the run file holds, and the perturbed
trajectory costs what a second run costs.
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import xarray as xr

from sim.analysis.lyapunov import BenettinResult, benettin
from sim.model.assembly import crank_period, omega
from sim.model.continuation import State
from sim.run import Integration, Run, SimulationError, Snapshot, diagnose, prepare
from sim.solve.state import CLOCK, Trajectory
from sim.solve.status import OK

#: default separation d0 of the two trajectories (m, in the metric of :class:`LinkagePropagator`)
DEFAULT_D0 = 1e-6
#: default renormalisation interval, in crank revolutions
DEFAULT_INTERVAL_REVOLUTIONS = 1 / 32
#: default revolutions of :func:`run_with_exponent`'s perturbed trajectory before recording
DEFAULT_ALIGNMENT_REVOLUTIONS = 2.0
#: default integration tolerances (rtol, atol) of both trajectories, unless the scene's are
#: tighter: the two trajectories' different step sequences differ by their local errors, and
#: at the runs' rtol 1e-6 that noise floor lies just below separations of 1e-6 m
#: (see :func:`linkage_lyapunov`)
DEFAULT_TOLERANCES = (1e-8, 1e-11)
#: the fields of the integration's clock (sim.solve.state.CLOCK) packed with a trajectory
CONTROLLER = ("t", "h", "facold")


@dataclass(frozen=True, eq=False)
class LinkagePropagator:
    """``advance(state, t, dt)`` of a linkage for :func:`~sim.analysis.lyapunov.benettin`.

    The packed state of a trajectory is everything its future depends on:
    ``(q, q̇, W_drive, E_dissipated)`` (the integrator's ``y``), the contact memory of every gap
    (in-contact flag, onset rate δ̇⁻, graze mark) and the step-size controller's state (t, h,
    previous error). Only q and q̇ are continuous (``mask``); the contact memory travels with
    its trajectory unchanged, the energy quadratures do not enter the distance.

    Distance (see :meth:`weights`): the Euclidean norm of (Δq, Δq̇ / ω), ω the crank speed, so that
    positions (m; rad and dimensionless slopes count as they are) and velocities weigh alike
    over one radian of crank motion. Any norm gives the same exponent; this one keeps the
    separation's components of comparable size, which shortens the transient.

    Attributes:
        integration: the prepared run (:func:`sim.run.prepare`) whose compiled integrator and
            work arrays both trajectories share, one after the other.
        scene_name: for error messages.
    """

    integration: Integration
    scene_name: str

    @property
    def _sizes(self) -> tuple[int, int, int]:
        integ = self.integration
        return integ.y.size, integ.mem.size, len(CONTROLLER)

    def pack(self) -> np.ndarray:
        """The integration's current trajectory (:class:`sim.solve.state.Trajectory`) as one
        array."""
        integ = self.integration
        clock = integ.trajectory.clock[0]
        return np.concatenate([integ.y, integ.mem.ravel(), [clock[k] for k in CONTROLLER]])

    def mask(self) -> np.ndarray:
        """True for the continuous entries of a packed state: q and q̇."""
        mask = np.zeros(sum(self._sizes), dtype=bool)
        mask[: 2 * self.integration.system.n] = True
        return mask

    def distance(self, scene: dict) -> Callable[[np.ndarray, np.ndarray], float]:
        """The distance between two packed states: the norm of (Δq, Δq̇ / ω) (class docstring)."""
        mask = self.mask()
        n = self.integration.system.n
        weights = np.concatenate([np.ones(n), np.full(n, 1.0 / omega(scene))])

        def distance(a: np.ndarray, b: np.ndarray) -> float:
            return float(np.linalg.norm(weights * (a[mask] - b[mask])))

        return distance

    def advance(self, state: np.ndarray, t: float, dt: float) -> np.ndarray:
        """The packed state at t + dt from the packed ``state`` at t (``state`` is not changed)."""
        integ = self.integration
        n_y, n_mem, _ = self._sizes
        clock = np.zeros(1, dtype=CLOCK)
        for k, value in zip(CONTROLLER, state[n_y + n_mem :], strict=True):
            clock[0][k] = value
        if not np.isclose(clock[0]["t"], t, rtol=0.0, atol=1e-9 * max(1.0, abs(t))):
            raise ValueError(f"state is at t = {clock[0]['t']} s, not at t = {t} s")
        trajectory = Trajectory(
            y=state[:n_y], mem=state[n_y : n_y + n_mem].reshape(integ.mem.shape), clock=clock
        )
        # the carried step data belong to the other trajectory (or to the state before its
        # renormalisation): restored without them, the integrator re-evaluates them
        integ.restore(Snapshot(trajectory, carry=None))
        status = integ.advance(t + dt)
        if status != OK:
            raise SimulationError(
                f"scene '{self.scene_name}' (Lyapunov trajectory): {diagnose(integ, status)}"
            )
        return self.pack()


def linkage_propagator(
    scene: dict, *, ideal: bool = False, rigid: bool = False
) -> LinkagePropagator:
    """A propagator of ``scene`` positioned at its assembled initial state (t = 0).

    No output samples are recorded (a run of zero revolutions is prepared), so the propagator
    costs the integration alone.
    """
    return LinkagePropagator(prepare(scene, ideal=ideal, rigid=rigid, revolutions=0), scene["name"])


def with_tolerances(scene: dict, tolerances: tuple[float, float]) -> dict:
    """A copy of ``scene`` whose solver rtol and atol are at most ``tolerances``."""
    rtol, atol = tolerances
    solver = scene["solver"]
    return {
        **scene,
        "solver": {**solver, "rtol": min(solver["rtol"], rtol), "atol": min(solver["atol"], atol)},
    }


def linkage_lyapunov(
    scene: dict,
    *,
    revolutions: float,
    transient_revolutions: float,
    d0: float = DEFAULT_D0,
    interval_revolutions: float = DEFAULT_INTERVAL_REVOLUTIONS,
    tolerances: tuple[float, float] = DEFAULT_TOLERANCES,
    ideal: bool = False,
    rigid: bool = False,
) -> BenettinResult:
    """Largest Lyapunov exponent (1/s) of a linkage scene by two nearby trajectories.

    Explanation of the method:
        :func:`sim.analysis.lyapunov.benettin` on the full state of the mechanism: the
        reference trajectory starts at the scene's assembled initial state, the perturbed one
        d0 away in a fixed random direction of (q, q̇); both are integrated by the run's own
        compiled integrator (:class:`LinkagePropagator`), with their contact memory, and the
        separation is renormalised to d0 every ``interval_revolutions``. The perturbation
        leaves the ideal constraints by d0. In minimal coordinates (a tree mechanism,
        :mod:`sim.model.tree`) the first step's projection drops that component; in absolute
        coordinates Baumgarte stabilisation pulls it back at its rates (−α ± √(α² − β²)), so
        it fades within the transient unless the motion is more stable than the stabilisation
        itself (then the exponent found is the stabilisation's, −α + Re √(α² − β²): the
        all-ideal mechanism has no other dynamics). Both forms give the same exponent on the
        flagship (A + B 0.5 mm, 150 rpm, 40 revolutions with 10 transient: 120 ± 11 1/s
        minimal, 115 ± 9 absolute).

    Choosing the parameters:
        tolerances: the two trajectories take different adaptive step sequences, so they also
            differ by their integration errors, which the method reads as divergence. Measured
            on the flagship (A and B 0.5 mm, 150 rpm, interval 1/32 revolution): at the runs'
            rtol 1e-6 the exponent rises as d0 falls below 1e-6 m (121, 135, 157, 217 1/s for
            d0 = 1e-6 … 1e-9 over 30 recorded revolutions), while at d0 = 1e-6 m it still
            agrees with the tighter runs (116 ± 4 1/s over 180 revolutions); at rtol 1e-8
            (atol 1e-11) it is flat from d0 = 1e-7 to 1e-5 m (97, 104, 101 ± 8 1/s over 20
            revolutions; 126 ± 6 and 123 ± 5 for 1e-7 and 1e-6 over 180). Hence the default
            (1e-8, 1e-11), applied where the scene's own tolerances are looser, which leaves a
            decade of d0 on either side of the default; ``tolerances=(1, 1)`` keeps the
            scene's (half the cost, no margin below d0 = 1e-6 m).
        d0: inside the linear regime and above the integration noise. Impacts make the motion
            non-linear on the scale of the Hertz penetration (flagship: 1–2 µm median while in
            contact, 18 µm at the peak), so d0 · e^(λ · interval) should not exceed it; the
            default 1e-6 m agrees with 1e-7 m within the standard error.
        interval_revolutions: short enough that the separation grows by little more than one
            e-fold (λ · interval ≲ 1.5; at λ · interval ≈ 3 the flagship's exponent came out
            2 standard errors low); the default 1/32 revolution (12.5 ms at 150 rpm) suits
            exponents up to ~120 1/s. Halve it for faster divergence.
        transient_revolutions: let the reference settle on its attractor and the separation
            align with the most unstable direction; as for the run's analyses (20 by default).
        Check with a second setting (d0 / 10, interval / 2) that the exponent does not move
        beyond its standard error: benchmarks/lyapunov_cost.py does.

    Minimum data length:
        The standard error falls like 1 / sqrt(recorded time): about ±8 1/s from 20 recorded
        revolutions of the flagship, ±4 1/s from 180; at least 2 · N_BLOCKS renormalisation
        intervals.

    Cost:
        Two integrations of the scene over ``revolutions`` at ``tolerances``, without output
        sampling: about twice one run of the same length and tolerances.

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
        tolerances: upper bounds on the solver's (rtol, atol) for both trajectories.
        ideal, rigid: the reference mechanism, as for :func:`sim.run.simulate`.

    Returns:
        A :class:`~sim.analysis.lyapunov.BenettinResult` in seconds (``time``, ``interval``) and
        1/s (``exponent``, ``stderr``, ``running``).
    """
    if not 0 <= transient_revolutions < revolutions:
        raise ValueError(
            f"transient_revolutions = {transient_revolutions} must lie in [0, {revolutions})"
        )
    if interval_revolutions <= 0:
        raise ValueError(f"interval_revolutions = {interval_revolutions} must be positive")
    scene = with_tolerances(scene, tolerances)
    propagator = linkage_propagator(scene, ideal=ideal, rigid=rigid)
    interval = interval_revolutions * crank_period(scene)
    return benettin(
        propagator.advance,
        propagator.pack(),
        0.0,
        interval=interval,
        n_intervals=round((revolutions - transient_revolutions) / interval_revolutions),
        d0=d0,
        distance=propagator.distance(scene),
        mask=propagator.mask(),
        transient_intervals=round(transient_revolutions / interval_revolutions),
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
        The scene's tolerances: both trajectories use them, and their different step
            sequences add integration noise to the separation. Measured over 6 members
            (initial crank angle perturbed) of the rigid flagship family at 0.5 mm, 150 rpm,
            d0 = 1e-6 m: 162 ± 6 1/s at rtol 1e-5 (atol 1e-7), against 116 ± 5 at rtol 1e-6
            (atol 1e-8) and 117 ± 5 by :func:`linkage_lyapunov` at rtol 1e-8; at 1.0 mm
            (4 members) 110 ± 7, 69 ± 3 and 59 ± 8. So give the scene rtol 1e-6 or tighter;
            at 1e-5 the exponent is mostly noise-inflated (docs/performance.md, "The run as
            the exponent's reference").

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

    Returns:
        The run's output Dataset and final state (as :func:`sim.run.simulate_from`) and the
        :class:`~sim.analysis.lyapunov.BenettinResult`.
    """
    if not 0 < alignment_revolutions <= transient_revolutions:
        raise ValueError(
            f"alignment_revolutions = {alignment_revolutions} must lie in "
            f"(0, transient_revolutions = {transient_revolutions}]"
        )
    run = Run(scene, start, progress=progress)
    if not transient_revolutions < run.revolutions:
        raise ValueError(
            f"transient_revolutions = {transient_revolutions} must be below the run's "
            f"{run.revolutions} revolutions"
        )
    reference = LinkagePropagator(run.integ, scene["name"])
    perturbed = LinkagePropagator(prepare(run.scene, revolutions=0), scene["name"])
    t_align = (transient_revolutions - alignment_revolutions) * run.period
    run.advance_to(t_align)

    def advance_reference(state: np.ndarray, t: float, dt: float) -> np.ndarray:
        run.advance_to(t + dt)
        return reference.pack()

    result = benettin(
        perturbed.advance,
        reference.pack(),
        t_align,
        interval=interval_revolutions * run.period,
        n_intervals=round((run.revolutions - transient_revolutions) / interval_revolutions),
        d0=d0,
        distance=perturbed.distance(run.scene),
        mask=perturbed.mask(),
        transient_intervals=round(alignment_revolutions / interval_revolutions),
        advance_reference=advance_reference,
    )
    dataset, final = run.finish()
    return dataset, final, result


def model_lyapunov_dataset(result: BenettinResult, tolerances: tuple[float, float]) -> xr.Dataset:
    """The exponent, its standard error and its convergence curve as CF-annotated variables,
    with the settings (d0, interval, transient, the solver's rtol and atol) as attributes."""
    return xr.Dataset(
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

"""Largest Lyapunov exponent: from a model (Benettin), a 1-D map, or a time series (Rosenstein).

All exponents are natural-log rates per unit of the time axis given (1/s for the linkage), never
per sample or per renormalisation interval.
"""

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.integrate import solve_ivp

from sim.analysis.embedding import (
    delay_embed,
    embedding_dimension,
    embedding_lag,
    mean_period,
    nearest_neighbours,
)

Advance = Callable[[np.ndarray, float, float], np.ndarray]
Distance = Callable[[np.ndarray, np.ndarray], float]
Perturb = Callable[[np.ndarray, float], np.ndarray]
Rescale = Callable[[np.ndarray, np.ndarray, float], np.ndarray]

#: seed of the default perturbation direction in :func:`benettin`
PERTURBATION_SEED = 20_240_601
#: number of consecutive blocks the standard errors are computed over
N_BLOCKS = 10


def block_standard_error(values: np.ndarray, n_blocks: int = N_BLOCKS) -> float:
    """Standard error of the mean of a correlated series from the means of consecutive blocks.

    Consecutive values (stretching rates along one trajectory) are correlated, so the naive
    std / sqrt(N) is too small; block means far apart in time are nearly independent.
    """
    values = np.asarray(values, dtype=float)
    if len(values) < 2 * n_blocks:
        raise ValueError(f"need at least {2 * n_blocks} values for {n_blocks} blocks")
    means = np.array([block.mean() for block in np.array_split(values, n_blocks)])
    return float(means.std(ddof=1) / np.sqrt(n_blocks))


@dataclass(frozen=True, eq=False)
class BenettinResult:
    """Largest Lyapunov exponent from two nearby trajectories.

    Attributes:
        exponent: largest Lyapunov exponent (1 / time unit of ``advance``).
        stderr: standard error from ``N_BLOCKS`` consecutive blocks of renormalisation
            intervals (see :func:`block_standard_error`).
        time: end time of every recorded renormalisation interval.
        running: running estimate of the exponent at ``time`` (the convergence curve).
        d0: separation restored at every renormalisation.
        interval: renormalisation interval.
        n_intervals: number of recorded intervals.
        transient_intervals: number of intervals run before recording.
    """

    exponent: float
    stderr: float
    time: np.ndarray
    running: np.ndarray
    d0: float
    interval: float
    n_intervals: int
    transient_intervals: int


def interval_stretch(result: BenettinResult) -> np.ndarray:
    """The logarithmic stretch ln(d / d0) of every recorded renormalisation interval: the
    running estimate times the recorded time, differenced."""
    recorded = result.time - (result.time[0] - result.interval)
    return np.diff(result.running * recorded, prepend=0.0)


def rhs_propagator(
    f: Callable[[float, np.ndarray], np.ndarray],
    *,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    method: str = "DOP853",
) -> Advance:
    """Turn a right-hand side f(t, y) into a propagator ``advance(y, t, dt) -> y(t + dt)``.

    The propagator integrates with :func:`scipy.integrate.solve_ivp` and fails loudly if the
    integrator does. Tolerances must resolve the separation of the two trajectories in
    :func:`benettin`: keep ``atol`` well below ``d0``.
    """

    def advance(y: np.ndarray, t: float, dt: float) -> np.ndarray:
        solution = solve_ivp(f, (t, t + dt), y, method=method, rtol=rtol, atol=atol)
        if not solution.success:
            raise RuntimeError(f"rhs_propagator: integration from t={t} failed: {solution.message}")
        return solution.y[:, -1]

    return advance


def _masked_distance(mask: np.ndarray) -> Distance:
    def distance(y_a: np.ndarray, y_b: np.ndarray) -> float:
        return float(np.linalg.norm(y_a[mask] - y_b[mask]))

    return distance


def _direction_perturbation(mask: np.ndarray) -> Perturb:
    def perturb(y: np.ndarray, d0: float) -> np.ndarray:
        direction = np.random.default_rng(PERTURBATION_SEED).standard_normal(int(mask.sum()))
        perturbed = y.copy()
        perturbed[mask] += d0 * direction / np.linalg.norm(direction)
        return perturbed

    return perturb


def _radial_rescale(mask: np.ndarray, distance: Distance) -> Rescale:
    def rescale(y_ref: np.ndarray, y_pert: np.ndarray, d0: float) -> np.ndarray:
        # discrete entries (contact memory) stay as the perturbed trajectory has them
        rescaled = y_pert.copy()
        factor = d0 / distance(y_ref, y_pert)
        rescaled[mask] = y_ref[mask] + factor * (y_pert[mask] - y_ref[mask])
        return rescaled

    return rescale


def benettin(
    advance: Advance,
    y0: np.ndarray,
    t0: float,
    *,
    interval: float,
    n_intervals: int,
    d0: float = 1e-8,
    distance: Distance | None = None,
    perturb: Perturb | None = None,
    rescale: Rescale | None = None,
    mask: np.ndarray | None = None,
    transient_intervals: int = 0,
    advance_reference: Advance | None = None,
) -> BenettinResult:
    """Largest Lyapunov exponent of a model by two nearby trajectories (Benettin et al. 1980).

    Explanation of the method:
        A reference trajectory and a perturbed one, a distance d0 apart, are advanced together.
        After every ``interval`` their distance d is measured, ln(d / d0) is recorded and the
        perturbed state is pulled back to distance d0 along the current separation. The
        separation thereby aligns with the most unstable direction, and the mean of
        ln(d / d0) / interval converges to the largest Lyapunov exponent. Renormalising keeps the
        separation small enough to stay linear and avoids overflow.

        Any propagator works: ``advance(y, t, dt)`` returns the state at t + dt and must not
        modify y. States may carry discrete entries (e.g. which contacts are active, or the
        penetration at contact onset); mark the continuous entries in ``mask``: only they enter
        the default distance, perturbation and rescaling, while the others are taken from the
        perturbed trajectory as they are. The reference may have its own propagator
        (``advance_reference``), e.g. a run that records its outputs as it goes, so the run
        itself serves as the reference and only the perturbed trajectory costs extra. In each
        interval the reference is advanced first, so the perturbed propagator may take the
        reference's own steps (:mod:`sim.solve.lockstep`).

    Choosing the parameters:
        d0: small enough to stay in the linear regime over one interval (d0 · e^(λ·interval)
            ≪ the size of the attractor), large enough to stand well above the integrator's
            error (d0 ≫ atol). The default 1e-8 suits states of order 1 integrated to 1e-12.
        interval: short enough that the separation grows by at most a few e-folds (λ·interval
            ≲ 3), long enough that the cost of renormalising is small. The result must not
            depend on d0 and interval: check with a second setting.
        n_intervals: the estimate converges like 1 / sqrt(total time); the standard error tells
            when it is long enough. At least 2 · N_BLOCKS intervals are required.
        transient_intervals: intervals run (with renormalisation) before recording, to let the
            reference reach the attractor and the separation align with the unstable direction.
        distance / perturb / rescale: replace the defaults (Euclidean norm over ``mask``; a
            fixed random unit direction drawn from ``PERTURBATION_SEED``; radial rescaling
            along the current separation) when the state needs another metric.

    Minimum data length:
        Total recorded time of several hundred 1/λ for two significant digits on a chaotic
        attractor (Lorenz: ~10^3 time units for ±0.01).

    References:
        G. Benettin, L. Galgani, A. Giorgilli, J.-M. Strelcyn, "Lyapunov characteristic
        exponents for smooth dynamical systems and for Hamiltonian systems; a method for
        computing all of them. Part 1: Theory", Meccanica 15 (1980) 9–20.
        A. Wolf, J. B. Swift, H. L. Swinney, J. A. Vastano, "Determining Lyapunov exponents from
        a time series", Physica D 16 (1985) 285–317.

    Args:
        advance: propagator, see above.
        y0: initial state of the reference trajectory.
        t0: initial time.
        interval: renormalisation interval (time units of ``advance``).
        n_intervals: number of recorded intervals.
        d0: separation of the two trajectories after every renormalisation.
        distance: distance between two states; default Euclidean over ``mask``.
        perturb: perturb(y, d0) returns the initial perturbed state.
        rescale: rescale(y_ref, y_pert, d0) returns the renormalised perturbed state.
        mask: boolean array, True for continuous state entries; default all True.
        transient_intervals: intervals run before recording.
        advance_reference: propagator of the reference trajectory; default ``advance``.

    Returns:
        A :class:`BenettinResult` (exponent, stderr, convergence curve, parameters).
    """
    y_ref = np.array(y0, dtype=float)
    mask = np.ones(y_ref.shape, dtype=bool) if mask is None else np.asarray(mask, dtype=bool)
    distance = distance or _masked_distance(mask)
    perturb = perturb or _direction_perturbation(mask)
    rescale = rescale or _radial_rescale(mask, distance)

    advance_reference = advance_reference or advance
    y_pert = perturb(y_ref, d0)
    t = t0
    log_stretch = np.empty(n_intervals)
    for k in range(-transient_intervals, n_intervals):
        # measured rather than assumed d0, so a non-homogeneous distance stays correct
        d_start = distance(y_ref, y_pert)
        # the reference first: a perturbed propagator may follow the reference's own steps
        y_ref = advance_reference(y_ref, t, interval)
        y_pert = advance(y_pert, t, interval)
        t += interval
        d_end = distance(y_ref, y_pert)
        if not d_end > 0.0:
            raise RuntimeError(
                f"benettin: trajectories coincide at t={t}; raise d0 or check the propagator"
            )
        if k >= 0:
            log_stretch[k] = np.log(d_end / d_start)
        y_pert = rescale(y_ref, y_pert, d0)

    rates = log_stretch / interval
    recorded = np.arange(1, n_intervals + 1)
    return BenettinResult(
        exponent=float(rates.mean()),
        stderr=block_standard_error(rates),
        time=t0 + (transient_intervals + recorded) * interval,
        running=np.cumsum(rates) / recorded,
        d0=d0,
        interval=interval,
        n_intervals=n_intervals,
        transient_intervals=transient_intervals,
    )


def map_lyapunov(
    f: Callable[[float], float],
    df: Callable[[float], float],
    x0: float,
    n: int,
    transient: int,
) -> float:
    """Lyapunov exponent of a 1-D map x → f(x): the orbit average of ln|f'(x)|.

    Explanation of the method:
        For a 1-D map the separation of nearby orbits is multiplied by |f'(x_k)| at every
        step, so the exponent (per iteration) is lim (1/n) Σ ln|f'(x_k)| along a typical orbit.

    Choosing the parameters:
        x0: any point of the basin that is not on an unstable periodic orbit (for the logistic
            map avoid 0, 0.5, 0.75 and 1, which floating point maps onto fixed points).
        transient: iterations dropped first so the orbit lies on the attractor.
        n: the error falls like 1 / sqrt(n); 10^5 iterations give ~0.005 for the logistic map
            at r = 4.

    Minimum data length:
        10^4 iterations for two digits on a typical chaotic map.

    References:
        H. G. Schuster, W. Just, "Deterministic Chaos: An Introduction", 4th ed., Wiley-VCH
        (2005), section 3.1.

    Args:
        f: the map.
        df: its derivative.
        x0: initial point.
        n: iterations averaged.
        transient: iterations dropped before averaging.

    Returns:
        The exponent per iteration; −inf if the orbit lands on a critical point (f'(x) = 0,
        superstable).
    """
    x = x0
    for _ in range(transient):
        x = f(x)
    total = 0.0
    with np.errstate(divide="ignore"):
        for _ in range(n):
            total += np.log(abs(df(x)))
            x = f(x)
    return float(total / n)


@dataclass(frozen=True, eq=False)
class RosensteinResult:
    """Largest Lyapunov exponent from a time series.

    Attributes:
        exponent: slope of the mean log divergence over ``fit_range`` (1 / time unit of dt);
            NaN when ``fitted`` is False.
        stderr: standard error of the exponent (see "Uncertainty" in :func:`rosenstein`); NaN
            when ``fitted`` is False.
        time: divergence time of every point of ``divergence`` (k · dt).
        divergence: mean over reference points of ln(distance to the neighbour) after k steps.
        fit_range: (first, last) index into ``divergence`` of the fitted points, inclusive;
            None when ``fitted`` is False.
        intercept: intercept of the fitted line (for plotting it over ``divergence``); NaN when
            ``fitted`` is False.
        emb_dim: embedding dimension used.
        lag: embedding delay used (samples).
        min_tsep: Theiler window used (samples).
        trajectory_len: number of divergence steps followed (samples).
        saturation: mean ln distance between unrelated embedded points, the level the
            divergence curve saturates at.
        fitted: False when the curve has no linear region to fit (it starts at, or reaches,
            saturation within one fit window); ``reason`` says why.
        reason: why the curve was not fitted; empty when ``fitted``.
    """

    exponent: float
    stderr: float
    time: np.ndarray
    divergence: np.ndarray
    fit_range: tuple[int, int] | None
    intercept: float
    emb_dim: int
    lag: int
    min_tsep: int
    trajectory_len: int
    saturation: float
    fitted: bool
    reason: str


#: start of the automatic fit window of :func:`rosenstein`, in mean periods after the search
FIT_START_PERIODS = 0.5
#: width of the automatic fit window of :func:`rosenstein`, in mean periods
FIT_PERIODS = 1.0
#: fewest points of the divergence curve any fit of :func:`rosenstein` uses
MIN_FIT_POINTS = 10
#: default follow-up (``trajectory_len``) of :func:`rosenstein`, in mean periods
FOLLOW_PERIODS = 4.0
#: the automatic fit window must end before the divergence curve comes within this many nats
#: (a factor 1.2 in distance) of its saturation level, where neighbours are nearly as far apart
#: as unrelated points
SATURATION_MARGIN = 0.2
#: number of shifts the saturation level is averaged over (see ``_saturation_level``)
SATURATION_SHIFTS = 8
#: default neighbourhood of every reference point in :func:`rosenstein`: the mean distance to
#: this many nearest neighbours is followed (Kantz 1994); see "Neighbourhood" there
NEIGHBOURS = 2
#: fewest reference points :func:`rosenstein` needs besides the two Theiler windows
MIN_REFERENCE_POINTS = 10 * N_BLOCKS
#: numbers held at once by the divergence curve's squared differences (32 MB)
DIVERGENCE_CHUNK = 1 << 22
#: neighbour distances below this fraction of the series' standard deviation are rounding
#: noise (exact recurrences of periodic data), not dynamics; they are raised to it
DISTANCE_FLOOR = 1e-12


def _log_distances(points: np.ndarray, i: np.ndarray, j: np.ndarray, floor: float) -> np.ndarray:
    """ln of the distance between points i and j, at least ln ``floor``."""
    return np.log(np.maximum(np.linalg.norm(points[i] - points[j], axis=-1), floor))


def _divergence_sum(
    x: np.ndarray,
    ref: np.ndarray,
    neighbour: np.ndarray,
    emb_dim: int,
    lag: int,
    steps: int,
    floor: float,
) -> np.ndarray:
    """Σ over the reference points ``ref`` of ln(mean distance to their ``neighbour`` rows),
    k = 0 … ``steps`` − 1 samples later (at least ln ``floor``), for delay vectors of ``x``.

    From the series rather than from the delay vectors: the squared distance of two delay
    vectors k samples on is the sum of (x[i + s] − x[j + s])² over s = k, k + lag, …,
    k + (emb_dim − 1) · lag, so each pair's squared differences are formed once for all k,
    in chunks of reference points that bound the memory (``DIVERGENCE_CHUNK`` numbers).
    """
    span = steps + (emb_dim - 1) * lag
    offsets = np.arange(span)[:, None, None]
    chunk = max(1, DIVERGENCE_CHUNK // (span * neighbour.shape[1]))
    total = np.zeros(steps)
    for first in range(0, len(ref), chunk):
        i, j = ref[first : first + chunk], neighbour[first : first + chunk]
        squared = (x[i[None, :, None] + offsets] - x[j[None] + offsets]) ** 2
        distance2 = squared[:steps].copy()
        for d in range(1, emb_dim):
            distance2 += squared[d * lag : d * lag + steps]
        distance = np.sqrt(distance2).mean(axis=2)
        total += np.log(np.maximum(distance, floor)).sum(axis=1)
    return total


def _saturation_level(points: np.ndarray, floor: float) -> float:
    """Mean ln distance between unrelated embedded points.

    Every point is paired with the point a fixed fraction of the series later (cyclically);
    averaging over several fractions keeps one shift that happens to match a slow modulation
    from setting the level.
    """
    index = np.arange(len(points))
    levels = [
        _log_distances(
            points, index, (index + len(points) * k // SATURATION_SHIFTS) % len(points), floor
        ).mean()
        for k in range(1, SATURATION_SHIFTS)
    ]
    return float(np.mean(levels))


def _line_fit(t: np.ndarray, y: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Least-squares slope and intercept of y (or of every column of y) against t.

    Closed form rather than np.polyfit: the fits are never rank deficient (t holds at least
    MIN_FIT_POINTS distinct values), and no RankWarning can arise.
    """
    centred = t - t.mean()
    slope = centred @ (y - y.mean(axis=0)) / (centred @ centred)
    return slope, y.mean(axis=0) - slope * t.mean()


def _automatic_fit_range(
    divergence: np.ndarray, saturation: float, first: int, last: int
) -> tuple[tuple[int, int] | None, str]:
    """The fixed window (first, last) and an empty reason, or None and the reason it cannot be
    fitted: the curve comes near its saturation level before the window ends."""
    near = divergence[: last + 1] >= saturation - SATURATION_MARGIN
    if not near.any():
        return (first, last), ""
    return (
        None,
        f"the divergence curve comes within {SATURATION_MARGIN} of its saturation level "
        f"{saturation:.3g} after {int(np.argmax(near))} steps, before the fit window "
        f"{first}..{last} ends: the nearest neighbours are hardly closer than unrelated points "
        f"(noise, or too few samples for the embedding dimension)",
    )


def rosenstein(
    x: np.ndarray,
    dt: float,
    *,
    emb_dim: int | None = None,
    lag: int | None = None,
    min_tsep: int | None = None,
    trajectory_len: int | None = None,
    fit_range: tuple[int, int] | None = None,
    neighbours: int = NEIGHBOURS,
) -> RosensteinResult:
    """Largest Lyapunov exponent of a scalar time series (Rosenstein et al. 1993, with Kantz's
    neighbourhood average).

    Explanation of the method:
        The series is delay-embedded (m = ``emb_dim`` coordinates ``lag`` samples apart). For
        every embedded point (reference point) its ``neighbours`` nearest neighbours more than
        ``min_tsep`` samples away in time are found (k-d tree), and all are followed for
        ``trajectory_len`` steps. The mean over reference points of ln(mean distance to its
        neighbours) after k steps, the divergence curve d(k) (Kantz's form; Rosenstein's with
        one neighbour), grows like λ · k · dt while the separations are small, then
        bends over and saturates near the mean ln distance of unrelated points (the
        ``saturation`` level). λ is the slope of a straight line fitted to the linear part
        against the time k · dt, so it is per unit of dt (1/s), not per sample.

    Choosing the fit range (automatic unless ``fit_range`` is given):
        A fixed window: from ``FIT_START_PERIODS`` (0.5) mean periods after the neighbour
        search, ``FIT_PERIODS`` (1) mean period long (and at least ``MIN_FIT_POINTS`` (10)
        points). It starts half a period late because just after the search the separation
        has not yet turned into the most unstable direction: Lorenz neighbours first separate
        about twice as fast as e^λt, Duffing neighbours more slowly. It is one period long
        because the stretching rate varies along an orbit (Rössler stretches once per turn), and
        a whole turn averages that; a longer window reaches into the bend of the curve, which
        on Rössler's x(t) starts one to two turns after the search, far below saturation. If
        the curve comes within ``SATURATION_MARGIN`` (0.2) of its saturation level before the
        window ends, there is no linear region to fit (``fitted`` False, see below). The
        window is not chosen from the curve (e.g. as its steepest part, used before): on five
        stretches of Lorenz x(t) the steepest window of two periods took in the fast start and
        read 13 % high on average, and any choice driven by the curve's own wiggles favours
        noise. Always look at the curve.

    Neighbourhood:
        ``neighbours`` (default ``NEIGHBOURS``, 2): averaging the distance over a small
        neighbourhood rather than following the single nearest neighbour (Kantz 1994) removes
        most of the low bias on the forced Duffing oscillator, whose single nearest neighbours
        often lie across a fold of the attractor and separate slowly: over 20 stretches, the
        median error at 100, 200 and 300 forcing periods went from −20, −12 and −15 % (one
        neighbour) to −10, −3 and −2 % (two). Four neighbours take Duffing further (−15 … −3 %)
        but read Rössler high (median +10 % at 500 time units, +22 % at 200, against −6 and
        +3 % with one neighbour; two: +9 and +14 %).

    Choosing the other parameters:
        lag: default, the first minimum of the mutual information
            (:func:`sim.analysis.embedding.embedding_lag`).
        emb_dim: default, false nearest neighbours below 1 %
            (:func:`sim.analysis.embedding.embedding_dimension`).
        min_tsep: Theiler window; default, the mean period of the series (reciprocal of the
            power-weighted mean frequency), as Rosenstein et al. recommend: nearer points in
            time lie on the same stretch of trajectory and would bias λ low.
        trajectory_len: follow-up in samples; default ``FOLLOW_PERIODS`` (4) mean periods:
            the fit window, and after it room for the curve to show whether it gives its
            growth back (see "Uncertainty"). It must hold the fit window. A longer follow-up
            does not move the automatic fit, only leaves fewer reference points.

    Uncertainty:
        ``stderr`` combines in quadrature (1) the spread of the exponent across sub-series:
        the reference points are split into ``N_BLOCKS`` consecutive blocks, each block's
        curve is fitted over the same range, std(slopes) / sqrt(N_BLOCKS); this holds the
        scatter of the stretching rate along the orbit, the main error of short series; and
        (2) the growth the curve gives back: how far it falls below its value at the end of
        the fit range before it reaches saturation (or its end), divided by the duration of
        the fit range. Divergence does not undo itself; on a quasi-periodic signal the
        neighbours drift apart and together again with the beat of the frequencies, and a
        window on the rising half of that wobble would otherwise read as chaos (seen in 9 of
        45 two-frequency signals before this term; none since, all below 0.9 ``stderr``). On a
        chaotic curve it is near zero. The standard error of the regression slope is not
        used: the points of one curve are strongly correlated. ``stderr`` is somewhat
        optimistic: measured with one neighbour on 20 to 42 stretches, |exponent − published|
        reached 2.6 ``stderr`` for Lorenz at 100 time units (3.7 at 50) and 3.6 for Rössler
        at 500 (4.7 at 200), where about 2.5 is expected of the largest of 20 to 40 normal
        errors; for Duffing 5.0 (its bias then, see "Neighbourhood"). On a regular (periodic
        or quasi-periodic) signal the exponent stays below two ``stderr``, the significance
        :mod:`sim.analysis.classify` asks of a positive exponent.

    When no fit is possible:
        A ``ValueError`` says what is wrong and what is needed when the series is too short
        for the embedding, follow-up and Theiler window, when ``trajectory_len`` does not
        hold the fit window, or when ``fit_range`` is out of the curve or has fewer than
        ``MIN_FIT_POINTS`` points. When the curve reaches saturation before the fit window ends
        (it starts there: noise, or too few samples for ``emb_dim``), the result has
        ``fitted`` False, NaN ``exponent`` and ``stderr`` and a ``reason``; such a signal
        must not be read as regular.

    Minimum data length:
        Hard limit (else ValueError): (emb_dim − 1) · lag + trajectory_len + 2 · min_tsep +
        ``MIN_REFERENCE_POINTS`` (100) samples. Accuracy, measured over 20 to 42 independent
        stretches per case (relative error to the published exponent; tests/analysis):

        - Lorenz x(t), dt = 0.01: 50 time units (~30 mean periods), median −1 %, standard
          deviation 9 %, worst +20 %; 100 time units, median +2 %, worst −11 %.
        - Rössler x(t), dt = 0.1: 500 time units (~90 turns), median +9 %, standard deviation
          10 %, worst +20 %; 200 time units, median +14 %, standard deviation 20 %, worst
          −48 %, and the exponent is not always two ``stderr`` above zero.
        - Forced Duffing (Ueda) x(t), 40 samples per forcing period: 100, 200 and 300 forcing
          periods, medians −10, −3 and −2 %, standard deviations 11, 10 and 6 %, worst −35,
          −26 and −14 % (one neighbour instead of two: medians −20, −12 and −15 %; neither a
          larger embedding dimension, a longer delay, a wider Theiler window, a later fit
          window nor neighbours of the same forcing phase removed that bias).

        Much of the scatter is not the method's: a stretch of finite length has its own
        exponent, the mean stretching rate along it, which on these lengths already scatters
        by −11 … +23 % (Rössler, 500 time units) and −28 … +7 % (Duffing, 100 periods) about
        the infinite-time value. ``stderr`` largely reflects it (see "Uncertainty"). So a
        single series of these lengths gives λ to ±15 % only for Lorenz at 100 time units and
        Duffing at 300 periods; otherwise read ``stderr``, give several hundred mean periods,
        or compare several stretches.

    The result is deterministic: the same input gives the same output.

    References:
        M. T. Rosenstein, J. J. Collins, C. J. De Luca, "A practical method for calculating
        largest Lyapunov exponents from small data sets", Physica D 65 (1993) 117–134.
        H. Kantz, "A robust method to estimate the maximal Lyapunov exponent of a time
        series", Physics Letters A 185 (1994) 77–87 (the neighbourhood average, and reading λ
        off the linear region).
        J. Theiler, "Spurious dimension from correlation algorithms applied to limited
        time-series data", Physical Review A 34 (1986) 2427–2432 (the Theiler window).
        The parameter names follow ``lyap_r`` of the nolds package (C. Schölzel).

    Args:
        x: 1-D series sampled every ``dt``.
        dt: sampling interval (s, or the time unit of the exponent wanted).
        emb_dim: embedding dimension.
        lag: embedding delay (samples).
        min_tsep: Theiler window (samples).
        trajectory_len: number of divergence steps (samples).
        fit_range: (first, last) indices of the fitted part of the divergence curve,
            inclusive; default automatic (see above).

    Returns:
        A :class:`RosensteinResult`.

    Raises:
        ValueError: x is not a finite 1-D series, is too short, or the parameters leave no
            room for a fit (see "When no fit is possible").
    """
    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or not np.all(np.isfinite(x)):
        raise ValueError("rosenstein: x must be a 1-D array of finite values")
    period = mean_period(x)
    min_tsep = round(period) if min_tsep is None else min_tsep
    window_first = round(FIT_START_PERIODS * period)
    window_last = window_first + max(round(FIT_PERIODS * period), MIN_FIT_POINTS - 1)
    if trajectory_len is None:
        trajectory_len = max(round(FOLLOW_PERIODS * period), window_last + 1)
    if trajectory_len <= window_last:
        raise ValueError(
            f"rosenstein: trajectory_len={trajectory_len} is shorter than the fit window: it "
            f"must be at least {window_last + 1} steps ({FIT_START_PERIODS:g} + "
            f"{FIT_PERIODS:g} mean periods of {period:.1f} samples, and at least "
            f"{MIN_FIT_POINTS} points)"
        )
    if fit_range is not None:
        first, last = fit_range
        if not 0 <= first < last < trajectory_len or last - first + 1 < MIN_FIT_POINTS:
            raise ValueError(
                f"rosenstein: fit_range={fit_range} must satisfy 0 <= first < last < "
                f"trajectory_len={trajectory_len} and hold at least {MIN_FIT_POINTS} points"
            )
    lag = embedding_lag(x) if lag is None else lag
    emb_dim = embedding_dimension(x, lag, min_tsep=min_tsep) if emb_dim is None else emb_dim
    needed = (emb_dim - 1) * lag + trajectory_len + 2 * min_tsep + MIN_REFERENCE_POINTS
    if len(x) < needed:
        raise ValueError(
            f"rosenstein: {len(x)} samples are too few for emb_dim={emb_dim}, lag={lag}, "
            f"trajectory_len={trajectory_len} and min_tsep={min_tsep}: at least {needed} are "
            f"needed, (emb_dim - 1) * lag + trajectory_len + 2 * min_tsep + "
            f"{MIN_REFERENCE_POINTS} reference points"
        )

    points = delay_embed(x, emb_dim, lag)
    n_ref = len(points) - trajectory_len
    neighbour, _ = nearest_neighbours(points[:n_ref], min_tsep, neighbours)
    ref = np.nonzero(neighbour[:, -1] >= 0)[0]
    neighbour = neighbour[ref]
    floor = DISTANCE_FLOOR * np.std(x)

    blocks = np.array_split(np.arange(len(ref)), N_BLOCKS)
    block_sizes = np.array([len(block) for block in blocks])
    block_sums = np.column_stack(
        [
            _divergence_sum(x, ref[block], neighbour[block], emb_dim, lag, trajectory_len, floor)
            for block in blocks
        ]
    )
    divergence = block_sums.sum(axis=1) / len(ref)
    block_curves = block_sums / block_sizes
    saturation = _saturation_level(points, floor)
    time = np.arange(trajectory_len) * dt
    common = dict(
        time=time,
        divergence=divergence,
        emb_dim=int(emb_dim),
        lag=int(lag),
        min_tsep=int(min_tsep),
        trajectory_len=int(trajectory_len),
        saturation=saturation,
    )

    if fit_range is None:
        fit_range, reason = _automatic_fit_range(divergence, saturation, window_first, window_last)
        if fit_range is None:
            return RosensteinResult(
                exponent=np.nan,
                stderr=np.nan,
                fit_range=None,
                intercept=np.nan,
                fitted=False,
                reason=f"rosenstein: {reason}",
                **common,
            )
    first, last = int(fit_range[0]), int(fit_range[1])
    fitted = slice(first, last + 1)
    slope, intercept = _line_fit(time[fitted], divergence[fitted])
    block_slopes, _ = _line_fit(time[fitted], block_curves[fitted])
    block_error = np.std(block_slopes, ddof=1) / np.sqrt(N_BLOCKS)
    # growth that the curve gives back before saturation is not divergence (quasi-periodic
    # neighbours drift apart and together again)
    near = divergence[last:] >= saturation - SATURATION_MARGIN
    end = last + (int(np.argmax(near)) if near.any() else len(near))
    fall_back = divergence[last] - divergence[last : end + 1].min()
    return_error = fall_back / (time[last] - time[first])
    return RosensteinResult(
        exponent=float(slope),
        stderr=float(np.hypot(block_error, return_error)),
        fit_range=(first, last),
        intercept=float(intercept),
        fitted=True,
        reason="",
        **common,
    )

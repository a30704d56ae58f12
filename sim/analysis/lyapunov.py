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
        perturbed trajectory as they are.

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

    Returns:
        A :class:`BenettinResult` (exponent, stderr, convergence curve, parameters).
    """
    y_ref = np.array(y0, dtype=float)
    mask = np.ones(y_ref.shape, dtype=bool) if mask is None else np.asarray(mask, dtype=bool)
    distance = distance or _masked_distance(mask)
    perturb = perturb or _direction_perturbation(mask)
    rescale = rescale or _radial_rescale(mask, distance)

    y_pert = perturb(y_ref, d0)
    t = t0
    log_stretch = np.empty(n_intervals)
    for k in range(-transient_intervals, n_intervals):
        # measured rather than assumed d0, so a non-homogeneous distance stays correct
        d_start = distance(y_ref, y_pert)
        y_ref, y_pert = advance(y_ref, t, interval), advance(y_pert, t, interval)
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
        exponent: slope of the mean log divergence over ``fit_range`` (1 / time unit of dt).
        stderr: standard error of the exponent from the spread of the slopes of ``N_BLOCKS``
            sub-series (consecutive blocks of reference points), std / sqrt(N_BLOCKS).
        time: divergence time of every point of ``divergence`` (k · dt).
        divergence: mean over reference points of ln(distance to the neighbour) after k steps.
        fit_range: (first, last) index into ``divergence`` of the fitted points, inclusive.
        intercept: intercept of the fitted line (for plotting it over ``divergence``).
        emb_dim: embedding dimension used.
        lag: embedding delay used (samples).
        min_tsep: Theiler window used (samples).
        trajectory_len: number of divergence steps followed (samples).
    """

    exponent: float
    stderr: float
    time: np.ndarray
    divergence: np.ndarray
    fit_range: tuple[int, int]
    intercept: float
    emb_dim: int
    lag: int
    min_tsep: int
    trajectory_len: int


#: default fit range of :func:`rosenstein`: the part of the divergence curve between these
#: fractions of its rise from the initial level to the saturation level
FIT_LEVELS = (0.25, 0.65)
#: neighbour distances below this fraction of the series' standard deviation are rounding
#: noise (exact recurrences of periodic data), not dynamics; they are raised to it
DISTANCE_FLOOR = 1e-12


def _log_distances(points: np.ndarray, i: np.ndarray, j: np.ndarray, floor: float) -> np.ndarray:
    return np.log(np.maximum(np.linalg.norm(points[i] - points[j], axis=1), floor))


def _automatic_fit_range(divergence: np.ndarray, saturation: float) -> tuple[int, int]:
    start, rise = divergence[0], saturation - divergence[0]
    low = divergence >= start + FIT_LEVELS[0] * rise
    high = divergence >= start + FIT_LEVELS[1] * rise
    # a curve that never rises (regular motion) is fitted whole; one that never reaches the
    # upper level (trajectory_len too short) is fitted to its end
    first = int(np.argmax(low)) if low.any() else 0
    last = int(np.argmax(high)) if high.any() else len(divergence) - 1
    return first, max(last, first + 2)


def rosenstein(
    x: np.ndarray,
    dt: float,
    *,
    emb_dim: int | None = None,
    lag: int | None = None,
    min_tsep: int | None = None,
    trajectory_len: int | None = None,
    fit_range: tuple[int, int] | None = None,
) -> RosensteinResult:
    """Largest Lyapunov exponent of a scalar time series (Rosenstein et al. 1993).

    Explanation of the method:
        The series is delay-embedded (m = ``emb_dim`` coordinates ``lag`` samples apart). For
        every embedded point the nearest neighbour that is more than ``min_tsep`` samples away
        in time is found (k-d tree), and both are followed for ``trajectory_len`` steps. The
        mean over all pairs of ln(distance) after k steps grows like λ · k · dt while the
        separation is small, then saturates at the size of the attractor. λ is the slope of a
        straight line fitted to the linear part, divided by nothing more: the time axis is
        k · dt, so the exponent is per unit of dt (1/s), not per sample.

    Choosing the parameters:
        lag: default, the first minimum of the mutual information
            (:func:`sim.analysis.embedding.embedding_lag`).
        emb_dim: default, false nearest neighbours below 1 %
            (:func:`sim.analysis.embedding.embedding_dimension`).
        min_tsep: default, the mean period of the series (reciprocal of the power-weighted mean
            frequency), as Rosenstein et al. recommend; smaller values let points on the same
            stretch of trajectory pose as neighbours and bias λ low.
        trajectory_len: default four mean periods, enough for the curve to saturate for
            exponents above ~1 / (mean period); increase it for weak chaos.
        fit_range: (first, last) indices of the divergence curve fitted, inclusive. Default:
            from where the curve has covered 25 % of its rise to 65 % of it, the rise running
            from its initial value to the saturation level (the mean log distance between
            embedded points half a series apart, i.e. unrelated points). This skips the
            initial alignment transient and the bend into saturation. A curve that never
            reaches 25 % (regular motion) is fitted whole. Always look at the curve.

    Uncertainty:
        ``stderr`` is the spread of the exponent across sub-series: the reference points are
        split into ``N_BLOCKS`` consecutive blocks, each block's divergence curve is fitted over
        the same range, and the standard error is std(slopes) / sqrt(N_BLOCKS). (The standard
        error of the regression slope is not used: the points of one divergence curve are
        strongly correlated, so it would be far too small.)

    Minimum data length:
        About 10^(emb_dim) points and several hundred mean periods for ±15 %; Rosenstein et
        al. report usable results from 1000 points of the Lorenz system. The series must be
        longer than (emb_dim − 1) · lag + trajectory_len + 2 · min_tsep.

    References:
        M. T. Rosenstein, J. J. Collins, C. J. De Luca, "A practical method for calculating
        largest Lyapunov exponents from small data sets", Physica D 65 (1993) 117–134.

    Args:
        x: 1-D series sampled every ``dt``.
        dt: sampling interval (s).
        emb_dim: embedding dimension.
        lag: embedding delay (samples).
        min_tsep: Theiler window (samples).
        trajectory_len: number of divergence steps.
        fit_range: indices of the fitted part of the divergence curve.

    Returns:
        A :class:`RosensteinResult`.
    """
    x = np.asarray(x, dtype=float)
    if x.ndim != 1 or not np.all(np.isfinite(x)):
        raise ValueError("rosenstein: x must be a 1-D array of finite values")
    period = mean_period(x)
    min_tsep = round(period) if min_tsep is None else min_tsep
    lag = embedding_lag(x) if lag is None else lag
    emb_dim = embedding_dimension(x, lag, min_tsep=min_tsep) if emb_dim is None else emb_dim
    trajectory_len = round(4 * period) if trajectory_len is None else trajectory_len

    points = delay_embed(x, emb_dim, lag)
    n_ref = len(points) - trajectory_len
    if n_ref <= 2 * min_tsep + N_BLOCKS:
        raise ValueError(
            f"rosenstein: {len(x)} samples are too few for emb_dim={emb_dim}, lag={lag}, "
            f"trajectory_len={trajectory_len} and min_tsep={min_tsep}"
        )
    neighbour, _ = nearest_neighbours(points[:n_ref], min_tsep)
    ref = np.nonzero(neighbour >= 0)[0]
    neighbour = neighbour[ref]
    floor = DISTANCE_FLOOR * np.std(x)

    # per-block sums rather than the full (trajectory_len × pairs) matrix, to bound memory
    block_starts = np.array([block[0] for block in np.array_split(np.arange(len(ref)), N_BLOCKS)])
    block_sizes = np.diff(np.append(block_starts, len(ref)))
    block_sums = np.empty((trajectory_len, N_BLOCKS))
    for k in range(trajectory_len):
        log_d = _log_distances(points, ref + k, neighbour + k, floor)
        block_sums[k] = np.add.reduceat(log_d, block_starts)
    divergence = block_sums.sum(axis=1) / len(ref)
    block_curves = block_sums / block_sizes

    if fit_range is None:
        unrelated = (np.arange(len(points)) + len(points) // 2) % len(points)
        saturation = _log_distances(points, np.arange(len(points)), unrelated, floor).mean()
        fit_range = _automatic_fit_range(divergence, saturation)
    first, last = fit_range
    time = np.arange(trajectory_len) * dt
    fitted = slice(first, last + 1)
    slope, intercept = np.polyfit(time[fitted], divergence[fitted], 1)
    block_slopes = np.polyfit(time[fitted], block_curves[fitted], 1)[0]
    return RosensteinResult(
        exponent=float(slope),
        stderr=float(np.std(block_slopes, ddof=1) / np.sqrt(N_BLOCKS)),
        time=time,
        divergence=divergence,
        fit_range=(int(first), int(last)),
        intercept=float(intercept),
        emb_dim=int(emb_dim),
        lag=int(lag),
        min_tsep=int(min_tsep),
        trajectory_len=int(trajectory_len),
    )

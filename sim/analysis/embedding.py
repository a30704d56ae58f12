"""Delay-embedding parameters of a scalar time series.

A scalar series x(t) is turned into vectors (x(t), x(t + τ), …, x(t + (m − 1)τ)) that stand in
for the unobserved state (Takens 1981). This module chooses the delay τ (``lag``), the dimension
m (``emb_dim``) and the Theiler window that keeps temporally close samples from being taken as
neighbours. All choices are deterministic.
"""

import numpy as np
from scipy.signal import find_peaks
from scipy.spatial import cKDTree

#: smallest depth of a mutual-information minimum, as a fraction of I(0), for embedding_lag
MIN_PROMINENCE = 0.01


def delay_embed(x: np.ndarray, emb_dim: int, lag: int) -> np.ndarray:
    """Delay vectors of a scalar series.

    Args:
        x: 1-D series.
        emb_dim: embedding dimension m ≥ 1.
        lag: delay τ in samples, ≥ 1.

    Returns:
        Array of shape (len(x) − (m − 1)τ, m); row i is (x[i], x[i + τ], …, x[i + (m − 1)τ]).
    """
    x = np.asarray(x, dtype=float)
    n_vectors = len(x) - (emb_dim - 1) * lag
    if emb_dim < 1 or lag < 1 or n_vectors < 1:
        raise ValueError(
            f"cannot embed {len(x)} samples with emb_dim={emb_dim} and lag={lag}: "
            f"at least (emb_dim - 1) * lag + 1 samples are needed"
        )
    return np.stack([x[k * lag : k * lag + n_vectors] for k in range(emb_dim)], axis=1)


def mean_period(x: np.ndarray) -> float:
    """Mean period of a series in samples: the reciprocal of the power-weighted mean frequency.

    Rosenstein et al. (1993) use this as the Theiler window: neighbours closer in time than one
    mean period lie on the same stretch of trajectory and would bias the divergence low. The
    zero-frequency (mean) term is left out.

    Args:
        x: 1-D series, at least 4 samples.

    Returns:
        Mean period in samples (a float ≥ 2, the Nyquist limit).

    References:
        M. T. Rosenstein, J. J. Collins, C. J. De Luca, "A practical method for calculating
        largest Lyapunov exponents from small data sets", Physica D 65 (1993) 117–134.
    """
    x = np.asarray(x, dtype=float)
    power = np.abs(np.fft.rfft(x - x.mean())) ** 2
    freq = np.fft.rfftfreq(len(x))
    total = power[1:].sum()
    if total == 0.0:
        raise ValueError("mean_period: the series is constant, it has no period")
    return float(1.0 / (np.sum(freq[1:] * power[1:]) / total))


def mutual_information(x: np.ndarray, max_lag: int, n_bins: int | None = None) -> np.ndarray:
    """Average mutual information I(x(t); x(t + k)) for k = 0 … max_lag, in nats.

    The estimate uses a histogram with equiprobable marginal bins (ranks), so it does not depend
    on the amplitude distribution of the series and needs no smoothing parameter besides the
    number of bins. Only the location of the first minimum is used downstream, which is robust
    to the estimator's bias.

    Args:
        x: 1-D series.
        max_lag: largest delay in samples.
        n_bins: number of bins per axis; default sqrt(N / 5) clipped to [4, 64], so that the
            joint histogram holds about five samples per cell.

    Returns:
        Array of length max_lag + 1.

    References:
        A. M. Fraser, H. L. Swinney, "Independent coordinates for strange attractors from mutual
        information", Physical Review A 33 (1986) 1134–1140.
    """
    x = np.asarray(x, dtype=float)
    if n_bins is None:
        n_bins = int(np.clip(np.sqrt(len(x) / 5), 4, 64))
    # ranks make the marginals uniform: every bin holds ~N/n_bins samples
    symbols = (np.argsort(np.argsort(x, kind="stable"), kind="stable") * n_bins) // len(x)
    ami = np.empty(max_lag + 1)
    for k in range(max_lag + 1):
        a, b = symbols[: len(x) - k], symbols[k:]
        joint = np.bincount(a * n_bins + b, minlength=n_bins * n_bins).reshape(n_bins, n_bins)
        p_ab = joint / joint.sum()
        p_a, p_b = p_ab.sum(axis=1), p_ab.sum(axis=0)
        nonzero = p_ab > 0
        ami[k] = np.sum(p_ab[nonzero] * np.log(p_ab[nonzero] / np.outer(p_a, p_b)[nonzero]))
    return ami


def autocorrelation(x: np.ndarray, max_lag: int) -> np.ndarray:
    """Normalised autocorrelation for lags 0 … max_lag (biased estimator, FFT based)."""
    x = np.asarray(x, dtype=float)
    centred = x - x.mean()
    spectrum = np.fft.rfft(centred, n=2 * len(x))
    acf = np.fft.irfft(np.abs(spectrum) ** 2)[: max_lag + 1]
    return acf / acf[0]


def embedding_lag(x: np.ndarray, max_lag: int | None = None) -> int:
    """Delay τ in samples: the first minimum of the average mutual information.

    Fraser and Swinney (1986) take the first minimum of the mutual information between x(t) and
    x(t + τ) as the delay that makes the coordinates as independent as possible without being
    unrelated. Minima shallower than ``MIN_PROMINENCE`` (1 %) of I(0) are binning jitter and are
    skipped. When there is no minimum up to ``max_lag`` (a strictly periodic signal keeps a high
    mutual information at every lag; a strongly oversampled one decays slowly), the first lag
    at which the autocorrelation falls below 1/e is used instead; if neither exists, a
    ValueError is raised.

    Args:
        x: 1-D series; a few hundred samples at least, and several of the slowest oscillations.
        max_lag: largest delay considered, default a quarter of the series length.

    Returns:
        The delay in samples (≥ 1).

    References:
        A. M. Fraser, H. L. Swinney, Physical Review A 33 (1986) 1134–1140.
    """
    x = np.asarray(x, dtype=float)
    if max_lag is None:
        max_lag = len(x) // 4
    ami = mutual_information(x, max_lag)
    # the histogram estimate of a smooth deterministic signal jitters from lag to lag by a
    # few per cent of the entropy; a minimum must stand out by 1 % of I(0) to count
    minima, _ = find_peaks(-ami, prominence=MIN_PROMINENCE * ami[0])
    if minima.size:
        return int(minima[0])
    below = autocorrelation(x, max_lag) < np.exp(-1.0)
    if below.any():
        return int(np.argmax(below))
    raise ValueError(
        f"embedding_lag: neither a mutual-information minimum nor an autocorrelation below 1/e "
        f"within {max_lag} samples; pass lag explicitly or give a longer series"
    )


def nearest_neighbours(
    points: np.ndarray, min_tsep: int, count: int = 1
) -> tuple[np.ndarray, np.ndarray]:
    """The ``count`` nearest neighbours of every point among points at least ``min_tsep + 1``
    indices away, nearest first.

    Uses a k-d tree and asks for more candidates only for the points whose closest candidates
    are mostly temporal neighbours, so the cost stays near one query of 8 · ``count``.

    Args:
        points: array (n, m) of delay vectors in time order.
        min_tsep: Theiler window in samples; |i − j| ≤ min_tsep is excluded (and so is i itself).
        count: neighbours wanted per point.

    Returns:
        (index, distance) arrays of shape (n, count); index −1 and distance inf where fewer
        than ``count`` admissible neighbours exist.
    """
    n = len(points)
    tree = cKDTree(points)
    index = np.full((n, count), -1)
    distance = np.full((n, count), np.inf)
    pending = np.arange(n)
    k = 8 * count
    while pending.size:
        k = min(k, n)
        dist, idx = tree.query(points[pending], k=k)
        dist, idx = dist.reshape(len(pending), k), idx.reshape(len(pending), k)
        admissible = np.abs(idx - pending[:, None]) > min_tsep
        # query results are sorted by distance: the first `count` admissible ones are nearest
        taken = admissible & (np.cumsum(admissible, axis=1) <= count)
        found = taken.sum(axis=1) == count
        rows = np.nonzero(found)[0]
        index[pending[rows]] = idx[rows][taken[rows]].reshape(-1, count)
        distance[pending[rows]] = dist[rows][taken[rows]].reshape(-1, count)
        pending = pending[~found]
        if k == n:
            break
        k *= 4
    return index, distance


def false_nearest_neighbours(
    x: np.ndarray,
    lag: int,
    max_dim: int,
    *,
    min_tsep: int = 0,
    rtol: float = 10.0,
    atol: float = 2.0,
    stop_below: float | None = None,
) -> np.ndarray:
    """Fraction of false nearest neighbours for embedding dimensions 1 … max_dim.

    A neighbour in dimension m is false when adding the (m + 1)-th coordinate separates it
    by more than ``rtol`` times its distance in m dimensions, or by more than ``atol`` times the
    standard deviation of the series (Kennel et al. 1992, criteria 1 and 2). The fraction drops
    to about zero once the attractor is unfolded.

    Args:
        x: 1-D series; the embedding needs well over 10^m samples for dimension m.
        lag: delay in samples.
        max_dim: largest dimension tested.
        min_tsep: Theiler window in samples: temporally close samples are not taken as
            neighbours (they would almost never be false and hide the unfolding).
        rtol: threshold of criterion 1 (Kennel et al.: 10 to 15).
        atol: threshold of criterion 2 (Kennel et al.: 2).
        stop_below: if given, stop after the first dimension whose fraction is below it
            (the higher dimensions' neighbour searches cost the most); later entries are NaN.

    Returns:
        Array of length max_dim; entry m − 1 is the fraction for dimension m.

    References:
        M. B. Kennel, R. Brown, H. D. I. Abarbanel, "Determining embedding dimension for
        phase-space reconstruction using a geometrical construction", Physical Review A 45
        (1992) 3403–3411.
    """
    x = np.asarray(x, dtype=float)
    size = np.std(x)
    fractions = np.full(max_dim, np.nan)
    for dim in range(1, max_dim + 1):
        # the extra coordinate x[i + dim * lag] must exist for every vector
        points = delay_embed(x[: len(x) - lag], dim, lag)
        index, distance = nearest_neighbours(points, min_tsep)
        index, distance = index[:, 0], distance[:, 0]
        valid = (index >= 0) & (distance > 0)
        i, j = np.nonzero(valid)[0], index[valid]
        extra = np.abs(x[i + dim * lag] - x[j + dim * lag])
        grown = np.sqrt(distance[valid] ** 2 + extra**2)
        false = (extra > rtol * distance[valid]) | (grown > atol * size)
        fractions[dim - 1] = false.mean() if false.size else np.nan
        if stop_below is not None and fractions[dim - 1] < stop_below:
            break
    return fractions


def embedding_dimension(
    x: np.ndarray,
    lag: int,
    *,
    min_tsep: int = 0,
    max_dim: int = 10,
    threshold: float = 0.01,
) -> int:
    """Embedding dimension: the smallest m whose false-nearest-neighbour fraction < threshold.

    If no dimension up to ``max_dim`` reaches the threshold (noise or too short a series), the
    dimension with the smallest fraction is returned.

    Args:
        x: 1-D series.
        lag: delay in samples (see :func:`embedding_lag`).
        min_tsep: Theiler window in samples (see :func:`false_nearest_neighbours`).
        max_dim: largest dimension tested.
        threshold: acceptable fraction of false neighbours (Kennel et al. 1992 report values
            falling to ~0; 1 % tolerates a little noise).

    Returns:
        The embedding dimension.

    References:
        M. B. Kennel, R. Brown, H. D. I. Abarbanel, Physical Review A 45 (1992) 3403–3411.
    """
    fractions = false_nearest_neighbours(x, lag, max_dim, min_tsep=min_tsep, stop_below=threshold)
    below = fractions < threshold
    if below.any():
        return int(np.argmax(below)) + 1
    if np.isnan(fractions).all():
        # No neighbour at a non-zero distance in any dimension: the series repeats
        # exactly (to its stored precision). A closed orbit needs two dimensions to
        # unfold; one would make its two branches through each value neighbours.
        return 2
    return int(np.nanargmin(fractions)) + 1

"""The 0–1 test for chaos (Gottwald and Melbourne), correlation method."""

from dataclasses import dataclass

import numpy as np

#: seed of the random frequencies c; fixed so that the test is reproducible
FREQUENCY_SEED = 20_090_129
#: interval the frequencies are drawn from: away from the resonances at c = 0 and c = π
FREQUENCY_RANGE = (np.pi / 5, 4 * np.pi / 5)


@dataclass(frozen=True, eq=False)
class ZeroOneResult:
    """Outcome of the 0–1 test.

    Attributes:
        K: median over the frequencies of the correlation K_c (≈ 0 regular, ≈ 1 chaotic).
        spread: interquartile range of K_c over the frequencies.
        K_c: the correlation for every frequency.
        c: the frequencies.
        n_cut: largest displacement lag used.
    """

    K: float
    spread: float
    K_c: np.ndarray
    c: np.ndarray
    n_cut: int


def _mean_square_displacement(walk: np.ndarray, n_cut: int) -> np.ndarray:
    """M(n) = mean_j |z(j + n) − z(j)|² for n = 1 … n_cut, one row per frequency.

    The cross term Σ z(j + n) conj(z(j)) is a correlation, computed for all n at once by FFT.
    """
    n_c, length = walk.shape
    power = np.abs(walk) ** 2
    cumulative = np.concatenate([np.zeros((n_c, 1)), np.cumsum(power, axis=1)], axis=1)
    spectrum = np.fft.fft(walk, n=2 * length, axis=1)
    cross = np.fft.ifft(np.abs(spectrum) ** 2, axis=1)[:, 1 : n_cut + 1].real
    lags = np.arange(1, n_cut + 1)
    count = length - lags
    # Σ_{j < N−n} |z(j + n)|² and Σ_{j < N−n} |z(j)|² from the running sums
    later = cumulative[:, -1:] - cumulative[:, lags]
    earlier = cumulative[:, count]
    return (later + earlier - 2.0 * cross) / count


def zero_one_test(
    phi: np.ndarray,
    *,
    n_c: int = 100,
    n_cut: int | None = None,
    noise_floor: float = 0.0,
) -> ZeroOneResult:
    """The 0–1 test for chaos: K ≈ 0 for regular dynamics, K ≈ 1 for chaotic dynamics.

    Explanation of the method:
        The observable φ(j) drives a walk in the plane, p_c(n) + i q_c(n) = Σ_{j ≤ n} φ(j)
        e^{ijc}. For regular (periodic or quasi-periodic) dynamics the walk stays bounded; for
        chaotic dynamics it diffuses, its mean square displacement M_c(n) growing linearly in n.
        The test uses the modified (regularised) mean square displacement
        D_c(n) = M_c(n) − (E φ)² (1 − cos nc) / (1 − cos c), which removes the bounded
        oscillation that the mean of φ adds and would otherwise mask the growth. Here the mean
        is removed from φ before the walk is formed, which makes the correction term zero and
        avoids the cancellation between two large numbers that the subtraction suffers when
        |E φ| is much larger than the fluctuations (section points of an eccentricity that
        hovers near the clearance). The test then takes
        K_c = corr(n, D_c(n)) over n = 1 … n_cut (the correlation method of Gottwald and
        Melbourne 2009, more robust than a log-log regression). K is the median of K_c over
        ``n_c`` frequencies c drawn uniformly from (π/5, 4π/5) with ``FREQUENCY_SEED``; the
        median discards the few c that resonate with a period of the data.

    Choosing the parameters:
        phi: samples of a map, or of a flow on a Poincaré section or sampled at about the
            decorrelation time: an oversampled flow looks regular to the test.
        n_c: 100 frequencies, as recommended; fewer make K noisier.
        n_cut: lags of the mean square displacement, default N / 10 as recommended.
        noise_floor: fluctuations of φ whose standard deviation is at most this (same units
            as φ) are taken as numerical noise around a constant, and the test returns K = 0:
            the test alone would call rounding noise chaotic (noise diffuses too).

    Minimum data length:
        Several hundred samples; Gottwald and Melbourne use 1000 to 10000. K approaches 0 or 1
        as N grows.

    References:
        G. A. Gottwald, I. Melbourne, "A new test for chaos in deterministic systems",
        Proceedings of the Royal Society A 460 (2004) 603–611.
        G. A. Gottwald, I. Melbourne, "On the implementation of the 0–1 test for chaos", SIAM
        Journal on Applied Dynamical Systems 8 (2009) 129–145.

    Args:
        phi: 1-D series of the observable.
        n_c: number of frequencies.
        n_cut: largest displacement lag.
        noise_floor: see above.

    Returns:
        A :class:`ZeroOneResult` with K, its interquartile spread and the per-frequency K_c.
    """
    phi = np.asarray(phi, dtype=float)
    if phi.ndim != 1 or len(phi) < 20 or not np.all(np.isfinite(phi)):
        raise ValueError("zero_one_test: phi must be a 1-D array of at least 20 finite values")
    n_cut = len(phi) // 10 if n_cut is None else n_cut
    c = np.random.default_rng(FREQUENCY_SEED).uniform(*FREQUENCY_RANGE, size=n_c)
    if np.std(phi) <= noise_floor:
        return ZeroOneResult(K=0.0, spread=0.0, K_c=np.zeros(n_c), c=c, n_cut=n_cut)

    j = np.arange(1, len(phi) + 1)
    # centring removes the mean's oscillation exactly (V_osc with E φ = 0); subtracting V_osc
    # from M_c of the raw data instead loses the growth to cancellation when |E φ| ≫ std φ
    walk = np.cumsum((phi - phi.mean()) * np.exp(1j * np.outer(c, j)), axis=1)
    lags = np.arange(1, n_cut + 1)
    displacement = _mean_square_displacement(walk, n_cut)
    K_c = np.array([np.corrcoef(lags, row)[0, 1] for row in displacement])
    q25, median, q75 = np.percentile(K_c, [25, 50, 75])
    return ZeroOneResult(K=float(median), spread=float(q75 - q25), K_c=K_c, c=c, n_cut=n_cut)

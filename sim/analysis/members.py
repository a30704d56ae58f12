"""Summaries of one quantity over the members of an ensemble (sim/ensemble.py).

An ensemble has few members (3–4): too few for a bootstrap of the median to mean much (it
resamples four numbers). The interval here is distribution-free instead: the order statistics
x₍k₎ ≤ x₍n+1−k₎ of n independent draws enclose the population median with probability
1 − 2 · P(Bin(n, ½) ≤ k − 1), whatever the distribution (continuous), because each draw falls
below the median with probability ½. The narrowest such interval reaching the asked level is
taken; with too few members for that (n = 4 reaches 87.5 % at most, with the range), the range
is given with the coverage it has, and the table says so.

References:
    W. J. Conover, "Practical Nonparametric Statistics", 3rd ed., Wiley (1999), section 3.2
    (confidence interval for a quantile).
    H. A. David, H. N. Nagaraja, "Order Statistics", 3rd ed., Wiley (2003), section 7.1.
"""

from dataclasses import dataclass
from math import comb

import numpy as np


@dataclass(frozen=True)
class MedianInterval:
    """The median of n members and a distribution-free interval for the population median.

    Attributes:
        n: members.
        median: their median (units of the values).
        low, high: the interval's ends, order statistics of the values (the value itself
            for n = 1).
        coverage: probability that [low, high] holds the population median (0 for n = 1).
    """

    n: int
    median: float
    low: float
    high: float
    coverage: float


def order_statistic_coverage(n: int, k: int) -> float:
    """Probability that the k-th smallest and k-th largest of n independent draws of a
    continuous distribution enclose its median: 1 − 2 · P(Bin(n, ½) ≤ k − 1)."""
    if not 1 <= k <= n // 2:
        raise ValueError(f"k = {k} must lie in [1, {n // 2}] for n = {n}")
    return 1.0 - 2.0 * sum(comb(n, i) for i in range(k)) / 2.0**n


def median_interval(values: np.ndarray, level: float = 0.95) -> MedianInterval:
    """Median of ``values`` (one per member; NaN not allowed) and the narrowest interval
    x₍k₎ … x₍n+1−k₎ whose coverage of the population median is at least ``level``; the range
    (k = 1) with its own, lower coverage when no k reaches ``level``."""
    x = np.sort(np.asarray(values, dtype=float))
    if x.size == 0 or not np.all(np.isfinite(x)):
        raise ValueError(f"median_interval needs finite values, got {x.tolist()}")
    if not 0.0 < level < 1.0:
        raise ValueError(f"level = {level} must lie in (0, 1)")
    n = x.size
    median = float(np.median(x))
    if n == 1:
        return MedianInterval(1, median, median, median, 0.0)
    k = 1
    while k + 1 <= n // 2 and order_statistic_coverage(n, k + 1) >= level:
        k += 1
    return MedianInterval(
        n, median, float(x[k - 1]), float(x[n - k]), order_statistic_coverage(n, k)
    )

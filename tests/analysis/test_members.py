"""The distribution-free interval for a median over ensemble members (sim.analysis.members)."""

import numpy as np
import pytest
from scipy.stats import binom

from sim.analysis.members import median_interval, order_statistic_coverage


@pytest.mark.parametrize("n", [2, 3, 4, 7, 20, 51])
def test_coverage_is_the_binomial_closed_form(n):
    """1 − 2 · P(Bin(n, ½) ≤ k − 1), against scipy's binomial distribution; the range of four
    members encloses the median with 1 − 2/16 = 87.5 %."""
    for k in range(1, n // 2 + 1):
        assert order_statistic_coverage(n, k) == pytest.approx(1 - 2 * binom.cdf(k - 1, n, 0.5))
    if n == 4:
        assert order_statistic_coverage(4, 1) == 0.875


def test_interval_covers_the_median_of_a_known_distribution_as_stated():
    """Draws of a skewed distribution (exponential, median ln 2): over 4000 seeded ensembles
    the share of intervals holding ln 2 matches the stated coverage within 4 binomial standard
    errors (a wrong k or an off-by-one order statistic moves it by ≥ 7 points for n = 20)."""
    rng = np.random.default_rng(7)
    trials = 4000
    for n in (4, 20):
        hits, stated = 0, None
        for _ in range(trials):
            interval = median_interval(rng.exponential(size=n), level=0.95)
            stated = interval.coverage
            hits += interval.low <= np.log(2) <= interval.high
        margin = 4 * np.sqrt(stated * (1 - stated) / trials)
        assert abs(hits / trials - stated) < margin


def test_narrowest_interval_reaching_the_level():
    """n = 20 at 95 %: k = 6 (coverage 95.9 %; k = 7 gives 88.5 %); four members cannot reach
    95 %, so the range with its 87.5 %; one member, the value with no coverage."""
    values = np.arange(20.0)[::-1]
    interval = median_interval(values, level=0.95)
    assert (interval.low, interval.high, interval.median) == (5.0, 14.0, 9.5)
    assert interval.coverage == pytest.approx(1 - 2 * binom.cdf(5, 20, 0.5))
    four = median_interval([3.0, 1.0, 4.0, 2.0])
    assert (four.low, four.high, four.median, four.coverage) == (1.0, 4.0, 2.5, 0.875)
    one = median_interval([5.0])
    assert (one.n, one.low, one.high, one.coverage) == (1, 5.0, 5.0, 0.0)


def test_bad_input_is_named():
    with pytest.raises(ValueError, match="finite values"):
        median_interval([1.0, np.nan])
    with pytest.raises(ValueError, match="level"):
        median_interval([1.0, 2.0], level=1.5)

"""Time-series exponent (Rosenstein) and its embedding choices against published values."""

import numpy as np
import pytest
from conftest import (
    DUFFING_DT,
    DUFFING_EXPONENT,
    LORENZ_DT,
    LORENZ_EXPONENT,
    N_STRETCHES,
    ROSSLER_DT,
    ROSSLER_EXPONENT,
)

from sim.analysis import lyapunov
from sim.analysis.embedding import (
    delay_embed,
    embedding_dimension,
    embedding_lag,
    false_nearest_neighbours,
    mean_period,
)
from sim.analysis.lyapunov import MIN_FIT_POINTS, rosenstein

# a RankWarning (a degenerate fit) or any other warning fails the test
pytestmark = pytest.mark.filterwarnings("error")

#: An exponent counts as positive above this many standard errors, as in
#: sim.analysis.classify (SIGNIFICANCE)
SIGNIFICANCE = 2.0

# What is asserted, and why: a stretch of finite length has its own exponent (the mean
# stretching rate along that very piece of orbit), which scatters around the published,
# infinite-time value whatever the estimator. Integrating the tangent dynamics along five
# stretches gave, relative to the published value: Rössler at 500 time units -11 % … +23 %, at
# 200 -20 % … +17 %; Duffing at 300 forcing periods -10 % … +4 %, at 100 -28 % … +7 %; Lorenz
# at 100 time units -4 % … +4 %. So no estimator puts every stretch within 15 % of the
# published value at these lengths; the median over the stretches is asserted within 15 % (but
# for the shortest Rössler series, see its case), and every single stretch within a wider band.
# The bands are the worst relative errors of rosenstein (two neighbours) measured over 20
# stretches per case (four seeds) plus a margin, since another machine's rounding gives other
# stretches; the measured worst is noted per case.
#
# (fixture key, sampling step, published exponent, length in samples, tolerance of the median,
# band for every stretch, whether every stretch is significantly positive)
CASES = [
    # 50 and 100 time units (~30 and ~60 mean periods): worst +20 % and -11 % of 20
    ("lorenz", LORENZ_DT, LORENZ_EXPONENT, 5000, 0.15, 0.35, True),
    ("lorenz", LORENZ_DT, LORENZ_EXPONENT, 10_000, 0.15, 0.2, True),
    # 500 time units (~90 turns): median +9 %, standard deviation 10 %, worst +20 % of 20
    ("rossler", ROSSLER_DT, ROSSLER_EXPONENT, 5000, 0.15, 0.45, True),
    # 200 time units (~36 turns) is too short for 15 %: median +14 %, standard deviation 20 %
    # (worst -48 %) over 20 stretches, which stderr (~15 %) roughly reflects; the median of nine
    # is asserted within 30 % (the +14 % plus two standard deviations of a median of nine,
    # ~8 %), and the chaos is not always significant (down to 2.7 stderr)
    ("rossler", ROSSLER_DT, ROSSLER_EXPONENT, 2000, 0.3, 0.6, False),
    # 200 and 300 forcing periods: worst -26 % and -14 % of 20 (medians -3 % and -2 %); with a
    # single nearest neighbour instead of two the medians were -12 % and -15 % (see
    # "Neighbourhood" in rosenstein's docstring)
    ("duffing", DUFFING_DT, DUFFING_EXPONENT, 8000, 0.15, 0.36, True),
    ("duffing", DUFFING_DT, DUFFING_EXPONENT, 12_000, 0.15, 0.25, True),
]


@pytest.fixture(scope="session")
def published_cases(stretches) -> dict[tuple[str, int], list]:
    """rosenstein on every stretch of every case, computed once for the tests below."""
    return {
        (system, length): [rosenstein(x[:length], dt) for x in stretches[system]]
        for system, dt, _, length, *_ in CASES
    }


def _case_id(case: tuple) -> str:
    return f"{case[0]}-{case[3]}"


def test_lorenz_embedding_parameters(stretches):
    # Kennel et al. (1992, fig. 1): false neighbours vanish at dimension 3 for Lorenz x(t);
    # the mutual information of x(t) at step 0.01 has its first minimum near 0.16
    for x in stretches["lorenz"]:
        lag = embedding_lag(x)
        assert 12 <= lag <= 20
        assert embedding_dimension(x, lag, min_tsep=round(mean_period(x))) == 3


@pytest.mark.parametrize("case", CASES, ids=_case_id)
def test_published_exponent_over_stretches(published_cases, case):
    system, _, published, length, tolerance, band, _ = case
    results = published_cases[system, length]
    assert len(results) == N_STRETCHES[system]
    assert all(result.fitted for result in results), [result.reason for result in results]
    errors = np.array([result.exponent / published - 1 for result in results])
    assert abs(np.median(errors)) < tolerance, errors
    assert np.all(np.abs(errors) < band), errors


@pytest.mark.parametrize("case", CASES, ids=_case_id)
def test_chaos_is_significant_and_the_fit_range_proper(published_cases, case):
    system, _, _, length, _, _, significant = case
    for result in published_cases[system, length]:
        assert result.exponent > (SIGNIFICANCE if significant else 0.0) * result.stderr
        first, last = result.fit_range
        assert 0 <= first and last < result.trajectory_len == len(result.divergence)
        assert last - first + 1 >= MIN_FIT_POINTS


def test_longer_follow_up_keeps_the_estimate(stretches):
    # the fit window is fixed in mean periods after the neighbour search, so a longer follow-up
    # only costs reference points; it must not move the fit into the bend of the curve
    x = stretches["rossler"][0]
    default = rosenstein(x, ROSSLER_DT)
    longer = rosenstein(x, ROSSLER_DT, trajectory_len=3 * default.trajectory_len)
    assert longer.fit_range == default.fit_range
    assert abs(longer.exponent - default.exponent) < SIGNIFICANCE * default.stderr


@pytest.mark.parametrize("step", [0.01, 2 * np.pi / 50], ids=["incommensurate", "commensurate"])
def test_periodic_signal_is_not_positive(step):
    # two harmonics; with a period of 50 steps the orbit recurs exactly (neighbour distances
    # at the rounding floor), otherwise only nearly
    period = 1.37 * np.sqrt(2.0) if step == 0.01 else 2 * np.pi
    t = np.arange(5000) * step
    x = np.sin(2 * np.pi * t / period) + 0.3 * np.sin(4 * np.pi * t / period)
    result = rosenstein(x, step)
    assert result.fitted, result.reason
    assert result.exponent <= SIGNIFICANCE * result.stderr


@pytest.mark.parametrize("length", [2000, 5000])
def test_quasi_periodic_signal_is_not_positive(length):
    # two incommensurate frequencies (1 and sqrt 2): the divergence curve wobbles without
    # growing, and the slope of a wobble must stay within the uncertainty
    t = np.arange(length) * 0.05
    x = np.sin(t) + 0.6 * np.sin(np.sqrt(2.0) * t)
    result = rosenstein(x, 0.05)
    assert result.fitted, result.reason
    assert result.exponent <= SIGNIFICANCE * result.stderr


def test_noise_is_flagged_not_fitted():
    # white noise: the neighbours are no closer than unrelated points one step later, so
    # there is no linear region; the result says so rather than reading as regular
    x = np.random.default_rng(1).standard_normal(5000)
    result = rosenstein(x, 1.0)
    assert not result.fitted
    assert np.isnan(result.exponent) and np.isnan(result.stderr) and result.fit_range is None
    assert "saturation" in result.reason


def test_too_short_series_raises_with_the_length_needed(stretches):
    with pytest.raises(ValueError, match=r"at least \d+ are needed"):
        rosenstein(stretches["lorenz"][0][:400], LORENZ_DT)


def test_follow_up_shorter_than_the_window_raises(stretches):
    with pytest.raises(ValueError, match="trajectory_len=20 is shorter than the fit window"):
        rosenstein(stretches["rossler"][0], ROSSLER_DT, trajectory_len=20)


@pytest.mark.parametrize("fit_range", [(0, MIN_FIT_POINTS - 2), (50, 10), (100, 10**6)])
def test_degenerate_fit_range_raises(stretches, fit_range):
    with pytest.raises(ValueError, match="fit_range"):
        rosenstein(stretches["rossler"][0], ROSSLER_DT, fit_range=fit_range)


def test_given_fit_range_is_used(stretches):
    result = rosenstein(stretches["rossler"][0], ROSSLER_DT, fit_range=(10, 100))
    assert result.fitted and result.fit_range == (10, 100)
    fitted = slice(10, 101)
    slope = np.polyfit(result.time[fitted], result.divergence[fitted], 1)[0]
    assert result.exponent == pytest.approx(slope, rel=1e-9)


def test_deterministic(stretches):
    x = stretches["rossler"][1][:2000]
    first, second = rosenstein(x, ROSSLER_DT), rosenstein(x, ROSSLER_DT)
    assert (first.exponent, first.stderr, first.fit_range) == (
        second.exponent,
        second.stderr,
        second.fit_range,
    )
    np.testing.assert_array_equal(first.divergence, second.divergence)


def test_divergence_from_the_series_is_that_of_the_delay_vectors(stretches, monkeypatch):
    # ln of the mean distance between the delay vectors themselves, followed step by step,
    # against the sum formed from the series' squared differences (in several chunks)
    monkeypatch.setattr(lyapunov, "DIVERGENCE_CHUNK", 5000)
    x, emb_dim, lag, steps = stretches["lorenz"][0][:3000], 3, 15, 40
    points = delay_embed(x, emb_dim, lag)
    rng = np.random.default_rng(1)
    ref = rng.choice(len(points) - steps, 200, replace=False)
    neighbour = rng.integers(0, len(points) - steps, size=(200, 2))
    expected = [
        np.log(np.linalg.norm(points[ref + k, None] - points[neighbour + k], axis=-1).mean(1)).sum()
        for k in range(steps)
    ]
    got = lyapunov._divergence_sum(x, ref, neighbour, emb_dim, lag, steps, 1e-12)
    np.testing.assert_allclose(got, expected, rtol=1e-12)


def test_false_neighbours_stop_at_the_first_dimension_below_the_threshold(stretches):
    x = stretches["lorenz"][0]
    lag, min_tsep = embedding_lag(x), round(mean_period(x))
    every = false_nearest_neighbours(x, lag, 6, min_tsep=min_tsep)
    early = false_nearest_neighbours(x, lag, 6, min_tsep=min_tsep, stop_below=0.01)
    dim = int(np.argmax(every < 0.01)) + 1
    assert dim == 3  # Kennel et al. (1992): Lorenz unfolds in three dimensions
    np.testing.assert_array_equal(early[:dim], every[:dim])
    assert np.isnan(early[dim:]).all()

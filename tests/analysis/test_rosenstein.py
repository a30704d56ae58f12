"""Time-series exponent (Rosenstein) and its embedding choices against published values."""

import numpy as np
from conftest import LORENZ_EXPONENT

from sim.analysis.embedding import embedding_dimension, embedding_lag, mean_period
from sim.analysis.lyapunov import rosenstein


def test_lorenz_embedding_parameters(lorenz_x):
    # Kennel et al. (1992, fig. 1): false neighbours vanish at dimension 3 for Lorenz x(t);
    # the mutual information of x(t) at step 0.01 has its first minimum near 0.16
    lag = embedding_lag(lorenz_x)
    assert 12 <= lag <= 20
    assert embedding_dimension(lorenz_x, lag, min_tsep=round(mean_period(lorenz_x))) == 3


def test_lorenz_x_within_15_percent(lorenz_x):
    result = rosenstein(lorenz_x, 0.01)
    assert abs(result.exponent - LORENZ_EXPONENT) < 0.15 * LORENZ_EXPONENT
    first, last = result.fit_range
    assert 0 < first < last < result.trajectory_len


def test_periodic_signal_is_not_positive():
    # two harmonics with a period incommensurate with the sampling step
    t = np.arange(10_000) * 0.01
    period = 1.37 * np.sqrt(2.0)
    x = np.sin(2 * np.pi * t / period) + 0.3 * np.sin(4 * np.pi * t / period)
    result = rosenstein(x, 0.01)
    assert result.exponent <= result.stderr


def test_deterministic(lorenz_x):
    assert rosenstein(lorenz_x[:4000], 0.01).exponent == rosenstein(lorenz_x[:4000], 0.01).exponent

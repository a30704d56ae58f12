"""The 0–1 test for chaos on the logistic map (Gottwald and Melbourne 2004, figure 1)."""

import numpy as np

from sim.analysis.zero_one import zero_one_test


def logistic_orbit(r: float, n: int, x0: float = 0.1234, transient: int = 1000) -> np.ndarray:
    x = x0
    orbit = np.empty(n)
    for k in range(transient + n):
        x = r * x * (1.0 - x)
        if k >= transient:
            orbit[k - transient] = x
    return orbit


def test_chaotic_logistic_map_gives_one():
    assert zero_one_test(logistic_orbit(4.0, 2000)).K > 0.8


def test_periodic_logistic_map_gives_zero():
    assert abs(zero_one_test(logistic_orbit(3.5, 2000)).K) < 0.2


def test_constant_within_noise_floor_is_regular():
    phi = 1.0 + 1e-12 * np.random.default_rng(0).standard_normal(500)
    assert zero_one_test(phi).K > 0.8  # the bare test calls rounding noise chaotic
    assert zero_one_test(phi, noise_floor=1e-9).K == 0.0

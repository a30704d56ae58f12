"""Model-based exponents (Benettin) and map exponents against published values."""

import numpy as np
from conftest import LORENZ_EXPONENT, lorenz_advance

from sim.analysis.lyapunov import benettin, map_lyapunov, rhs_propagator


def lorenz_exponent(interval: float, d0: float):
    return benettin(
        lorenz_advance,
        np.array([1.0, 1.0, 1.0]),
        0.0,
        interval=interval,
        n_intervals=round(4000 / interval),
        d0=d0,
        transient_intervals=round(20 / interval),
    )


def test_lorenz_matches_published_exponent():
    result = lorenz_exponent(interval=1.0, d0=1e-8)
    assert abs(result.exponent - LORENZ_EXPONENT) < 0.02
    assert result.stderr < 0.02
    # the convergence curve ends at the estimate and spans the recorded time
    assert np.isclose(result.running[-1], result.exponent, rtol=1e-12)
    assert result.time[-1] == 4020.0


def test_lorenz_does_not_depend_on_d0_and_interval():
    first = lorenz_exponent(interval=1.0, d0=1e-8)
    second = lorenz_exponent(interval=0.5, d0=1e-6)
    assert abs(first.exponent - second.exponent) < np.hypot(first.stderr, second.stderr)


def test_damped_oscillator_from_any_right_hand_side():
    # x'' + 2 ζ ω x' + ω² x = 0, underdamped: both exponents equal −ζω
    zeta, omega = 0.05, 2.0

    def oscillator(t: float, y: np.ndarray) -> np.ndarray:
        return np.array([y[1], -2 * zeta * omega * y[1] - omega**2 * y[0]])

    duration = 100.0
    result = benettin(
        rhs_propagator(oscillator),
        np.array([1.0, 0.0]),
        0.0,
        interval=1.0,
        n_intervals=round(duration),
    )
    # over a finite time the separation's norm also swings between the eigenvector directions:
    # |δ(T)| / |δ(0)| = exp(−ζωT) times a factor within [1/κ, κ], κ the condition number of the
    # eigenvector matrix, so the estimate is −ζω within ln(κ) / T
    jacobian = np.array([[0.0, 1.0], [-(omega**2), -2 * zeta * omega]])
    kappa = np.linalg.cond(np.linalg.eig(jacobian)[1])
    assert abs(result.exponent - (-zeta * omega)) <= np.log(kappa) / duration


def test_discrete_state_entries_are_copied_not_scaled():
    # a counter of intervals stands for contact memory: it must survive renormalisation as is
    def advance(y: np.ndarray, t: float, dt: float) -> np.ndarray:
        return np.array([y[0] * np.exp(0.3 * dt), y[1] + 1.0])

    mask = np.array([True, False])
    seen = []

    def rescale_spy(y_ref, y_pert, d0):
        seen.append(y_pert[1])
        rescaled = y_pert.copy()
        rescaled[0] = y_ref[0] + d0 * np.sign(y_pert[0] - y_ref[0])
        return rescaled

    default = benettin(advance, np.array([1.0, 0.0]), 0.0, interval=0.5, n_intervals=20, mask=mask)
    spied = benettin(
        advance,
        np.array([1.0, 0.0]),
        0.0,
        interval=0.5,
        n_intervals=20,
        mask=mask,
        rescale=rescale_spy,
    )
    # a separation of d0 = 1e-8 on a state of order 1 is resolved to eps / d0 ~ 1e-8
    assert abs(default.exponent - 0.3) < 1e-6
    assert abs(spied.exponent - 0.3) < 1e-6
    assert seen == list(np.arange(1.0, 21.0))


def test_logistic_map_at_r4_gives_ln2():
    exponent = map_lyapunov(
        lambda x: 4.0 * x * (1.0 - x), lambda x: 4.0 - 8.0 * x, 0.1234, 100_000, 1_000
    )
    assert abs(exponent - np.log(2.0)) < 0.01

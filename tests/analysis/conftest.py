"""Shared reference systems: the Lorenz, Rössler and forced Duffing flows, and synthetic run
datasets (the run contract)."""

import numba
import numpy as np
import pytest
import xarray as xr
from scipy.integrate import solve_ivp

#: Lorenz (1963) parameters; the largest exponent is 0.9056 (Sprott, "Chaos and Time-Series
#: Analysis", Oxford University Press 2003, table A.1)
LORENZ_EXPONENT = 0.9056
LORENZ_STEP = 0.005


@numba.njit(cache=True)
def _lorenz(y: np.ndarray) -> np.ndarray:
    return np.array(
        [10.0 * (y[1] - y[0]), y[0] * (28.0 - y[2]) - y[1], y[0] * y[1] - 8.0 / 3.0 * y[2]]
    )


@numba.njit(cache=True)
def _lorenz_rk4(y: np.ndarray, n_steps: int) -> np.ndarray:
    # fixed-step RK4: at h = 0.005 its error on the exponent is far below 1e-3, and compiled
    # it is ~100 times faster than solve_ivp, which keeps the suite short
    h = LORENZ_STEP
    y = y.copy()
    for _ in range(n_steps):
        k1 = _lorenz(y)
        k2 = _lorenz(y + 0.5 * h * k1)
        k3 = _lorenz(y + 0.5 * h * k2)
        k4 = _lorenz(y + h * k3)
        y = y + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
    return y


def lorenz_advance(y: np.ndarray, t: float, dt: float) -> np.ndarray:
    """Propagator of the Lorenz flow for Benettin (dt a multiple of LORENZ_STEP)."""
    return _lorenz_rk4(y, round(dt / LORENZ_STEP))


@numba.njit(cache=True)
def _flow(system: int, t: float, y: np.ndarray) -> np.ndarray:
    if system == 0:  # Lorenz
        return _lorenz(y)
    if system == 1:  # Rössler
        return np.array([-y[1] - y[2], y[0] + 0.2 * y[1], 0.2 + y[2] * (y[0] - 5.7)])
    # x'' + 0.05 x' + x^3 = 7.5 cos t: the forced Duffing oscillator of Ueda's chaotic regime
    return np.array([y[1], -0.05 * y[1] - y[0] ** 3 + 7.5 * np.cos(t)])


@numba.njit(cache=True)
def _flow_x(system: int, y0: np.ndarray, h: float, sub: int, n_skip: int, n: int) -> np.ndarray:
    """x of the flow sampled every sub · h for n samples after n_skip samples (RK4 step h)."""
    y, t = y0.copy(), 0.0
    x = np.empty(n)
    for i in range(n_skip + n):
        if i >= n_skip:
            x[i - n_skip] = y[0]
        for _ in range(sub):
            k1 = _flow(system, t, y)
            k2 = _flow(system, t + 0.5 * h, y + 0.5 * h * k1)
            k3 = _flow(system, t + 0.5 * h, y + 0.5 * h * k2)
            k4 = _flow(system, t + h, y + h * k3)
            y = y + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
            t += h
    return x


#: Rössler (1976) with a = b = 0.2, c = 5.7: largest exponent 0.0714 (Sprott 2003, appendix A)
ROSSLER_EXPONENT = 0.0714
ROSSLER_DT = 0.1
#: the forced Duffing oscillator x'' + 0.05 x' + x^3 = 7.5 cos t (Ueda): largest exponent
#: 0.1034 per unit of t (Sprott 2003, appendix A, "Ueda oscillator")
DUFFING_EXPONENT = 0.1034
DUFFING_DT = 2 * np.pi / 40
LORENZ_DT = 0.01
#: independent stretches per system in the ``stretches`` fixture: more of Rössler, whose
#: estimates scatter most (their cost is small: the series are short)
N_STRETCHES = {"lorenz": 5, "rossler": 9, "duffing": 5}
#: samples dropped before every stretch so it lies on the attractor: 50 Lorenz time units,
#: 500 of Rössler (~80 turns), 125 forcing periods of Duffing
TRANSIENT_SAMPLES = 5000
#: system: (index in _flow, RK4 step, RK4 steps per sample, samples per stretch)
_SYSTEMS = {
    "lorenz": (0, LORENZ_STEP, 2, 10_000),
    "rossler": (1, ROSSLER_DT / 5, 5, 5_000),
    "duffing": (2, DUFFING_DT / 10, 10, 12_000),
}


@pytest.fixture(scope="session")
def stretches() -> dict[str, list[np.ndarray]]:
    """``N_STRETCHES`` independent stretches of x(t) of each system ("lorenz", "rossler",
    "duffing"), sampled every ``LORENZ_DT``, ``ROSSLER_DT`` and ``DUFFING_DT``: 100 Lorenz time
    units, 500 Rössler time units (~90 turns) and 300 forcing periods.

    Every stretch starts from its own random initial condition (fixed seed) and drops
    ``TRANSIENT_SAMPLES`` first, so the stretches are unrelated pieces of the attractor.
    Fixed-step compiled RK4 (Lorenz at the step ``lorenz_advance`` uses, 5 and 10 steps per
    sample for Rössler and Duffing): its error changes which orbit is followed, as any
    integrator's does on a chaotic attractor, not the attractor's statistics; all stretches
    take about a second.
    """
    rng = np.random.default_rng(20_241_123)
    series = {}
    for name, (system, h, sub, n) in _SYSTEMS.items():
        starts = [1.0, 1.0, 1.0] + 0.5 * rng.standard_normal((N_STRETCHES[name], 3))
        # Rössler's z stays positive on the attractor; Duffing has two state variables
        starts[:, 2] = np.abs(starts[:, 2])
        series[name] = [
            _flow_x(system, start[: 2 if system == 2 else 3], h, sub, TRANSIENT_SAMPLES, n)
            for start in starts
        ]
    return series


def run_dataset(
    crank_period: float,
    samples_per_revolution: int,
    joints: dict[str, np.ndarray],
    bodies: dict[str, np.ndarray],
) -> xr.Dataset:
    """A dataset following the run contract.

    Every item of ``joints`` (eccentricity) and ``bodies`` (position) is an array
    (time, axis, 2): along the last dimension the value and its rate.
    """
    n_time = len(next(iter((joints | bodies).values())))
    time = np.arange(n_time) * crank_period / samples_per_revolution
    # the section is the crank back at its initial angle: the end of every revolution
    section = np.arange(samples_per_revolution, n_time, samples_per_revolution)

    def stack(items: dict[str, np.ndarray], which: int) -> np.ndarray:
        if not items:
            return np.empty((n_time, 0, 2))
        return np.stack([array[:, :, which] for array in items.values()], axis=1)

    variables = {}
    for name, items, dim in (("eccentricity", joints, "joint"), ("position", bodies, "body")):
        rate = "eccentricity_rate" if dim == "joint" else "velocity"
        for variable, which in ((name, 0), (rate, 1)):
            values = stack(items, which)
            variables[variable] = (("time", dim, "axis"), values)
            variables[f"section_{variable}"] = (("revolution", dim, "axis"), values[section])
    variables["crank_angle"] = ("time", 2 * np.pi * time / crank_period)
    return xr.Dataset(
        variables,
        coords={
            "time": time,
            "joint": list(joints),
            "axis": ["x", "y"],
            "body": list(bodies),
            "revolution": np.arange(1, len(section) + 1),
        },
        attrs={"crank_period": crank_period},
    )


def _slider_crank(time: np.ndarray, crank_period: float) -> dict[str, np.ndarray]:
    """Bodies of an ideal slider-crank turning at constant speed (crank 0.1 m, rod 0.4 m)."""
    omega = 2 * np.pi / crank_period
    angle = omega * time
    crank_pin = np.stack([0.1 * np.cos(angle), 0.1 * np.sin(angle)], axis=-1)
    crank_pin_rate = omega * np.stack([-0.1 * np.sin(angle), 0.1 * np.cos(angle)], axis=-1)
    rod = np.sqrt(0.4**2 - crank_pin[:, 1] ** 2)
    slider = np.stack([np.zeros_like(time), crank_pin[:, 0] + rod], axis=-1)
    slider_rate = np.stack(
        [np.zeros_like(time), crank_pin_rate[:, 0] - crank_pin[:, 1] * crank_pin_rate[:, 1] / rod],
        axis=-1,
    )
    return {
        "crank": np.stack([crank_pin, crank_pin_rate], axis=-1),
        "slider": np.stack([slider, slider_rate], axis=-1),
    }


def _duffing(t: float, y: np.ndarray) -> list[float]:
    # x'' + 0.3 x' - x + x^3 = 0.5 cos(1.2 t): a chaotic double-well oscillator
    return [y[1], -0.3 * y[1] + y[0] - y[0] ** 3 + 0.5 * np.cos(1.2 * t)]


DUFFING_PERIOD = 2 * np.pi / 1.2
SAMPLES_PER_REVOLUTION = 64
N_REVOLUTIONS = 400


@pytest.fixture(scope="session")
def ideal_run() -> xr.Dataset:
    """An all-ideal run: no clearance joint, the bodies of a slider-crank at 150 rpm."""
    crank_period = 0.4
    time = np.arange(N_REVOLUTIONS * SAMPLES_PER_REVOLUTION + 1) * (
        crank_period / SAMPLES_PER_REVOLUTION
    )
    return run_dataset(crank_period, SAMPLES_PER_REVOLUTION, {}, _slider_crank(time, crank_period))


@pytest.fixture(scope="session")
def duffing_run() -> xr.Dataset:
    """A run whose joint A moves like a forced Duffing oscillator in x, periodically in y."""
    time = np.arange(N_REVOLUTIONS * SAMPLES_PER_REVOLUTION + 1) * (
        DUFFING_PERIOD / SAMPLES_PER_REVOLUTION
    )
    solution = solve_ivp(
        _duffing, (0, time[-1]), [0.1, 0.0], t_eval=time, method="DOP853", rtol=1e-9, atol=1e-9
    )
    x, v = solution.y * 1e-4  # eccentricities of a 0.1 mm-scale clearance
    omega = 1.2
    y, w = 5e-5 * np.cos(omega * time), -5e-5 * omega * np.sin(omega * time)
    joint = np.stack([np.stack([x, v], axis=-1), np.stack([y, w], axis=-1)], axis=1)
    bodies = _slider_crank(time, DUFFING_PERIOD)
    return run_dataset(DUFFING_PERIOD, SAMPLES_PER_REVOLUTION, {"A": joint}, bodies)

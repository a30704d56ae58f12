"""Shared reference systems: the Lorenz flow, and synthetic run datasets (the run contract)."""

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


@pytest.fixture(scope="session")
def lorenz_x() -> np.ndarray:
    """x(t) of the Lorenz flow sampled every 0.01 for 100 time units, after a transient of 50."""
    y = lorenz_advance(np.array([1.0, 1.0, 1.0]), 0.0, 50.0)
    samples = np.empty(10_000)
    for k in range(len(samples)):
        samples[k] = y[0]
        y = lorenz_advance(y, 0.0, 0.01)
    return samples


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
N_REVOLUTIONS = 160


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

"""Per-point chaos indicators of a sweep, stacked and tabulated, on section series whose
nature is known in closed form: a period-2 alternation and the logistic map at r = 4."""

import matplotlib
import numpy as np
import pytest
import xarray as xr
from conftest import run_dataset

from sim.analysis.bifurcation import (
    MIN_SECTION_POINTS,
    SECTION_VARIABLES,
    section_indicators,
    stack_points,
)
from sim.plots.bifurcation import indicators_table, plot_bifurcation

matplotlib.use("Agg")

PERIOD = 0.4  # s, 150 rpm
PER_REV = 8
REVOLUTIONS = 300


def logistic(n: int, x0: float = 0.2345) -> np.ndarray:
    """The logistic map at r = 4: chaotic, Lyapunov exponent ln 2 per iterate."""
    x = np.empty(n)
    x[0] = x0
    for k in range(1, n):
        x[k] = 4.0 * x[k - 1] * (1.0 - x[k - 1])
    return x


def synthetic_point(clearance: float) -> xr.Dataset:
    """A run whose joint A alternates between two eccentricities revolution by revolution
    along x (period 2) and follows the logistic map along y (chaotic), held over each
    revolution; both within ``clearance``."""
    n = (REVOLUTIONS + 1) * PER_REV
    revolution = np.arange(n) // PER_REV
    x = clearance * 0.5 * (-1.0) ** revolution
    y = clearance * (logistic(REVOLUTIONS + 1)[revolution] - 0.5)
    channel = np.zeros((n, 2, 2))
    channel[:, 0, 0], channel[:, 1, 0] = x, y
    channel[:, 0, 1], channel[:, 1, 1] = -x, np.roll(y, -PER_REV)
    return run_dataset(PERIOD, PER_REV, {"A": channel}, {})


def test_known_sections_get_their_period_K_and_verdict():
    """x: period 2 and K ≈ 0 whatever the exponent; y: no period, K ≈ 1 (Gottwald and
    Melbourne: K → 1 for the logistic map at r = 4; 0.9 leaves room for the finite series of
    300 points), and the model exponent decides when its interval does: chaotic when
    significantly positive, quasi-periodic when significantly below any growth; an exponent
    within two standard errors of 0 does not vote, and K decides."""
    run = synthetic_point(5e-4)
    diverging = section_indicators(run, 10, exponent=50.0, stderr=5.0)
    assert float(diverging.model_lyapunov_exponent) == 50.0
    x, y = (diverging.sel(joint="A", axis=axis) for axis in ("x", "y"))
    assert int(x.section_period) == 2 and str(x.verdict.item()) == "periodic"
    assert float(x.zero_one_K) < 0.1
    assert int(y.section_period) == 0 and str(y.verdict.item()) == "chaotic"
    assert float(y.zero_one_K) > 0.9
    # a significantly negative exponent votes regular: it leads over K
    contracting = section_indicators(run, 10, exponent=-20.0, stderr=2.0)
    assert str(contracting.verdict.sel(joint="A", axis="y").item()) == "quasi-periodic"
    # an exponent within two standard errors of 0 decides nothing: K's vote stands
    flat = section_indicators(run, 10, exponent=1.0, stderr=5.0)
    assert str(flat.verdict.sel(joint="A", axis="y").item()) == "chaotic"


def test_too_few_section_points_fail_before_any_test():
    run = synthetic_point(5e-4).isel(revolution=slice(0, MIN_SECTION_POINTS + 4))
    with pytest.raises(ValueError, match=f"the indicators need {MIN_SECTION_POINTS}"):
        section_indicators(run, 5, exponent=1.0, stderr=1.0)


def test_ideal_point_stacks_without_channels_and_tabulates_none():
    """A point whose joints are ideal has no channels: stacked beside a clearance point its
    K is NaN and its verdict empty, and the table has rows for the clearance point only."""
    clearance = synthetic_point(5e-4)
    ideal = run_dataset(PERIOD, PER_REV, {}, {"slider": np.zeros(((REVOLUTIONS + 1) * 8, 2, 2))})
    parts = []
    for run, exponent in ((ideal, -3.0), (clearance, 50.0)):
        extra = section_indicators(run, 10, exponent=exponent, stderr=1.0)
        parts.append(xr.merge([run[list(SECTION_VARIABLES)], extra]))
    coordinate = xr.Variable("parameter", [0.0, 5e-4], {"name": "joints.A.clearance"})
    combined = stack_points(parts, coordinate)
    assert np.isnan(combined.zero_one_K.sel(parameter=0.0)).all()
    assert (combined.verdict.sel(parameter=0.0) == "").all()
    np.testing.assert_array_equal(combined.model_lyapunov_exponent.values, [-3.0, 50.0])
    table = indicators_table(combined)
    assert list(table["joints.A.clearance"]) == [5e-4, 5e-4]
    assert list(table.channel) == ["A.x", "A.y"]
    assert list(table.verdict) == ["periodic", "chaotic"]
    assert list(table.section_period) == [2, 0]
    combined.attrs.update(title="test", model="rigid links, dopri5 rtol 1e-05")
    fig = plot_bifurcation(combined, label="clearance", unit="m", transient=10)
    assert len(fig.axes) == 6  # A x and A y: points, exponent, K
    assert "rigid links, dopri5 rtol 1e-05" in fig._suptitle.get_text()

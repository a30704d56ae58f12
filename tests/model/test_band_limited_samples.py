"""Recorded samples of the fast quantities are interval means (sim.solve.means): free of the
aliasing that point samples suffer on flexible links.

The ideal six-bar with rod2–rod4 as ANCF beams rings at 5–10 kHz; at the default 200 samples
a revolution (500 per second) point samples fold that ringing into the band a 100 Hz low-pass
keeps. The reference is the same run recorded at 100 times the rate (DOPRI5's steps do not
depend on the output times: the runs below take the same steps), where the boxcar is 100 times
shorter and the ringing is resolved. One revolution: the two runs of the default test took
81 s on a machine whose two cores ran four other jobs (load average 8).
"""

import numpy as np
import pytest
from scipy.signal import butter, sosfiltfilt

from sim.run import simulate
from sim.scene import load_scene

BEAMS = [f"bodies.{b}.kind=beam" for b in ("rod2", "rod3", "rod4")]
PER_REV = 200  # the scene's default output rate
FINE = 100  # times the rate of the reference run
CUTOFF_HZ = 100.0  # docs/model.md, "The filter"


def _run(per_rev: int, sampling: str):
    scene = load_scene(
        "sixbar",
        [
            *BEAMS,
            "simulation.revolutions=1",
            f"simulation.output_per_revolution={per_rev}",
            f"simulation.sampling={sampling}",
        ],
    )
    return simulate(scene, ideal=True)


def _lowpass(x: np.ndarray, interval: float) -> np.ndarray:
    return sosfiltfilt(butter(4, CUTOFF_HZ, fs=1.0 / interval, output="sos"), x)


@pytest.fixture(scope="module")
def fine():
    return _run(PER_REV * FINE, "mean")


@pytest.fixture(scope="module")
def means():
    return _run(PER_REV, "mean")


@pytest.fixture(scope="module")
def points():
    return _run(PER_REV, "point")


def _low_passed_error(coarse, fine, name: str, select: dict, *, span: bool = False) -> float:
    """Largest difference of the 100 Hz low-passed coarse and fine signals at the coarse
    sample times, as a share of the fine signal's peak (`span`: of its range). The filter is
    applied forward and backward with padding a fixed number of samples long, so its start-up
    differs between the two rates: the first and last 0.05 revolution (10 samples, 20 ms, two
    time constants of the 100 Hz filter) are left out."""
    c = coarse[name].sel(**select).values.astype(float)
    f = fine[name].sel(**select).values.astype(float)
    dt = float(coarse.time[1] - coarse.time[0])
    low_c = _lowpass(c, dt)
    low_f = _lowpass(f, dt / FINE)[::FINE]
    edge = PER_REV // 20
    scale = np.ptp(f) if span else np.abs(f).max()
    return float(np.abs(low_c - low_f)[edge:-edge].max() / scale)


SIGNALS = [("acceleration", {"body": "slider", "axis": "y"}), ("drive_torque", {})]


@pytest.mark.parametrize("name, select", SIGNALS)
def test_low_passed_samples_at_the_default_rate_match_a_hundredfold_rate(means, fine, name, select):
    # Bound 1e-3 of the peak (measured over two revolutions: 3.2e-4 for the slider's
    # acceleration along the guide, 3.7e-4 for the torque; what is left is the ringing the
    # boxcar attenuates by π f Δt and still folds, and its in-band loss (π f Δt)²/6).
    # sampling does not steer the steps: on one machine both runs take the same ones
    assert means.attrs["solver_accepted_steps"] == fine.attrs["solver_accepted_steps"]
    assert _low_passed_error(means, fine, name, select) < 1e-3


@pytest.mark.slow
@pytest.mark.parametrize("name, select", SIGNALS)
def test_point_samples_at_the_default_rate_alias(points, fine, name, select):
    # Point samples at the same rate differ by 3.1e-2 and 1.4e-2 of the peak (two
    # revolutions): the bound above tells them apart. Slow: a third run (about 20 s).
    assert _low_passed_error(points, fine, name, select) > 5e-3


@pytest.mark.slow
def test_positions_and_velocities_alias_little_as_point_samples(points, fine):
    # The slider's point-sampled position and velocity, low-passed, against the fine run's:
    # measured over two revolutions 3.4e-5 of the velocity's peak and 4.5e-5 of the
    # position's range (docs/model.md); bound 1e-3 as for the interval means.
    select = {"body": "slider", "axis": "y"}
    assert _low_passed_error(points, fine, "velocity", select) < 1e-3
    assert _low_passed_error(points, fine, "position", select, span=True) < 1e-3


@pytest.fixture(scope="module")
def rigid_ideal():
    """The ideal six-bar with rigid links: the beams' motion without their bending, the
    reference their low-passed samples approach (the static deflections are micrometres)."""
    return simulate(load_scene("sixbar", ["simulation.revolutions=1"]), ideal=True, rigid=True)


@pytest.fixture(scope="module")
def implicit_means():
    scene = load_scene(
        "sixbar", [*BEAMS, "simulation.revolutions=1", "solver.method=generalized_alpha"]
    )
    return simulate(scene, ideal=True)


@pytest.mark.parametrize("name, select", SIGNALS)
@pytest.mark.parametrize("method", ["dopri5", "generalized_alpha"])
def test_both_integrators_low_passed_samples_follow_the_rigid_links(
    method, name, select, means, implicit_means, rigid_ideal
):
    # The flexible ideal six-bar at the default rate, low-passed at 100 Hz, against its rigid
    # links: measured 1.8e-4 (torque) and 2.5e-4 (slider acceleration) of the peak under
    # DOPRI5, 3.5e-4 and 4.2e-4 under generalized-α, whose torque means come from the energy
    # balance (sim.solve.means): from its integrated drive work, which samples the beams'
    # unresolved ringing, they read 2.5e-2. Bound 1e-3 of the peak, as above.
    flexible = means if method == "dopri5" else implicit_means
    dt = float(flexible.time[1] - flexible.time[0])
    low = _lowpass(flexible[name].sel(**select).values.astype(float), dt)
    reference = _lowpass(rigid_ideal[name].sel(**select).values.astype(float), dt)
    edge = PER_REV // 20
    assert np.abs(low - reference)[edge:-edge].max() < 1e-3 * np.abs(reference).max()

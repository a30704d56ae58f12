"""sim.studies.fidelity on synthetic runs with known answers, and on real runs of the six-bar."""

import json

import numpy as np
import pytest
import xarray as xr

from sim.plots import tables
from sim.run import simulate
from sim.scene import load_scene
from sim.studies import fidelity

PERIOD = 0.4
CLEARANCE = 5e-4


def synthetic_run(
    per_revolution: int = 100,
    revolutions: float = 2.0,
    *,
    acceleration=np.sin,
    torque=np.cos,
    eccentricity=lambda t: (CLEARANCE * np.cos(t), CLEARANCE * np.sin(t)),
    sections: dict | None = None,
    peaks: tuple[float, float, float] = (10.0, 5.0, 100.0),
    links: str = "rigid",
    rtol: float = 1e-6,
) -> xr.Dataset:
    """A run dataset with the variables sim.studies.fidelity reads: responses given as functions of
    the crank phase 2πt/T, section eccentricities of joint A (``sections``: axis → values)
    and the peaks (slider acceleration, torque, contact force of A); its scene and solver
    attributes (link kind, rtol) as the work–precision table reads them."""
    time = np.arange(round(revolutions * per_revolution) + 1) * PERIOD / per_revolution
    phase = 2 * np.pi * time / PERIOD
    acc = np.zeros((time.size, 1, 2))
    acc[:, 0, 1] = acceleration(phase)
    ecc = np.stack(eccentricity(phase), axis=-1)[:, None, :]
    sections = sections or {"x": np.zeros(3), "y": np.zeros(3)}
    section = np.stack([sections["x"], sections["y"]], axis=-1)[:, None, :]
    scene = {
        "joints": {"A": {"clearance": CLEARANCE}},
        "bodies": {"rod2": {"kind": links, "elements": 2}},
        "solver": {"method": "dopri5", "rtol": rtol, "atol": rtol / 100},
        "simulation": {"revolutions": revolutions, "output_per_revolution": per_revolution},
    }
    solver = {
        "solver_wall_time_s": 1.0,
        "real_time_factor": revolutions * PERIOD,
        "solver_accepted_steps": 100,
        "energy_error_relative": 1e-6,
    }
    return xr.Dataset(
        {
            "acceleration": (("time", "body", "axis"), acc),
            "drive_torque": ("time", torque(phase)),
            "eccentricity": (("time", "joint", "axis"), ecc),
            "section_eccentricity": (("revolution", "joint", "axis"), section),
            "peak_acceleration": (("body", "axis"), [[0.0, peaks[0]]]),
            "peak_drive_torque": ((), peaks[1]),
            "peak_normal_force": (("joint",), [peaks[2]]),
        },
        coords={
            "time": time,
            "body": ["slider"],
            "axis": ["x", "y"],
            "joint": ["A"],
            "revolution": np.arange(section.shape[0]),
        },
        attrs={"crank_period": PERIOD, "scene": json.dumps(scene), **solver},
    )


def test_a_run_against_itself_has_no_error():
    run = synthetic_run()
    errors = fidelity.short_horizon_errors(run, run, revolutions=2)
    assert errors == {name: (0.0, 0.0) for name in fidelity.SHORT_CHANNELS}
    assert fidelity.separation_time(run, run) == np.inf


def test_known_differences_give_known_errors():
    # sin + ε against sin: d = ε everywhere, peak 1 → RMS = max = ε.
    # cos (1 + ε sin) against cos: d = ε |sin cos| = ε |sin 2φ| / 2, maximum ε / 2; the mean
    # of sin² 2φ over N samples of whole periods is 1/2, and the last sample (φ = 4π) adds a
    # zero: RMS = ε / (2√2) · sqrt(N / (N + 1)).
    # The eccentricity turned by a small angle α: d = 2 c sin(α/2) at every time, peak c.
    eps, alpha = 1e-3, 0.01
    reference = synthetic_run(per_revolution=200)
    run = synthetic_run(
        per_revolution=200,
        acceleration=lambda p: np.sin(p) + eps,
        torque=lambda p: np.cos(p) * (1 + eps * np.sin(p)),
        eccentricity=lambda p: (CLEARANCE * np.cos(p + alpha), CLEARANCE * np.sin(p + alpha)),
    )
    errors = fidelity.short_horizon_errors(run, reference, revolutions=2)
    np.testing.assert_allclose(errors["slider_acceleration"], (eps, eps), rtol=1e-9)
    n = 400
    np.testing.assert_allclose(
        errors["drive_torque"][0], eps / (2 * np.sqrt(2)) * np.sqrt(n / (n + 1)), rtol=1e-6
    )
    np.testing.assert_allclose(errors["drive_torque"][1], eps / 2, rtol=1e-6)
    chord = 2 * np.sin(alpha / 2)
    np.testing.assert_allclose(errors["eccentricity_A"], (chord, chord), rtol=1e-9)


def test_window_limits_the_comparison():
    # a difference only after the first revolution is invisible in a one-revolution window
    reference = synthetic_run()
    run = synthetic_run(acceleration=lambda p: np.sin(p) + (p > 2 * np.pi + 1e-9))
    assert fidelity.short_horizon_errors(run, reference, revolutions=1)["slider_acceleration"] == (
        0.0,
        0.0,
    )
    rms, largest = fidelity.short_horizon_errors(run, reference, revolutions=2)[
        "slider_acceleration"
    ]
    assert largest == 1.0
    np.testing.assert_allclose(rms, np.sqrt(100 / 201))  # 100 of the 201 samples differ by 1


def test_finer_sampling_on_the_same_grid_is_accepted_other_times_are_not():
    reference = synthetic_run(per_revolution=100)
    finer = synthetic_run(per_revolution=400, acceleration=lambda p: np.sin(p) + 0.5)
    assert fidelity.short_horizon_errors(finer, reference, revolutions=2)[
        "slider_acceleration"
    ] == pytest.approx((0.5, 0.5))
    with pytest.raises(ValueError, match="sampled on the same times"):
        fidelity.short_horizon_errors(synthetic_run(per_revolution=30), reference, revolutions=2)


def test_separation_time_of_an_exponentially_growing_difference():
    # d = 1e-6 e^{φ} (φ the crank phase) crosses 0.1 of the peak (1) at φ = ln(1e5):
    # the first sample after it, within one sample interval.
    reference = synthetic_run(per_revolution=1000)
    run = synthetic_run(per_revolution=1000, acceleration=lambda p: np.sin(p) + 1e-6 * np.exp(p))
    crossing = np.log(1e5) / (2 * np.pi) * PERIOD
    found = fidelity.separation_time(run, reference, name="slider_acceleration", share=0.1)
    assert crossing < found <= crossing + PERIOD / 1000


def test_peak_differences_are_relative():
    run = synthetic_run(peaks=(12.0, 4.0, 100.0))
    reference = synthetic_run(peaks=(10.0, 5.0, 100.0))
    assert fidelity.peak_differences(run, reference) == pytest.approx(
        {"slider_acceleration": 0.2, "drive_torque": -0.2, "contact_force_A": 0.0}
    )


def test_section_distance_of_a_set_to_itself_is_zero_and_a_shift_is_the_shift():
    rng = np.random.default_rng(1)
    points = rng.normal(size=500)
    assert fidelity.section_distance(points, points, 1.0) == 0.0
    assert fidelity.section_distance(points + 0.3, points, 2.0) == pytest.approx(0.15)
    # the order of the points does not matter: it is a distance between distributions
    assert fidelity.section_distance(rng.permutation(points), points, 1.0) == 0.0


def test_section_distance_of_two_uniform_grids():
    # U(0, 1) against U(0, 2) by quantiles: W₁ = ∫₀¹ |u − 2u| du = 1/2, exactly on
    # midpoint grids of equal size
    u = (np.arange(1000) + 0.5) / 1000
    assert fidelity.section_distance(u, 2 * u, 1.0) == pytest.approx(0.5, rel=1e-12)


def test_poincare_distances_per_axis_after_the_transient():
    shift = 1e-4
    base = np.array([9.0, 9.0, 1e-4, 2e-4, 3e-4])  # the first two are the transient
    reference = synthetic_run(sections={"x": base, "y": base})
    run = synthetic_run(sections={"x": base + shift, "y": -base})
    distances = fidelity.poincare_distances(run, reference, transient_revolutions=2)
    assert distances["A.x"] == pytest.approx(shift / CLEARANCE)
    # y mirrored: {−1, −2, −3}·1e-4 against {1, 2, 3}·1e-4 → W₁ = mean of 2, 4, 6 (·1e-4)
    assert distances["A.y"] == pytest.approx(4e-4 / CLEARANCE)


def test_lyapunov_differences_are_matched_by_channel():
    def analysis(channels, exponents):
        return xr.Dataset(
            {"lyapunov_exponent": ("channel", exponents)}, coords={"channel": channels}
        )

    ours = analysis(["A.y", "A.x", "B.x"], [2.0, 5.0, 1.0])
    reference = analysis(["A.x", "A.y"], [4.0, 3.0])
    assert fidelity.lyapunov_differences(ours, reference) == {"A.y": -1.0, "A.x": 1.0}


def test_work_precision_table_against_the_reference_and_the_same_model():
    # reference: beams, sin + 0.1; rigid at 1e-9: sin; rigid at 1e-5: sin + 0.01; a coarser
    # rigid run (50 a revolution) is not on the reference's grid and gets no short errors
    cases = ["beam", "rigid-tight", "rigid-loose", "coarse"]
    runs = [
        synthetic_run(acceleration=lambda p: np.sin(p) + 0.1, links="beam", rtol=1e-10),
        synthetic_run(rtol=1e-9),
        synthetic_run(acceleration=lambda p: np.sin(p) + 0.01, rtol=1e-5),
        synthetic_run(per_revolution=50, rtol=1e-7),
    ]
    table = tables.work_precision_table(cases, runs, reference="beam", window=2).set_index("case")
    assert table.loc["beam", "is_reference"]
    assert table.loc["beam", "error_rms_slider_acceleration"] == 0.0
    assert list(table.links) == ["beam 2", "rigid", "rigid", "rigid"]
    loose = table.loc["rigid-loose"]
    assert loose.solver_reference == "rigid-tight"
    assert loose.solver_rms_slider_acceleration == pytest.approx(0.01)  # peak of sin: 1
    assert loose.error_rms_slider_acceleration == pytest.approx(0.09 / 1.1)  # peak 1.1
    assert table.loc["rigid-tight", "solver_rms_slider_acceleration"] == 0.0
    assert np.isnan(table.loc["coarse", "error_rms_slider_acceleration"])


def test_tighter_tolerance_is_closer_to_the_reference_on_the_six_bar():
    """Over the first 0.05 revolution (before the impacts' chaos separates runs), each
    decade of tolerance must bring every response closer to a run at 1e-10."""
    base = [
        "joints.A.clearance=0.5e-3",
        "joints.B.clearance=0.5e-3",
        "simulation.revolutions=0.05",
        "simulation.output_per_revolution=2000",
    ]

    def run(rtol: float) -> xr.Dataset:
        return simulate(
            load_scene("sixbar", [*base, f"solver.rtol={rtol}", f"solver.atol={rtol / 100}"])
        )

    reference = run(1e-10)
    errors = [
        fidelity.short_horizon_errors(run(r), reference, revolutions=0.05)
        for r in (1e-5, 1e-6, 1e-7)
    ]
    for name in fidelity.SHORT_CHANNELS:
        rms = [e[name][0] for e in errors]
        assert rms[0] > rms[1] > rms[2] > 0, (name, rms)

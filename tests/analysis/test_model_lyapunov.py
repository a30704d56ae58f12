"""The model-based exponent of a linkage (Benettin on the run's own integrator)."""

import numpy as np
import pytest

from sim.model.assembly import crank_period
from sim.model.clearance import eccentricity
from sim.run import simulate
from sim.scene import load_scene
from sim.studies.model_lyapunov import linkage_lyapunov, linkage_propagator, run_with_exponent

FLAGSHIP = ["joints.A.clearance=0.5e-3", "joints.B.clearance=0.5e-3"]


def test_ideal_sixbar_exponent_is_the_baumgarte_rate():
    # With every joint ideal the driven six-bar has no degree of freedom: a perturbation only
    # violates the constraints, and Baumgarte stabilisation makes them obey
    # Φ'' + 2α Φ' + β² Φ = 0, whose slowest rate is −α + sqrt(α² − β²) = −10 + 8 = −2 1/s
    # (the fast one, −18 1/s, is gone after the 2 s transient). The recorded span is whole
    # revolutions, over which Φ_q repeats, so the distance's change of metric cancels: what is
    # left is integration error (rtol 1e-8). A propagator that lost state between intervals
    # or a wrong time unit moves the estimate by O(1).
    scene = load_scene("sixbar", ["solver.baumgarte_alpha=10", "solver.baumgarte_beta=6"])
    result = linkage_lyapunov(scene, revolutions=25, transient_revolutions=5)
    assert abs(result.exponent - (-2.0)) < 1e-3
    assert result.stderr < 1e-3
    assert np.isclose(result.time[-1], 25 * crank_period(scene))


def test_propagator_follows_the_run_exactly():
    # Quarter revolutions are the chunks `simulate` advances by; the propagator packs and
    # unpacks state, contact memory and step-size state between them, and must reproduce the
    # run through its impacts to rounding.
    scene = load_scene("sixbar", [*FLAGSHIP, "simulation.revolutions=2"])
    run = simulate(scene)
    assert run.attrs["solver_contact_events"] > 20
    propagator = linkage_propagator(scene)
    state, t, quarter = propagator.pack(), 0.0, crank_period(scene) / 4
    for _ in range(8):
        state = propagator.advance(state, t, quarter)
        t += quarter
    system = propagator.integration.system
    q = state[: system.n]
    ecc = np.array(eccentricity(system, 0, q))
    np.testing.assert_allclose(
        ecc, run.section_eccentricity.sel(joint="A", revolution=2).values, rtol=0, atol=1e-12
    )
    slider = propagator.integration.layout.offset["slider"]
    np.testing.assert_allclose(
        q[slider : slider + 2],
        run.section_position.sel(body="slider", revolution=2).values,
        rtol=0,
        atol=1e-12,
    )


#: the ideal six-bar with Baumgarte rates −2 and −18 1/s, integrated tightly (see above)
IDEAL_TIGHT = [
    "solver.baumgarte_alpha=10",
    "solver.baumgarte_beta=6",
    "solver.rtol=1e-8",
    "solver.atol=1e-11",
    "simulation.revolutions=25",
]


def test_run_as_reference_finds_the_baumgarte_rate_and_keeps_the_run():
    # The exponent with the run as its reference trajectory must be the same closed-form
    # −2 1/s as above: the perturbed trajectory starts 3 revolutions (1.2 s) before the
    # recorded window, over which the fast rate's share falls by e^(−16 · 1.2) ≈ 5e-9. The
    # run paused at every renormalisation must keep every sample and differ from the
    # uninterrupted run only by integration error: the motion is periodic (no chaos to
    # amplify it), so rtol 1e-8 over 25 revolutions bounds it well below 1e-6 of the slider's
    # stroke scale (0.1 m).
    scene = load_scene("sixbar", IDEAL_TIGHT)
    run, _, result = run_with_exponent(
        scene, None, transient_revolutions=5, alignment_revolutions=3
    )
    assert abs(result.exponent - (-2.0)) < 1e-3
    assert result.stderr < 1e-3
    assert np.isclose(result.time[-1], 25 * crank_period(scene))
    assert result.transient_intervals == 3 * 32 and result.n_intervals == 20 * 32
    alone = simulate(scene)
    assert run.sizes == alone.sizes
    slider = run.position.sel(body="slider").values
    np.testing.assert_allclose(slider, alone.position.sel(body="slider").values, atol=1e-7)


@pytest.mark.parametrize(
    ("transient", "alignment", "message"),
    [
        (5, 0, r"alignment_revolutions = 0 must lie in \(0, transient_revolutions = 5\]"),
        (5, 6, r"alignment_revolutions = 6 must lie in"),
        (25, 2, r"transient_revolutions = 25 must be below the run's 25"),
    ],
)
def test_run_with_exponent_rejects_bad_windows(transient, alignment, message):
    scene = load_scene("sixbar", IDEAL_TIGHT)
    with pytest.raises(ValueError, match=message):
        run_with_exponent(
            scene, None, transient_revolutions=transient, alignment_revolutions=alignment
        )

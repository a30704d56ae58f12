"""The contact law itself against an independent code: our damping law on joint A of the rigid
six-bar against Exudyn's own contact object (ObjectContactSphereSphere, a sphere in a hollow
sphere; sim.crosscheck.model), where Exudyn has the same law (`EXUDYN_IMPACT_MODELS`:
impactModel 1 = hunt-crossley, 2 = gonthier-carvalho). Nothing of ours computes Exudyn's contact
force. A alone at 0.5 mm (and the four-bar's B), no friction (Exudyn's friction law is not
ours), the first impact (six-bar: t ≈ 6.4 ms, onset rate 0.156 m/s, peak force 3.1 kN, 10 µm
deep, 0.19 ms long) sampled every 5 µs (about 40 samples per impact).

Tolerances, from the measured convergence: with Exudyn's step 2.5 µs the peak force and the
rebound differ by 3.9e-4 and 1.6e-4, at 0.625 µs by 2.3e-5 and 7.5e-6 (16- and 22-fold for the
4-fold step: the trapezoidal rule's second order, so what remains is Exudyn's step error; ours
at rtol 1e-9). Peak force, deepest penetration and rebound must agree within 2e-4 (8 x the
largest of them) and the onset within 1e-9 s (measured 3e-12 s; the onset depends on the
motion before the contact only). Lankarani–Nikravesh against Hunt–Crossley at e = 0.9
(χ = 0.1425 against 0.15, the closest pair of the table) differ by 1.9e-3 in peak force and
4.7e-3 in rebound, 10 to 20 x the tolerance: the test tells laws apart.
"""

import pytest

pytest.importorskip("exudyn")

from sim.crosscheck.compare import impact
from sim.crosscheck.model import EXUDYN_IMPACT_MODELS, CrossCheckError
from sim.crosscheck.run import ExudynSettings, simulate_exudyn
from sim.run import simulate
from sim.scene import load_scene

SIXBAR = [f"bodies.{b}.kind=rigid" for b in ("rod2", "rod3", "rod4")] + ["joints.A.clearance=5e-4"]
#: (scene, its overrides, the clearance joint compared): A alone at 0.5 mm on the rigid six-bar;
#: the four-bar's own B (0.3 mm, rigid links)
CASES = {"sixbar": ("sixbar", SIXBAR, "A"), "fourbar": ("fourbar", [], "B")}
TOLERANCE = 2e-4
ONSET_S = 1e-9
SETTINGS = ExudynSettings(
    steps_per_sample=8, newton_relative_tolerance=1e-8, builtin_contact=True, contact_tolerance=1e3
)


def _scene(case: str, law: str) -> dict:
    """The case's scene under `law`, no friction, ours at rtol 1e-9: the first 0.1 revolution
    (0.05 of the six-bar) sampled at points every 5 µs (6.25 µs for the four-bar's 120 rpm)."""
    name, sets, _ = CASES[case]
    revolutions = 0.05 if name == "sixbar" else 0.1
    return load_scene(
        name,
        [
            *sets,
            "contact.friction=0",
            f"contact.law={law}",
            "solver.rtol=1e-9",
            "solver.atol=1e-12",
            "simulation.sampling=point",
            f"simulation.revolutions={revolutions}",
            "simulation.output_per_revolution=80000",
        ],
    )


def _first_impact(case: str, ours_law: str, exudyn_law: str) -> dict:
    ours = simulate(_scene(case, ours_law))
    theirs = simulate_exudyn(_scene(case, exudyn_law), settings=SETTINGS)
    return impact(ours, theirs, CASES[case][2])


def _assert_same_law(metrics: dict) -> None:
    diff = metrics["difference"]
    assert abs(diff["onset_s"]) < ONSET_S, metrics
    for key in ("peak_force", "max_penetration", "rebound"):
        assert abs(diff[key]) < TOLERANCE, (key, metrics)


@pytest.mark.parametrize(
    ("case", "law"),
    [("sixbar", law) for law in sorted(EXUDYN_IMPACT_MODELS)] + [("fourbar", "hunt-crossley")],
)
def test_the_same_law_agrees_on_the_first_impact(case, law):
    """Measured on the six-bar: hunt-crossley peak force 3111.13 against 3111.06 N (2.3e-5),
    rebound 0.906425 against 0.906432 (7.5e-6), penetration 1.5e-5, onset 3e-12 s apart;
    gonthier-carvalho 3098.50 against 3098.43 N (2.3e-5), rebound 0.897207 against 0.897213
    (6.9e-6). On the four-bar's B (t = 6.0 ms, 2.6 kN): 3.2e-5, 6.2e-6, 1.4e-11 s."""
    metrics = _first_impact(case, law, law)
    _assert_same_law(metrics)
    assert metrics["ours"]["peak_force"] > 1e3  # a real impact, not a graze


def test_a_different_law_is_told_apart():
    """Ours Lankarani–Nikravesh, Exudyn Hunt–Crossley: the same onset (the law acts only in
    contact) but peak force and rebound apart by 1.9e-3 and 4.7e-3, beyond the tolerance
    (four-bar: 2.0e-3 and 4.8e-3)."""
    metrics = _first_impact("sixbar", "lankarani-nikravesh", "hunt-crossley")
    assert abs(metrics["difference"]["onset_s"]) < ONSET_S
    with pytest.raises(AssertionError):
        _assert_same_law(metrics)
    assert abs(metrics["difference"]["rebound"]) > 10 * TOLERANCE


def test_a_law_exudyn_lacks_is_refused():
    """Exudyn's contact object has no Lankarani–Nikravesh: the error names the key."""
    with pytest.raises(CrossCheckError, match=r"joints\.A\.law"):
        simulate_exudyn(_scene("sixbar", "lankarani-nikravesh"), settings=SETTINGS)

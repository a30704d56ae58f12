"""The extremes of docs/studies.md at short duration: every case must finish with finite results,
bounded constraint violation and a closing energy audit (the workflow's `extremes` study runs
them at full length). Clearance 0 and the approach to the ideal joint of A and B alone are in
test_clearance_limits.py; here clearance 0 is checked on every joint with flexible links.

Bounds, from what the quantities mean rather than from the measured values:
- constraint violation below 1 % of the case's smallest clearance (10 nm for the 1 µm case):
  drift of the ideal joints must not compete with the clearance being modelled;
- energy audit below 1e-3 of the energy scale: the bound under which the default fidelity
  (rtol 1e-5) was chosen (docs/fidelity.md, "The default tolerance": 4.7e-4 over the
  200-revolution flagship); test_energy.py holds the audit itself to 1e-4 at rtol 1e-6.
Measured at these durations and the default rtol 1e-5: violation ≤ 3e-8 m (600 rpm, 6e-5 of
its 0.5 mm clearance; 7e-10 m at rtol 1e-6), audit ≤ 1.1e-4 (rigid), ≤ 1e-10 (beams).
"""

import numpy as np
import pytest

from sim.results import scene_of

AB = ["joints.A.clearance=0.5e-3", "joints.B.clearance=0.5e-3"]
RIGID = "simulation.revolutions=0.5"
# 0.025 revolution: past the first impacts (at ~0.017), short enough for explicit beams
BEAMS = "simulation.revolutions=0.025"
# 5 rpm: 0.05 revolution is 0.6 s of motion, sampled every 3 ms
SLOW = ["drive.speed_rpm=5", "simulation.revolutions=0.05", "simulation.output_per_revolution=4000"]
FLEXIBLE = [f"bodies.{body}.kind=beam" for body in ("rod2", "rod3", "rod4")]
ALL_JOINTS = ("A", "C", "D1", "D2", "E", "B")

VIOLATION_SHARE = 0.01  # of the case's smallest clearance
ENERGY_BOUND = 1e-3


def elements(n: int) -> list[str]:
    return [*FLEXIBLE, *(f"bodies.{body}.elements={n}" for body in ("rod2", "rod3", "rod4"))]


CASES = {
    "clearance-1um": [RIGID, "joints.A.clearance=1e-6", "joints.B.clearance=1e-6"],
    "clearance-1mm": [RIGID, "joints.A.clearance=1e-3", "joints.B.clearance=1e-3"],
    "clearance-2mm": [RIGID, "joints.A.clearance=2e-3", "joints.B.clearance=2e-3"],
    "speed-5rpm": SLOW,
    "speed-600rpm": [RIGID, "drive.speed_rpm=600"],
    "restitution-1.0": [RIGID, "contact.restitution=1.0"],
    "restitution-0.3": [RIGID, "contact.restitution=0.3"],
    "friction-0": [RIGID, "contact.friction=0"],
    "friction-0.5": [RIGID, "contact.friction=0.5"],
    "modulus-x100": [BEAMS, *elements(2), "materials.steel.youngs_modulus=2.07e13"],
    "modulus-div100": [BEAMS, *elements(2), "materials.steel.youngs_modulus=2.07e9"],
    "elements-1": [BEAMS, *elements(1)],
    "elements-8": [BEAMS, *elements(8)],
}


@pytest.mark.parametrize("case", list(CASES))
def test_extreme_case_finishes_within_bounds(run, case):
    ds = run("sixbar", *AB, *CASES[case])
    for name in ("position", "velocity", "acceleration", "drive_torque", "normal_force"):
        assert np.isfinite(ds[name].values).all(), name
    clearance = min(scene_of(ds)["joints"][joint]["clearance"] for joint in ("A", "B"))
    assert float(ds.constraint_violation.max()) < VIOLATION_SHARE * clearance
    assert ds.attrs["energy_error_relative"] < ENERGY_BOUND
    # the case reached the contacts it is about
    assert ds.attrs["solver_contact_events"] > 0
    assert float(ds.peak_normal_force.max()) > 0.0


def test_zero_clearance_on_every_joint_with_flexible_links_is_the_ideal_mechanism(run):
    zero = [f"joints.{joint}.clearance=0" for joint in ALL_JOINTS]
    ideal = run("sixbar", BEAMS, *elements(2), ideal=True)
    ds = run("sixbar", BEAMS, *elements(2), *zero)
    assert ds.sizes["joint"] == 0
    for name in ("position", "acceleration", "drive_torque", "strain_energy"):
        np.testing.assert_array_equal(ds[name].values, ideal[name].values)


def test_resting_contact_carries_the_load_at_the_hertz_penetration(run):
    """Grazing and resting contact (zero approach velocity). At 5 rpm and restitution 0.3
    the journal of A settles against its bearing within the first half of the run and stays
    there, sliding along the wall with a radial rate below contact.min_impact_speed: the
    regime where the Lankarani–Nikravesh damping is guarded. There the force must be the
    elastic Hertz force K δ^1.5 up to that guarded damping, whose share is at most
    b = ¾ (1 − c_e²) |δ̇|max / v_min; so δ / (F / K)^(2/3) lies in [(1 + b)^(-2/3), (1 − b)^(-2/3)].
    """
    ds = run("sixbar", *AB, *SLOW, "contact.restitution=0.3")
    scene = scene_of(ds)
    later = ds.isel(time=slice(ds.sizes["time"] // 2, None)).sel(joint="A")
    touching = later.in_contact.values > 0
    assert touching.all()
    e, rate = later.eccentricity.values, later.eccentricity_rate.values
    radial_rate = np.abs(np.sum(e * rate, axis=1) / np.linalg.norm(e, axis=1))
    v_min = scene["contact"]["min_impact_speed"]
    assert radial_rate.max() < v_min
    # K = (4/3) E* sqrt(R_B R_J / c) of docs/model.md, E* = E / (2 (1 − ν²)) for steel on steel
    c, radius = scene["joints"]["A"]["clearance"], scene["joints"]["A"]["bearing_radius"]
    steel = scene["materials"]["steel"]
    e_star = steel["youngs_modulus"] / (2 * (1 - steel["poisson"] ** 2))
    stiffness = 4 / 3 * e_star * np.sqrt(radius * (radius - c) / c)
    share = 0.75 * (1 - scene["contact"]["restitution"] ** 2) * radial_rate.max() / v_min
    ratio = later.penetration.values / (later.normal_force.values / stiffness) ** (2 / 3)
    assert (1 + share) ** (-2 / 3) <= ratio.min()
    assert ratio.max() <= (1 - share) ** (-2 / 3)
    assert ds.attrs["energy_error_relative"] < ENERGY_BOUND

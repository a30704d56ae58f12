"""Benchmark of continuation in bifurcation sweeps (issue 3): does starting each value from
the previous value's final state shorten the transient, and does it change the picture?

Two sweeps of the rigid six-bar (A and B with clearance, restitution 0.9, friction 0.15),
each run cold (every value from its assembled, centred state) and continued (every value
after the first from its neighbour's final state):
  - crank speed 90…210 rpm at 0.2 mm clearance;
  - clearance 0.5…0.1 mm (A and B together) at 150 rpm.
For every value it prints, per joint and axis (Wasserstein distance W₁ of the section
eccentricities over the clearance, sim.studies.fidelity.section_distance):
  - transient: W₁ of the first FIRST revolutions' section points against the run's settled
    part (revolutions TRANSIENT…end): large while the motion is still finding its attractor;
  - picture: W₁ between the continued and the cold run's settled parts, beside the W₁
    between the cold runs of this value and the previous one (what a sweep step changes).
Continuation is sound where "picture" is well below "step" and "transient" shrinks.

Usage: python benchmarks/continuation.py [--revolutions N]
"""

import argparse
import time

from sim.results import scene_of
from sim.run import simulate_from
from sim.scene import load_scene
from sim.studies.fidelity import poincare_distances, section_distance
from sim.studies.sweep import point_overrides

FIRST = 5  # revolutions judged as the transient
TRANSIENT = 20  # revolutions dropped before comparing pictures
COMMON = ["contact.restitution=0.9", "contact.friction=0.15", "simulation.output_per_revolution=20"]
SWEEPS = {
    "speed": (
        ["joints.A.clearance=2e-4", "joints.B.clearance=2e-4"],
        ["drive.speed_rpm"],
        [90.0, 120.0, 150.0, 180.0, 210.0],
    ),
    "clearance": (
        ["drive.speed_rpm=150"],
        ["joints.A.clearance", "joints.B.clearance"],
        [5e-4, 4e-4, 3e-4, 2e-4, 1e-4],
    ),
}


def transient_distance(run) -> dict[str, float]:
    """W₁ of the first FIRST revolutions' section points against the settled part, per channel."""
    joints = scene_of(run)["joints"]
    out = {}
    for joint in run.joint.values:
        for axis in run.axis.values:
            e = run.section_eccentricity.sel(joint=joint, axis=axis).values
            out[f"{joint}.{axis}"] = section_distance(
                e[1 : FIRST + 1], e[TRANSIENT:], joints[str(joint)]["clearance"]
            )
    return out


def sweep(name: str, revolutions: int) -> None:
    overrides, keys, values = SWEEPS[name]
    scenes = [
        load_scene(
            "sixbar",
            [
                *COMMON,
                *overrides,
                f"simulation.revolutions={revolutions}",
                *point_overrides(keys, v),
            ],
        )
        for v in values
    ]
    cold, continued, final = [], [], None
    cpu = {"cold": 0.0, "continued": 0.0}
    for scene in scenes:
        t0 = time.process_time()
        cold.append(simulate_from(scene, None)[0])
        t1 = time.process_time()
        run, final = simulate_from(scene, final)
        continued.append(run)
        cpu["cold"] += t1 - t0
        cpu["continued"] += time.process_time() - t1
    print(
        f"\n{name} sweep, {revolutions} revolutions per value; CPU cold {cpu['cold']:.1f} s, "
        f"continued {cpu['continued']:.1f} s"
    )
    print(
        f"  {'value':>8} {'channel':7} {'transient cold':>15} {'continued':>10} "
        f"{'picture':>8} {'step':>8}"
    )
    for k, value in enumerate(values):
        t_cold = transient_distance(cold[k])
        t_cont = transient_distance(continued[k])
        picture = poincare_distances(continued[k], cold[k], transient_revolutions=TRANSIENT)
        step = (
            poincare_distances(cold[k], cold[k - 1], transient_revolutions=TRANSIENT) if k else {}
        )
        for ch in t_cold:
            print(
                f"  {value:8g} {ch:7} {t_cold[ch]:15.3f} {t_cont[ch]:10.3f} "
                f"{picture[ch]:8.3f} {step.get(ch, float('nan')):8.3f}"
            )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--revolutions", type=int, default=60)
    args = parser.parse_args()
    simulate_from(load_scene("sixbar", ["simulation.revolutions=0.01"]), None)  # compile
    for name in SWEEPS:
        sweep(name, args.revolutions)


if __name__ == "__main__":
    main()

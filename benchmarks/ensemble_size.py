"""How many ensemble members the verdicts need: the clearance-size claims judged on two
ensembles with different base seeds, for N = 1 … N_max members (sim.ensemble,
sim.analysis.verdicts). The smallest N from which the two agree (no component of a claim
supported by one and decided against by the other) for every larger N is the measured ensemble
size. Prints one line per N and claim.

    python benchmarks/ensemble_size.py [--revolutions 30] [--transient 5] [--members 4]

Rigid links (DOPRI5, rtol 1e-5) to keep it affordable: ~15 min on a loaded core of this
machine at the defaults (the 0.1 mm case ~1-4 s per revolution, the 0.4 mm case 0.2 s).
Measured at the defaults: "larger clearance, larger peaks" supported by both ensembles at
every N; "smaller clearance, more and smaller impacts" undecided by both for N <= 3, at N = 4
not supported by one (joint B's median contact force is lower at 0.4 mm: -1110 [-1910, -150] N)
and undecided by the other (-924 [-1920, +1130] N).
"""

import argparse

import pandas as pd

from sim.analysis.revolutions import Bootstrap, revolution_table
from sim.analysis.verdicts import combine, consistent, trend
from sim.ensemble import member
from sim.run import simulate
from sim.scene import load_scene

CASES = {"clearance-0.1mm": 1.0e-4, "clearance-0.4mm": 4.0e-4}
CLAIMS = {
    "larger clearance, larger peaks": {"slider_acceleration": +1, "drive_torque": +1},
    "smaller clearance, more and smaller impacts": {
        "contact_events": -1,
        "contact_force_A": +1,
        "contact_force_B": +1,
    },
}
SEEDS = (20261123, 777)


def member_tables(revolutions: int, transient: int, members: int) -> dict:
    """Per-revolution tables of every (case, base seed, member); member 0 is shared."""
    tables = {}
    for case, clearance in CASES.items():
        scene = load_scene(
            "sixbar",
            [
                f"joints.A.clearance={clearance}",
                f"joints.B.clearance={clearance}",
                f"simulation.revolutions={revolutions}",
                "simulation.output_per_revolution=40",
            ],
        )
        nominal = revolution_table(simulate(scene), case, transient)
        for base in SEEDS:
            tables[case, base, 0] = nominal
            for k in range(1, members):
                run = simulate(scene, member=member(k, base))
                tables[case, base, k] = revolution_table(run, case, transient)
    return tables


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--revolutions", type=int, default=30)
    parser.add_argument("--transient", type=int, default=5)
    parser.add_argument("--members", type=int, default=4)
    args = parser.parse_args()
    tables = member_tables(args.revolutions, args.transient, args.members)
    boot = Bootstrap(resamples=2000, level=0.95, seed=20261123)
    for n in range(1, args.members + 1):
        for claim, quantities in CLAIMS.items():
            components = []
            for base in SEEDS:
                parts = [tables[case, base, k] for case in CASES for k in range(n)]
                table = pd.concat(parts, ignore_index=True)
                components.append([c.verdict for c in trend(table, list(CASES), quantities, boot)])
            verdicts = " / ".join(combine(c) for c in components)
            agree = "agree" if consistent(*components) else "DISAGREE"
            print(f"N = {n}  {claim}: {verdicts} ({agree})", flush=True)


if __name__ == "__main__":
    main()

"""Benchmark of the modal links' axial modes (issue 19): the flagship's per-revolution peaks
with modal rod2–rod4 against the ANCF beams, and what each model costs.

The flagship (A + B 0.5 mm, 150 rpm) with rod2–rod4 as 2-element ANCF beams under
generalized-α at rtol 1e-5 and 1e-6 (the reference and the floor between two ANCF runs),
then as modal links with and without axial modes. For each case it prints the real-time
factor of the integration, the accepted steps per revolution and the energy audit, and the
median per-revolution peaks after the transient (slider acceleration along the guide, drive
torque, contact forces at A and B, contact events) with their 95 % moving-block bootstrap
intervals over revolutions (sim.analysis.revolutions): one run of a chaotic system is one
sample, so two models agree on a statistic when their intervals overlap.

Run it alone: the cases run one after another on one core, and the real-time factors are
those of an otherwise idle machine.

Usage: python benchmarks/modal_peaks.py [--revolutions N] [--transient T]
       [--case NAME ...]
"""

import argparse

import pandas as pd

from sim.analysis.revolutions import Bootstrap, revolution_table, summarise
from sim.run import simulate
from sim.scene import load_scene

RODS = ("rod2", "rod3", "rod4")
FLAGSHIP = ["joints.A.clearance=0.5e-3", "joints.B.clearance=0.5e-3"]
GA = "solver.method=generalized_alpha"


def _tolerance(rtol: float) -> list[str]:
    return [f"solver.rtol={rtol}", f"solver.atol={rtol / 100}"]


def _modal(modes: int, axial: int) -> list[str]:
    return [
        setting
        for b in RODS
        for setting in (
            f"bodies.{b}.kind=modal",
            f"bodies.{b}.modes={modes}",
            f"bodies.{b}.axial_modes={axial}",
        )
    ]


BEAMS = [s for b in RODS for s in (f"bodies.{b}.kind=beam", f"bodies.{b}.elements=2")]
CASES = {
    "ANCF 2 el., GA 1e-5": [*BEAMS, GA, *_tolerance(1e-5)],
    "ANCF 2 el., GA 1e-6": [*BEAMS, GA, *_tolerance(1e-6)],
    "modal 1, DOPRI5 1e-5": [*_modal(1, 0), *_tolerance(1e-5)],
    "modal 1+1 axial, GA 1e-5": [*_modal(1, 1), GA, *_tolerance(1e-5)],
    "modal 1+2 axial, GA 1e-5": [*_modal(1, 2), GA, *_tolerance(1e-5)],
    "modal 3+2 axial, GA 1e-5": [*_modal(3, 2), GA, *_tolerance(1e-5)],
    "modal 3+3 axial, GA 1e-5": [*_modal(3, 3), GA, *_tolerance(1e-5)],
}


def run(case: str, revolutions: float, transient: int) -> tuple[dict, pd.DataFrame]:
    """One case after a short warm-up run (compilation): its solver statistics and its
    per-revolution peaks table."""
    sets = [*FLAGSHIP, *CASES[case]]
    simulate(load_scene("sixbar", [*sets, "simulation.revolutions=0.005"]))
    ds = simulate(load_scene("sixbar", [*sets, f"simulation.revolutions={revolutions}"]))
    return ds.attrs, revolution_table(ds, case, transient)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--revolutions", type=int, default=60)
    parser.add_argument("--transient", type=int, default=5)
    parser.add_argument("--case", action="append", choices=list(CASES), help="default: all")
    args = parser.parse_args()
    print(
        f"flagship: A + B 0.5 mm, 150 rpm, {args.revolutions} revolutions, {args.transient} dropped"
    )
    tables = []
    for case in args.case or CASES:
        st, table = run(case, args.revolutions, args.transient)
        tables.append(table)
        print(
            f"  {case:26s} real-time factor {st['real_time_factor']:.2f}, "
            f"{st['solver_accepted_steps'] / args.revolutions:.0f} steps per revolution, "
            f"energy audit {st['energy_error_relative']:.1e}",
            flush=True,
        )
    summary = summarise(pd.concat(tables, ignore_index=True), Bootstrap())
    print("median per-revolution peak [95 % interval]:")
    for quantity, rows in summary.groupby("quantity", sort=False):
        print(f"  {quantity} ({rows.unit.iloc[0]})")
        for row in rows.itertuples():
            print(
                f"    {row.case:26s} {row.median:9.0f} [{row.median_low:.0f}, "
                f"{row.median_high:.0f}]"
            )


if __name__ == "__main__":
    main()

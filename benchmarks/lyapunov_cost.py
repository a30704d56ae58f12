"""Cost and robustness of the model-based Lyapunov exponent (issue 3).

On the flagship (rigid six-bar, A and B clearances 0.5 mm, 150 rpm), one process:
  - wall time of one run (`simulate`) at the scene's tolerances (rtol 1e-6) and at the
    exponent's tolerances (sim.studies.model_lyapunov.exponent_tolerances);
  - the exponent (Benettin, both trajectories on the run's compiled integrator) with its
    standard error, and its cost relative to both runs;
  - the same with d0 / 10 and with the renormalisation interval halved (the result must not
    move beyond the standard errors), and at the scene's own tolerances (integration noise).

Costs are CPU seconds of this process (time.process_time; the kernels run on one thread), which
other jobs on a shared machine disturb far less than wall time; wall time is printed too.

Usage: python benchmarks/lyapunov_cost.py [--revolutions N] [--transient N] [--no-checks]
"""

import argparse
import time

import numpy as np

from sim.run import simulate
from sim.scene import load_scene
from sim.studies.model_lyapunov import (
    DEFAULT_D0,
    DEFAULT_INTERVAL_REVOLUTIONS,
    exponent_tolerances,
    linkage_lyapunov,
    with_tolerances,
)

CASE = ["joints.A.clearance=0.5e-3", "joints.B.clearance=0.5e-3"]


def timed(function, *args, **kwargs):
    """(result, CPU seconds, wall seconds) of one call."""
    cpu0, wall0 = time.process_time(), time.perf_counter()
    result = function(*args, **kwargs)
    return result, time.process_time() - cpu0, time.perf_counter() - wall0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--revolutions", type=float, default=200.0)
    parser.add_argument("--transient", type=float, default=20.0)
    parser.add_argument("--no-checks", action="store_true", help="skip the d0/interval checks")
    args = parser.parse_args()
    scene = load_scene("sixbar", [*CASE, f"simulation.revolutions={args.revolutions}"])
    # the tolerances the exponent's trajectories take
    rtol, atol = exponent_tolerances(scene)
    tight = with_tolerances(scene, (rtol, atol))
    # compile (or load) every kernel outside the timings
    simulate(scene, revolutions=0.01)
    linkage_lyapunov(scene, revolutions=0.5, transient_revolutions=0.0, interval_revolutions=0.02)

    _, run_cpu, run_wall = timed(simulate, scene)
    _, tight_cpu, tight_wall = timed(simulate, tight)
    print(
        f"flagship, {args.revolutions:g} revolutions ({args.transient:g} transient); one run: "
        f"{run_cpu:.1f} s CPU ({run_wall:.1f} s wall) at rtol {scene['solver']['rtol']:g}, "
        f"{tight_cpu:.1f} s CPU ({tight_wall:.1f} s wall) at rtol {rtol:g} / atol {atol:g}"
    )

    def exponent(label: str, **settings) -> float:
        result, cpu, wall = timed(
            linkage_lyapunov,
            scene,
            revolutions=args.revolutions,
            transient_revolutions=args.transient,
            **settings,
        )
        print(
            f"  {label:40s} λ = {result.exponent:7.2f} ± {result.stderr:5.2f} 1/s  "
            f"{cpu:6.1f} s CPU ({wall:.1f} s wall) = {cpu / run_cpu:4.2f} × run, "
            f"{cpu / tight_cpu:4.2f} × run at the same tolerances"
        )
        return result

    default = exponent(
        f"default (d0 {DEFAULT_D0:g} m, interval 1/{1 / DEFAULT_INTERVAL_REVOLUTIONS:g} rev)"
    )
    if args.no_checks:
        return
    smaller = exponent("d0 / 10", d0=DEFAULT_D0 / 10)
    shorter = exponent("interval / 2", interval_revolutions=DEFAULT_INTERVAL_REVOLUTIONS / 2)
    for name, other in (("d0 / 10", smaller), ("interval / 2", shorter)):
        gap = abs(other.exponent - default.exponent)
        combined = float(np.hypot(other.stderr, default.stderr))
        print(f"  {name}: moves the exponent by {gap:.2f} 1/s = {gap / combined:.2f} σ")
    exponent("at the scene's tolerances (noise check)", tolerances=(1.0, 1.0))


if __name__ == "__main__":
    main()

"""Real-time factors in CPU time of the flagship's three link models, and what sets them.

The flagship (A and B clearances of 0.5 mm, 150 rpm) with rigid links under DOPRI5, modal
links of one bending mode under DOPRI5, and two-element ANCF beams under generalized-α, each at
the scene's default rtol 1e-5 (atol 1e-7). A real-time factor is simulated time over the CPU
time of the integration alone (`sim.run.Run.advance_to`: the compiled loop and the energy
audit between its pieces; not the assembly, the compile or the output Dataset), in this
process after a warm-up run that compiles or loads the kernels. Each case runs --repeats
times; the median and the range are printed, with the step statistics of the run: accepted and
rejected steps per revolution, right-hand side evaluations per step, iteration matrices per
revolution (generalized-α) and contact events per revolution. The runs are deterministic, so
the statistics are the same in every repeat; the times are not.

Usage:
    python benchmarks/run_speed.py [--repeats N] [--case rigid|modal|beams ...] [--set KEY=VALUE]
"""

import argparse
import statistics
import time

from sim.run import Run
from sim.scene import load_scene

FLAGSHIP = ["joints.A.clearance=5e-4", "joints.B.clearance=5e-4"]
RODS = ("rod2", "rod3", "rod4")
#: case → (scene overrides, revolutions)
CASES = {
    "rigid": ([], 40.0),
    "modal": ([f"bodies.{b}.kind=modal" for b in RODS], 20.0),
    "beams": ([f"bodies.{b}.kind=beam" for b in RODS] + ["solver.method=generalized_alpha"], 10.0),
}


def timed_run(scene: dict, revolutions: float) -> tuple[float, Run]:
    """CPU seconds of one run's integration, and the run."""
    run = Run(scene, None, revolutions=revolutions)
    start = time.process_time()
    run.advance_to(run.t_end)
    return time.process_time() - start, run


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=3)
    parser.add_argument("--case", action="append", choices=sorted(CASES))
    parser.add_argument("--set", dest="extra", action="append", default=[])
    args = parser.parse_args()
    print("case   real-time factor, CPU: median (range)   per revolution: steps + rejected, ")
    print("       evaluations per step, iteration matrices, contact events")
    for name in args.case or CASES:
        overrides, revolutions = CASES[name]
        scene = load_scene("sixbar", [*FLAGSHIP, *overrides, *args.extra])
        timed_run(scene, 0.05)  # compile or load the kernels
        factors = []
        for _ in range(args.repeats):
            cpu, run = timed_run(scene, revolutions)
            factors.append(run.t_end / cpu)
        integ = run.integ
        accepted, rejected = integ.count("accepted"), integ.count("rejected")
        print(
            f"{name:6} {statistics.median(factors):7.2f} ({min(factors):.2f}-{max(factors):.2f})"
            f"   {accepted / revolutions:7.0f} + {rejected / revolutions:5.0f}"
            f"   {integ.count('evaluations') / (accepted + rejected):5.2f}"
            f"   {integ.count('jacobians') / revolutions:6.0f}"
            f"   {integ.count('events') / revolutions:5.0f}",
            flush=True,
        )


if __name__ == "__main__":
    main()

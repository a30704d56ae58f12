"""Cost of one dense-sweep point: its run and its model-based exponent (issue 17).

For a few points of each bifurcation study of config/config.yaml (its link model, revolutions,
transient and exponent alignment), one process times, in CPU seconds (time.process_time: one
thread, so other jobs on a shared machine disturb it far less than wall time):
  - the run alone (`sim.run.simulate`);
  - the point as the sweep computes it: the run with its exponent, the run being the
    reference trajectory (`sim.studies.model_lyapunov.run_with_exponent`);
  - with --separate, the exponent as two trajectories of its own from the assembled state
    (`sim.studies.model_lyapunov.linkage_lyapunov` at the run's tolerances), the way the
    sweeps computed it before;
and prints the exponent ± its standard error beside each, then each study's estimate: the
point cost interpolated log-log between the points timed (held constant beyond them), summed
over the study's grid.

Usage: python benchmarks/sweep_point_cost.py [--alignment R ...] [--separate] [--study NAME]
"""

import argparse
import time

import numpy as np
import yaml

from sim.run import simulate
from sim.scene import load_scene
from sim.studies.grid import sweep_grid
from sim.studies.model_lyapunov import linkage_lyapunov, run_with_exponent
from sim.studies.sweep import point_overrides

#: points timed per study: the ends and the middle of each range
POINTS = {
    "bifurcation-clearance": [1.0e-4, 5.0e-4, 1.0e-3],
    "bifurcation-speed": [30.0, 60.0, 135.0, 240.0],
}


def cpu(function, *args, **kwargs):
    """(result, CPU seconds) of one call."""
    start = time.process_time()
    result = function(*args, **kwargs)
    return result, time.process_time() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--alignment",
        type=float,
        nargs="+",
        help="alignment revolutions (default: the study's); the estimate uses the last",
    )
    parser.add_argument("--separate", action="store_true", help="also the separate exponent")
    parser.add_argument("--study", choices=sorted(POINTS), action="append", help="default: all")
    args = parser.parse_args()
    with open("config/config.yaml") as handle:
        config = yaml.safe_load(handle)
    for name in args.study or POINTS:
        entry = config["studies"][name]
        sweep = entry["sweep"]
        revolutions, transient = entry["revolutions"], entry["transient"]
        base = [f"{key}={value}" for key, value in entry.get("overrides", {}).items()]
        base += [f"simulation.revolutions={revolutions}"]
        base += [f"simulation.output_per_revolution={entry['output_per_revolution']}"]
        costs = []
        for value in POINTS[name]:
            scene = load_scene("sixbar", [*base, *point_overrides(sweep["keys"], value)])
            simulate(scene, revolutions=0.01)  # compile or load the kernels outside the timing
            _, run_cpu = cpu(simulate, scene)
            where = f"{name} {value:g} {sweep['unit']}"
            print(f"{where}: run alone {run_cpu:.1f} s", flush=True)
            for alignment in args.alignment or [sweep["lyapunov_alignment"]]:
                (_, _, result), point_cpu = cpu(
                    run_with_exponent,
                    scene,
                    None,
                    transient_revolutions=transient,
                    alignment_revolutions=alignment,
                )
                print(
                    f"{where}: run with exponent (alignment {alignment:g} rev) {point_cpu:.1f} s "
                    f"= {point_cpu / run_cpu:.2f} runs, lambda = {result.exponent:.4g} "
                    f"+- {result.stderr:.2g} 1/s",
                    flush=True,
                )
            costs.append(point_cpu)
            if args.separate:
                solver = scene["solver"]
                result, exponent_cpu = cpu(
                    linkage_lyapunov,
                    scene,
                    revolutions=revolutions,
                    transient_revolutions=transient,
                    tolerances=(solver["rtol"], solver["atol"]),
                )
                print(
                    f"{where}: separate exponent {exponent_cpu:.1f} s "
                    f"(point {(run_cpu + exponent_cpu) / run_cpu:.2f} runs), lambda = "
                    f"{result.exponent:.4g} +- {result.stderr:.2g} 1/s",
                    flush=True,
                )
        grid = np.array(sweep_grid(sweep))
        timed = np.log(POINTS[name])
        clipped = np.log(np.clip(grid, min(POINTS[name]), max(POINTS[name])))
        total = np.exp(np.interp(clipped, timed, np.log(costs))).sum()
        print(
            f"{name}: {total / grid.size:.1f} CPU s per point x {grid.size} points = "
            f"{total / 60:.1f} CPU min ({revolutions} revolutions, {transient} transient)",
            flush=True,
        )


if __name__ == "__main__":
    main()

"""Cost of one dense-sweep point: its run and its model-based exponent (issue 17).

For a few points of each bifurcation study of config/config.yaml (its link model, revolutions,
transient and exponent tolerances), one process times, in CPU seconds (time.process_time: one
thread, so other jobs on a shared machine disturb it far less than wall time):
  - the run (`sim.run.simulate`, the Poincaré points);
  - the model exponent (`sim.studies.model_lyapunov.linkage_lyapunov`, two trajectories);
and prints them with the exponent ± its standard error, then each study's estimate: the mean
per-point cost over the points timed times the number of points, over 2 cores.

Usage: python benchmarks/sweep_point_cost.py [--revolutions N] [--transient N]
"""

import argparse
import time

import yaml

from sim.run import simulate
from sim.scene import load_scene
from sim.studies.model_lyapunov import linkage_lyapunov
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
    parser.add_argument("--revolutions", type=float, help="default: the study's")
    parser.add_argument("--transient", type=int, help="default: the study's")
    args = parser.parse_args()
    with open("config/config.yaml") as handle:
        config = yaml.safe_load(handle)
    for name, values in POINTS.items():
        entry = config["studies"][name]
        sweep = entry["sweep"]
        revolutions = args.revolutions or entry["revolutions"]
        transient = entry["transient"] if args.transient is None else args.transient
        base = [f"{key}={value}" for key, value in entry.get("overrides", {}).items()]
        base += [f"simulation.revolutions={revolutions}"]
        base += [f"simulation.output_per_revolution={entry['output_per_revolution']}"]
        costs = []
        for value in values:
            scene = load_scene("sixbar", [*base, *point_overrides(sweep["keys"], value)])
            simulate(scene, revolutions=0.01)  # compile or load the kernels outside the timing
            _, run_cpu = cpu(simulate, scene)
            result, exponent_cpu = cpu(
                linkage_lyapunov,
                scene,
                revolutions=revolutions,
                transient_revolutions=transient,
                tolerances=tuple(sweep["lyapunov_tolerances"]),
            )
            costs.append(run_cpu + exponent_cpu)
            print(
                f"{name} {value:g} {sweep['unit']}: run {run_cpu:.1f} s, exponent "
                f"{exponent_cpu:.1f} s ({exponent_cpu / run_cpu:.2f} x the run), "
                f"lambda = {result.exponent:.3g} +- {result.stderr:.2g} 1/s "
                f"({revolutions:g} revolutions, {transient} transient)",
                flush=True,
            )
        count = sweep["range"][2]
        mean = sum(costs) / len(costs)
        print(
            f"{name}: {mean:.1f} CPU s per point x {count} points = {mean * count / 60:.1f} "
            f"CPU min, {mean * count / 120:.1f} min on 2 cores",
            flush=True,
        )


if __name__ == "__main__":
    main()

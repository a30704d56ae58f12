"""Benchmark of the simulation core (issue 2).

Prints, on one core after compilation:
  - the real-time factor (simulated s per wall-clock s) of the rigid six-bar with
    A and B clearances of 0.5 mm at 150 rpm over 20 revolutions, rtol 1e-6 (the
    scene's own tolerance, 1e-5, with --rtol 1e-5), in the scene's minimal coordinates
    (its ideal joints form a tree: sim.model.tree) or, with --coordinates absolute, in
    absolute coordinates under multipliers;
  - the start-up cost (import, compilation or cache load, first run) with the
    numba cache cold and warm, each in a fresh process.

Usage: python benchmarks/core_speed.py [--revolutions N] [--rtol R] [--no-startup]
       [--coordinates minimal|absolute]
"""

import argparse
import os
import subprocess
import sys
import tempfile
import time

CASE = ["joints.A.clearance=0.5e-3", "joints.B.clearance=0.5e-3"]

STARTUP = """
import time
t0 = time.perf_counter()
from sim.scene import load_scene
from sim.run import simulate
simulate(load_scene("sixbar", ["simulation.revolutions=0.01"]))
print(time.perf_counter() - t0)
"""


def startup_seconds(cache_dir: str) -> float:
    """Wall time of import + first tiny run in a fresh process using `cache_dir`."""
    env = dict(os.environ, NUMBA_CACHE_DIR=cache_dir)
    out = subprocess.run(
        [sys.executable, "-c", STARTUP], env=env, check=True, capture_output=True, text=True
    )
    return float(out.stdout.strip().splitlines()[-1])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--revolutions", type=float, default=20.0)
    parser.add_argument("--rtol", type=float, default=1e-6, help="relative tolerance")
    parser.add_argument(
        "--no-startup", action="store_true", help="skip the start-up timings (minutes cold)"
    )
    parser.add_argument("--coordinates", choices=("minimal", "absolute"), default="minimal")
    args = parser.parse_args()

    if not args.no_startup:
        with tempfile.TemporaryDirectory() as cache:
            cold = startup_seconds(cache)
            warm = startup_seconds(cache)
        print(f"start-up with numba cache cold: {cold:6.1f} s")
        print(f"start-up with numba cache warm: {warm:6.1f} s")

    from sim.run import simulate
    from sim.scene import load_scene

    scene = load_scene(
        "sixbar",
        [
            *CASE,
            f"solver.rtol={args.rtol}",
            f"simulation.revolutions={args.revolutions}",
            f"solver.coordinates={args.coordinates}",
        ],
    )
    simulate(scene, revolutions=0.01)  # compile (or load) outside the timing
    t0 = time.perf_counter()
    ds = simulate(scene)
    wall = time.perf_counter() - t0
    a = ds.attrs
    print(
        f"rigid six-bar, A+B 0.5 mm, 150 rpm, {args.revolutions:g} rev, rtol {args.rtol:g}, "
        f"{args.coordinates} coordinates: "
        f"simulated {a['simulated_time_s']:.2f} s in {wall:.2f} s wall "
        f"(integrator {a['solver_wall_time_s']:.2f} s): real-time factor "
        f"{a['simulated_time_s'] / wall:.2f}"
    )
    print(
        f"  steps {a['solver_accepted_steps']} accepted, {a['solver_rejected_steps']} rejected, "
        f"{a['solver_function_evaluations']} evaluations "
        f"({1e6 * a['solver_wall_time_s'] / a['solver_function_evaluations']:.2f} µs each), "
        f"{a['solver_contact_events']} contact events, "
        f"energy error {a['energy_error_relative']:.2e}"
    )


if __name__ == "__main__":
    main()

"""Throughput of batched sweep points: the worker processes of one job against one by one
(issue 19).

Runs the same sweep points (the clearance of A and B over 0.1 … 1 mm at 150 rpm, rigid links,
DOPRI5 at the scene's rtol 1e-5) twice: one by one in this process
(`sim.studies.sweep.run_sweep` with one worker) and as a batch shared among `--workers` worker
processes (sim.studies.batch). Prints both wall times, the throughput ratio (target ≥ 1.8 with
16 points on 2 cores), and, of the one-by-one wall time, the energy watch between compiled
calls (every quarter revolution; timed by wrapping `sim.run.EnergyWatch.drift`) and
everything outside the runs' integration loops (scene loading, the output Dataset, writing).

The ratio is meaningful on an otherwise idle machine only: other processes take cores from
the batch but not from the sequential run's one process. The cores in use (CPU seconds of the
processes per wall second) show on a busy machine too whether the workers ran at once.

Usage: python benchmarks/batch_throughput.py [--points 16] [--workers 2] [--revolutions 5]
       [--indicators] [--transient 0]
"""

import argparse
import resource
import tempfile
import time
from pathlib import Path

import numpy as np
import xarray as xr

import sim.run
from sim.run import simulate
from sim.scene import load_scene
from sim.studies.sweep import Indicators, run_sweep

KEYS = ["joints.A.clearance", "joints.B.clearance"]
WATCH_SECONDS = [0.0]


def _timed_drift(drift):
    def wrapper(self):
        start = time.perf_counter()
        try:
            return drift(self)
        finally:
            WATCH_SECONDS[0] += time.perf_counter() - start

    return wrapper


def _cpu_seconds() -> float:
    """CPU seconds of this process and of its worker processes that have ended."""
    children = resource.getrusage(resource.RUSAGE_CHILDREN)
    return time.process_time() + children.ru_utime + children.ru_stime


def timed_sweep(
    values, overrides, workers, transient, indicators, out_dir: Path
) -> tuple[float, float]:
    """Wall seconds and CPU seconds (this process and its finished worker processes) of one
    sweep over `values`."""
    start, cpu = time.perf_counter(), _cpu_seconds()
    run_sweep(
        "sixbar",
        overrides,
        KEYS,
        values,
        out_dir=out_dir,
        label="clearance",
        transient_revolutions=transient,
        workers=workers,
        indicators=indicators,
    )
    return time.perf_counter() - start, _cpu_seconds() - cpu


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--points", type=int, default=16)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--revolutions", type=float, default=5.0)
    parser.add_argument(
        "--indicators",
        action="store_true",
        help="also each point's model exponent and 0-1 K (needs revolutions >= transient + 20, "
        "transient >= 1: the exponent aligns over the transient's last revolution)",
    )
    parser.add_argument("--transient", type=int, default=0)
    args = parser.parse_args()
    if args.indicators and args.transient < 1:
        parser.error("--indicators needs --transient of at least 1")
    values = [float(v) for v in np.linspace(1e-4, 1e-3, args.points)]
    overrides = [f"simulation.revolutions={args.revolutions}"]
    indicators = Indicators(alignment_revolutions=1.0) if args.indicators else None
    # compile (or load) every kernel outside the timings
    simulate(load_scene("sixbar", [f"{k}=5e-4" for k in KEYS]), revolutions=0.01)
    with tempfile.TemporaryDirectory() as tmp:
        alone_dir, batch_dir = Path(tmp) / "alone", Path(tmp) / "batch"
        alone_dir.mkdir()
        batch_dir.mkdir()
        drift = sim.run.EnergyWatch.drift
        sim.run.EnergyWatch.drift = _timed_drift(drift)
        alone, alone_cpu = timed_sweep(values, overrides, 1, args.transient, indicators, alone_dir)
        sim.run.EnergyWatch.drift = drift
        batch, batch_cpu = timed_sweep(
            values, overrides, args.workers, args.transient, indicators, batch_dir
        )
        integrator = 0.0
        for path in sorted(alone_dir.glob("*.nc")):
            with xr.open_dataset(path) as run:
                integrator += float(run.attrs["solver_wall_time_s"])
    print(
        f"{args.points} points x {args.revolutions:g} revolutions"
        f"{' + model exponent and 0-1 K' if indicators else ''}: one by one {alone:.1f} s, "
        f"{args.workers} processes {batch:.1f} s; throughput ratio {alone / batch:.2f}"
    )
    # cores in use: on a busy machine the wall-time ratio says little, but a batch whose
    # processes ran at once still shows more CPU seconds per wall second than one by one
    print(
        f"cores in use (CPU s / wall s): one by one {alone_cpu / alone:.2f}, "
        f"{args.workers} processes {batch_cpu / batch:.2f}"
    )
    print(
        f"one by one, of {alone:.1f} s: energy watch {WATCH_SECONDS[0]:.2f} s "
        f"({WATCH_SECONDS[0] / alone:.1%}); outside the runs' integration loops "
        f"{alone - integrator:.2f} s ({(alone - integrator) / alone:.1%})"
        + (" (includes the indicators)" if indicators else "")
    )


if __name__ == "__main__":
    main()

"""Compile time of one integrator's kernels from an empty numba cache, phase by phase and
kernel by kernel.

Runs in a fresh temporary cache (never the user's): the right-hand side alone, then `prepare`
(which records the first sample row, compiling `record_row`), then the integration loop and
what it calls, and prints each phase's wall time. Then, per compiled kernel of the package,
numba's own timers (seconds, each including the kernels it compiled on the way): the compiler
lock (all of it), the LLVM lock (optimisation and code generation: every non-inlined kernel
re-optimises everything it calls), and the lowering, typing and inlining passes. A kernel that
appears twice was compiled for two argument types.

Usage:
    python benchmarks/compile_time.py [dopri5|generalized_alpha] [--kernels N]
"""

import argparse
import os
import sys
import tempfile
import time


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("method", nargs="?", default="dopri5")
    parser.add_argument("--kernels", type=int, default=30, help="rows of the per-kernel table")
    args = parser.parse_args()
    # before numba is imported: sim.jit reads the cache directory when it loads
    os.environ["NUMBA_CACHE_DIR"] = tempfile.mkdtemp(prefix="sim-compile-time-")

    import numba
    import numpy as np
    from numba.core.registry import CPUDispatcher

    from sim.model.assembly import build_system
    from sim.model.gaps import contact_memory
    from sim.run import prepare
    from sim.scene import load_scene
    from sim.solve import dae, stepping
    from sim.solve.dae import make_work

    scene = load_scene("sixbar", ["simulation.revolutions=0.01", f"solver.method={args.method}"])
    system, _ = build_system(scene)
    y = np.zeros(2 * system.n + 2)
    rhs_arguments = (system, make_work(system), contact_memory(system), 0.0, y, y.copy())

    def timed(label: str, compile_step) -> None:
        start = time.perf_counter()
        compile_step()
        print(f"{label:>24}: {time.perf_counter() - start:6.1f} s", flush=True)

    timed("right-hand side", lambda: dae.rhs.compile(tuple(map(numba.typeof, rhs_arguments))))
    integ = None

    def prepared() -> None:
        nonlocal integ
        integ = prepare(scene)

    timed("prepare (sample row)", prepared)
    loop = tuple(map(numba.typeof, integ.arguments(0.01)))
    timed("integration loop", lambda: stepping.integrate.compile(loop))

    rows = []
    for module_name, module in list(sys.modules.items()):
        if not module_name.startswith("sim."):
            continue
        for name, value in vars(module).items():
            if not (isinstance(value, CPUDispatcher) and value.__module__ == module_name):
                continue
            for result in value.overloads.values():
                timers = result.metadata.get("timers", {})
                passes = result.metadata.get("pipeline_times", {}).get("nopython", {})

                def spent(word: str, passes=passes) -> float:
                    return sum(v.run for k, v in passes.items() if word in k)

                rows.append(
                    (
                        timers.get("compiler_lock", 0.0),
                        timers.get("llvm_lock", 0.0),
                        spent("lowering"),
                        spent("type"),
                        spent("inline"),
                        f"{module_name.removeprefix('sim.')}.{name}",
                    )
                )
    rows.sort(reverse=True)
    print(f"\n{'compile':>8} {'LLVM':>8} {'lower':>8} {'typing':>8} {'inline':>8}  kernel (s)")
    for row in rows[: args.kernels]:
        print(" ".join(f"{v:8.1f}" for v in row[:5]), "", row[5])


if __name__ == "__main__":
    main()

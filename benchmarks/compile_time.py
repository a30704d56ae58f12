"""What a new user waits for numba: the first `sim run` of each integrator from an empty cache.

In a fresh temporary numba cache (never the user's), one process after the other, as a user
meets them: the rigid flagship (A and B clearances of 0.5 mm) under DOPRI5, then the flexible
flagship (rod2–rod4 as two-element ANCF beams) under generalized-α, which finds DOPRI5's
kernels in the cache and compiles what is its own. Each is `sim run` for 0.05 revolution;
it prints each process's CPU time (user + system; the compile is single-threaded, so wall time
is the same on an idle core) and, per compiled function, its exclusive compile time: numba's
compilation of that function alone, the compiles it set off for its callees subtracted (a
kernel's library includes the optimisation and machine code of everything linked into it).
The kind says how the kernel is compiled (sim.jit): entry, kernel, inline (LLVM always-inline)
or twin (a kernel called from Python); spliced parts have no compilation of their own.

Usage:
    python benchmarks/compile_time.py [--kernels N]
"""

import argparse
import json
import os
import resource
import subprocess
import sys
import tempfile
import time

RUNS = {
    "DOPRI5, rigid flagship": ["joints.A.clearance=5e-4", "joints.B.clearance=5e-4"],
    "generalized-α after it, flexible flagship": [
        "joints.A.clearance=5e-4",
        "joints.B.clearance=5e-4",
        "bodies.rod2.kind=beam",
        "bodies.rod3.kind=beam",
        "bodies.rod4.kind=beam",
        "solver.method=generalized_alpha",
    ],
}


def child(report: str, overrides: list[str]) -> None:
    """Run `sim run` in this process with numba's compiler instrumented: write the exclusive
    compile time of every compiled function to `report` (JSON)."""
    from numba.core import compiler

    from sim import jit

    twin = getattr(jit, "TWIN_SUFFIX", None)  # (an older checkout compiled against has none)

    compiled, nested = [], []
    plain = compiler.compile_extra

    def compile_extra(typingctx, targetctx, func, args, return_type, flags, locals, **kw):
        start = time.process_time()
        nested.append(0.0)
        try:
            return plain(typingctx, targetctx, func, args, return_type, flags, locals, **kw)
        finally:
            spent = time.process_time() - start
            inner = nested.pop()
            if nested:
                nested[-1] += spent
            name = f"{func.__module__}.{func.__qualname__}"
            if twin and name.endswith(twin):
                kind = "twin"
            elif flags.forceinline:
                kind = "inline"
            else:
                kind = "kernel" if flags.no_cpython_wrapper else "entry"
            compiled.append((name.removeprefix("sim."), kind, spent - inner))

    compiler.compile_extra = compile_extra
    from sim.cli import main

    sets = [f"--set={s}" for s in overrides]
    with tempfile.TemporaryDirectory() as out:
        code = main(
            ["run", "sixbar", "-o", f"{out}/run.nc", "--set=simulation.revolutions=0.05", *sets]
        )
    with open(report, "w") as f:
        json.dump({"status": code, "compiled": compiled}, f)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--kernels", type=int, default=15, help="rows of each per-kernel table")
    parser.add_argument("--child", nargs=2, metavar=("REPORT", "OVERRIDES"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.child:
        child(args.child[0], json.loads(args.child[1]))
        return
    cache = tempfile.mkdtemp(prefix="sim-compile-time-")
    env = {**os.environ, "NUMBA_CACHE_DIR": cache}
    total = 0.0
    for label, overrides in RUNS.items():
        report = os.path.join(cache, "report.json")
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        command = [sys.executable, __file__, "--child", report, json.dumps(overrides)]
        subprocess.run(command, env=env, check=True, stdout=subprocess.DEVNULL)
        wall = time.perf_counter() - start
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
        total += cpu
        with open(report) as f:
            result = json.load(f)
        if result["status"] != 0:
            sys.exit(f"{label}: sim run failed (exit status {result['status']})")
        compiled = result["compiled"]
        spent = sum(s for _, _, s in compiled)
        print(f"\n{label}: {cpu:.1f} s CPU ({wall:.1f} s wall), of which {spent:.1f} s in")
        print(f"{len(compiled)} compilations; the longest (s, exclusive):")
        for name, kind, seconds in sorted(compiled, key=lambda c: -c[2])[: args.kernels]:
            print(f"  {seconds:6.2f}  {kind:6}  {name}")
    print(f"\nboth: {total:.1f} s CPU")


if __name__ == "__main__":
    main()

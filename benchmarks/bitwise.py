"""Bit-for-bit comparison of two checkouts of sim: the same scenes run with each, every
data variable and attribute compared exactly (NaNs equal to NaNs, -0.0 unequal to 0.0).

A refactoring of the integrator must not change a single step: this runs a set of cases
(the rigid flagship with DOPRI5, the flexible flagship with generalized-α, modal links, runs
that end in each failure a scene can provoke cheaply, a continued run and a short model
exponent) with
each checkout in a subprocess of its own (its own PYTHONPATH and numba cache), stores what
each returned under --out, and prints one line per case. Attributes that measure wall time
are left out. Exit status 1 if any case differs.

With --results it compares two workflow result trees instead (e.g. the quick workflow run by
each checkout): every netCDF file of OLD_RESULTS against the file of the same path in
NEW_RESULTS, or else (a sweep point's run, which <study>/run/ held before the sweeps ran in
batches) of the same name under <study>/sweep/; the `scene`
attribute is compared after filling in the scene defaults (sim.scene.with_defaults), which
newer run files record.

Usage:
    python benchmarks/bitwise.py OLD_CHECKOUT NEW_CHECKOUT [--out DIR] [--case NAME ...]
    python benchmarks/bitwise.py ... --reuse   # keep results already stored under --out
    python benchmarks/bitwise.py --results OLD_RESULTS NEW_RESULTS
"""

import argparse
import os
import pickle
import subprocess
import sys
from pathlib import Path

import numpy as np

RIGID = ["joints.A.clearance=5e-4", "joints.B.clearance=5e-4"]
BEAMS = [f"bodies.{b}.kind=beam" for b in ("rod2", "rod3", "rod4")]
FLEXIBLE = [*RIGID, *BEAMS, "solver.method=generalized_alpha", "solver.rtol=1e-5"]
MODAL = [*RIGID, *(f"bodies.{b}.kind=modal" for b in ("rod2", "rod3", "rod4"))]

# name → (overrides, revolutions, kind); kind "run" is simulate(rigid=...) on the six-bar.
CASES = {
    "rigid-dopri5": (RIGID, 3.0, "rigid"),
    "flexible-galpha": (FLEXIBLE, 0.5, "run"),
    "modal-dopri5": (MODAL, 0.5, "run"),
    "rigid-galpha": ([*RIGID, "solver.method=generalized_alpha"], 0.5, "rigid"),
    "max-steps-dopri5": ([*RIGID, "solver.max_steps=300"], 1.0, "rigid"),
    "max-steps-galpha": ([*FLEXIBLE, "solver.max_steps=50"], 0.5, "run"),
    "penetration": ([*RIGID, "materials.steel.youngs_modulus=2e6"], 1.0, "rigid"),
    "continued": (RIGID, 1.0, "continued"),
    "model-lyapunov": (RIGID, 0.5, "lyapunov"),
}
SKIPPED_ATTRS = {
    "solver_wall_time_s",
    "solver_cpu_time_s",
    "solver_compile_time_s",
    "real_time_factor",
    "history",
}
# attributes of result files that name where and with what they were made
SKIPPED_FILE_ATTRS = {"runs", "library_versions", "source"}


def run_case(name: str) -> dict:
    """Run one case with the sim on sys.path: {"dataset": …} or {"error": message}, plus
    whatever else the case returns (arrays)."""
    from sim.run import SimulationError, simulate, simulate_from
    from sim.scene import load_scene

    sets, revolutions, kind = CASES[name]
    scene = load_scene("sixbar", [*sets, f"simulation.revolutions={revolutions}"])
    try:
        if kind == "lyapunov":
            from sim.studies.model_lyapunov import linkage_lyapunov

            result = linkage_lyapunov(
                scene,
                revolutions=revolutions,
                transient_revolutions=revolutions / 4,
                interval_revolutions=1 / 64,  # 24 recorded intervals: enough for 10 blocks
                rigid=True,
            )
            return {k: np.asarray(v) for k, v in vars(result).items()}
        if kind == "continued":
            _, state = simulate_from(scene, None, rigid=True)
            nearby = load_scene(
                "sixbar",
                [*sets, "joints.A.clearance=4e-4", f"simulation.revolutions={revolutions}"],
            )
            dataset, final = simulate_from(nearby, state, rigid=True)
            return {"dataset": dataset, "final_q": final.q, "final_mem": final.mem}
        return {"dataset": simulate(scene, rigid=kind == "rigid")}
    except SimulationError as error:
        return {"error": str(error)}


def _same(a, b) -> bool:
    a, b = np.asarray(a), np.asarray(b)
    if a.dtype != b.dtype or a.shape != b.shape:
        return False
    if a.dtype.kind in "fc":
        return a.tobytes() == b.tobytes()
    return bool(np.array_equal(a, b))


def differences(old: dict, new: dict) -> list[str]:
    """What differs between two results of one case (empty when bitwise equal)."""
    diffs = []
    if old.keys() != new.keys():
        return [f"returned {sorted(old)} vs {sorted(new)}"]
    for key in old:
        a, b = old[key], new[key]
        if key == "dataset":
            if set(a.data_vars) != set(b.data_vars):
                diffs.append(f"data variables {sorted(a.data_vars)} vs {sorted(b.data_vars)}")
            for var in a.data_vars:
                if var in b.data_vars and not _same(a[var].values, b[var].values):
                    diffs.append(f"data variable {var}")
            for coord in a.coords:
                if coord not in b.coords or not _same(a[coord].values, b[coord].values):
                    diffs.append(f"coordinate {coord}")
            keys = (set(a.attrs) | set(b.attrs)) - SKIPPED_ATTRS
            diffs += [f"attribute {k}" for k in sorted(keys) if a.attrs.get(k) != b.attrs.get(k)]
        elif key == "error":
            if a != b:
                diffs.append(f"error {a!r} vs {b!r}")
        elif not _same(a, b):
            diffs.append(key)
    return diffs


def _scene_filled(dataset) -> None:
    """Replace the dataset's `scene` attribute by the scene with its defaults filled in."""
    import json

    from sim.scene import with_defaults

    if str(dataset.attrs.get("scene", "")).startswith("{"):  # a resolved scene, not a name
        scene = with_defaults(json.loads(dataset.attrs["scene"]))
        dataset.attrs["scene"] = json.dumps(scene, sort_keys=True)


def compare_results(old_root: Path, new_root: Path) -> bool:
    """Print IDENTICAL or DIFFERENT (what) for every netCDF file under old_root against its
    counterpart under new_root; True if all are identical."""
    import xarray as xr

    new_files = {p.relative_to(new_root): p for p in new_root.rglob("*.nc")}
    by_name = {}  # (study, name) of the runs of batched sweep points
    for rel, path in new_files.items():
        if len(rel.parts) > 2 and rel.parts[1] == "sweep":
            by_name.setdefault((rel.parts[0], rel.name), []).append(path)
    same = True
    for old in sorted(old_root.rglob("*.nc")):
        rel = old.relative_to(old_root)
        moved = by_name.get((rel.parts[0], rel.name), []) if rel.parts[1:2] == ("run",) else []
        new = new_files.get(rel) or next(iter(moved), None)
        if new is None:
            print(f"{rel}  MISSING in {new_root}")
            same = False
            continue
        with xr.open_dataset(old) as a, xr.open_dataset(new) as b:
            a, b = a.load(), b.load()
        for dataset in (a, b):
            _scene_filled(dataset)
            for key in SKIPPED_FILE_ATTRS:
                dataset.attrs.pop(key, None)
        diffs = differences({"dataset": a}, {"dataset": b})
        where = "" if new.relative_to(new_root) == rel else f" (as {new.relative_to(new_root)})"
        print(f"{rel}{where}  {'IDENTICAL' if not diffs else 'DIFFERENT'}")
        for d in diffs:
            print(f"    {d}")
        same &= not diffs
    return same


def stored(checkout: Path, name: str, out: Path, reuse: bool) -> dict:
    """The result of case `name` run by `checkout` (in a subprocess), stored under `out`."""
    path = out / f"{checkout.resolve().name}-{name}.pkl"
    if not (reuse and path.exists()):
        env = dict(
            os.environ,
            PYTHONPATH=str(checkout.resolve()),
            NUMBA_CACHE_DIR=str(checkout.resolve() / ".numba-cache"),
        )
        subprocess.run(
            [sys.executable, __file__, "--run", name, "--to", str(path)], env=env, check=True
        )
    with path.open("rb") as f:
        return pickle.load(f)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("old", type=Path, nargs="?")
    parser.add_argument("new", type=Path, nargs="?")
    parser.add_argument("--out", type=Path, default=Path("bitwise-results"))
    parser.add_argument("--case", action="append", choices=sorted(CASES))
    parser.add_argument("--reuse", action="store_true")
    parser.add_argument(
        "--results", action="store_true", help="OLD and NEW are workflow result trees"
    )
    parser.add_argument("--run", choices=sorted(CASES), help=argparse.SUPPRESS)
    parser.add_argument("--to", type=Path, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.run:
        with args.to.open("wb") as f:
            pickle.dump(run_case(args.run), f)
        return
    if args.old is None or args.new is None:
        parser.error("give the OLD and NEW checkouts")
    if args.results:
        sys.exit(0 if compare_results(args.old, args.new) else 1)
    if args.old.resolve().name == args.new.resolve().name:
        parser.error(
            "the two checkouts need different directory names (results are stored by name)"
        )
    args.out.mkdir(parents=True, exist_ok=True)
    failed = False
    for name in args.case or CASES:
        old = stored(args.old, name, args.out, args.reuse)
        new = stored(args.new, name, args.out, args.reuse)
        diffs = differences(old, new)
        outcome = f"error: {old['error']}" if "error" in old else "completed"
        print(f"{name:18s} {'IDENTICAL' if not diffs else 'DIFFERENT'} ({outcome})", flush=True)
        for d in diffs:
            print(f"    {d}")
        failed |= bool(diffs)
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()

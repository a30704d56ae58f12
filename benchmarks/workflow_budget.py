"""What the full reproduction costs, study by study (issue 17's budget).

Two modes:

- `--measured RESULTS`: the table of a finished workflow run, from the benchmark file Snakemake
  writes for every job (`RESULTS/benchmarks/<study>/...tsv`, `workflow/rules/paths.smk`): jobs,
  wall seconds and, where Snakemake sampled it, CPU seconds per study and kind of job.
- the estimate (without `--measured`): the simulation jobs of a configuration (runs,
  ensemble members, ideal references, the extremes' runs, the synthetic recording, model
  exponents and sweep batches) run shortened, one at a time, in a scratch copy of the workflow,
  and each job's cost is extrapolated to its full length. Every duration R runs twice, at
  r1 = max(0.25, R/50) and r2 = max(0.5, R/20) revolutions (R itself when R is at most that
  floor, run once; the model exponent's revolutions at floors of 2 and 4, its transient in
  proportion), and the job's wall time is fitted as a + b r through both: a is what the job
  pays whatever its length (start-up, assembly, writing), b its cost per revolution. Sweeps
  keep their revolutions and run every `--every`-th point of their grid, scaled by the points
  left out. Jobs run one at a time (`--cores 1`), so wall seconds are one core's seconds. Not
  included: the chaos analyses, figures and report (seconds each in the quick run:
  `--measured`), and the cross-check, whose chaotic case cannot be shortened below its
  statistics' transient (it needs the optional Exudyn extra; ~10 min, config/config.yaml).

The full run's wall time on two cores is the sum divided by the throughput two concurrent jobs
get on the machine (1.9-2.0 x on an idle 2-core machine: docs/performance.md, "Batched runs and
dense sweeps").

Usage:
  python benchmarks/workflow_budget.py [--configfile config/rigid.yaml] [--every 20]
                                       [--study NAME ...] [--keep DIR [--reuse]]
  python benchmarks/workflow_budget.py --measured results
"""

import argparse
import copy
import csv
import shutil
import subprocess
import sys
import tempfile
from collections import defaultdict
from pathlib import Path

import yaml
from snakemake.utils import validate

from sim.studies import config as resolver
from sim.studies.grid import sweep_grid

ROOT = Path(__file__).resolve().parent.parent
#: what a copy of the workflow needs
WORKFLOW_ITEMS = ("Snakefile", "config", "workflow", "report", "data")
#: the rules of the simulation stage (workflow/rules/simulate.smk, sweep.smk, analyze.smk,
#: experiment.smk), in two rounds: Snakemake's --until stops at the first of its rules on a
#: path, and a model exponent needs its member's run
SIMULATION_RULES = (
    ("run", "run_member", "run_ideal", "run_tolerant", "sweep_batch", "synthesize_recording"),
    ("model_exponent",),
)
#: (fraction of the full duration, floor in revolutions) of the two shortened passes
PASSES = ((1 / 50, 0.25), (1 / 20, 0.5))
#: the model exponent's floors: its standard error needs 20 renormalisations after the transient
EXPONENT_FLOORS = (2.0, 4.0)


def shortened(full: float, fraction: float, floor: float) -> float:
    """Revolutions a job of `full` revolutions runs in a pass: full if at most the floor."""
    return full if full <= floor else max(floor, full * fraction)


def full_revolutions(config: dict, name: str, case: str) -> float:
    """Revolutions of one case, by the workflow's precedence (sim.studies.config)."""
    settings = resolver.study_settings(config, name)
    return float(resolver.case_overrides(settings, case)["simulation.revolutions"])


def shorten(config: dict, index: int, every: int, last: bool) -> tuple[dict, dict[str, dict]]:
    """The configuration of pass `index` and, per study, {case: (full, run) revolutions} and
    the model exponent's (full, run) revolutions; a sweep study maps "sweep" to the factor of
    the points left out and "batches" to its jobs in the full run. Sweeps, and cases that run
    in full, run in the last pass only."""
    fraction, floor = PASSES[index]
    config = copy.deepcopy(config)
    # each study its own copy: YAML aliases (`sweep: *clearance_sweep`) share one object
    config["studies"] = {name: copy.deepcopy(entry) for name, entry in config["studies"].items()}
    config["quick"] = False
    validate(config, str(ROOT / "workflow/schemas/config.schema.yaml"), set_default=True)
    durations = {}
    for name, entry in config["studies"].items():
        if not entry.get("enabled", True):
            continue
        entry.pop("quick", None)
        if "case_grid" in entry:
            entry["cases"] = resolver.grid_cases(entry.pop("case_grid"))
        if "sweep" in entry:
            values = sweep_grid(entry["sweep"])
            entry["sweep"].pop("range", None)
            kept = values[::every]
            entry["sweep"]["values"] = kept
            entry["enabled"] = last
            batches = -(-len(values) // entry["sweep"]["batch"])
            durations[name] = {"sweep": len(values) / len(kept), "batches": batches}
            continue
        cases = {}
        settings = resolver.study_settings(config, name)
        for case, overrides in list(entry["cases"].items()):
            full = full_revolutions(config, name, case)
            run = shortened(full, fraction, floor)
            if run == full and not last:
                del entry["cases"][case]
                continue
            overrides["simulation.revolutions"] = run
            cases[case] = (full, run)
        if not entry["cases"]:
            entry["enabled"] = False
            continue
        exponent = settings["model_lyapunov"]
        run = shortened(exponent["revolutions"], fraction, EXPONENT_FLOORS[index])
        share = run / exponent["revolutions"]
        entry["model_lyapunov"] = {
            **exponent,
            "revolutions": run,
            "transient": exponent["transient"] * share,
        }
        durations[name] = {
            "cases": cases,
            "model_exponent": (exponent["revolutions"], run),
            "member_length": float(settings["ensemble"].get("revolutions", float("inf"))),
        }
    return config, durations


def read_benchmarks(results: Path) -> dict[str, dict]:
    """{job stem (relative to RESULTS/benchmarks, no suffix): its benchmark row}."""
    rows = {}
    for tsv in sorted((results / "benchmarks").rglob("*.tsv")):
        with tsv.open() as handle:
            row = next(csv.DictReader(handle, delimiter="\t"))
        rows[str(tsv.relative_to(results / "benchmarks").with_suffix(""))] = row
    return rows


def kind_of(stem: str) -> tuple[str, str, str]:
    """(study, kind of job, case or '') of a benchmark stem (paths.smk's JOBS patterns)."""
    parts = stem.split("/")
    study, kind = parts[0], parts[1] if len(parts) > 1 else parts[0]
    if kind == "run" and len(parts) == 4:
        return study, "member", parts[2]
    case = parts[2] if len(parts) > 2 else ""
    return study, kind, case


def run_pass(config: dict, work: Path) -> dict[str, dict]:
    """Run one pass's simulation jobs in a scratch copy of the workflow, one at a time (so
    that wall seconds are one core's); its benchmarks."""
    work.mkdir(parents=True)
    for item in WORKFLOW_ITEMS:
        source = ROOT / item
        if source.is_dir():
            shutil.copytree(source, work / item)
        elif source.exists():
            shutil.copy(source, work / item)
    # in place of the copy's config.yaml: a --configfile would be merged into it, not replace it
    (work / "config" / "config.yaml").write_text(yaml.safe_dump(config, sort_keys=False))
    snakemake = shutil.which("snakemake") or str(Path(sys.executable).with_name("snakemake"))
    for rules in SIMULATION_RULES:
        command = [snakemake, "--cores", "1", "--quiet", "--keep-going", "--until", *rules]
        done = subprocess.run(command, cwd=work, capture_output=True, text=True)
        if done.returncode != 0:
            print(f"some jobs failed (see {work}/logs):\n{done.stderr[-2000:]}", file=sys.stderr)
    return read_benchmarks(work / "results")


def extrapolate(c1: float | None, r1: float, c2: float, r2: float, full: float) -> float:
    """Cost at `full` revolutions of a job that cost c1 at r1 and c2 at r2 revolutions, on the
    line a + b r through both. A slope below zero (the length's cost lost in the noise of the
    fixed one) counts as zero; with one pass only, the cost is taken as proportional to r."""
    if r2 == full:
        return c2
    if c1 is None or r1 == r2:
        return c2 * full / r2
    return c2 + max(c2 - c1, 0.0) / (r2 - r1) * (full - r2)


def merge(config: dict, update: dict) -> None:
    """Merge `update` into `config` key by key, as Snakemake merges a --configfile."""
    for key, value in update.items():
        if isinstance(value, dict) and isinstance(config.get(key), dict):
            merge(config[key], value)
        else:
            config[key] = value


def estimate(args) -> None:
    config = yaml.safe_load((ROOT / "config" / "config.yaml").read_text())
    if args.configfile:
        merge(config, yaml.safe_load((ROOT / args.configfile).read_text()))
    if args.study:
        config["studies"] = {k: v for k, v in config["studies"].items() if k in args.study}
    scratch = Path(args.keep or tempfile.mkdtemp(prefix="budget-"))
    passes = []
    for index, (fraction, floor) in enumerate(PASSES):
        last = index == len(PASSES) - 1
        shortened_config, durations = shorten(config, index, args.every, last)
        print(f"pass {index + 1}: {fraction:.3g} of each duration, >= {floor} rev", flush=True)
        work = scratch / f"pass-{index + 1}"
        if args.reuse:
            passes.append((read_benchmarks(work / "results"), durations))
        else:
            passes.append((run_pass(shortened_config, work), durations))
    (first, _), (last, durations) = passes
    table = defaultdict(lambda: defaultdict(float))
    counts = defaultdict(lambda: defaultdict(int))
    for stem, row in last.items():
        study, kind, case = kind_of(stem)
        if study not in durations:
            continue
        c2 = float(row["s"])
        c1 = float(first[stem]["s"]) if stem in first else None
        plan = durations[study]
        if "sweep" in plan:
            cost = c2 * plan["sweep"]
        elif kind == "model-exponent":
            full, r2 = plan["model_exponent"]
            r1 = shortened(full, PASSES[0][0], EXPONENT_FLOORS[0])
            cost = extrapolate(c1, r1, c2, r2, full)
        elif kind == "member":
            # a member runs its case's revolutions, at most the ensemble's in every pass
            full, r2 = plan["cases"][case]
            r1 = shortened(full, *PASSES[0])
            length = plan["member_length"]
            cost = extrapolate(c1, min(r1, length), c2, min(r2, length), min(full, length))
        elif case in plan["cases"] or kind == "recording":
            # the synthetic recording runs the study's first case (common.smk, synthetic_sets)
            full, r2 = plan["cases"].get(case) or next(iter(plan["cases"].values()))
            r1 = shortened(full, *PASSES[0])
            cost = extrapolate(c1, r1, c2, r2, full)
        else:
            cost = c2
        table[study][kind] += cost
        counts[study][kind] = plan["batches"] if "sweep" in plan else counts[study][kind] + 1
    print_table(table, counts, "estimated one-core seconds of the full-length jobs")
    print(f"scratch copies: {scratch}")


def measured_table(results: Path) -> tuple[dict, dict, dict]:
    """Per study and kind of job: summed wall seconds and job counts of a finished run's
    benchmarks; per study, the CPU seconds Snakemake sampled."""
    table = defaultdict(lambda: defaultdict(float))
    counts = defaultdict(lambda: defaultdict(int))
    cpu = defaultdict(float)
    for stem, row in read_benchmarks(results).items():
        study, kind, _ = kind_of(stem)
        table[study][kind] += float(row["s"])
        counts[study][kind] += 1
        if row.get("cpu_time", "NA") not in ("NA", ""):
            cpu[study] += float(row["cpu_time"])
    return table, counts, cpu


def measured(results: Path) -> None:
    table, counts, cpu = measured_table(results)
    print_table(table, counts, "measured wall seconds per job, summed")
    print("CPU seconds sampled by Snakemake (every 30 s after a job's first 30 s):")
    for study in sorted(cpu):
        print(f"  {study}: {cpu[study]:.0f}")


def print_table(table, counts, what: str) -> None:
    print(f"\n{what}\n")
    print("| study | jobs | seconds | minutes | by kind of job (seconds) |")
    print("|---|---|---|---|---|")
    total = 0.0
    for study in sorted(table, key=lambda s: -sum(table[s].values())):
        seconds = sum(table[study].values())
        total += seconds
        jobs = sum(counts[study].values())
        kinds = ", ".join(
            f"{kind} {cost:.0f} ({counts[study][kind]:.0f})"
            for kind, cost in sorted(table[study].items(), key=lambda kv: -kv[1])
        )
        print(f"| {study} | {jobs:.0f} | {seconds:.0f} | {seconds / 60:.1f} | {kinds} |")
    print(f"| all | | {total:.0f} | {total / 60:.1f} | |")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--configfile", help="merged into config/config.yaml, as Snakemake does")
    parser.add_argument("--every", type=int, default=20, help="sweep points: every k-th runs")
    parser.add_argument("--study", nargs="*", help="only these studies")
    parser.add_argument("--keep", help="scratch directory (kept; default a new temporary one)")
    parser.add_argument("--reuse", action="store_true", help="read the passes kept in --keep")
    parser.add_argument("--measured", type=Path, help="summarise a finished run's results")
    args = parser.parse_args()
    if args.measured:
        measured(args.measured)
    else:
        estimate(args)


if __name__ == "__main__":
    main()

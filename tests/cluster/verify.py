"""Checks of a workflow run through SLURM (tests/cluster/run-slurm.sh).

Compares Snakemake's plan (the job counts per rule of a dry run) with what ran: the jobs the
run's log submitted to SLURM and ran locally, SLURM's own record of every finished job (its
job completion log, jobcomp/filetxt) and the SLURM job logs the profile keeps. Then checks the
report, and, given the results of a local run of the same sources, that every netCDF file holds
the same data. Prints a summary; exits 1 if any check fails.

    python tests/cluster/verify.py --plan plan.txt --log snakemake.log \
        --jobcomp jobcomp.log --project DIR [--reference RESULTS]
"""

import argparse
import re
import sys
from collections import Counter
from pathlib import Path

#: rules whose jobs run a simulation: each must be its own SLURM job, never a local one
SIMULATION_RULES = {
    "run",
    "run_member",
    "run_ideal",
    "run_tolerant",
    "crosscheck_case",
    "synthesize_recording",
}
#: netCDF attributes that record when or how fast, not what, was computed
CLOCK_ATTRIBUTES = re.compile(r"history|wall|cpu_time|compile_time|real_time_factor")


def plan_counts(text: str) -> Counter:
    """Job counts per rule of the first "Job stats" table of Snakemake's output."""
    counts = Counter()
    lines = iter(text.splitlines())
    for line in lines:
        if line.startswith("Job stats:"):
            break
    else:
        raise SystemExit("no 'Job stats' table in the plan")
    for line in lines:
        fields = line.split()
        if not fields or fields[0] in ("job", "total") or set(fields[0]) == {"-"}:
            if fields and fields[0] == "total":
                break
            continue
        counts[fields[0]] = int(fields[1])
    return counts


def run_log(text: str) -> dict:
    """What the run's log says: its SLURM run id, the submitted jobs (Snakemake job id ->
    SLURM job id, rule, SLURM log), the local jobs per rule, and whether it completed."""
    run_id = re.search(r"SLURM run ID: (\S+)", text)
    submitted = {}
    pattern = r"Job (\d+) has been submitted with SLURM jobid (\d+) \(log: (\S+)\)\."
    for job, slurm_id, log in re.findall(pattern, text):
        rule = re.search(r"/rule_([^/]+)/", log)
        submitted[job] = (slurm_id, rule.group(1) if rule else "?", Path(log))
    local = Counter(re.findall(r"^localrule (\w+):", text, flags=re.M))
    done = re.findall(r"^(\d+) of (\d+) steps \((\d+)%\) done", text, flags=re.M)
    return {
        "run_id": run_id.group(1) if run_id else None,
        "submitted": submitted,
        "local": local,
        "complete": bool(done) and done[-1][0] == done[-1][1],
        "steps": f"{done[-1][0]} of {done[-1][1]}" if done else "none",
    }


def jobcomp(text: str, run_id: str) -> dict:
    """SLURM's completion record of every job of this run: job id -> (state, exit code)."""
    jobs = {}
    for line in text.splitlines():
        fields = dict(re.findall(r"(\w+)=(\S*)", line))
        if fields.get("Name") == run_id:
            jobs[fields["JobId"]] = (fields.get("JobState"), fields.get("ExitCode"))
    return jobs


def compare_netcdf(results: Path, reference: Path) -> tuple[int, list[str]]:
    """Number of netCDF files compared and the differences found: every file of either tree
    must exist in both, with equal data variables and coordinates (values, dimensions, NaN
    equal to NaN) and equal attributes apart from clock readings (CLOCK_ATTRIBUTES)."""
    import xarray as xr

    ours = {p.relative_to(results) for p in results.rglob("*.nc")}
    theirs = {p.relative_to(reference) for p in reference.rglob("*.nc")}
    problems = [f"only in the cluster's results: {p}" for p in sorted(ours - theirs)]
    problems += [f"only in the reference: {p}" for p in sorted(theirs - ours)]
    for path in sorted(ours & theirs):
        with xr.open_dataset(results / path) as a, xr.open_dataset(reference / path) as b:
            if not a.drop_attrs().equals(b.drop_attrs()):
                changed = [
                    name
                    for name in sorted(set(a.variables) | set(b.variables))
                    if name not in a.variables
                    or name not in b.variables
                    or not a[name].variable.equals(b[name].variable)
                ]
                problems.append(f"{path}: data differ ({', '.join(changed) or 'structure'})")
            attrs = [
                key
                for key in sorted(set(a.attrs) | set(b.attrs))
                if not CLOCK_ATTRIBUTES.search(key) and a.attrs.get(key) != b.attrs.get(key)
            ]
            if attrs:
                problems.append(f"{path}: attributes differ ({', '.join(attrs)})")
    return len(ours & theirs), problems


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--plan", type=Path, required=True, help="output of snakemake -n")
    parser.add_argument("--log", type=Path, required=True, help="output of the run")
    parser.add_argument("--jobcomp", type=Path, required=True, help="SLURM's JobCompLoc")
    parser.add_argument("--project", type=Path, required=True, help="where the workflow ran")
    parser.add_argument("--reference", type=Path, help="results/ of a local run to compare")
    args = parser.parse_args()

    failures = []

    def check(ok: bool, message: str) -> None:
        print(("ok    " if ok else "FAIL  ") + message)
        if not ok:
            failures.append(message)

    plan = plan_counts(args.plan.read_text())
    log = run_log(args.log.read_text())
    submitted = log["submitted"]
    remote = Counter(rule for _, rule, _ in submitted.values())
    local = log["local"]
    check(log["run_id"] is not None, f"SLURM run id {log['run_id']}")
    check(log["complete"], f"workflow completed: {log['steps']} steps")

    print(f"\n{'rule':24} {'planned':>7} {'SLURM':>6} {'local':>6}")
    for rule in sorted(set(plan) | set(remote) | set(local)):
        print(f"{rule:24} {plan[rule]:7d} {remote[rule]:6d} {local[rule]:6d}")
    print()
    rules = sorted(set(plan) | set(remote) | set(local))
    short = [rule for rule in rules if remote[rule] + local[rule] != plan[rule]]
    check(not short, "every planned job ran" + (f"; not for {', '.join(short)}" if short else ""))
    mixed = [rule for rule in rules if remote[rule] and local[rule]]
    check(
        not mixed,
        "each rule's jobs ran all on SLURM or all locally"
        + (f"; not {', '.join(mixed)}" if mixed else ""),
    )
    for rule in sorted(SIMULATION_RULES & set(plan)):
        check(
            remote[rule] == plan[rule] and local[rule] == 0,
            f"{rule}: each of its {plan[rule]} jobs was its own SLURM job",
        )

    slurm_ids = [slurm_id for slurm_id, _, _ in submitted.values()]
    check(len(set(slurm_ids)) == len(slurm_ids), f"{len(slurm_ids)} distinct SLURM job ids")
    record = jobcomp(args.jobcomp.read_text(), log["run_id"])
    check(
        set(record) == set(slurm_ids),
        f"SLURM's job completion log lists the {len(record)} jobs of this run "
        f"(submitted: {len(slurm_ids)})",
    )
    completed = [j for j, (state, code) in record.items() if state == "COMPLETED" and code == "0:0"]
    check(len(completed) == len(slurm_ids), f"{len(completed)} jobs COMPLETED with exit code 0")
    kept = [log_path for _, _, log_path in submitted.values() if log_path.is_file()]
    check(len(kept) == len(submitted), f"{len(kept)} SLURM job logs kept")
    shell_runs = [
        log_path
        for _, rule, log_path in submitted.values()
        if rule in ("run", "run_ideal") and log_path.is_file()
    ]
    check(
        all("Shell command: sim run " in p.read_text() for p in shell_runs),
        f"each of the {len(shell_runs)} run and run_ideal SLURM logs shows its `sim run`",
    )

    results = args.project / "results"
    run_files = list(results.glob("*/run/*.nc")) + list(results.glob("*/ideal/*.nc"))
    check(
        len(run_files) == plan["run"] + plan["run_ideal"],
        f"{len(run_files)} run and ideal files, one per run and run_ideal job",
    )
    report = args.project / "report.html"
    check(report.is_file() and report.stat().st_size > 0, "report.html written")
    check((results / "report" / "landing.rst").is_file(), "landing page written")

    if args.reference:
        compared, problems = compare_netcdf(results, args.reference)
        for problem in problems:
            print("      " + problem)
        check(
            compared > 0 and not problems,
            f"{compared} netCDF files identical to the local run's (data variables, "
            "coordinates, attributes but clock readings)",
        )
    else:
        print("skip  no --reference: outputs not compared with a local run")

    print(
        f"\njobs planned {sum(plan.values())}: {sum(remote.values())} through SLURM, "
        f"{sum(local.values())} local; SLURM jobs completed with exit 0: {len(completed)}"
    )
    if failures:
        print(f"{len(failures)} check(s) failed", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

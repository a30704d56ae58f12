"""One case of a tolerant study (extremes): run `sim run`, never fail the workflow.

Writes a JSON status: `passed` when the run finished with finite results, bounded constraint
violation and a passing energy audit (and, for the ideal-reference case, the ideal motion of
every body), or when it stopped early with sim's exit code 1 and a diagnosis naming the time;
`failed` otherwise; `incomplete` when it was still running at the timeout.
"""

import json
import shlex
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np
import xarray as xr

from sim.results import scene_of


def violation_bound(ds: xr.Dataset, limits: dict) -> float:
    """Largest admissible constraint drift (m): `constraint_violation_share` of the run's
    smallest clearance (drift must not compete with the clearance being modelled), or
    `constraint_violation` for a run without clearance."""
    joints = scene_of(ds)["joints"].values()
    clearances = [j["clearance"] for j in joints if j["clearance"] > 0.0]
    if clearances and "constraint_violation_share" in limits:
        return limits["constraint_violation_share"] * min(clearances)
    return limits.get("constraint_violation", 1e-4)


def _checks(run: Path, ideal: Path | None, limits: dict) -> tuple[bool, list[str], dict]:
    numbers = {}
    problems = []
    with xr.open_dataset(run) as ds:
        finite = all(
            bool(np.isfinite(ds[name].values).all())
            for name in ("position", "velocity", "acceleration", "drive_torque")
        )
        numbers["finite"] = finite
        if not finite:
            problems.append("non-finite results")
        violation = float(ds.constraint_violation.max())
        numbers["constraint_violation_m"] = violation
        if violation > violation_bound(ds, limits):
            problems.append(f"constraint violation {violation:.3g} m")
        energy = float(ds.attrs["energy_error_relative"])
        numbers["energy_error_relative"] = energy
        if energy > limits.get("energy_error_relative", 1e-2):
            problems.append(f"energy audit {energy:.3g} of the energy scale")
        numbers["solver_wall_time_s"] = float(ds.attrs["solver_wall_time_s"])
        numbers["real_time_factor"] = float(ds.attrs["real_time_factor"])
        numbers["contact_events"] = int(ds.attrs["solver_contact_events"])
        numbers["max_penetration_m"] = float(ds.penetration.max()) if ds.sizes["joint"] else 0.0
        if ideal is not None:
            with xr.open_dataset(ideal) as ref:
                # every body of the scene, along both axes
                n = min(ds.sizes["time"], ref.sizes["time"])
                a = ds.position.isel(time=slice(n)).transpose("time", "body", "axis").values
                b = ref.position.isel(time=slice(n)).transpose("time", "body", "axis").values
                difference = float(np.max(np.abs(a - b)))
            numbers["ideal_displacement_difference_m"] = difference
            if difference > limits.get("ideal_displacement", 1e-6):
                problems.append(f"differs from the ideal joint by {difference:.3g} m")
    return not problems, problems, numbers


def main(snakemake) -> None:
    status_path = Path(snakemake.output[0])
    log = open(snakemake.log[0], "w")
    sets = shlex.split(snakemake.params.sets)
    ideal = Path(snakemake.input.ideal[0]) if snakemake.input.ideal else None
    with tempfile.TemporaryDirectory(dir=status_path.parent.parent) as tmp:
        out = Path(tmp) / "run.nc"
        command = ["sim", "run", snakemake.params.scene, "-o", str(out), "-q", *sets]
        start = time.perf_counter()
        try:
            done = subprocess.run(
                command, capture_output=True, text=True, timeout=snakemake.params.timeout
            )
            code, stdout, stderr = done.returncode, done.stdout, done.stderr
        except subprocess.TimeoutExpired as expired:
            code, stdout, stderr = None, str(expired.stdout or ""), str(expired.stderr or "")
        wall = time.perf_counter() - start
        log.write(f"$ {shlex.join(command)}\n{stdout}{stderr}")
        status = {
            "case": snakemake.wildcards.case,
            "command": shlex.join(["sim", "run", snakemake.params.scene, "-o", "OUT.nc", *sets]),
            "exit_code": code,
            "wall_time_s": wall,
        }
        message = stderr.strip().splitlines()[-1] if stderr.strip() else ""
        if code is None:
            status |= {
                "result": "incomplete",
                "outcome": f"still running after {snakemake.params.timeout:g} s (timeout)",
                "message": "",
            }
        elif code == 0:
            passed, problems, numbers = _checks(out, ideal, snakemake.params.checks)
            status |= numbers | {
                "result": "pass" if passed else "fail",
                "outcome": "finished" if passed else "finished: " + "; ".join(problems),
                "message": stdout.strip().replace(str(out), "OUT.nc"),
            }
        elif code == 1:
            clear = "at t =" in message
            status |= {
                "result": "pass" if clear else "fail",
                "outcome": "stopped early with a diagnosis"
                if clear
                else "stopped early without naming the time",
                "message": message,
            }
        else:
            status |= {"result": "fail", "outcome": f"exit code {code}", "message": message}
    status_path.write_text(json.dumps(status, indent=2) + "\n")
    log.close()


main(snakemake)  # noqa: F821 (injected by Snakemake)

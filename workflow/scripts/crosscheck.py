"""The cross-check study: each case run by sim and by Exudyn in one job (same machine,
same run, so their wall times compare), the agreement measured, and a summary table that says
whether the cross-check ran. One function per rule of workflow/rules/crosscheck.smk."""

import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import pandas as pd
import xarray as xr

from sim.crosscheck import compare, exudyn_available
from sim.plots import style, tables
from sim.results import write_netcdf
from sim.run import simulate
from sim.scene import load_scene

INSTALL = "pip install -e '.[crosscheck]'"


def _open(path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def _write_json(data: dict, path) -> None:
    path = Path(path)
    tmp = path.with_name(f".{path.name}.tmp")
    tmp.write_text(json.dumps(data, indent=1))
    tmp.replace(path)


def _kind(scene: dict) -> tuple[bool, bool]:
    """(any beam, any clearance joint) of a resolved scene."""
    flexible = any(b["kind"] == "beam" for b in scene["bodies"].values())
    clearance = any(j["clearance"] > 0 for j in scene["joints"].values())
    return flexible, clearance


def _timing(ds: xr.Dataset) -> dict:
    return {
        "wall_time_s": float(ds.attrs["solver_wall_time_s"]),
        "real_time_factor": float(ds.attrs["real_time_factor"]),
        "simulated_time_s": float(ds.attrs["simulated_time_s"]),
        "method": str(ds.attrs["solver_method"]),
    }


def rule_crosscheck_case(sm) -> None:
    from sim.crosscheck.figures import plot_overlay
    from sim.crosscheck.run import ExudynSettings, run_both

    sets = [f"{key}={value}" for key, value in sm.params.overrides.items()]
    scene = load_scene(sm.params.scene, sets)
    settings = ExudynSettings(**sm.params.exudyn)
    ours, theirs = run_both(scene, settings)
    write_netcdf(ours, sm.output.sim)
    write_netcdf(theirs, sm.output.exudyn)
    flexible, clearance = _kind(scene)
    cutoff = sm.params.lowpass_hz if flexible else None
    metrics = {
        "case": sm.wildcards.case,
        "flexible": flexible,
        "clearance": clearance,
        "lowpass_hz": cutoff,
        "exudyn_settings": json.loads(theirs.attrs["exudyn_settings"]),
        "exudyn_version": theirs.attrs["exudyn_version"],
        "timing": {"sim": _timing(ours), "exudyn": _timing(theirs)},
        "deterministic": compare.deterministic(ours, theirs, cutoff),
    }
    if settings.builtin_contact:
        # Exudyn's own contact law on the clearance joints: compared impact by impact (the
        # first one, before chaos separates the runs), not by statistics.
        metrics["impact"] = [
            compare.impact(ours, theirs, joint)
            for joint in theirs.joint.values
            if scene["joints"][joint]["type"] == "revolute"
        ]
    elif clearance:
        transient = sm.params.transient
        metrics["statistical"] = compare.statistical(ours, theirs, transient)
        # The spread of these statistics between two accurate runs of one code: ours again at
        # a 100-fold tighter tolerance (chaos separates the trajectories all the same).
        tight = load_scene(
            sm.params.scene,
            [
                *sets,
                f"solver.rtol={scene['solver']['rtol'] / 100}",
                f"solver.atol={scene['solver']['atol'] / 100}",
            ],
        )
        metrics["statistical_baseline"] = compare.statistical(ours, simulate(tight), transient)
    _write_json(metrics, sm.output.metrics)
    window = 1.0 if clearance else None
    style.save(plot_overlay(ours, theirs, cutoff=cutoff, revolutions=window), sm.output.overlay)


def rule_crosscheck_statistics(sm) -> None:
    from sim.crosscheck.figures import plot_statistics

    fig = plot_statistics(_open(sm.input.sim), _open(sm.input.exudyn), sm.params.transient)
    style.save(fig, sm.output[0])


def _rows(metrics: dict) -> list[dict]:
    """One table row per compared signal of a case."""
    rows = []
    timing = metrics["timing"]
    for name, entry in metrics["deterministic"].items():
        row = {
            "case": metrics["case"],
            "signal": name,
            "raw_max_error_over_peak": entry["raw"]["max"],
            "raw_rms_error_over_peak": entry["raw"]["rms"],
        }
        if "low" in entry:
            row["lowpass_max_error_over_peak"] = entry["low"]["max"]
            high = entry["high"]
            row["high_band_rms_sim"] = high["rms_ours"]
            row["high_band_rms_exudyn"] = high["rms_exudyn"]
            row["high_band_frequencies_sim_Hz"] = " ".join(
                f"{f:.0f}" for f in high["frequencies_ours"]
            )
            row["high_band_frequencies_exudyn_Hz"] = " ".join(
                f"{f:.0f}" for f in high["frequencies_exudyn"]
            )
        row["sim_wall_time_s"] = timing["sim"]["wall_time_s"]
        row["exudyn_wall_time_s"] = timing["exudyn"]["wall_time_s"]
        row["sim_real_time_factor"] = timing["sim"]["real_time_factor"]
        row["exudyn_real_time_factor"] = timing["exudyn"]["real_time_factor"]
        rows.append(row)
    if "statistical" in metrics:
        rows += _statistics_rows(metrics)
    for entry in metrics.get("impact", []):
        rows.append(_impact_row(metrics["case"], entry))
    return rows


def _impact_row(case: str, entry: dict) -> dict:
    """The first impact of a joint with Exudyn's own contact law: both codes' figures and
    their differences (times in s, the rest Exudyn's over sim's minus 1)."""
    ours, theirs, diff = entry["ours"], entry["exudyn"], entry["difference"]
    return {
        "case": case,
        "signal": f"first impact at {entry['joint']}",
        "onset_s_sim": ours["onset_s"],
        "onset_difference_s": diff["onset_s"],
        "peak_force_N_sim": ours["peak_force"],
        "peak_force_N_exudyn": theirs["peak_force"],
        "peak_force_relative_difference": diff["peak_force"],
        "rebound_sim": ours["rebound"],
        "rebound_exudyn": theirs["rebound"],
        "rebound_relative_difference": diff["rebound"],
        "max_penetration_relative_difference": diff["max_penetration"],
    }


def _statistics_rows(metrics: dict) -> list[dict]:
    """Per-revolution peaks and Poincaré points: sim against Exudyn, and sim against itself
    at a 100-fold tighter tolerance (the spread of the statistic between two accurate runs)."""
    rows = []
    exudyn, baseline = metrics["statistical"], metrics["statistical_baseline"]
    for group, label in (("peaks", "per-revolution peak"), ("poincare", "Poincaré")):
        for name, entry in exudyn[group].items():
            tight = baseline[group][name]
            rows.append(
                {
                    "case": metrics["case"],
                    "signal": f"{label} {name}",
                    "mean_sim": entry["mean_ours"],
                    "mean_exudyn": entry["mean_exudyn"],
                    "mean_sim_tight": tight["mean_exudyn"],
                    "std_sim": entry["std_ours"],
                    "std_exudyn": entry["std_exudyn"],
                    "wasserstein_over_spread_exudyn": entry["wasserstein_over_spread"],
                    "wasserstein_over_spread_sim_tight": tight["wasserstein_over_spread"],
                    "ks_pvalue_exudyn": entry["ks_pvalue"],
                    "ks_pvalue_sim_tight": tight["ks_pvalue"],
                }
            )
    return rows


def rule_crosscheck_table(sm) -> None:
    metrics = [json.loads(Path(path).read_text()) for path in sm.input.metrics]
    if metrics:
        summary = {"ran": True, "cases": {m["case"]: m for m in metrics}}
        table = pd.DataFrame([row for m in metrics for row in _rows(m)])
        note = (
            "errors over the peak |value| of sim's signal; low-pass: zero-phase Butterworth; "
            "timings of both codes in the same job"
        )
    else:
        reason = (
            f"Exudyn is not importable in this environment ({sys.executable}): the cross-check "
            f"did not run. Install it with {INSTALL} and rerun the workflow."
        )
        summary = {"ran": False, "reason": reason, "cases": {}}
        table = pd.DataFrame(
            [{"case": case, "result": "not run", "reason": reason} for case in sm.params.cases]
        )
        note = reason
    tables.write_table(table, sm.output.csv, sm.output.html, "Cross-check against Exudyn", note)
    _write_json(summary, sm.output.summary)


def main(sm) -> None:
    with open(sm.log[0], "w") as log:
        log.write(f"exudyn importable: {exudyn_available()}\n")
        globals()[f"rule_{sm.rule}"](sm)
        log.write(f"{sm.rule}: wrote {', '.join(map(str, sm.output))}\n")


main(snakemake)  # noqa: F821 (injected by Snakemake)

"""The report's landing page: each claim of STUDIES.md judged on our results.

Verdicts: "supported", "not supported", "mixed" (part holds), "not evaluated" (the study is
disabled, not run in this configuration, or needs data we do not have). The numbers behind
every verdict are on the page and in claims.csv.
"""

import json
from pathlib import Path

import jinja2
import numpy as np
import pandas as pd
import xarray as xr
import yaml

NOT_EVALUATED = "not evaluated"


def _open(path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def _deviation(run: xr.Dataset, ideal: xr.Dataset, variable: str) -> float:
    """Largest |run − ideal| over the ideal's range (after the first revolution)."""
    data, ref = run[variable], ideal[variable]
    if "body" in data.dims:
        data = data.sel(body="slider", axis="y")
        ref = ref.sel(body="slider", axis="y")
    start = float(run.attrs["crank_period"])
    data = data.sel(time=slice(start, None))
    ref = ref.interp(time=data.time)
    return float(np.abs(data - ref).max() / (ref.max() - ref.min()))


def claim_responses(inp) -> dict:
    claim = (
        "Displacement and velocity of the slider stay close to ideal; acceleration and "
        "driving torque show sharp peaks and vibration from impacts."
    )
    if "flagship_run" not in inp:
        return {"claim": claim, "verdict": NOT_EVALUATED, "evidence": "flagship not run"}
    run, ideal = _open(inp["flagship_run"]), _open(inp["flagship_ideal"])
    dev = {v: _deviation(run, ideal, v) for v in ("position", "velocity", "acceleration")}
    dev["drive_torque"] = _deviation(run, ideal, "drive_torque")
    close = dev["position"] < 0.05 and dev["velocity"] < 0.2
    peaky = dev["acceleration"] > 0.5 and dev["drive_torque"] > 0.5
    verdict = "supported" if close and peaky else ("mixed" if close or peaky else "not supported")
    evidence = (
        "flagship, largest deviation from ideal over the ideal's range: displacement "
        f"{dev['position']:.3g}, velocity {dev['velocity']:.3g}, acceleration "
        f"{dev['acceleration']:.3g}, torque {dev['drive_torque']:.3g} "
        "(close: displacement < 0.05 and velocity < 0.2; peaks: acceleration and torque > 0.5)"
    )
    return {"claim": claim, "verdict": verdict, "evidence": evidence}


def _peak_trend(path, column, order_column) -> tuple[bool, str]:
    table = pd.read_csv(path).sort_values(order_column)
    values = table[column].to_numpy()
    grows = bool(np.all(np.diff(values) > 0))
    text = ", ".join(f"{row[order_column]:g}: {row[column]:.4g}" for _, row in table.iterrows())
    return grows, text


def claim_peaks(inp) -> list[dict]:
    rows = []
    claim = "Larger clearance gives larger acceleration and torque peaks."
    if "clearance_size_peaks" in inp:
        acc, acc_text = _peak_trend(
            inp["clearance_size_peaks"], "peak_slider_acceleration_m_s2", "clearance_A_mm"
        )
        tq, tq_text = _peak_trend(
            inp["clearance_size_peaks"], "peak_drive_torque_N_m", "clearance_A_mm"
        )
        verdict = "supported" if acc and tq else ("mixed" if acc or tq else "not supported")
        rows.append(
            {
                "claim": claim,
                "verdict": verdict,
                "evidence": f"peak slider acceleration (m/s²) by clearance (mm) {acc_text}; "
                f"peak torque (N·m) {tq_text}",
            }
        )
        table = pd.read_csv(inp["clearance_size_peaks"]).sort_values("clearance_A_mm")
        events = table.contact_events_per_revolution.to_numpy()
        peaks = table.peak_slider_acceleration_m_s2.to_numpy()
        frequent = bool(events[0] > events[-1])
        smaller = bool(peaks[0] < peaks[-1])
        verdict = (
            "supported"
            if frequent and smaller
            else ("mixed" if frequent or smaller else "not supported")
        )
        rows.append(
            {
                "claim": "Smaller clearance gives more frequent, smaller impacts.",
                "verdict": verdict,
                "evidence": "contact events per revolution by clearance (mm): "
                + ", ".join(
                    f"{c:g}: {e:.3g}" for c, e in zip(table.clearance_A_mm, events, strict=True)
                ),
            }
        )
    else:
        rows.append(
            {"claim": claim, "verdict": NOT_EVALUATED, "evidence": "clearance-size not run"}
        )
    claim = "Higher speed gives larger acceleration and torque peaks."
    if "speed_peaks" in inp:
        acc, acc_text = _peak_trend(
            inp["speed_peaks"], "peak_slider_acceleration_m_s2", "speed_rpm"
        )
        tq, tq_text = _peak_trend(inp["speed_peaks"], "peak_drive_torque_N_m", "speed_rpm")
        verdict = "supported" if acc and tq else ("mixed" if acc or tq else "not supported")
        rows.append(
            {
                "claim": claim,
                "verdict": verdict,
                "evidence": f"peak slider acceleration (m/s²) by speed (rpm) {acc_text}; "
                f"peak torque (N·m) {tq_text}",
            }
        )
    else:
        rows.append({"claim": claim, "verdict": NOT_EVALUATED, "evidence": "speed not run"})
    return rows


def claim_flagship_chaos(inp) -> dict:
    claim = (
        "At 0.5 mm and 150 rpm: largest Lyapunov exponent positive for A x, A y, B x and "
        "negative for B y; the Poincaré map of B y stays a single point."
    )
    if "flagship_analysis" not in inp:
        return {"claim": claim, "verdict": NOT_EVALUATED, "evidence": "no chaos analysis"}
    a = _open(inp["flagship_analysis"])
    lam = {str(c): float(a.lyapunov_exponent.sel(channel=c)) for c in a.channel.values}
    verdicts = {str(c): str(a.verdict.sel(channel=c).item()) for c in a.channel.values}
    period = {str(c): int(a.section_period.sel(channel=c)) for c in a.channel.values}
    expected = {"A.x": 1, "A.y": 1, "B.x": 1, "B.y": -1}
    signs = [np.sign(lam.get(c, np.nan)) == s for c, s in expected.items()]
    single = period.get("B.y") == 1
    held = sum(signs) + single
    verdict = "supported" if held == 5 else ("not supported" if held <= 1 else "mixed")
    evidence = "; ".join(
        f"{c}: λ = {lam[c]:.3g} 1/s ({verdicts[c]}, section period {period[c]})" for c in lam
    )
    evidence += (
        f" ({a.attrs['transient_revolutions']} transient, "
        f"{a.sizes['revolution']} analysed revolutions)"
    )
    return {"claim": claim, "verdict": verdict, "evidence": evidence}


def _growth(path) -> tuple[str, str, bool]:
    table = pd.read_csv(path)
    parameter = table.columns[0]
    joints = table[table.quantity == "eccentricity"]
    chaotic = joints.assign(chaotic=joints.verdict == "chaotic").groupby(parameter).chaotic.mean()
    mean_lam = joints.groupby(parameter).lyapunov_exponent_per_s.mean()
    by_point = ", ".join(
        f"{p:g}: {chaotic[p]:.2f} chaotic, mean λ {mean_lam[p]:.3g}" for p in chaotic.index
    )
    grows = (
        len(chaotic) >= 2
        and chaotic.iloc[-1] >= chaotic.iloc[0]
        and (mean_lam.iloc[-1] > mean_lam.iloc[0])
    )
    by = joints[joints.channel == "B.y"]
    by_periodic = bool((by.verdict == "periodic").all()) and len(by) > 0
    by_text = ", ".join(f"{p:g}: {v}" for p, v in zip(by[parameter], by.verdict, strict=True))
    return by_point, by_text, (grows, by_periodic)


def claim_bifurcation(inp) -> dict:
    claim = "Chaos grows with clearance (0 to 1 mm) and with speed; B y stays periodic throughout."
    parts, states = [], []
    for role, what in (("bifurcation_clearance", "clearance"), ("bifurcation_speed", "speed")):
        key = f"{role}_table"
        if key not in inp:
            parts.append(f"{what}: not run")
            continue
        by_point, by_text, (grows, by_periodic) = _growth(inp[key])
        states += [grows, by_periodic]
        parts.append(
            f"{what}: share of chaotic clearance channels and mean λ by value ({by_point}); "
            f"grows: {grows}; B y verdicts ({by_text})"
        )
    if not states:
        verdict = NOT_EVALUATED
    else:
        verdict = "supported" if all(states) else ("not supported" if not any(states) else "mixed")
    return {"claim": claim, "verdict": verdict, "evidence": "; ".join(parts)}


def claim_all_joints(inp) -> dict:
    claim = "Modelling all five clearances is much slower than A and B alone."
    if "all_joints_run" not in inp or "flagship_run" not in inp:
        return {
            "claim": claim,
            "verdict": NOT_EVALUATED,
            "evidence": "all-joints or flagship not run",
        }
    cost = {}
    for role in ("all_joints", "flagship"):
        ds = xr.open_dataset(inp[f"{role}_run"])
        cost[role] = 1.0 / float(ds.attrs["real_time_factor"])
        ds.close()
    ratio = cost["all_joints"] / cost["flagship"]
    verdict = "supported" if ratio > 2 else "not supported"
    evidence = (
        f"solver wall time per simulated second: all joints {cost['all_joints']:.3g} s "
        f"(0.1 mm), A and B {cost['flagship']:.3g} s (0.5 mm); ratio {ratio:.3g} "
        "(different clearance sizes, as in the studies)"
    )
    return {"claim": claim, "verdict": verdict, "evidence": evidence}


def claim_cross_check(inp) -> dict:
    """Our model against an independent code (Exudyn, in place of the paper's ADAMS): the
    largest difference of each response over its peak, per case of the cross-check study."""
    claim = (
        "The model agrees with ADAMS on displacement and velocity, less on acceleration and torque."
    )
    if "cross_check_summary" not in inp:
        return {"claim": claim, "verdict": NOT_EVALUATED, "evidence": "cross-check not run"}
    summary = json.loads(Path(inp["cross_check_summary"]).read_text())
    if not summary.get("ran"):
        reason = summary.get("reason", "Exudyn is not installed")
        return {"claim": claim, "verdict": NOT_EVALUATED, "evidence": f"not run: {reason}"}
    parts, close, rougher = [], True, False
    for name, case in summary["cases"].items():
        shares = {
            signal: stats["raw"]["max"] / stats["raw"]["peak"]
            for signal, stats in case["deterministic"].items()
        }
        parts.append(
            f"{name}: " + ", ".join(f"{signal} {share:.2g}" for signal, share in shares.items())
        )
        if not case["clearance"]:
            smooth = max(shares["displacement"], shares["velocity"])
            close &= smooth < 1e-3
            rougher |= max(shares["acceleration"], shares["drive_torque"]) > smooth
    # Agreement where the motion is deterministic; "less" where the beams vibrate.
    verdict = "supported" if close and rougher else ("mixed" if close else "not supported")
    return {
        "claim": claim,
        "verdict": verdict,
        "evidence": "Exudyn in place of ADAMS; largest difference over the peak, raw signals "
        "(the clearance case separates by chaos: statistics in the cross-check tables): "
        + "; ".join(parts),
    }


def claim_experiment(inp) -> tuple[dict, dict]:
    claim = (
        "The measured slider acceleration follows the model's trend; frequency and peaks differ."
    )
    if "experiment_comparison" not in inp:
        return {"claim": claim, "verdict": NOT_EVALUATED, "evidence": "experiment not run"}, {}
    summary = json.loads(Path(inp["experiment_comparison"]).read_text())
    meta = yaml.safe_load(Path(inp["experiment_meta"]).read_text())
    metrics = summary["metrics"]
    numbers = ", ".join(
        f"{name} {m['mean']:.3g} ± {m['std']:.2g} {m['unit']}" for name, m in metrics.items()
    )
    if meta.get("synthetic"):
        verdict = NOT_EVALUATED
        evidence = (
            f"SYNTHETIC recording only (no rig data): a consistency check, not evidence. {numbers}"
        )
    else:
        corr = metrics.get("correlation", {}).get("mean", np.nan)
        verdict = "supported" if corr > 0.5 else "not supported"
        evidence = f"measured recording: {numbers}"
    return {"claim": claim, "verdict": verdict, "evidence": evidence}, meta


def main(sm) -> None:
    inp = {key: value for key, value in sm.input.items() if key != "template"}
    claims = [
        claim_responses(inp),
        *claim_peaks(inp),
        claim_flagship_chaos(inp),
        claim_bifurcation(inp),
        claim_all_joints(inp),
        claim_cross_check(inp),
    ]
    experiment, meta = claim_experiment(inp)
    claims.append(experiment)
    table = pd.DataFrame(claims)
    table.to_csv(sm.output.csv, index=False)

    scene, assumptions = {}, []
    if "flagship_run" in inp:
        with xr.open_dataset(inp["flagship_run"]) as ds:
            scene = json.loads(ds.attrs["scene"])
            assumptions = json.loads(ds.attrs["assumptions"])
    template = jinja2.Template(Path(sm.input.template).read_text())
    page = template.render(
        claims=claims,
        quick=sm.params.quick,
        studies=sm.params.studies,
        model=sm.params.model,
        assumptions=assumptions,
        scene=scene,
        recording=sm.params.recording,
        recording_meta=meta,
    )
    if "{{" in page or "{%" in page:
        raise ValueError("landing page would be re-rendered by Snakemake's Jinja: remove braces")
    Path(sm.output.rst).write_text(page)
    with open(sm.log[0], "w") as log:
        log.write(table.to_string() + "\n")


main(snakemake)  # noqa: F821 (injected by Snakemake)

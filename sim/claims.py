"""Each claim of docs/studies.md judged on the workflow's results (the report's landing page).

Every judge takes `inputs`, a mapping of role to file (the landing rule's named inputs,
`<role>_<name>` of sim.studies.config.LANDING_INPUTS, and `experiment_meta`), and returns rows
of {claim, short, verdict, key, intervals, evidence}: the claim in full and in a few words, the
key number with its interval in one line, and everything behind it. Numbers have at most three
significant digits; a missing one is said in words. Verdicts (sim.analysis.verdicts):
"supported", "not supported", "mixed" (part of the claim holds and part is contradicted),
"undecided" (a statistical claim that no interval decides against and not every one for), "not
evaluated" (the study is disabled, not run in this configuration, or needs data we do not
have). The claims on peaks and impacts compare distributions of per-revolution peaks over
revolutions and ensemble members with bootstrap intervals; the others are judged on one run,
and say so.
"""

import json
from collections.abc import Mapping
from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr
import yaml

from sim.analysis.revolutions import (
    CONTACT_EVENTS,
    DRIVE_TORQUE,
    SLIDER_ACCELERATION,
    Bootstrap,
    contact_force,
    unit_of,
)
from sim.analysis.verdicts import (
    MIXED,
    NOT_EVALUATED,
    NOT_SUPPORTED,
    SUPPORTED,
    UNDECIDED,
    combine,
    intervals_text,
    trend,
)
from sim.front_page import digits, interval, number
from sim.results import OUTPUT_VARIABLES, output_series
from sim.studies.config import LANDING_INPUTS

Inputs = Mapping[str, str]

#: the input names the judges read: the landing page's table, and the recording's metadata
INPUT_NAMES = frozenset(
    [f"{item.role}_{item.name}" for item in LANDING_INPUTS] + ["experiment_meta"]
)


def _row(
    claim: str, verdict: str, evidence: str, intervals: str = "", *, short: str, key: str
) -> dict:
    """A claim's row: the claim in full and in a few words (`short`), the verdict, the key
    number with its interval in one line (`key`), the intervals and the full evidence."""
    return {
        "claim": claim,
        "short": short,
        "verdict": verdict,
        "key": key,
        "intervals": intervals,
        "evidence": evidence,
    }


def _open(path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def _deviation(run: xr.Dataset, ideal: xr.Dataset, variable: str) -> float:
    """Largest |run − ideal| over the ideal's range (after the first revolution); of the
    run's output channel (its scene's `output`) for a quantity of the bodies."""
    if variable in OUTPUT_VARIABLES:
        data, ref = output_series(run, variable), output_series(ideal, variable)
    else:
        data, ref = run[variable], ideal[variable]
    start = float(run.attrs["crank_period"])
    data = data.sel(time=slice(start, None))
    ref = ref.interp(time=data.time)
    return float(np.abs(data - ref).max() / (ref.max() - ref.min()))


def claim_responses(inputs: Inputs) -> dict:
    """Slider motion close to ideal, acceleration and torque peaky: one run (the flagship's
    nominal member) against its ideal reference."""
    claim = (
        "Displacement and velocity of the slider stay close to ideal; acceleration and "
        "driving torque show sharp peaks and vibration from impacts."
    )
    short = "Slider motion near ideal; acceleration and torque peaky"
    if "flagship_run" not in inputs:
        return _row(claim, NOT_EVALUATED, "flagship not run", short=short, key="flagship not run")
    run, ideal = _open(inputs["flagship_run"]), _open(inputs["flagship_ideal"])
    dev = {v: _deviation(run, ideal, v) for v in ("position", "velocity", "acceleration")}
    dev["drive_torque"] = _deviation(run, ideal, "drive_torque")
    close = dev["position"] < 0.05 and dev["velocity"] < 0.2
    peaky = dev["acceleration"] > 0.5 and dev["drive_torque"] > 0.5
    verdict = SUPPORTED if close and peaky else (MIXED if close or peaky else NOT_SUPPORTED)
    evidence = (
        "flagship, largest deviation from ideal over the ideal's range: displacement "
        f"{dev['position']:.3g}, velocity {dev['velocity']:.3g}, acceleration "
        f"{dev['acceleration']:.3g}, torque {dev['drive_torque']:.3g} "
        "(close: displacement < 0.05 and velocity < 0.2; peaks: acceleration and torque > 0.5)"
    )
    key = (
        f"off ideal, of its range: displacement {dev['position']:.2g}, velocity "
        f"{dev['velocity']:.2g}, acceleration {dev['acceleration']:.2g}, torque "
        f"{dev['drive_torque']:.2g}"
    )
    return _row(claim, verdict, evidence, short=short, key=key)


def _ordered(peaks_csv: str, column: str) -> tuple[list[str], pd.DataFrame]:
    """Cases in increasing order of a setting (peaks table column), and the table."""
    table = pd.read_csv(peaks_csv).sort_values(column)
    return list(table.case), table


def _ensemble_note(revolutions: pd.DataFrame) -> str:
    members = revolutions.groupby("case").member.nunique()
    per = revolutions.groupby(["case", "member"]).size().groupby("case").min()
    return ", ".join(
        f"{case}: {members[case]} members × {per[case]} revolutions" for case in per.index
    )


def _single_run_maxima(table: pd.DataFrame, column: str, setting: str, unit: str) -> str:
    """The nominal run's whole-run maxima, shown for reference (not used by the verdict)."""
    return ", ".join(f"{row[column]:g} {unit}: {row[setting]:.4g}" for _, row in table.iterrows())


def _trend_claim(
    claim: str,
    short: str,
    inputs: Inputs,
    role: str,
    setting: str,
    unit: str,
    quantities: dict[str, int],
    boot: Bootstrap,
) -> dict:
    """A claim that some per-revolution peaks grow (+1) or shrink (−1) with a setting."""
    cases, peaks = _ordered(inputs[f"{role}_peaks"], setting)
    revolutions = pd.read_csv(inputs[f"{role}_revolutions"])
    components = trend(revolutions, cases, quantities, boot)
    evidence = (
        f"per-revolution peaks ({_ensemble_note(revolutions)}), cases by {setting.split('_')[0]} "
        f"({unit}): "
        + ", ".join(f"{c} = {v:g}" for c, v in zip(peaks.case, peaks[setting], strict=True))
        + "; whole-run maximum of the nominal run, slider acceleration (m/s²) "
        + _single_run_maxima(peaks, setting, "peak_slider_acceleration_m_s2", unit)
    )
    return _row(
        claim,
        combine([c.verdict for c in components]),
        evidence,
        intervals_text(components),
        short=short,
        key=_medians_text(components),
    )


def _medians_text(components: list) -> str:
    """A trend claim's key line: how many components hold, and the difference of the medians
    of each quantity with its interval."""
    held = sum(c.verdict == SUPPORTED for c in components)
    medians = "; ".join(
        f"{c.quantity.replace('_', ' ')} {digits(c.estimate, '+')} "
        + interval(*c.interval, unit_of(c.quantity))
        for c in components
        if c.statistic == "median"
    )
    return f"{held} of {len(components)} components hold; medians, high − low: {medians}"


def claim_peaks(inputs: Inputs, boot: Bootstrap) -> list[dict]:
    """Peaks against clearance and speed, and impacts against clearance: tests on the
    distributions of per-revolution peaks (sim.analysis.verdicts)."""
    rows = []
    grow = {SLIDER_ACCELERATION: +1, DRIVE_TORQUE: +1}
    claim = "Larger clearance gives larger acceleration and torque peaks."
    short = "Larger clearance, larger peaks"
    impacts = "Smaller clearance gives more frequent, smaller impacts."
    impacts_short = "Smaller clearance, more and smaller impacts"
    if "clearance_size_revolutions" in inputs:
        rows.append(
            _trend_claim(claim, short, inputs, "clearance_size", "clearance_A_mm", "mm", grow, boot)
        )
        joints = [
            c[len("peak_contact_force_") : -len("_N")]
            for c in pd.read_csv(inputs["clearance_size_peaks"]).columns
            if c.startswith("peak_contact_force_")
        ]
        fewer_larger = {CONTACT_EVENTS: -1, **{contact_force(j): +1 for j in joints}}
        rows.append(
            _trend_claim(
                impacts,
                impacts_short,
                inputs,
                "clearance_size",
                "clearance_A_mm",
                "mm",
                fewer_larger,
                boot,
            )
        )
    else:
        for text, words in ((claim, short), (impacts, impacts_short)):
            rows.append(_not_run(text, words, "clearance-size"))
    claim = "Higher speed gives larger acceleration and torque peaks."
    short = "Higher speed, larger peaks"
    if "speed_revolutions" in inputs:
        rows.append(_trend_claim(claim, short, inputs, "speed", "speed_rpm", "rpm", grow, boot))
    else:
        rows.append(_not_run(claim, short, "speed"))
    return rows


def _not_run(claim: str, short: str, what: str) -> dict:
    """The row of a claim whose study did not run in this configuration."""
    return _row(claim, NOT_EVALUATED, f"{what} not run", short=short, key=f"{what} not run")


#: why the model-based exponent and the per-channel time-series exponents differ
MODEL_AND_CHANNEL_EXPONENTS = (
    "They differ because they measure different things: the model exponent follows two nearby "
    "states of the whole mechanism through its own equations, impacts included, so it is one "
    "number, the linkage's; a time-series exponent embeds one channel's samples in delays and "
    "fits the divergence of neighbours, which the impacts' non-smooth jumps, the embedding and "
    "the fit range all bias, and which can differ between channels of the same motion (a "
    "negative B y beside a positive A x is the paper's reading, not a second exponent)."
)


#: the paper's reading of its Table 3, as the verdicts of the flagship's channels: a positive
#: largest exponent for A x, A y and B x (chaotic), a negative one for B y (periodic)
FLAGSHIP_VERDICTS = {"A.x": "chaotic", "A.y": "chaotic", "B.x": "chaotic", "B.y": "periodic"}


def _channel_component(verdict: str, expected: str) -> str:
    """A channel's part of a claim: supported when its verdict is the expected one, undecided
    when its indicators decide nothing, not supported when they decide otherwise."""
    if verdict == expected:
        return SUPPORTED
    return UNDECIDED if verdict == "undecided" else NOT_SUPPORTED


def flagship_verdicts(a: xr.Dataset) -> tuple[str, dict[str, str], dict[str, int]]:
    """Claim 5 on one chaos analysis `a` of the flagship: its verdict (each channel of
    FLAGSHIP_VERDICTS judged as expected, and B y's Poincaré map a single point), each
    channel's verdict and its section period."""
    verdicts = {str(c): str(a.verdict.sel(channel=c).item()) for c in a.channel.values}
    period = {str(c): int(a.section_period.sel(channel=c)) for c in a.channel.values}
    components = [
        _channel_component(verdicts.get(c, "undecided"), v) for c, v in FLAGSHIP_VERDICTS.items()
    ]
    components.append(SUPPORTED if period.get("B.y") == 1 else NOT_SUPPORTED)
    return combine(components), verdicts, period


def claim_flagship_chaos(inputs: Inputs) -> dict:
    """The verdicts of A x, A y, B x (chaotic) and B y (periodic, a single section point), each
    from its decided indicators (sim.analysis.classify): one run."""
    claim = (
        "At 0.5 mm and 150 rpm: largest Lyapunov exponent positive for A x, A y, B x and "
        "negative for B y; the Poincaré map of B y stays a single point."
    )
    short = "Flagship: A x, A y, B x chaotic; B y periodic"
    if "flagship_analysis" not in inputs:
        return _row(claim, NOT_EVALUATED, "no chaos analysis", short=short, key="not run")
    a = _open(inputs["flagship_analysis"])
    verdict, verdicts, period = flagship_verdicts(a)
    lam = {str(c): float(a.lyapunov_exponent.sel(channel=c)) for c in a.channel.values}
    evidence = "; ".join(
        f"{c}: λ {'= ' if np.isfinite(lam[c]) else ''}"
        f"{number(lam[c], '1/s', 'not estimated')} ({verdicts[c]}, section period {period[c]})"
        for c in lam
    )
    key = ", ".join(f"{c} {verdicts[c]}" for c in FLAGSHIP_VERDICTS if c in verdicts)
    evidence += (
        f" ({a.attrs['transient_revolutions']} transient, "
        f"{a.sizes['revolution']} analysed revolutions; one run)"
    )
    model = None
    if "flagship_model_exponents" in inputs:
        _, (primary, *beside) = exponents_by_case(inputs["flagship_model_exponents"])[0]
        model = _members_text(primary)
        model += "".join(f"; beside it, {_members_text(row)}" for row in beside)
        key = f"model exponent {members_summary(primary)}; {key}"
    elif "model_lyapunov_exponent" in a:
        model = (
            f"{float(a.model_lyapunov_exponent):.3g} ± {float(a.model_lyapunov_stderr):.2g} 1/s "
            "(one run)"
        )
        key = f"model exponent {model}; {key}"
    if model is not None:
        evidence = (
            "model-based largest exponent of the linkage (Benettin on the model's own "
            f"integrator): {model}. Per-channel verdicts, from the decided indicators (the "
            f"Poincaré period, the exponents, the 0–1 test): {evidence}. "
            + MODEL_AND_CHANNEL_EXPONENTS
        )
    return _row(claim, verdict, evidence, short=short, key=key)


#: the link model of the members' exponent (the study's `model_lyapunov.links`) in words, with
#: what the model convergence measured of it (docs/exponent.md, "Model convergence")
MEMBER_LINKS = {
    "rigid": "rigid links",
    "modal": (
        "modal links of one bending mode each, which read about 10 % below four modes and "
        "18 % below the ANCF beams on the flagship (docs/exponent.md)"
    ),
}


def _members_text(row: pd.Series) -> str:
    """A case's model exponent over its members (a row of the model_exponent table)."""
    n = int(row.members)
    stderr = f"mean member standard error {row.mean_member_stderr_per_s:.2g} 1/s"
    links = MEMBER_LINKS.get(row.links, "the run's links")
    span = f"{links}, {row.revolutions:g} revolutions, {row.transient_revolutions:g} transient"
    if n == 1:
        return (
            f"{row.median_exponent_per_s:.3g} ± {row.mean_member_stderr_per_s:.2g} 1/s "
            f"(one member: no interval over members; {span})"
        )
    return (
        f"median over {n} members {row.median_exponent_per_s:.3g} 1/s, interval "
        f"[{row.interval_low_per_s:.3g}, {row.interval_high_per_s:.3g}] 1/s "
        f"({row.interval_coverage:.1%} distribution-free coverage of the median), {stderr} "
        f"({span})"
    )


def members_summary(row: pd.Series) -> str:
    """A case's model exponent over its members in a few words (a row of a model_exponent
    table): the median and its interval (one member: ± its standard error)."""
    if int(row.members) == 1:
        return (
            f"{number(row.median_exponent_per_s)} ± {number(row.mean_member_stderr_per_s, '1/s')}"
        )
    bounds = interval(row.interval_low_per_s, row.interval_high_per_s, "1/s", missing="")
    if not bounds:
        return f"{number(row.median_exponent_per_s, '1/s')} (no interval)"
    return f"{number(row.median_exponent_per_s)} {bounds}"


def exponents_by_case(path) -> list[tuple[str, list[pd.Series]]]:
    """The rows of a model_exponent table case by case, each case's primary link model (the
    study's `model_lyapunov.links`, the one its verdicts read) first."""
    table = pd.read_csv(path)
    if "primary" not in table:
        table["primary"] = True
    return [
        (
            str(case),
            [
                row
                for _, row in part.sort_values("primary", ascending=False, kind="stable").iterrows()
            ],
        )
        for case, part in table.groupby("case", sort=False)
    ]


def exponent_comparison(inputs: Inputs) -> list[dict]:
    """The model exponent of every ensemble case of the studies the landing page reads, on each
    link model the study takes it on (`model_lyapunov.links`, then `compare`): one row per case,
    {role, case, exponents: [(links, primary, members text)]}, the primary link model first."""
    return [
        {
            "role": key.removesuffix("_model_exponents").replace("_", " "),
            "case": case,
            "exponents": [(str(r.links), bool(r.primary), _members_text(r)) for r in rows],
        }
        for key, path in inputs.items()
        if key.endswith("_model_exponents")
        for case, rows in exponents_by_case(path)
    ]


def _third_text(
    table: pd.DataFrame, parameter: str, values: np.ndarray
) -> tuple[float, float, str]:
    """Share of chaotic channels and median model exponent over the points of ``values``."""
    part = table[table[parameter].isin(values)]
    share = float((part.verdict == "chaotic").mean())
    lam = float(part.groupby(parameter).model_lyapunov_exponent_per_s.first().median())
    text = (
        f"{values[0]:g} to {values[-1]:g} ({len(values)} points): {share:.2f} of the channels "
        f"chaotic, median model exponent {lam:.3g} 1/s"
    )
    return share, lam, text


def _listed(items: list[str], limit: int = 5) -> str:
    """The first ``limit`` items joined by commas, an ellipsis for the rest."""
    return ", ".join(items[:limit]) + (", …" if len(items) > limit else "")


def chaotic_points(table: pd.DataFrame, values: np.ndarray) -> np.ndarray:
    """For each of a sweep's points ``values``, whether some channel is judged chaotic there
    in ``table`` (a bifurcation table, the parameter its first column)."""
    return np.isin(values, table.loc[table.verdict == "chaotic", table.columns[0]])


def chaos_onset(table: pd.DataFrame, values: np.ndarray) -> int | None:
    """The index in ``values`` (a sweep's points, increasing) of the lowest point with a
    channel judged chaotic in ``table``; None when there is none."""
    chaotic = chaotic_points(table, values)
    return int(np.argmax(chaotic)) if chaotic.any() else None


def _onset_text(table: pd.DataFrame, parameter: str, values: np.ndarray) -> str:
    """Where chaos starts along a sweep: the lowest point with a channel judged chaotic, how
    many points from there on have one, and the stretches of consecutive points without one
    (periodic windows, or points no indicator decides)."""
    start = chaos_onset(table, values)
    if start is None:
        return "no point has a chaotic channel"
    chaotic = chaotic_points(table, values)
    after, rest = chaotic[start:], values[start:]
    # a window opens where a chaotic point is followed by a regular one and closes before
    # the next chaotic one (or at the sweep's end)
    edges = np.flatnonzero(np.diff(np.r_[True, after, True].astype(int)))
    windows = [
        f"{rest[a]:g}" if b - a == 1 else f"{rest[a]:g}–{rest[b - 1]:g}"
        for a, b in zip(edges[::2], edges[1::2], strict=True)
    ]
    onset = (
        f"chaos starts at {values[start]:g}: {int(after.sum())} of {after.size} points from "
        "there on have a chaotic channel"
    )
    return onset + (f", none at {_listed(windows)}" if windows else "")


def growth(path) -> tuple[str, str, tuple[bool, bool], str]:
    """Chaos at the low against the high end of a sweep (the lowest and the highest third of
    its points, at least one each), where it starts, B y's verdicts along it, and the key
    numbers in a few words."""
    table = pd.read_csv(path)
    parameter = table.columns[0]
    values = np.sort(table[parameter].unique())
    third = max(1, -(-len(values) // 3))
    low, low_lam, low_text = _third_text(table, parameter, values[:third])
    high, high_lam, high_text = _third_text(table, parameter, values[-third:])
    grows = len(values) >= 2 and high >= low and high_lam > low_lam
    by = table[table.channel == "B.y"]
    not_periodic = by[by.verdict != "periodic"][parameter].to_numpy()
    by_periodic = len(by) > 0 and not_periodic.size == 0
    by_text = f"periodic at {len(by) - not_periodic.size} of {len(by)} points" + (
        f" (not at {_listed([f'{v:g}' for v in not_periodic])})" if not_periodic.size else ""
    )
    ends = f"low end {low_text}; high end {high_text}; {_onset_text(table, parameter, values)}"
    start = chaos_onset(table, values)
    key = (
        f"chaotic channels {low:.0%} → {high:.0%}, "
        + ("none chaotic" if start is None else f"chaos from {values[start]:g}")
        + f", B y periodic at {len(by) - not_periodic.size} of {len(by)} points"
    )
    return ends, by_text, (bool(grows), by_periodic), key


def states_verdict(states: list[bool]) -> str:
    """A claim of several parts, each held or not: supported when all hold, not supported when
    none does, mixed between; not evaluated without parts."""
    if not states:
        return NOT_EVALUATED
    return SUPPORTED if all(states) else (NOT_SUPPORTED if not any(states) else MIXED)


def claim_bifurcation(inputs: Inputs) -> dict:
    """Chaos against clearance and speed: the verdicts of the dense sweeps (model exponent,
    0–1 K and Poincaré period per point), low end against high end."""
    claim = "Chaos grows with clearance (0 to 1 mm) and with speed; B y stays periodic throughout."
    short = "Chaos grows with clearance and speed; B y periodic"
    parts, states, keys = [], [], []
    for role, what in (("bifurcation_clearance", "clearance"), ("bifurcation_speed", "speed")):
        if f"{role}_table" not in inputs:
            parts.append(f"{what}: not run")
            keys.append(f"{what}: not run")
            continue
        ends, by_text, (grows, by_periodic), key = growth(inputs[f"{role}_table"])
        keys.append(f"{what}: {key}")
        states += [grows, by_periodic]
        drawn = ""
        if f"{role}_dataset" in inputs:
            with xr.open_dataset(inputs[f"{role}_dataset"]) as ds:
                drawn = f" (drawn on {ds.attrs.get('model', 'an unrecorded model')})"
        parts.append(f"{what}{drawn}: {ends}; grows: {grows}; B y {by_text}")
    return _row(claim, states_verdict(states), "; ".join(parts), short=short, key="; ".join(keys))


def claim_all_joints(inputs: Inputs) -> dict:
    """Cost of all five clearances against A and B: solver wall time per simulated second."""
    claim = "Modelling all five clearances is much slower than A and B alone."
    short = "All five clearances much slower"
    if "all_joints_run" not in inputs or "flagship_run" not in inputs:
        return _not_run(claim, short, "all-joints or flagship")
    cost = {}
    for role in ("all_joints", "flagship"):
        with xr.open_dataset(inputs[f"{role}_run"]) as ds:
            cost[role] = 1.0 / float(ds.attrs["real_time_factor"])
    ratio = cost["all_joints"] / cost["flagship"]
    verdict = SUPPORTED if ratio > 2 else NOT_SUPPORTED
    evidence = (
        f"solver wall time per simulated second: all joints {cost['all_joints']:.3g} s "
        f"(0.1 mm), A and B {cost['flagship']:.3g} s (0.5 mm); ratio {ratio:.3g} "
        "(different clearance sizes, as in the studies)"
    )
    key = f"wall time per simulated second, all joints over A and B: {ratio:.3g}"
    return _row(claim, verdict, evidence, short=short, key=key)


def claim_cross_check(inputs: Inputs) -> dict:
    """Our model against an independent code (Exudyn, in place of the paper's ADAMS): the
    largest difference of each response over its peak, per case of the cross-check study."""
    claim = (
        "The model agrees with ADAMS on displacement and velocity, less on acceleration and torque."
    )
    short = "Agrees with ADAMS (here Exudyn)"
    if "cross_check_summary" not in inputs:
        return _not_run(claim, short, "cross-check")
    summary = json.loads(Path(inputs["cross_check_summary"]).read_text())
    if not summary.get("ran"):
        reason = summary.get("reason", "Exudyn is not installed")
        why = f"not run: {reason}"
        return _row(claim, NOT_EVALUATED, why, short=short, key=why)
    parts, close, rougher, worst = [], True, False, {}
    for name, case in summary["cases"].items():
        # error_norms (sim.crosscheck.compare) gives the largest difference over the peak
        shares = {signal: stats["raw"]["max"] for signal, stats in case["deterministic"].items()}
        parts.append(
            f"{name}: " + ", ".join(f"{signal} {share:.2g}" for signal, share in shares.items())
        )
        if not case["clearance"]:
            for signal, share in shares.items():
                worst[signal] = max(worst.get(signal, 0.0), share)
            smooth = max(shares["displacement"], shares["velocity"])
            close &= smooth < 1e-3
            rougher |= max(shares["acceleration"], shares["drive_torque"]) > smooth
    # Agreement where the motion is deterministic; "less" where the beams vibrate.
    verdict = SUPPORTED if close and rougher else (MIXED if close else NOT_SUPPORTED)
    key = "largest difference over the peak without clearance: " + ", ".join(
        f"{signal.replace('_', ' ')} {share:.2g}" for signal, share in worst.items()
    )
    return _row(
        claim,
        verdict,
        "Exudyn in place of ADAMS; largest difference over the peak, raw signals "
        "(with clearance the runs separate by chaos, or are compared at their first impact: "
        "the cross-check tables): " + "; ".join(parts),
        short=short,
        key=key,
    )


def claim_experiment(inputs: Inputs) -> tuple[dict, dict]:
    """The model against the accelerometer recording; and the recording's metadata."""
    claim = (
        "The measured slider acceleration follows the model's trend; frequency and peaks differ."
    )
    short = "Measured acceleration follows the model's trend"
    if "experiment_comparison" not in inputs:
        return _not_run(claim, short, "experiment"), {}
    summary = json.loads(Path(inputs["experiment_comparison"]).read_text())
    meta = yaml.safe_load(Path(inputs["experiment_meta"]).read_text())
    metrics = summary["metrics"]
    numbers = ", ".join(
        f"{name} {m['mean']:.3g} ± {m['std']:.2g} {m['unit']}" for name, m in metrics.items()
    )
    correlation = metrics.get("correlation", {}).get("mean", np.nan)
    key = f"correlation {number(correlation, missing='not computed')}"
    if meta.get("synthetic"):
        verdict = NOT_EVALUATED
        evidence = (
            f"SYNTHETIC recording only (no rig data): a consistency check, not evidence. {numbers}"
        )
        key = f"synthetic recording: a consistency check only ({key})"
    else:
        verdict = SUPPORTED if correlation > 0.5 else NOT_SUPPORTED
        evidence = f"measured recording: {numbers}"
    return _row(claim, verdict, evidence, short=short, key=key), meta


def judge_all(inputs: Inputs, boot: Bootstrap) -> tuple[list[dict], dict]:
    """Every claim's row, in the report's order, and the recording's metadata."""
    unknown = sorted(set(inputs) - INPUT_NAMES)
    if unknown:
        raise ValueError(f"landing inputs {unknown}: not in sim.studies.config.LANDING_INPUTS")
    experiment, meta = claim_experiment(inputs)
    claims = [
        claim_responses(inputs),
        *claim_peaks(inputs, boot),
        claim_flagship_chaos(inputs),
        claim_bifurcation(inputs),
        claim_all_joints(inputs),
        claim_cross_check(inputs),
        experiment,
    ]
    return claims, meta

"""Tables of the workflow (peak values, work–precision, extremes) and their figures."""

import json

import numpy as np
import pandas as pd
import xarray as xr
from matplotlib.figure import Figure

from sim.plots import style


def peaks_table(cases: list[str], runs: list[xr.Dataset], ideals: list[xr.Dataset]) -> pd.DataFrame:
    """Tables 4 and 5 of the paper: per case, the peak slider acceleration (m/s², along the
    guide) and peak driving torque (N·m) with clearance and for the ideal mechanism, their
    ratio, the peak contact force per clearance joint (N), the contact events per crank
    revolution and the solver's wall time per simulated second."""
    rows = []
    for case, run, ideal in zip(cases, runs, ideals, strict=True):
        scene = json.loads(run.attrs["scene"])
        revolutions = float(run.attrs["simulated_time_s"]) / float(run.attrs["crank_period"])
        acc = float(run.peak_acceleration.sel(body="slider", axis="y"))
        acc_ideal = float(ideal.peak_acceleration.sel(body="slider", axis="y"))
        torque = float(run.peak_drive_torque)
        torque_ideal = float(ideal.peak_drive_torque)
        row = {
            "case": case,
            "speed_rpm": scene["drive"]["speed_rpm"],
            "clearance_A_mm": scene["joints"]["A"]["clearance"] * 1e3,
            "clearance_B_mm": scene["joints"]["B"]["clearance"] * 1e3,
            "peak_slider_acceleration_m_s2": acc,
            "ideal_peak_slider_acceleration_m_s2": acc_ideal,
            "acceleration_peak_ratio": acc / acc_ideal if acc_ideal else np.nan,
            "peak_drive_torque_N_m": torque,
            "ideal_peak_drive_torque_N_m": torque_ideal,
            "torque_peak_ratio": torque / torque_ideal if torque_ideal else np.nan,
        }
        for joint in run.joint.values:
            row[f"peak_contact_force_{joint}_N"] = float(run.peak_normal_force.sel(joint=joint))
        row["contact_events_per_revolution"] = run.attrs["solver_contact_events"] / revolutions
        row["wall_time_per_simulated_s"] = 1.0 / float(run.attrs["real_time_factor"])
        rows.append(row)
    return pd.DataFrame(rows)


def work_precision_table(
    cases: list[str], runs: list[xr.Dataset], reference: str, revolutions: float = 2.0
) -> pd.DataFrame:
    """Work against precision: per case, the solver's wall time (s), steps, function
    evaluations and the error of the slider acceleration (m/s², along the guide) over the
    first ``revolutions`` crank revolutions against the ``reference`` case (RMS and maximum,
    and RMS over the reference's RMS)."""
    by_name = dict(zip(cases, runs, strict=True))
    ref = by_name[reference]
    period = float(ref.attrs["crank_period"])
    window = slice(0.0, revolutions * period)
    ref_acc = ref.acceleration.sel(body="slider", axis="y", time=window)
    scale = float(np.sqrt(np.mean(ref_acc.values**2)))
    rows = []
    for case, run in by_name.items():
        scene = json.loads(run.attrs["scene"])
        acc = run.acceleration.sel(body="slider", axis="y", time=window).interp(time=ref_acc.time)
        diff = acc.values - ref_acc.values
        rms = float(np.sqrt(np.nanmean(diff**2)))
        rows.append(
            {
                "case": case,
                "rtol": scene["solver"]["rtol"],
                "atol": scene["solver"]["atol"],
                "links": ",".join(sorted({b["kind"] for b in scene["bodies"].values()})),
                "wall_time_s": float(run.attrs["solver_wall_time_s"]),
                "accepted_steps": int(run.attrs["solver_accepted_steps"]),
                "function_evaluations": int(run.attrs["solver_function_evaluations"]),
                "rms_error_m_s2": rms,
                "max_error_m_s2": float(np.nanmax(np.abs(diff))),
                "relative_rms_error": rms / scale if scale else np.nan,
                "is_reference": case == reference,
            }
        )
    return pd.DataFrame(rows)


def plot_work_precision(table: pd.DataFrame) -> Figure:
    """Work–precision diagram: solver wall time (s) against the relative RMS error of the
    slider acceleration (against the reference case), log–log, one labelled point per case;
    the reference (error zero by definition) is left out."""
    with style.style():
        fig = style.figure(5.5, 4.0)
        ax = fig.subplots()
        rows = table[~table.is_reference]
        ax.loglog(rows.relative_rms_error, rows.wall_time_s, "o-", color=style.CLEARANCE)
        for _, row in rows.iterrows():
            ax.annotate(
                row.case,
                (row.relative_rms_error, row.wall_time_s),
                fontsize=7,
                xytext=(3, 3),
                textcoords="offset points",
            )
        reference = table[table.is_reference].case.tolist()
        ax.set_xlabel(f"relative RMS error of slider acceleration against {reference[0]} [–]")
        ax.set_ylabel("solver wall time [s]")
        ax.set_title("Work against precision")
    return fig


EXTREME_COLUMNS = [
    "case",
    "result",
    "outcome",
    "exit_code",
    "wall_time_s",
    "energy_error_relative",
    "constraint_violation_m",
    "ideal_displacement_difference_m",
    "contact_events",
    "message",
    "command",
]


def extremes_table(statuses: list[dict]) -> pd.DataFrame:
    """Pass/fail table of the extremes study, one row per case: result (pass, fail,
    incomplete), outcome, exit code, wall time (s), energy audit (share of the energy
    scale), largest constraint violation (m), difference from the ideal joint (m, clearance
    0 only), contact events, sim's message and the command to reproduce it."""
    table = pd.DataFrame(statuses)
    for column in EXTREME_COLUMNS:
        if column not in table:
            table[column] = np.nan
    return table[EXTREME_COLUMNS]


def to_html(table: pd.DataFrame, title: str, note: str = "") -> str:
    """A self-contained HTML page of a table (for the report)."""
    body = table.to_html(index=False, float_format=lambda v: f"{v:.4g}", na_rep="–")
    return (
        "<!DOCTYPE html><html><head><meta charset='utf-8'>"
        f"<title>{title}</title><style>body{{font-family:sans-serif;font-size:12px}}"
        "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:2px 6px}"
        "</style></head><body>"
        f"<h3>{title}</h3><p>{note}</p>{body}</body></html>\n"
    )

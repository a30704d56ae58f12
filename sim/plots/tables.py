"""Tables of the workflow (peak values, work–precision, extremes) and their figures."""

from pathlib import Path

import numpy as np
import pandas as pd
import xarray as xr
from matplotlib.figure import Figure
from matplotlib.ticker import FuncFormatter, NullFormatter

from sim.plots import style
from sim.results import output_series, scene_of
from sim.studies import fidelity


def peaks_table(cases: list[str], runs: list[xr.Dataset], ideals: list[xr.Dataset]) -> pd.DataFrame:
    """Tables 4 and 5 of the paper: per case, the peak acceleration of the output channel
    (m/s², the scene's `output`: the slider along its guide) and peak driving torque (N·m)
    with clearance and for the ideal mechanism, their ratio, each clearance joint's clearance
    (mm) and peak contact force (N), the contact events per crank revolution and the solver's
    wall time per simulated second."""
    rows = []
    for case, run, ideal in zip(cases, runs, ideals, strict=True):
        scene = scene_of(run)
        revolutions = float(run.attrs["simulated_time_s"]) / float(run.attrs["crank_period"])
        acc = float(output_series(run, "peak_acceleration"))
        acc_ideal = float(output_series(ideal, "peak_acceleration"))
        torque = float(run.peak_drive_torque)
        torque_ideal = float(ideal.peak_drive_torque)
        row = {"case": case, "speed_rpm": scene["drive"]["speed_rpm"]}
        for joint in run.joint.values:
            row[f"clearance_{joint}_mm"] = scene["joints"][str(joint)]["clearance"] * 1e3
        row |= {
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


def _modal_label(body: dict) -> str:
    """A modal link's modes: "3" (bending only) or "3+2 axial"."""
    axial = body.get("axial_modes", 0)
    return f"{body['modes']}+{axial} axial" if axial else str(body["modes"])


def _setting(case: str, run: xr.Dataset) -> dict:
    """What a run of the fidelity study was: integrator, tolerances, link model, clearances,
    duration and output rate, and what it cost (integrator wall time in s, real-time factor)."""
    scene = scene_of(run)
    elements = sorted({b["elements"] for b in scene["bodies"].values() if b["kind"] == "beam"})
    modes = sorted({_modal_label(b) for b in scene["bodies"].values() if b["kind"] == "modal"})
    links = "beam " + ",".join(map(str, elements)) if elements else "rigid"
    if modes:
        links = "modal " + ",".join(map(str, modes)) + ("" if links == "rigid" else " " + links)
    clearances = [name for name, joint in scene["joints"].items() if joint["clearance"] > 0]
    return {
        "case": case,
        "method": scene["solver"]["method"],
        "rtol": scene["solver"]["rtol"],
        "atol": scene["solver"]["atol"],
        "links": links,
        "clearances": ",".join(clearances),
        "revolutions": scene["simulation"]["revolutions"],
        "output_per_revolution": scene["simulation"]["output_per_revolution"],
        "wall_time_s": float(run.attrs["solver_wall_time_s"]),
        "real_time_factor": float(run.attrs["real_time_factor"]),
        "accepted_steps": int(run.attrs["solver_accepted_steps"]),
        "energy_error_relative": float(run.attrs["energy_error_relative"]),
    }


def _pointwise(run: xr.Dataset, reference: xr.Dataset, window: float, prefix: str) -> dict:
    errors = fidelity.short_horizon_errors(run, reference, revolutions=window)
    out = {f"{prefix}rms_{name}": rms for name, (rms, _) in errors.items()}
    return out | {f"{prefix}max_{name}": largest for name, (_, largest) in errors.items()}


def work_precision_table(
    cases: list[str],
    runs: list[xr.Dataset],
    *,
    reference: str,
    window: float,
    analyses: dict[str, xr.Dataset] | None = None,
    long_reference: str | None = None,
    transient: int = 0,
) -> pd.DataFrame:
    """Work against precision, one row per case (sim.studies.fidelity for the measures).

    Every case: its setting and cost (integrator wall time in s, real-time factor).
    Short horizon, for the cases sampled on the ``reference`` case's grid: the RMS and maximum
    error over the first ``window`` revolutions of slider acceleration, driving torque and
    joint A eccentricity, relative to the reference's peak, against ``reference``
    (``error_*``) and against the same model (links and clearances) at its tightest
    tolerance (``solver_*``: the integrator's share), and the separation time in revolutions
    (joint A eccentricity 10 % of its peak apart from the reference; inf: not within the run).
    Long horizon, for the cases in ``analyses`` (chaos analyses after ``transient``
    revolutions) against ``long_reference``: relative peak differences (``peak_*``), the
    Lyapunov exponent differences in 1/s (``lyapunov_*``) and the Poincaré distances over the
    clearance (``poincare_*``).
    """
    by_name = dict(zip(cases, runs, strict=True))
    rows = {case: _setting(case, run) for case, run in by_name.items()}
    grid = rows[reference]["output_per_revolution"]
    short = [c for c in cases if rows[c]["output_per_revolution"] % grid == 0]
    ref = by_name[reference]
    period = float(ref.attrs["crank_period"])
    for case in short:
        model = (rows[case]["links"], rows[case]["clearances"])
        same = [c for c in short if (rows[c]["links"], rows[c]["clearances"]) == model]
        own = min(same, key=lambda c: rows[c]["rtol"])
        rows[case] |= _pointwise(by_name[case], ref, window, "error_")
        rows[case] |= _pointwise(by_name[case], by_name[own], window, "solver_")
        rows[case]["solver_reference"] = own
        rows[case]["separation_revolutions"] = fidelity.separation_time(by_name[case], ref) / period
    analyses = analyses or {}
    if long_reference is not None and long_reference in analyses:
        long_ref = by_name[long_reference]
        for case, analysis in analyses.items():
            run = by_name[case]
            differences = {
                **{f"peak_{k}": v for k, v in fidelity.peak_differences(run, long_ref).items()},
                **{
                    f"lyapunov_{k}": v
                    for k, v in fidelity.lyapunov_differences(
                        analysis, analyses[long_reference]
                    ).items()
                },
                **{
                    f"poincare_{k}": v
                    for k, v in fidelity.poincare_distances(
                        run, long_ref, transient_revolutions=transient
                    ).items()
                },
            }
            rows[case] |= differences
    table = pd.DataFrame(list(rows.values()))
    table["is_reference"] = table.case == reference
    table["is_long_reference"] = table.case == long_reference
    return table


def _series(table: pd.DataFrame):
    """Rows grouped by model and integrator, each in order of tolerance."""
    for (method, links, clearances), rows in table.groupby(
        ["method", "links", "clearances"], sort=False
    ):
        yield f"{method}, {links}, {clearances}", rows.sort_values("rtol")


def _plain_log_labels(axis, limits: tuple[float, float]) -> None:
    """Plain numbers on a log axis; its minor ticks labelled only when it spans less than a
    decade (otherwise they crowd)."""
    plain = FuncFormatter(lambda value, _: f"{value:.3g}")
    axis.set_major_formatter(plain)
    narrow = limits[1] < 10 * limits[0]
    axis.set_minor_formatter(plain if narrow else NullFormatter())


def _work_panel(
    ax, table: pd.DataFrame, column: str, title: str, xlabel: str, log_x: bool = True
) -> None:
    """Integrator wall time (log) against one accuracy measure (log or linear), a line per
    series, each point labelled with its tolerance."""
    rows = table[np.isfinite(table[column]) & ((table[column] > 0) | (not log_x))]
    for name, series in _series(rows):
        line = ax.semilogy(series[column], series.wall_time_s, "o-", ms=3, lw=0.8, label=name)
        for _, row in series.iterrows():
            ax.annotate(
                f"{row.rtol:.0e}",
                (row[column], row.wall_time_s),
                fontsize=6,
                color=line[0].get_color(),
                xytext=(2, 2),
                textcoords="offset points",
            )
    if log_x:
        ax.set_xscale("log")
        _plain_log_labels(ax.xaxis, ax.get_xlim())
    _plain_log_labels(ax.yaxis, ax.get_ylim())
    ax.set_title(title)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("integrator wall time [s]")


def plot_work_precision(table: pd.DataFrame, window: float) -> Figure:
    """Work–precision diagrams, integrator wall time (s) against accuracy, one line per
    integrator and model, points labelled with the tolerance.

    Row 1: RMS error over the first ``window`` revolutions against the study's reference, per
    response (slider acceleration, driving torque, joint A eccentricity; over the reference's
    peak). Row 2: the same against each model's own tightest tolerance (the integrator's
    share). Row 3, when the table has long-horizon columns: the largest relative peak
    difference, the largest |Δλ| (1/s) and the largest Poincaré distance (over the clearance)
    against the long reference, over every channel.
    """
    reference = table[table.is_reference].case.tolist()[0]
    long_reference = table[table.is_long_reference]
    long_table = table[~table.is_long_reference].copy()
    long_measures = {
        "peak_": ("peak values", "largest |relative difference| [–]"),
        "lyapunov_": ("Lyapunov exponents", "largest |Δλ| over channels [1/s]"),
        "poincare_": ("Poincaré maps", "largest W₁ distance / clearance [–]"),
    }
    for prefix in long_measures:
        columns = [c for c in long_table if c.startswith(prefix)]
        long_table[prefix] = long_table[columns].abs().max(axis=1) if columns else np.nan
    has_long = bool(np.isfinite(long_table["poincare_"]).any())
    short = table[~table.is_reference & table.error_rms_slider_acceleration.notna()]
    solver = short[short.case != short.solver_reference]
    with style.style():
        fig = style.figure(12.0, 10.5 if has_long else 7.0)
        axes = fig.subplots(3 if has_long else 2, 3, squeeze=False)
        for col, name in enumerate(fidelity.SHORT_CHANNELS):
            words = name.replace("_", " ")
            _work_panel(
                axes[0, col],
                short,
                f"error_rms_{name}",
                f"{words}: against {reference}",
                "RMS error / reference peak [–]",
            )
            _work_panel(
                axes[1, col],
                solver,
                f"solver_rms_{name}",
                f"{words}: against the same model at its tightest rtol",
                "RMS error / reference peak [–]",
            )
        axes[0, 0].legend(loc="best", fontsize=6)
        if has_long:
            for col, (prefix, (title, xlabel)) in enumerate(long_measures.items()):
                _work_panel(
                    axes[2, col],
                    long_table,
                    prefix,
                    f"{title}: {long_reference.revolutions.iloc[0]:g} revolutions against "
                    f"{long_reference.case.iloc[0]}",
                    xlabel,
                    log_x=False,
                )
            axes[2, 0].legend(loc="best", fontsize=6)
        fig.suptitle(
            f"Work against precision, flagship scene: short horizon {window:g} revolution"
            + (", long horizon (bottom row)" if has_long else "")
        )
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
    "max_penetration_m",
    "real_time_factor",
    "message",
    "command",
]


def extremes_table(statuses: list[dict]) -> pd.DataFrame:
    """Pass/fail table of the extremes study, one row per case: result (pass, fail,
    incomplete), outcome, exit code, wall time (s), energy audit (share of the energy
    scale), largest constraint violation (m), difference from the ideal joint (m, clearance
    0 only), contact events, deepest contact penetration (m), real-time factor, sim's message
    and the command to reproduce it."""
    table = pd.DataFrame(statuses)
    for column in EXTREME_COLUMNS:
        if column not in table:
            table[column] = np.nan
    return table[EXTREME_COLUMNS]


def write_table(table: pd.DataFrame, csv, html, title: str, note: str = "") -> None:
    """Write a table as CSV (for reading back) and as the report's HTML page (`to_html`)."""
    table.to_csv(csv, index=False)
    Path(html).write_text(to_html(table, title, note))


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

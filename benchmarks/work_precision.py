"""Work against precision of the flagship scene (issue 6): what accuracy each setting buys.

The flagship scene (six-bar, A and B with 0.5 mm clearance, 150 rpm) runs over settings:
solver method (every `solver.method` the scene schema accepts, read at run time) × relative
tolerance 1e-3 … 1e-9 (atol = rtol / 100) × link model (rigid; rod2–rod4 ANCF beams with 1, 2,
4, 8 elements). For each setting it prints the CPU time of the run (s: one core, so that other
jobs on a shared machine do not inflate it), the real-time factor (simulated s per CPU s) and
its accuracy, measured by sim.studies.fidelity:

Short horizon (always): runs of DURATION revolutions (0.25 by default; timed over it), and the
pointwise RMS / maximum error of the slider acceleration, driving torque and joint A
eccentricity over their first WINDOW revolutions, relative to the reference's peak,
(a) against the same link model at the reference tolerance (the solver's error) and (b) against
the finest model (the model's and the solver's error), and the separation time (revolutions
until joint A's eccentricity differs by 10 % of its peak; ">run" if not within DURATION).
The motion is chaotic: runs separate within a fraction of a revolution, so WINDOW is short
(0.05 revolution by default); a block of two-revolution errors shows the saturation beyond it.
Also printed: the references' own convergence (halving the tolerance; doubling the elements of
the finest mesh) against the smallest error of the table, and the cost and effect of modelling
all five clearances (A, C, D1, D2, E revolute + B) instead of A and B.

Long horizon (--long): 200 revolutions (200 samples per revolution, 20 transient), where only
statistics can agree: the relative difference of the peak values, the difference of the largest
Lyapunov exponent per channel (1/s) and the Wasserstein distance of the Poincaré points per
joint and axis over the clearance, against a rigid reference at rtol 1e-11, for the tolerance
series, the paper's settings (rtol 1e-6, output every 1e-4 period), all five clearances and
flexible links at rtol 1e-6 (1 … 8 elements, those whose estimated cost fits --budget); the
reference against itself at half the tolerance gives the statistical noise floor.

Every run is one process after compilation (a warm-up run is not timed). --quick keeps fewer
settings (tolerances 1e-3, 1e-5, 1e-7, looser references, 1 and 2 elements) for a check of the
script in minutes.

Usage: python benchmarks/work_precision.py [--quick] [--long | --only-long] [--window R]
       [--duration R] [--budget S] [--methods M ...] [--csv FILE]
"""

import argparse
import dataclasses
import math
import time
from dataclasses import dataclass
from pathlib import Path

import pandas as pd
import xarray as xr

from sim.analysis.run import analyze_run
from sim.atomic import write_atomically
from sim.results import scene_of
from sim.run import SimulationError, simulate
from sim.scene import SOLVER, load_scene
from sim.studies import fidelity

FLAGSHIP = ["joints.A.clearance=0.5e-3", "joints.B.clearance=0.5e-3", "drive.speed_rpm=150"]
EXTRA_CLEARANCES = ("C", "D1", "D2", "E")
FLEXIBLE = ("rod2", "rod3", "rod4")
ATOL_PER_RTOL = 1e-2
TOLERANCES = (1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9)
ELEMENTS = (1, 2, 4, 8)
REFERENCE_METHOD = "dopri5"
SHORT_OUTPUT = 2000  # samples per revolution: the impacts' spikes need a fine grid
LONG_REVOLUTIONS, LONG_OUTPUT, TRANSIENT = 200, 200, 20
PAPER_OUTPUT = 10_000  # the paper's output step, 1e-4 crank period
SATURATION_REVOLUTIONS = 2.0
CHANNELS = tuple(fidelity.SHORT_CHANNELS)


@dataclass(frozen=True)
class Setting:
    """One simulation setting of the flagship scene."""

    method: str
    rtol: float
    elements: int = 0  # per flexible link; 0: rigid links
    all_clearances: bool = False
    output_per_revolution: int = SHORT_OUTPUT

    @property
    def links(self) -> str:
        return f"beam{self.elements}" if self.elements else "rigid"

    @property
    def label(self) -> str:
        extra = " 5 clearances" if self.all_clearances else ""
        if self.output_per_revolution == PAPER_OUTPUT:
            extra += " out 1e-4 T"
        return f"{self.method} {self.links} {self.rtol:.0e}{extra}"

    def overrides(self, revolutions: float) -> list[str]:
        out = [
            *FLAGSHIP,
            f"solver.method={self.method}",
            f"solver.rtol={self.rtol!r}",
            f"solver.atol={self.rtol * ATOL_PER_RTOL!r}",
            f"simulation.revolutions={revolutions!r}",
            f"simulation.output_per_revolution={self.output_per_revolution}",
        ]
        for body in FLEXIBLE:
            out.append(f"bodies.{body}.kind={'beam' if self.elements else 'rigid'}")
            if self.elements:
                out.append(f"bodies.{body}.elements={self.elements}")
        if self.all_clearances:
            out += [f"joints.{joint}.clearance=0.5e-3" for joint in EXTRA_CLEARANCES]
        return out


def methods() -> tuple[str, ...]:
    """Every integrator the scene schema accepts (a new one is measured when it lands)."""
    return SOLVER["method"].choices


_RUNS: dict[tuple[Setting, float], xr.Dataset] = {}


def run(setting: Setting, revolutions: float) -> xr.Dataset:
    """The output of one setting over `revolutions` (kept for reuse), with the CPU time of the
    whole `simulate` call (assembly, integration, output Dataset) as an attribute."""
    key = (setting, revolutions)
    if key not in _RUNS:
        scene = load_scene("sixbar", setting.overrides(revolutions))
        start = time.process_time()
        ds = simulate(scene)
        ds.attrs["simulate_cpu_time_s"] = time.process_time() - start
        _RUNS[key] = ds
    return _RUNS[key]


def attempt(setting: Setting, revolutions: float) -> xr.Dataset | None:
    """`run`, or None with the diagnosis printed when the setting cannot finish: a setting
    that stops is a result of the benchmark, not its end."""
    try:
        return run(setting, revolutions)
    except SimulationError as error:
        print(f"  {setting.label:34} stopped: {error}", flush=True)
        return None


def warm_up(settings: list[Setting]) -> None:
    """Compile (or load) every kernel the settings use, outside the timings."""
    for setting in {dataclasses.replace(s, rtol=1e-6, output_per_revolution=200) for s in settings}:
        simulate(load_scene("sixbar", setting.overrides(0.002)))


def cost(setting: Setting, ds: xr.Dataset) -> dict:
    """What a run cost: the CPU time of `simulate` (s; on one core it is the wall time of an
    unshared machine, and other jobs on a shared one do not inflate it), the real-time factor
    from it (simulated s per CPU s), and the integrator's wall time (s) as it recorded it."""
    simulated = float(ds.attrs["simulated_time_s"])
    cpu = float(ds.attrs["simulate_cpu_time_s"])
    return {
        "setting": setting.label,
        "method": setting.method,
        "links": setting.links,
        "rtol": setting.rtol,
        "all_clearances": setting.all_clearances,
        "output_per_revolution": setting.output_per_revolution,
        "revolutions": simulated / float(ds.attrs["crank_period"]),
        "cpu_time_s": cpu,
        "real_time_factor": simulated / cpu,
        "integrator_wall_time_s": float(ds.attrs["solver_wall_time_s"]),
        "accepted_steps": int(ds.attrs["solver_accepted_steps"]),
        "energy_error_relative": float(ds.attrs["energy_error_relative"]),
    }


def pointwise(ds: xr.Dataset, reference: xr.Dataset, window: float, prefix: str) -> dict:
    """Short-horizon errors and separation time (revolutions) as flat columns."""
    out = {}
    for name, (rms, largest) in fidelity.short_horizon_errors(
        ds, reference, revolutions=window
    ).items():
        out[f"{prefix}rms_{name}"] = rms
        out[f"{prefix}max_{name}"] = largest
    period = float(reference.attrs["crank_period"])
    out[f"{prefix}separation_rev"] = fidelity.separation_time(ds, reference) / period
    return out


def _e(value: float) -> str:
    return f"{value:8.1e}" if math.isfinite(value) else "    >run"


def print_short(rows: list[dict], prefix: str, title: str) -> None:
    print(f"\n{title}")
    head = "".join(f"  {name[:20]:>20}" for name in CHANNELS)
    print(f"{'setting':34} {'CPU s':>8} {'RTF':>8} {'steps':>8}{head}  {'sep rev':>8}")
    for row in rows:
        errors = "".join(
            f"  {_e(row[f'{prefix}rms_{n}'])}/{_e(row[f'{prefix}max_{n}']).strip():>8}"
            for n in CHANNELS
        )
        print(
            f"{row['setting']:34} {row['cpu_time_s']:8.3g} {row['real_time_factor']:8.3g} "
            f"{row['accepted_steps']:8d}{errors}  {_e(row[f'{prefix}separation_rev'])}"
        )


def short_horizon(args, refs: dict[int, Setting], finest: Setting) -> list[dict]:
    """Every setting over the duration, its errors over the window, against its model's
    reference and the finest model."""
    finest_ds = run(finest, args.duration)
    rows = []
    for method in args.methods:
        for elements in (0, *args.elements):
            for rtol in args.tolerances:
                setting = Setting(method, rtol, elements)
                ds = attempt(setting, args.duration)
                if ds is None:
                    continue
                own = run(refs[elements], args.duration)
                row = cost(setting, ds) | pointwise(ds, own, args.window, "solver_")
                rows.append(row | pointwise(ds, finest_ds, args.window, "total_"))
                print(f"  measured {setting.label}", flush=True)
    what = f"SHORT HORIZON: errors over {args.window:g} rev (RMS/max over the reference's peak)"
    print_short(rows, "solver_", f"{what} against the same link model at the reference tolerance")
    print_short(rows, "total_", f"{what} against the finest model, {finest.label}")
    return rows


def convergence(args, refs: dict[int, Setting], finest: Setting, rows: list[dict]) -> list[dict]:
    """Each reference against itself at half the tolerance, the finest mesh against twice the
    elements (over the window only: it is the costliest run): each must change less than the
    smallest error of the settings it judges."""
    print(
        f"\nREFERENCE CONVERGENCE ({args.window:g} rev): change of the reference, RMS/max, "
        "against the smallest RMS error of the settings it judges"
    )
    checks = [(refs[e], dataclasses.replace(refs[e], rtol=refs[e].rtol / 2), e) for e in refs]
    checks.append((finest, dataclasses.replace(finest, elements=2 * finest.elements), None))
    out = []
    for reference, changed, elements in checks:
        ds = run(changed, args.window)
        errors = fidelity.short_horizon_errors(
            ds, run(reference, args.duration), revolutions=args.window
        )
        prefix = "total_" if elements is None else "solver_"
        judged = [r for r in rows if elements is None or r["links"] == reference.links]
        row = cost(changed, ds) | {"reference": reference.label}
        verdicts = []
        for name, (rms, largest) in errors.items():
            smallest = min(r[f"{prefix}rms_{name}"] for r in judged)
            row |= {f"change_rms_{name}": rms, f"smallest_rms_{name}": smallest}
            verdicts.append(
                f"{name} {rms:.1e}/{largest:.1e} vs {smallest:.1e} "
                f"{'ok' if rms < smallest else 'NOT CONVERGED'}"
            )
        print(f"  {reference.label} → {changed.label}: " + "; ".join(verdicts), flush=True)
        out.append(row)
    return out


def saturation(args, refs: dict[int, Setting]) -> list[dict]:
    """Rigid tolerance series over two revolutions: pointwise errors saturate (chaos)."""
    revolutions = SATURATION_REVOLUTIONS
    ref_ds = run(refs[0], revolutions)
    rows = []
    for rtol in args.tolerances:
        setting = Setting(REFERENCE_METHOD, rtol)
        rows.append(
            cost(setting, run(setting, revolutions))
            | pointwise(run(setting, revolutions), ref_ds, revolutions, "solver_")
        )
    print_short(
        rows,
        "solver_",
        f"SATURATION: errors over {revolutions:g} rev (rigid) against {refs[0].label}, "
        "once chaos has separated the runs",
    )
    return rows


def clearances(args, refs: dict[int, Setting]) -> list[dict]:
    """Cost (over two revolutions) and effect (over the window) of modelling all five
    clearances instead of A and B, rigid links."""
    revolutions = SATURATION_REVOLUTIONS
    print(
        f"\nFIVE CLEARANCES against A and B only (rigid): CPU time over {revolutions:g} rev, "
        f"difference of each response over {args.window:g} rev (RMS/max over the peak of the "
        "five-clearance run)"
    )
    out = []
    for rtol in (1e-6, refs[0].rtol):
        ab = Setting(REFERENCE_METHOD, rtol)
        five = dataclasses.replace(ab, all_clearances=True)
        ab_ds, five_ds = run(ab, revolutions), run(five, revolutions)
        row = cost(five, five_ds) | pointwise(ab_ds, five_ds, args.window, "effect_")
        row["cpu_time_ratio"] = row["cpu_time_s"] / cost(ab, ab_ds)["cpu_time_s"]
        text = "; ".join(
            f"{n} {row[f'effect_rms_{n}']:.1e}/{row[f'effect_max_{n}']:.1e}" for n in CHANNELS
        )
        print(
            f"  rtol {rtol:.0e}: {row['cpu_time_s']:.3g} s, × {row['cpu_time_ratio']:.2f} of "
            f"A and B; {text}"
        )
        out.append(row)
    return out


def statistics(ds: xr.Dataset, reference: xr.Dataset, analysis, ref_analysis) -> dict:
    out = {f"peak_{n}": v for n, v in fidelity.peak_differences(ds, reference).items()}
    out |= {
        f"lyapunov_{n}": v for n, v in fidelity.lyapunov_differences(analysis, ref_analysis).items()
    }
    distances = fidelity.poincare_distances(ds, reference, transient_revolutions=TRANSIENT)
    return out | {f"poincare_{n}": v for n, v in distances.items()}


def analysis_of(ds: xr.Dataset) -> xr.Dataset:
    """Chaos analysis at the studies' sampling (LONG_OUTPUT per revolution)."""
    every = scene_of(ds)["simulation"]["output_per_revolution"] // LONG_OUTPUT
    return analyze_run(ds.isel(time=slice(None, None, every)), transient_revolutions=TRANSIENT)


def affordable(setting: Setting, duration: float, budget: float) -> bool:
    """Whether a long run of `setting` fits the budget (CPU s), estimated from the real-time
    factor of its short run (`duration` revolutions; the short part's, when it ran); printed
    when it does not."""
    probe = attempt(setting, duration)
    if probe is None:
        return False
    period = float(probe.attrs["crank_period"])
    estimate = LONG_REVOLUTIONS * period / cost(setting, probe)["real_time_factor"]
    if estimate > budget:
        print(f"  {setting.label:34} skipped: ~{estimate:.0f} s estimated > --budget {budget:g} s")
    return estimate <= budget


def long_horizon(args, frames: dict[str, list[dict]]) -> list[dict]:
    """200 revolutions: statistics against a rigid reference at a tight tolerance (each row
    is added to frames["long"] and the CSV as it is measured)."""
    reference = Setting(REFERENCE_METHOD, args.long_reference, output_per_revolution=LONG_OUTPUT)
    settings = [reference, dataclasses.replace(reference, rtol=reference.rtol / 2)]
    settings += [
        Setting(method, rtol, output_per_revolution=LONG_OUTPUT)
        for method in args.methods
        for rtol in args.tolerances
    ]
    settings.append(Setting(REFERENCE_METHOD, 1e-6, output_per_revolution=PAPER_OUTPUT))
    settings.append(
        Setting(REFERENCE_METHOD, 1e-6, all_clearances=True, output_per_revolution=LONG_OUTPUT)
    )
    settings += [
        Setting(m, 1e-6, e, output_per_revolution=LONG_OUTPUT)
        for m in args.methods
        for e in args.long_elements
        if affordable(Setting(m, 1e-6, e), args.duration, args.budget)
    ]
    ref_ds = run(reference, LONG_REVOLUTIONS)
    ref_analysis = analysis_of(ref_ds)
    rows = frames.setdefault("long", [])
    print(
        f"\nLONG HORIZON ({LONG_REVOLUTIONS} rev, {TRANSIENT} transient) against "
        f"{reference.label}: peak differences (relative), Lyapunov exponent differences "
        "(1/s), Poincaré distances (W1 / clearance); the first row is the noise floor"
    )
    print(
        "  reference: λ = "
        + ", ".join(
            f"{c} {v:.3g}"
            for c, v in zip(
                ref_analysis.channel.values, ref_analysis.lyapunov_exponent.values, strict=True
            )
        )
    )
    for setting in settings[1:]:
        ds = attempt(setting, LONG_REVOLUTIONS)
        if ds is None:
            continue
        row = cost(setting, ds) | statistics(ds, ref_ds, analysis_of(ds), ref_analysis)
        rows.append(row)
        save(frames, args.csv)
        _RUNS.pop((setting, LONG_REVOLUTIONS))  # 200-revolution outputs are large
        peaks = " ".join(f"{k[5:]} {v:+.1%}" for k, v in row.items() if k.startswith("peak_"))
        lyap = " ".join(f"{k[9:]} {v:+.2g}" for k, v in row.items() if k.startswith("lyapunov_"))
        dist = " ".join(f"{k[9:]} {v:.2g}" for k, v in row.items() if k.startswith("poincare_"))
        print(
            f"  {setting.label:34} CPU {row['cpu_time_s']:7.1f} s "
            f"(integrator wall {row['integrator_wall_time_s']:.1f} s) "
            f"RTF {row['real_time_factor']:6.3g} energy {row['energy_error_relative']:.1e} | "
            f"{peaks} | Δλ {lyap} | W {dist}",
            flush=True,
        )
    return rows


def save(frames: dict[str, list[dict]], path: str | None) -> None:
    """All rows so far in one CSV (column `part` names the block), written through a temporary
    file (a run stopped midway keeps what it measured); nothing without a path."""
    if not path:
        return
    table = pd.concat([pd.DataFrame(rows).assign(part=part) for part, rows in frames.items()])
    write_atomically(Path(path).absolute(), lambda temporary: table.to_csv(temporary, index=False))


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="fewer settings, looser references")
    parser.add_argument("--long", action="store_true", help="also the 200-revolution statistics")
    parser.add_argument(
        "--only-long", action="store_true", help="the 200-revolution statistics alone"
    )
    parser.add_argument("--window", type=float, default=0.05, help="short horizon, revolutions")
    parser.add_argument(
        "--duration", type=float, default=0.25, help="short runs, revolutions (timed)"
    )
    parser.add_argument("--csv", help="write every measured row to this CSV file")
    parser.add_argument(
        "--budget",
        type=float,
        default=1800.0,
        help="longest long-horizon beam run, s (estimated from the short run; longer: skipped)",
    )
    parser.add_argument(
        "--methods",
        nargs="+",
        choices=methods(),
        default=methods(),
        help="integrators measured (default: every solver.method the scene accepts)",
    )
    args = parser.parse_args()
    args.tolerances = (1e-3, 1e-5, 1e-7) if args.quick else TOLERANCES
    args.elements = (1, 2) if args.quick else ELEMENTS
    args.long_elements = () if args.quick else ELEMENTS
    args.long_reference = 1e-9 if args.quick else 1e-11
    rigid_rtol, beam_rtol = (1e-10, 1e-8) if args.quick else (1e-12, 1e-10)
    refs = {0: Setting(REFERENCE_METHOD, rigid_rtol)}
    refs |= {e: Setting(REFERENCE_METHOD, beam_rtol, e) for e in args.elements}
    finest = refs[max(args.elements)]
    tolerances = ", ".join(f"{t:g}" for t in args.tolerances)
    print(
        f"methods: {', '.join(args.methods)}; tolerances {tolerances} "
        f"(atol = rtol × {ATOL_PER_RTOL:g}); links rigid and beams of "
        f"{', '.join(map(str, args.elements))} elements; flagship A+B 0.5 mm, 150 rpm"
    )
    warm_up([*refs.values(), *(Setting(m, 1e-6, e) for m in args.methods for e in (0, 1))])
    frames: dict[str, list[dict]] = {}
    if not args.only_long:
        frames["short"] = short_horizon(args, refs, finest)
        frames["convergence"] = convergence(args, refs, finest, frames["short"])
        frames["saturation"] = saturation(args, refs)
        frames["clearances"] = clearances(args, refs)
        save(frames, args.csv)
    if args.long or args.only_long:
        long_horizon(args, frames)


if __name__ == "__main__":
    main()

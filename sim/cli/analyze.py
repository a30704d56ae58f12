"""The ``sim analyze`` and ``sim sweep`` subcommands."""

import argparse
import sys
from pathlib import Path

import numpy as np
import xarray as xr

from sim.analysis.poincare import MIN_REVOLUTIONS
from sim.cli.arguments import add_scene_arguments, check_output, interrupted_while
from sim.scene_keys import Field, check_option

#: default transient: this many revolutions, or a quarter of the run if that is fewer
DEFAULT_TRANSIENT_REVOLUTIONS = 20
#: what --transient accepts (crank revolutions)
TRANSIENT = Field("int", 0, unit="revolutions")
#: the variables of a model exponent (sim.studies.model_lyapunov.model_lyapunov_dataset)
MODEL_VARIABLES = ("model_lyapunov_exponent", "model_lyapunov_stderr")
#: what a model exponent may hold besides (`model_lyapunov_dataset` with its onset shares)
MODEL_SHARES = ("model_lyapunov_onset_stretch_share", "model_lyapunov_onset_interval_share")


def default_transient(n_revolutions: int) -> int:
    """Revolutions dropped by default: min(20, a quarter of the run)."""
    return min(DEFAULT_TRANSIENT_REVOLUTIONS, n_revolutions // 4)


def shortest_run(transient: int | None = None) -> int:
    """The fewest crank revolutions (simulation.revolutions) a run needs for `sim analyze`
    with this --transient (None: the default, which grows with the run): its sections
    (one per revolution and t = 0) less the transient must be MIN_REVOLUTIONS."""
    revolutions = 0
    while True:
        sections = revolutions + 1
        dropped = default_transient(sections) if transient is None else transient
        if sections - dropped >= MIN_REVOLUTIONS:
            return revolutions
        revolutions += 1


def _check_length(run: xr.Dataset, transient: int | None) -> None:
    """ValueError stating the fixed run length `sim analyze` needs, when the run is shorter."""
    need = shortest_run(transient)
    have = run.sizes.get("revolution", 1) - 1
    if have < need:
        dropped = "the default transient" if transient is None else f"--transient {transient}"
        raise ValueError(
            f"the run has {have} crank revolutions; with {dropped} the analysis needs runs of "
            f"at least {need} (simulation.revolutions ≥ {need})"
        )


def _value(number: float, spec: str) -> str:
    """A number as the table prints it; a dash where it could not be estimated."""
    return "–" if np.isnan(number) else format(number, spec)


def exponent_line(analysis: xr.Dataset) -> str | None:
    """The model exponent of an analysis with its standard error and settings, one line; None
    when the analysis has none."""
    if "model_lyapunov_exponent" not in analysis:
        return None
    a = analysis.attrs
    settings = ", ".join(
        f"{name} {a[key]:g}"
        for name, key in (("rtol", "model_lyapunov_rtol"), ("d0", "model_lyapunov_d0"))
        if key in a
    )
    links = a.get("model_lyapunov_links")
    on = f" on {links} links" if links in ("rigid", "modal") else ""
    return (
        f"model exponent {float(analysis.model_lyapunov_exponent):.3g} ± "
        f"{float(analysis.model_lyapunov_stderr):.2g} 1/s (Benettin on the linkage's own "
        f"equations{on}{', ' + settings if settings else ''}): the first chaos vote of every "
        "channel"
    )


def verdict_table(analysis: xr.Dataset) -> str:
    """The verdict of every channel, one line each, with its series exponent (Rosenstein, 1/s)
    and the reason, which names every indicator read."""
    lines = [f"{'channel':<14} {'verdict':<16} {'series λ (1/s)':>14}  reason"]
    for i, channel in enumerate(analysis["channel"].values):
        lines.append(
            f"{channel!s:<14} {analysis['verdict'].values[i]!s:<16} "
            f"{_value(float(analysis['lyapunov_exponent'].values[i]), '.3g'):>14}  "
            f"{analysis['verdict_reason'].values[i]}"
        )
    return "\n".join(lines)


def register(subparsers: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Add the ``analyze`` subcommand to the ``sim`` command's subparsers."""
    parser = subparsers.add_parser(
        "analyze",
        help="phase portraits, Poincaré maps, Lyapunov exponents and verdicts of a run",
        description=(
            "Analyse every clearance joint and axis of a run (every body and axis for an "
            "all-ideal run) and write a CF netCDF file."
        ),
    )
    parser.add_argument("run", type=Path, help="run file (netCDF) written by `sim run`")
    parser.add_argument("-o", "--output", type=Path, required=True, help="analysis file to write")
    parser.add_argument(
        "--transient",
        type=int,
        default=None,
        metavar="N",
        help=(
            f"crank revolutions dropped as transient (default: {DEFAULT_TRANSIENT_REVOLUTIONS} "
            "or a quarter of the run, whichever is smaller)"
        ),
    )
    model = parser.add_mutually_exclusive_group()
    model.add_argument(
        "--model-lyapunov",
        action="store_true",
        help=(
            "also compute the largest Lyapunov exponent of the model (Benettin: the run's scene "
            "integrated again beside a perturbed copy; costs about two runs); the verdicts "
            "read it first"
        ),
    )
    model.add_argument(
        "--model-exponent",
        type=Path,
        metavar="FILE",
        help=(
            "take the model exponent from FILE instead (an analysis made with "
            "--model-lyapunov, or the workflow's model-exponent file of the run)"
        ),
    )
    parser.set_defaults(func=analyze_command)
    return parser


def _model_lyapunov(run: xr.Dataset, transient: int) -> xr.Dataset:
    from sim.results import scene_of
    from sim.studies.model_lyapunov import (
        exponent_tolerances,
        linkage_exponent,
        model_lyapunov_dataset,
    )

    if "scene" not in run.attrs:
        raise ValueError("missing global attribute 'scene' (the run's resolved scene as JSON)")
    scene = scene_of(run)
    result, shares = linkage_exponent(
        scene,
        revolutions=scene["simulation"]["revolutions"],
        transient_revolutions=transient,
        ideal=bool(run.attrs.get("model_ideal", 0)),
        rigid=bool(run.attrs.get("model_rigid", 0)),
    )
    return model_lyapunov_dataset(result, exponent_tolerances(scene), shares)


def _exponent_file(path: Path) -> xr.Dataset:
    """The model exponent of a file holding one (`model_lyapunov_dataset`'s variables);
    ValueError naming the file and the variable when it holds none."""
    from sim.results import open_run

    ds = open_run(path)
    missing = [name for name in MODEL_VARIABLES if name not in ds]
    if missing:
        raise ValueError(
            f"{path}: no variable {missing[0]!r}: give a file written by `sim analyze "
            "--model-lyapunov` or the workflow's rule model_exponent"
        )
    shares = [name for name in MODEL_SHARES if name in ds]
    return ds[[*MODEL_VARIABLES, *shares]].assign_attrs(
        {k: v for k, v in ds.attrs.items() if k.startswith("model_lyapunov_")}
    )


def analyze_command(args: argparse.Namespace) -> int:
    """Handler of ``sim analyze``; returns the exit code."""
    from sim.analysis.run import analyze_run
    from sim.results import open_run, write_netcdf
    from sim.run import SimulationError

    # Bad input (options, an unreadable run file) goes to `sim`'s handler: exit code 2.
    if args.transient is not None:
        check_option("--transient", args.transient, TRANSIENT)
    check_output("--output", args.output)
    run = open_run(args.run)
    model = _exponent_file(args.model_exponent) if args.model_exponent else None
    try:
        _check_length(run, args.transient)
        transient = (
            default_transient(run.sizes.get("revolution", 0))
            if args.transient is None
            else args.transient
        )
        if args.model_lyapunov:
            with interrupted_while("computing the model exponent"):
                model = _model_lyapunov(run, transient)
        exponent = (
            {}
            if model is None
            else {
                "model_exponent": float(model.model_lyapunov_exponent),
                "model_stderr": float(model.model_lyapunov_stderr),
            }
        )
        with interrupted_while("analysing the channels"):
            analysis = analyze_run(run, transient_revolutions=transient, **exponent)
        if model is not None:
            analysis = analysis.merge(model, combine_attrs="no_conflicts")
    except (OSError, ValueError, SimulationError) as error:
        print(f"sim analyze: {args.run}: {error}", file=sys.stderr)
        return 1
    write_netcdf(analysis, args.output)  # atomic: a crash leaves no partial file
    print(f"{args.output}: {run.sizes['revolution'] - 1} revolutions, {transient} dropped")
    line = exponent_line(analysis)
    if line:
        print(line)
    print(verdict_table(analysis))
    return 0


def register_sweep(subparsers: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Add the ``sweep`` subcommand to the ``sim`` command's subparsers."""
    parser = subparsers.add_parser(
        "sweep",
        help="simulate a scene over the values of a parameter: one bifurcation dataset",
        description=(
            "Run the scene once per value of the swept key(s), write every run to --out-dir "
            "and their Poincaré samples, stacked along the dimension 'parameter', to -o."
        ),
    )
    add_scene_arguments(parser)
    parser.add_argument(
        "--key",
        dest="keys",
        action="append",
        required=True,
        metavar="DOTTED.KEY",
        help="scene key to sweep, e.g. joints.A.clearance (repeatable: all take the value)",
    )
    values = parser.add_mutually_exclusive_group(required=True)
    values.add_argument("--values", type=float, nargs="+", metavar="V", help="the values")
    values.add_argument(
        "--range",
        type=float,
        nargs=3,
        metavar=("START", "STOP", "COUNT"),
        help="COUNT evenly spaced values from START to STOP inclusive",
    )
    parser.add_argument(
        "--transient",
        type=int,
        default=DEFAULT_TRANSIENT_REVOLUTIONS,
        metavar="N",
        help=(
            "revolutions to drop before plotting, recorded in the dataset; the run length is "
            f"simulation.revolutions (default {DEFAULT_TRANSIENT_REVOLUTIONS})"
        ),
    )
    parser.add_argument(
        "--continuation",
        action="store_true",
        help=(
            "start each value from the previous value's final state, projected onto its "
            "scene, instead of the assembled state (a shorter transient; values in order)"
        ),
    )
    parser.add_argument(
        "--indicators",
        action="store_true",
        help=(
            "also each value's model exponent (Benettin, the run itself the reference, its "
            "perturbed copy aligned over the transient's last revolutions) and each channel's "
            "0-1 K, Poincaré period and verdict, which `sim plot` draws beneath the diagram; "
            f"about 1.8 runs a value, simulation.revolutions ≥ the transient + {MIN_REVOLUTIONS}"
        ),
    )
    parser.add_argument(
        "--label", help="short parameter name for file names (default: the key's last part)"
    )
    parser.add_argument(
        "--out-dir", type=Path, required=True, help="folder of the per-value run files"
    )
    parser.add_argument(
        "-o", "--output", type=Path, required=True, help="bifurcation dataset to write"
    )
    parser.add_argument("-q", "--quiet", action="store_true", help="no progress line")
    parser.set_defaults(func=sweep_command)
    return parser


def sweep_values(args: argparse.Namespace) -> list[float]:
    """The values of ``--values`` or ``--range`` (COUNT a positive whole number)."""
    if args.values is not None:
        return list(args.values)
    start, stop, count = args.range
    check_option("--range COUNT", count, Field("int", 1))
    return [float(v) for v in np.linspace(start, stop, int(count))]


def sweep_command(args: argparse.Namespace) -> int:
    """Handler of ``sim sweep``; returns the exit code (errors are reported by ``sim.cli``)."""
    from sim.results import write_netcdf
    from sim.studies.model_lyapunov import DEFAULT_ALIGNMENT_REVOLUTIONS
    from sim.studies.sweep import Indicators, run_sweep

    check_option("--transient", args.transient, TRANSIENT)
    if args.indicators and args.transient < 1:
        raise ValueError(
            "--indicators needs --transient ≥ 1: the exponent's perturbed copy aligns over the "
            "transient's last revolutions"
        )
    check_output("--output", args.output)
    check_output("--out-dir", args.out_dir, directory=True)
    values = sweep_values(args)
    combined = run_sweep(
        args.scene,
        args.overrides,
        args.keys,
        values,
        out_dir=args.out_dir,
        label=args.label or args.keys[0].rsplit(".", 1)[-1],
        transient_revolutions=args.transient,
        continuation=args.continuation,
        progress=not args.quiet,
        indicators=(
            Indicators(min(DEFAULT_ALIGNMENT_REVOLUTIONS, args.transient))
            if args.indicators
            else None
        ),
    )
    write_netcdf(combined, args.output)
    print(f"{args.output}: {len(values)} values of {','.join(args.keys)}; runs in {args.out_dir}")
    return 0

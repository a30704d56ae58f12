"""`sim plot`: a run, an analysis or a sweep drawn to PNG or SVG by the workflow's own figure
code (sim.plots)."""

import argparse
from pathlib import Path

import xarray as xr

from sim.cli.arguments import check_output, interrupted_while

#: what each kind of file can be drawn as; the first is the default
KINDS = {
    "run": ("responses", "trajectories"),
    "analysis": ("phase", "poincare"),
    "sweep": ("bifurcation",),
}


def file_kind(ds: xr.Dataset, path: Path) -> str:
    """Which of `KINDS` a file is: a sweep (`sim sweep`, dimension parameter), an analysis
    (`sim analyze`, verdicts per channel) or a run (`sim run`, its scene recorded);
    ValueError naming the file otherwise."""
    if "parameter" in ds.dims and "section_eccentricity" in ds:
        return "sweep"
    if "channel" in ds.dims and "verdict" in ds:
        return "analysis"
    if "time" in ds.dims and "scene" in ds.attrs:
        return "run"
    raise ValueError(
        f"{path}: not a run (sim run), an analysis (sim analyze) or a sweep (sim sweep) file"
    )


def _ideal_of(run: xr.Dataset, ideal: Path | None) -> xr.Dataset:
    """The ideal reference of a run: the file given, else the run's scene simulated with every
    joint ideal and every link rigid (what the workflow's ideal runs are)."""
    from sim.results import open_run, scene_of
    from sim.run import simulate

    if ideal is not None:
        return open_run(ideal)
    with interrupted_while("simulating the ideal reference"):
        return simulate(scene_of(run), ideal=True, rigid=True)


def _figure(ds: xr.Dataset, kind: str, args: argparse.Namespace):
    """The figure of `kind` for the dataset, by the functions the workflow's rules call."""
    from sim.plots import bifurcation, chaos, responses, trajectories

    if kind == "responses":
        return responses.plot_responses(ds, _ideal_of(ds, args.ideal), revolutions=args.revolutions)
    if kind == "trajectories":
        return trajectories.plot_trajectories(ds)
    if kind == "phase":
        return chaos.plot_phase(ds)
    if kind == "poincare":
        return chaos.plot_poincare(ds)
    parameter = ds.parameter.attrs
    return bifurcation.plot_bifurcation(
        ds,
        label=ds.attrs.get("label", str(parameter.get("name", "parameter")).rsplit(".", 1)[-1]),
        unit=parameter.get("units", ""),
        transient=int(ds.attrs.get("transient_revolutions", 0)),
    )


def plot_command(args: argparse.Namespace) -> int:
    """Handler of ``sim plot``; returns the exit code (errors are reported by ``sim.cli``)."""
    from sim.plots.style import FORMATS, save
    from sim.results import open_run

    suffix = args.output.suffix.lstrip(".").lower()
    if suffix not in FORMATS:
        endings = " or ".join(f".{name}" for name in FORMATS)
        raise ValueError(f"--output '{args.output}': give a file ending in {endings}")
    check_output("--output", args.output)
    ds = open_run(args.file, "file", "`sim run`, `sim analyze` or `sim sweep`")
    what = file_kind(ds, args.file)
    kind = args.kind or KINDS[what][0]
    if kind not in KINDS[what]:
        raise ValueError(
            f"--kind {kind}: the {what} file {args.file} is drawn as {' or '.join(KINDS[what])}"
        )
    if args.ideal is not None and kind != "responses":
        raise ValueError(f"--ideal: only the responses take an ideal reference, not --kind {kind}")
    save(_figure(ds, kind, args), args.output)
    print(f"{args.output}: {kind} of the {what} {args.file}")
    return 0


def _article(noun: str) -> str:
    return "an" if noun[0] in "aeiou" else "a"


def register(subparsers: argparse._SubParsersAction) -> argparse.ArgumentParser:
    """Add the ``plot`` subcommand to the ``sim`` command's subparsers."""
    kinds = "; ".join(
        f"{_article(what)} {what}: {', '.join(names)}" for what, names in KINDS.items()
    )
    parser = subparsers.add_parser(
        "plot",
        help="draw a run, an analysis or a sweep to PNG or SVG",
        description=(
            "Draw a file of `sim run`, `sim analyze` or `sim sweep` with the workflow's figure "
            f"code. Kinds ({kinds}; the first is the default)."
        ),
    )
    parser.add_argument("file", type=Path, help="a run, analysis or sweep file (netCDF)")
    parser.add_argument(
        "-o",
        "--output",
        type=Path,
        required=True,
        help="figure to write; its suffix, .png or .svg, names the format",
    )
    parser.add_argument(
        "--kind", choices=[name for names in KINDS.values() for name in names], help=kinds
    )
    parser.add_argument(
        "--ideal",
        type=Path,
        metavar="FILE",
        help=(
            "responses: the ideal reference run (default: the run's scene simulated with every "
            "joint ideal and every link rigid)"
        ),
    )
    parser.add_argument(
        "--revolutions",
        type=float,
        default=2.0,
        metavar="N",
        help="responses: the last N crank revolutions drawn (default 2)",
    )
    parser.set_defaults(func=plot_command)
    return parser

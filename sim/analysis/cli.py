"""The ``sim analyze`` subcommand: chaos analysis of one run file."""

import argparse
import os
import sys
from pathlib import Path

import xarray as xr

from sim.analysis.run import analyze_run

#: default transient: this many revolutions, or a quarter of the run if that is fewer
DEFAULT_TRANSIENT_REVOLUTIONS = 20


def default_transient(n_revolutions: int) -> int:
    """Revolutions dropped by default: min(20, a quarter of the run)."""
    return min(DEFAULT_TRANSIENT_REVOLUTIONS, n_revolutions // 4)


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
    parser.set_defaults(func=analyze_command)
    return parser


def analyze_command(args: argparse.Namespace) -> int:
    """Handler of ``sim analyze``; returns the exit code."""
    try:
        with xr.open_dataset(args.run) as run:
            transient = (
                default_transient(run.sizes.get("revolution", 0))
                if args.transient is None
                else args.transient
            )
            analysis = analyze_run(run.load(), transient_revolutions=transient)
    except (OSError, ValueError) as error:
        print(f"sim analyze: {args.run}: {error}", file=sys.stderr)
        return 1
    # written under a temporary name and renamed, so a crash never leaves a partial file
    partial = args.output.with_name(args.output.name + ".partial")
    analysis.to_netcdf(partial)
    os.replace(partial, args.output)
    return 0

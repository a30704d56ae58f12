"""The `sim` command line: run | scene | analyze | sweep | plot | experiment | restitution.

One module per group of subcommands (simulate, analyze, plot, experiment, restitution), each with a
`register(subparsers)`; `arguments` holds what they share. Nothing outside this package
imports it, so the command line sits on top of the library and no import cycle runs through it.

    sim run sixbar -o flagship.nc --set joints.A.clearance=0.5e-3
    sim run my-linkage.yaml -o mine.nc    # a scene file of one's own (docs/scenes.md)
    sim scene sixbar --set drive.speed_rpm=60
    sim analyze flagship.nc -o flagship-analysis.nc
    sim sweep sixbar --key joints.A.clearance --range 0 1e-3 11 --out-dir runs -o bifurcation.nc
    sim plot bifurcation.nc -o bifurcation.svg      # a run, an analysis or a sweep
    sim experiment synthesize | compare ...
    sim restitution --law tsuji --nominal 0.5 --speed 0.1 --json

Ctrl-C prints one line (what was interrupted, at which simulated time or sweep point, what was
kept) and exits with code 130; no output is left half-written. Errors in the input (scene,
overrides, files) are reported with exit code 2 before any computation (every problem of a
scene and its overrides in one message, each naming the file or the --set that wrote the key; a
linkage that cannot close or cannot be driven through a full crank turn with the loop and the
crank angle); a run that fails numerically reports the time, the joint and a diagnosis with
exit code 1 and writes no output file.
"""

import argparse
import sys
from collections.abc import Sequence

from sim import __version__
from sim.cli import analyze, experiment, plot, restitution, simulate

#: the exit code of a command stopped by Ctrl-C (SIGINT): 128 + 2, as a shell reports it
INTERRUPTED = 130


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of every subcommand."""
    parser = argparse.ArgumentParser(
        prog="sim", description="Planar linkages with joint clearances and flexible links."
    )
    parser.add_argument("--version", action="version", version=f"sim {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    simulate.register(sub)
    analyze.register(sub)
    analyze.register_sweep(sub)
    plot.register(sub)
    experiment.register(sub)
    restitution.register(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the `sim` console script."""
    from sim.model.assembly import AssemblyError
    from sim.run import Interrupted, SimulationError
    from sim.scene import SceneError

    args = build_parser().parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except KeyboardInterrupt as stop:
        where, kept = (stop.where, stop.kept) if isinstance(stop, Interrupted) else ("", "")
        print(
            f"sim {args.command}: interrupted{' ' + where if where else ''}; "
            f"{kept or 'nothing written'}",
            file=sys.stderr,
        )
        return INTERRUPTED
    except (SceneError, AssemblyError, FileNotFoundError, ValueError) as exc:
        print(f"sim {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except SimulationError as exc:
        print(f"sim {args.command}: simulation failed: {exc}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())

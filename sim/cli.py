"""The `sim` command line: run | scene | analyze | sweep | experiment.

    sim run sixbar -o flagship.nc --set joints.A.clearance=0.5e-3
    sim scene sixbar --set drive.speed_rpm=60
    sim analyze flagship.nc -o flagship-analysis.nc
    sim sweep sixbar --key joints.A.clearance --range 0 1e-3 11 --out-dir runs -o bifurcation.nc
    sim experiment synthesize | compare ...

Errors in the input (scene, overrides, files) are reported in one line with
exit code 2 before any computation; a run that fails numerically reports the
time, the joint and a diagnosis with exit code 1 and writes no output file.
"""

import argparse
import sys
from collections.abc import Sequence

from sim import __version__


def add_scene_arguments(parser: argparse.ArgumentParser) -> None:
    """The scene name or path and the repeatable --set overrides."""
    parser.add_argument("scene", help="built-in scene name (sixbar, slider-crank) or YAML path")
    parser.add_argument(
        "--set",
        dest="overrides",
        action="append",
        default=[],
        metavar="KEY=VALUE",
        help="override a scene key, e.g. joints.A.clearance=0.5e-3 (repeatable)",
    )


def _cmd_scene(args: argparse.Namespace) -> int:
    from sim.scene import dump_scene, load_scene

    sys.stdout.write(dump_scene(load_scene(args.scene, args.overrides)))
    return 0


def _cmd_run(args: argparse.Namespace) -> int:
    from sim.results import write_netcdf
    from sim.run import simulate
    from sim.scene import load_scene

    scene = load_scene(args.scene, args.overrides)
    ds = simulate(scene, progress=not args.quiet, ideal=args.ideal, rigid=args.rigid)
    write_netcdf(ds, args.output)
    a = ds.attrs
    peak_force = float(ds.peak_normal_force.max()) if ds.sizes["joint"] else 0.0
    print(
        f"{args.output}: {a['solver_accepted_steps']} steps "
        f"({a['solver_rejected_steps']} rejected, {a['solver_contact_events']} contact events), "
        f"real-time factor {a['real_time_factor']:.3g}, peak contact force {peak_force:.4g} N, "
        f"energy error {a['energy_error_relative']:.2e} of the energy scale"
    )
    return 0


def build_parser() -> argparse.ArgumentParser:
    """The argument parser of every subcommand."""
    parser = argparse.ArgumentParser(
        prog="sim", description="Planar linkages with joint clearances and flexible links."
    )
    parser.add_argument("--version", action="version", version=f"sim {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)

    run = sub.add_parser("run", help="simulate a scene to a netCDF file")
    add_scene_arguments(run)
    run.add_argument("-o", "--output", required=True, help="output netCDF path")
    run.add_argument("--ideal", action="store_true", help="every joint ideal (reference)")
    run.add_argument("--rigid", action="store_true", help="every link rigid (reference)")
    run.add_argument("-q", "--quiet", action="store_true", help="no progress line")
    run.set_defaults(func=_cmd_run)

    scene = sub.add_parser("scene", help="print the resolved scene as YAML")
    add_scene_arguments(scene)
    scene.set_defaults(func=_cmd_scene)

    from sim.analysis.cli import register as register_analyze
    from sim.analysis.cli import register_sweep
    from sim.experiment.cli import register as register_experiment

    register_analyze(sub)
    register_sweep(sub)
    register_experiment(sub)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the `sim` console script."""
    from sim.model.assembly import AssemblyError
    from sim.run import SimulationError
    from sim.scene import SceneError

    args = build_parser().parse_args(argv)
    try:
        return int(args.func(args) or 0)
    except (SceneError, AssemblyError, FileNotFoundError, ValueError) as exc:
        print(f"sim {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except SimulationError as exc:
        print(f"sim {args.command}: simulation failed: {exc}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())

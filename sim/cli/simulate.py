"""`sim run` and `sim scene`: simulate a scene to a netCDF file, or print it resolved."""

import argparse
import sys

from sim.cli.arguments import add_scene_arguments, check_output
from sim.quantities import SAMPLINGS


def _cmd_scene(args: argparse.Namespace) -> int:
    from sim.scene import dump_scene, load_scene

    sys.stdout.write(dump_scene(load_scene(args.scene, args.overrides)))
    return 0


def _cmd_run(args: argparse.Namespace) -> int:
    from sim.results import write_netcdf
    from sim.run import audit_advice, simulate
    from sim.scene import load_scene

    check_output("--output", args.output)
    overrides = list(args.overrides or [])
    if args.sampling is not None:
        overrides.append(f"simulation.sampling={args.sampling}")
    scene = load_scene(args.scene, overrides)
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
    if a["energy_audit_exceeded"]:
        beams = not args.rigid and any(b["kind"] == "beam" for b in scene["bodies"].values())
        print(
            f"{args.output}: the energy audit {a['energy_error_relative']:.2e} exceeds the bound "
            f"of a sound run, {a['energy_audit_bound']:g} of the energy scale "
            f"(docs/fidelity.md): {audit_advice(scene['solver']['method'], beams)}"
        )
    return 0


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add `run` and `scene` to the `sim` command line."""
    run = subparsers.add_parser("run", help="simulate a scene to a netCDF file")
    add_scene_arguments(run)
    run.add_argument("-o", "--output", required=True, help="output netCDF path")
    run.add_argument("--ideal", action="store_true", help="every joint ideal (reference)")
    run.add_argument("--rigid", action="store_true", help="every link rigid (reference)")
    run.add_argument(
        "--sampling",
        choices=SAMPLINGS,
        help="how the fast quantities are sampled: mean over each sample's window (the "
        "scene's simulation.sampling, default mean) or point value at the sample time",
    )
    run.add_argument("-q", "--quiet", action="store_true", help="no progress line")
    run.set_defaults(func=_cmd_run)

    scene = subparsers.add_parser("scene", help="print the resolved scene as YAML")
    add_scene_arguments(scene)
    scene.set_defaults(func=_cmd_scene)

"""`sim restitution`: the coefficient of restitution a damping law achieves in one impact."""

import argparse
import json

from sim.model.contact_laws import DEFAULT_LAW, LAW_NAMES


def _cmd_restitution(args: argparse.Namespace) -> int:
    from sim.model.restitution import NOMINAL, SPEED, effective_restitution
    from sim.scene_keys import check_option

    check_option("--nominal", args.nominal, NOMINAL)
    check_option("--speed", args.speed, SPEED)
    effective = effective_restitution(args.law, args.nominal, args.speed)
    if args.json:
        record = {"law": args.law, "nominal": args.nominal, "speed": args.speed}
        print(json.dumps({**record, "effective": effective}))
    else:
        print(
            f"{args.law}: nominal e = {args.nominal:g} at {args.speed:g} m/s restitutes "
            f"e_eff = {effective:.6f}"
        )
    return 0


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add `restitution` to the `sim` command line."""
    cmd = subparsers.add_parser(
        "restitution",
        help="the restitution a contact law achieves in one impact",
        description="Integrate one free central impact of a point mass on a Hertz half-space "
        "(n = 1.5) with the engine's compiled contact force and print the effective "
        "coefficient of restitution -(rate out)/(rate in). The laws with memory depend on "
        "the speed through the damping guard v_min = 1e-4 m/s (contact.min_impact_speed).",
    )
    cmd.add_argument(
        "--law", choices=LAW_NAMES, default=DEFAULT_LAW, help="damping law (docs/model.md)"
    )
    cmd.add_argument(
        "--nominal", type=float, required=True, help="nominal restitution e, 0 < e <= 1"
    )
    cmd.add_argument("--speed", type=float, required=True, help="impact speed (m/s), above 0")
    cmd.add_argument("--json", action="store_true", help="print one JSON object")
    cmd.set_defaults(func=_cmd_restitution)

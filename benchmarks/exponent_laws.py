"""The model exponent under each damping law at one operating point of the six-bar and one
link model, at several settings: whether the exponent is interval-invariant (a linearised
exponent) or not (a finite-size one) under each law.

Points, link models and settings as in benchmarks/exponent_invariance.py (RTOL:INTERVAL:D0,
atol = rtol / 100). One JSON line per (law, setting): the exponent (1/s, `linkage_lyapunov`),
its standard error, the CPU seconds it took and the stretch's quantiles. `--laws` restricts
the laws (all of docs/model.md's table by default).

Usage: python benchmarks/exponent_laws.py POINT LINKS REVOLUTIONS TRANSIENT SETTING...
                                          [--laws NAME ...]
e.g.   python benchmarks/exponent_laws.py slow rigid 24 4 1e-6:1/32:1e-6 1e-6:1/512:1e-6
"""

import argparse
import json

from exponent_invariance import POINTS, exponent_row, link_overrides

from sim.model.contact_laws import LAW_NAMES
from sim.scene import load_scene


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("point", choices=sorted(POINTS))
    parser.add_argument("links")
    parser.add_argument("revolutions")
    parser.add_argument("transient")
    parser.add_argument("settings", nargs="+", metavar="RTOL:INTERVAL:D0")
    parser.add_argument("--laws", nargs="+", choices=LAW_NAMES, default=list(LAW_NAMES))
    args = parser.parse_args()
    name, overrides = POINTS[args.point]
    for law in args.laws:
        scene = load_scene(name, [*overrides, *link_overrides(args.links), f"contact.law={law}"])
        for setting in args.settings:
            row = exponent_row(
                scene, args.point, args.links, args.revolutions, args.transient, setting
            )
            print(json.dumps({"law": law} | row), flush=True)


if __name__ == "__main__":
    main()

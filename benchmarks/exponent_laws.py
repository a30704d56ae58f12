"""The model exponent under each damping law at one operating point of the six-bar, rigid
links, at several renormalisation intervals: whether the exponent is interval-invariant (a
linearised exponent) or not (a finite-size one) under each law.

One JSON line per (law, interval): the exponent (1/s, `linkage_lyapunov`, its default
tolerances and d0 = 1e-6 m), its standard error and the CPU seconds it took.

Usage: python benchmarks/exponent_laws.py POINT REVOLUTIONS TRANSIENT INTERVAL...
e.g.   python benchmarks/exponent_laws.py flagship 8 2 1/32 1/128 1/512
"""

import json
import sys
import time
from fractions import Fraction

from exponent_invariance import POINTS

from sim.model.contact_laws import LAW_NAMES
from sim.scene import load_scene
from sim.studies.model_lyapunov import linkage_lyapunov


def main() -> None:
    point, revolutions, transient, *intervals = sys.argv[1:]
    for law in LAW_NAMES:
        scene = load_scene("sixbar", [*POINTS[point], f"contact.law={law}"])
        for interval in intervals:
            start = time.process_time()
            result = linkage_lyapunov(
                scene,
                revolutions=float(revolutions),
                transient_revolutions=float(transient),
                interval_revolutions=float(Fraction(interval)),
                rigid=True,
            )
            row = {
                "point": point,
                "law": law,
                "interval_revolutions": interval,
                "exponent_per_s": round(result.exponent, 1),
                "stderr_per_s": round(result.stderr, 1),
                "cpu_s": round(time.process_time() - start, 1),
            }
            print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()

"""Where the model exponent's stretch happens: per renormalisation interval, the logarithmic
stretch ln(d / d0) beside the contact events of the reference and of the perturbed trajectory.

The exponent of `sim.studies.model_lyapunov.linkage_lyapunov` on rigid links, at one operating
point of the six-bar (the points of benchmarks/exponent_invariance.py), rtol 1e-6, d0 = 1e-6 m;
its propagator is built here, counting the events, and run by `propagator_lyapunov`.
Prints one JSON line: the exponent; the share of intervals with a contact event in either
trajectory and with a different number of events in the two; the share of the total stretch
those intervals carry; the mean stretch of an interval without events, with the same events
and with different ones; and how many of the top 1 % stretches fall in each kind. Used for
docs/exponent.md, "The harder points".

Usage: python benchmarks/exponent_bursts.py POINT INTERVAL REVOLUTIONS TRANSIENT
e.g.   python benchmarks/exponent_bursts.py slow 1/512 24 4
"""

import json
import sys
from dataclasses import dataclass, field
from fractions import Fraction

import numpy as np
from exponent_invariance import POINTS

from sim.analysis.lyapunov import interval_stretch
from sim.scene import load_scene
from sim.studies.model_lyapunov import (
    LinkagePropagator,
    linkage_propagator,
    propagator_lyapunov,
    with_tolerances,
)


@dataclass(frozen=True, eq=False)
class CountingPropagator(LinkagePropagator):
    """The propagator of `linkage_lyapunov`, counting each trajectory's contact events (flag
    flips) per renormalisation interval."""

    reference_events: list[int] = field(default_factory=list)
    perturbed_events: list[int] = field(default_factory=list)

    def advance_leader(self, state: np.ndarray, t: float, dt: float) -> np.ndarray:
        before = self.leader.tally[0]["events"]
        out = super().advance_leader(state, t, dt)
        self.reference_events.append(int(self.leader.tally[0]["events"] - before))
        return out

    def advance(self, state: np.ndarray, t: float, dt: float) -> np.ndarray:
        before = self.integration.tally[0]["events"]
        out = super().advance(state, t, dt)
        self.perturbed_events.append(int(self.integration.tally[0]["events"] - before))
        return out


def main() -> None:
    point, interval_text, revolutions, transient = sys.argv[1:]
    scene = with_tolerances(load_scene("sixbar", POINTS[point]), (1e-6, 1e-8))
    plain = linkage_propagator(scene, rigid=True)
    counting = CountingPropagator(plain.integration, plain.leader, plain.scene_name)
    result = propagator_lyapunov(
        counting,
        scene,
        revolutions=float(revolutions),
        transient_revolutions=float(transient),
        interval_revolutions=float(Fraction(interval_text)),
    )
    stretch = interval_stretch(result)
    n = stretch.size
    reference = np.array(counting.reference_events[-n:])
    perturbed = np.array(counting.perturbed_events[-n:])
    eventful = (reference > 0) | (perturbed > 0)
    differing = reference != perturbed
    same = eventful & ~differing
    top = stretch > np.quantile(stretch, 0.99)
    row = {
        "point": point,
        "interval_revolutions": interval_text,
        "exponent_per_s": round(result.exponent, 1),
        "intervals": n,
        "share_with_events": round(float(eventful.mean()), 3),
        "share_with_differing_events": round(float(differing.mean()), 3),
        "stretch_share_with_events": round(float(stretch[eventful].sum() / stretch.sum()), 3),
        "stretch_share_with_differing_events": round(
            float(stretch[differing].sum() / stretch.sum()), 3
        ),
        "mean_stretch_without_events": round(float(stretch[~eventful].mean()), 3),
        "mean_stretch_same_events": round(float(stretch[same].mean()), 3),
        "mean_stretch_differing_events": round(float(stretch[differing].mean()), 3),
        "top1pct_with_events": round(float(eventful[top].mean()), 3),
        "top1pct_with_differing_events": round(float(differing[top].mean()), 3),
    }
    print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()

"""Where the model exponent's stretch happens: per renormalisation interval, the logarithmic
stretch ln(d / d0) beside the contact events of the reference and of the perturbed trajectory.

The exponent of `sim.studies.model_lyapunov.linkage_lyapunov` on rigid links, at one operating
point of the six-bar (the points of benchmarks/exponent_invariance.py), rtol 1e-6, d0 = 1e-6 m.
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
from fractions import Fraction

import numpy as np
from exponent_invariance import POINTS

from sim.analysis.lyapunov import benettin
from sim.model.assembly import crank_period
from sim.run import Integration
from sim.scene import load_scene
from sim.studies.model_lyapunov import linkage_propagator, with_tolerances


def events(integ: Integration) -> int:
    """Contact events (flag flips) an integration has made so far."""
    return int(integ.tally[0]["events"])


def main() -> None:
    point, interval_text, revolutions, transient = sys.argv[1:]
    scene = with_tolerances(load_scene("sixbar", POINTS[point]), (1e-6, 1e-8))
    propagator = linkage_propagator(scene, rigid=True)
    interval = float(Fraction(interval_text))
    distance = propagator.distance(scene)
    reference_events: list[int] = []
    perturbed_events: list[int] = []

    def advance_reference(state: np.ndarray, t: float, dt: float) -> np.ndarray:
        before = events(propagator.leader)
        out = propagator.advance_leader(state, t, dt)
        reference_events.append(events(propagator.leader) - before)
        return out

    def advance(state: np.ndarray, t: float, dt: float) -> np.ndarray:
        before = events(propagator.integration)
        out = propagator.advance(state, t, dt)
        perturbed_events.append(events(propagator.integration) - before)
        return out

    result = benettin(
        advance,
        propagator.pack(),
        0.0,
        interval=interval * crank_period(scene),
        n_intervals=round((float(revolutions) - float(transient)) / interval),
        d0=1e-6,
        distance=distance,
        rescale=propagator.rescale(distance),
        mask=propagator.mask(),
        transient_intervals=round(float(transient) / interval),
        advance_reference=advance_reference,
    )
    recorded = result.time - (result.time[0] - result.interval)
    stretch = np.diff(result.running * recorded, prepend=0.0)
    n = stretch.size
    reference = np.array(reference_events[-n:])
    perturbed = np.array(perturbed_events[-n:])
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

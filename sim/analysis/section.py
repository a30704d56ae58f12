"""What the Poincaré section says about each channel of a run: whether its points repeat,
whether a wall holds the channel there, and whether the mechanism's whole recorded state
returns with it.

A clearance channel can repeat at the section for two reasons: the motion is periodic, or the
joint is in contact at that crank angle every revolution and its wall pins the coordinate (a
slider pressed onto one face of its guide sits at ±c across the guide whatever the rest of
the mechanism does). The two are told apart by the rest of the state: a periodic motion
returns as a whole, so every recorded coordinate at the section (every clearance channel's
value and rate, every body's position and velocity) repeats with the channel; a pinned one
does not. A channel is read as periodic when its own points repeat and either it is not held
at its bound or the whole state returns too.
"""

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np
import xarray as xr

from sim.analysis.poincare import SECTION_RESOLUTION, SectionStructure, section_structure

#: a channel is held at its bound when its section value lies there in more than this share
#: of the crossings (the period search reads medians, so a majority is what can fool it)
HELD_SHARE = 0.5
#: a channel moves when its range exceeds this share of its largest magnitude: below it the
#: range is float32 storage noise (a slider across an ideal guide)
STILL_RANGE = 1e-6


@dataclass(frozen=True)
class SectionEvidence:
    """The Poincaré section's evidence on one channel.

    Attributes:
        period: smallest k (crossings) at which the channel's own points repeat, 0 for none
            (:func:`sim.analysis.poincare.section_structure`).
        return_distance: their median distance k crossings apart, over the orbit's extent.
        held: whether the channel's value at the section lies at its clearance bound (the
            bearing's circle, the guide's wall) in most crossings: its wall sets it there.
        state_period: smallest k at which every recorded coordinate of the mechanism repeats
            at the section (every clearance channel and every body, value and rate), 0 for
            none.
        state_return_distance: the largest coordinate's median return distance at that k
            (at the best k when none), over its extent.
    """

    period: int
    return_distance: float
    held: bool = False
    state_period: int = 0
    state_return_distance: float = float("nan")

    @property
    def periodic(self) -> bool:
        """The channel's points repeat, and not merely because its wall holds it there while
        the rest of the mechanism does not return."""
        return self.period > 0 and (not self.held or self.state_period > 0)

    def text(self) -> str:
        """What the section says, as a clause of a verdict's reason."""
        own = (
            f"its Poincaré points repeat every {self.period} crossing(s) (return distance "
            f"{self.return_distance:.2g} of the orbit size)"
            if self.period
            else f"its Poincaré points do not repeat (closest return {self.return_distance:.2g} "
            "of the orbit size)"
        )
        if not self.held:
            return own
        state = (
            f"returns every {self.state_period} crossing(s)"
            if self.state_period
            else f"does not return (closest {self.state_return_distance:.2g} of its size)"
        )
        return (
            f"{own}, the joint resting on its clearance bound at the section while the "
            f"mechanism's state {state}"
        )


@dataclass(frozen=True)
class Coordinate:
    """One recorded coordinate of a run after the transient with its rate: a clearance
    channel (joint and axis: eccentricity, m, and its rate, m/s) or a body's (position and
    velocity), its samples, its section points and how they are arranged."""

    name: str  # "A.x", "slider.y"
    source: str  # "joint" or "body"
    item: str
    axis: str
    quantity: str  # "eccentricity" or "position"
    value: np.ndarray
    rate: np.ndarray
    section_value: np.ndarray
    section_rate: np.ndarray
    extent: np.ndarray  # (value range, rate range)
    structure: SectionStructure


def clearance_bounds(scene: dict | None) -> dict[tuple[str, str], float]:
    """The bound (m) of each clearance channel's value, (joint, axis) → c: a revolute joint's
    eccentricity lies within its radial clearance c on both axes, a slider's across its guide
    (axis x) within c; along the guide (y) nothing bounds it. Empty without a scene."""
    if scene is None:
        return {}
    bounds = {}
    for name, joint in scene["joints"].items():
        if joint.get("clearance", 0.0) <= 0.0:
            continue
        axes = ("x", "y") if joint["type"] == "revolute" else ("x",)
        bounds.update({(name, axis): float(joint["clearance"]) for axis in axes})
    return bounds


def held_at_bound(section_values: np.ndarray, bound: float, extent: float) -> bool:
    """Whether a channel's section values lie at its bound |value| = c (within the section's
    resolution of its range, penetration included) in more than ``HELD_SHARE`` of the
    crossings."""
    at_bound = np.abs(section_values) >= bound - SECTION_RESOLUTION * extent
    return bool(np.mean(at_bound) > HELD_SHARE)


def state_return(structures: Sequence[SectionStructure]) -> tuple[int, float]:
    """(k, distance): the smallest lag k at which every coordinate's median return distance
    is below the section's resolution, and the largest of them there; (0, the smallest such
    largest over all lags) when there is none."""
    worst = np.max([s.returns for s in structures], axis=0)
    repeats = worst < SECTION_RESOLUTION
    if repeats.any():
        k = int(np.argmax(repeats)) + 1
        return k, float(worst[k - 1])
    return 0, float(worst.min())


def _coordinates(steady: xr.Dataset, source: str) -> list[Coordinate]:
    """Every coordinate pair of ``source`` ("joint" or "body") after the transient."""
    value, rate = (
        ("eccentricity", "eccentricity_rate") if source == "joint" else ("position", "velocity")
    )
    out = []
    for item in steady[source].values:
        for axis in steady["axis"].values:
            where = {source: item, "axis": axis}
            series = [
                steady[name].sel(where).values
                for name in (value, rate, f"section_{value}", f"section_{rate}")
            ]
            extent = np.array([np.ptp(series[0]), np.ptp(series[1])])
            structure = section_structure(np.column_stack(series[2:]), extent)
            if not extent[0] > STILL_RANGE * np.max(np.abs(series[0])):
                # a channel that does not move is a fixed point: it repeats every crossing
                structure = SectionStructure(1, 0.0, 0.0, tuple(0.0 for _ in structure.returns))
            name = f"{item}.{axis}"
            out.append(
                Coordinate(name, source, str(item), str(axis), value, *series, extent, structure)
            )
    return out


def section_evidence(
    steady: xr.Dataset, scene: dict | None
) -> dict[str, tuple[Coordinate, SectionEvidence]]:
    """The section's evidence on every channel of a run, keyed by channel name ('A.x').

    Channels are the clearance joints' axes or, for a run without clearance joints, the
    bodies'; the state is every clearance channel and every body, value and rate. ``steady``
    holds the samples and the section points after the transient (the run contract of
    :func:`sim.analysis.run.analyze_run`); ``scene`` (the run's resolved scene, None if
    unknown) gives the clearance bounds.
    """
    joints = _coordinates(steady, "joint")
    bodies = _coordinates(steady, "body")
    state_period, state_distance = state_return([c.structure for c in joints + bodies])
    bounds = clearance_bounds(scene)
    out = {}
    for coordinate in joints or bodies:
        bound = bounds.get((coordinate.item, coordinate.axis))
        held = bound is not None and held_at_bound(
            coordinate.section_value, bound, coordinate.extent[0]
        )
        out[coordinate.name] = (
            coordinate,
            SectionEvidence(
                period=coordinate.structure.period,
                return_distance=coordinate.structure.return_distance,
                held=held,
                state_period=state_period,
                state_return_distance=state_distance,
            ),
        )
    return out

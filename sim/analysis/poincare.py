"""Structure of Poincaré section points: do they repeat (periodic orbit) or not."""

from dataclasses import dataclass

import numpy as np

#: default resolution of the section, as a fraction of the phase portrait's extent: points
#: closer than this are the same point (1 % is what a plot of the section can tell apart)
SECTION_RESOLUTION = 0.01
#: longest period looked for, in section crossings
MAX_PERIOD = 12
#: section points needed after the transient (the period search needs 2 · 12 + 1)
MIN_REVOLUTIONS = 2 * MAX_PERIOD + 1


@dataclass(frozen=True)
class SectionStructure:
    """How the section points of one channel are arranged.

    Attributes:
        period: smallest k ≤ max_period such that the points repeat every k crossings (the
            number of distinct clusters of a periodic orbit); 0 when there is none.
        return_distance: median normalised distance between points k crossings apart, at the
            best k (at ``period`` when periodic): below the resolution for a periodic orbit.
        spread: RMS normalised distance of the points from their centroid: ~0 for period 1,
            of order 0.1–1 for a closed curve or a chaotic scatter.
        returns: the median normalised distance between points k crossings apart, for
            k = 1 … max_period.
    """

    period: int
    return_distance: float
    spread: float
    returns: tuple[float, ...]


def section_structure(
    points: np.ndarray,
    extent: np.ndarray,
    *,
    resolution: float = SECTION_RESOLUTION,
    max_period: int = MAX_PERIOD,
) -> SectionStructure:
    """Period of a sequence of Poincaré section points, relative to the size of the orbit.

    Explanation of the method:
        Coordinates are divided by the extent of the phase portrait in that coordinate (so
        eccentricity and its rate weigh alike). A periodic orbit of period k crosses the
        section in k distinct points, visited in turn: point n and point n + k coincide. For
        k = 1 … max_period the median distance between points k crossings apart is computed;
        the smallest k with a median below ``resolution`` is the period. Quasi-periodic motion
        (points on a closed curve) and chaos (a scatter) have no such k; they are told apart by
        the exponent and the 0–1 test, not here. The median, rather than the maximum, lets a
        rare numerical outlier (an event located late) pass.

    Choosing the parameters:
        extent: the range of each coordinate over the phase portrait (same units as points);
            coordinates with zero extent do not move and are compared unscaled.
        resolution: 0.01 by default; lower it to separate points of a nearly periodic orbit.
        max_period: longest period sought (12); subharmonic responses of impacting linkages
            rarely exceed a few crank revolutions.

    Minimum data length:
        2 · max_period + 1 points; a few dozen for a trustworthy median.

    References:
        T. S. Parker, L. O. Chua, "Practical Numerical Algorithms for Chaotic Systems",
        Springer (1989): Poincaré maps and the classification of steady-state behaviour.

    Args:
        points: array (n_crossings, n_coordinates), in crossing order.
        extent: array (n_coordinates,) of the phase-portrait ranges.
        resolution: fraction of the extent below which two points are the same.
        max_period: longest period looked for.

    Returns:
        A :class:`SectionStructure`.
    """
    points = np.asarray(points, dtype=float)
    extent = np.asarray(extent, dtype=float)
    if len(points) < 2 * max_period + 1:
        raise ValueError(
            f"section_structure: {len(points)} section points, need at least {2 * max_period + 1}"
        )
    scaled = points / np.where(extent > 0, extent, 1.0)
    returns = np.array(
        [
            np.median(np.linalg.norm(scaled[k:] - scaled[:-k], axis=1))
            for k in range(1, max_period + 1)
        ]
    )
    repeats = returns < resolution
    period = int(np.argmax(repeats)) + 1 if repeats.any() else 0
    spread = float(np.sqrt(np.mean(np.sum((scaled - scaled.mean(axis=0)) ** 2, axis=1))))
    return SectionStructure(
        period=period,
        return_distance=float(returns[period - 1] if period else returns.min()),
        spread=spread,
        returns=tuple(float(r) for r in returns),
    )

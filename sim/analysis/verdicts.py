"""Verdicts on claims that compare settings, as tests on distributions of per-revolution peaks.

A claim such as "larger clearance gives larger peaks" is a set of components (a quantity, a
statistic, a pair of neighbouring settings, the expected direction). Each component is a test:
the percentile bootstrap interval, at the configured level (95 %), of the difference of the
statistic (median or 95th percentile of the per-revolution peaks) between the two settings,
from independent two-stage bootstrap resamples of each setting (sim.analysis.revolutions;
Efron & Tibshirani, "An Introduction to the Bootstrap", 1993, ch. 13 and 16). The component
is "supported" when the interval lies wholly on the expected side of 0, "not supported" when
wholly on the other side, and "undecided" when it contains 0.

The claim is "supported" when every component is: an intersection–union test, whose level is
that of each component without correction (Berger, Technometrics 24, 1982). It is "mixed" when
components are decided both ways (say torque grows and acceleration falls: the claim holds for
one quantity and is contradicted for another), "not supported" when some component is decided
against it and none for it, and "undecided" otherwise.
"""

import itertools
from dataclasses import dataclass

import pandas as pd

from sim.analysis.revolutions import (
    Bootstrap,
    interval,
    members_matrix,
    replicates,
    statistic,
    unit_of,
)

SUPPORTED = "supported"
NOT_SUPPORTED = "not supported"
UNDECIDED = "undecided"
MIXED = "mixed"
NOT_EVALUATED = "not evaluated"

#: readable names of the statistics
STATISTIC_NAMES = {"median": "median", "p95": "95th percentile"}


@dataclass(frozen=True)
class Comparison:
    """One component of a claim: `statistic` of `quantity` at setting `high` minus at `low`,
    its point estimate and bootstrap interval (in the quantity's unit), the expected sign of
    the difference (+1: larger at `high`) and the verdict."""

    quantity: str
    statistic: str
    low: str
    high: str
    expected: int
    estimate: float
    interval: tuple[float, float]
    level: float
    verdict: str

    def describe(self) -> str:
        """e.g. 'median slider_acceleration, clearance-0.4mm − clearance-0.1mm: +336
        [+120, +540] m/s² (supported)'."""
        low, high = self.interval
        return (
            f"{STATISTIC_NAMES[self.statistic]} {self.quantity.replace('_', ' ')}, "
            f"{self.high} − {self.low}: {self.estimate:+.4g} "
            f"[{low:+.4g}, {high:+.4g}] {unit_of(self.quantity)} ({self.verdict})"
        )


def decide(interval_: tuple[float, float], expected: int) -> str:
    """The verdict of one component from the interval of the difference and its expected
    sign: wholly on the expected side of 0, wholly on the other, or containing 0."""
    low, high = (expected * v for v in interval_)
    low, high = min(low, high), max(low, high)
    if low > 0.0:
        return SUPPORTED
    if high < 0.0:
        return NOT_SUPPORTED
    return UNDECIDED


def compare(
    table: pd.DataFrame,
    low: str,
    high: str,
    quantity: str,
    name: str,
    expected: int,
    boot: Bootstrap,
) -> Comparison:
    """Test that `name` ("median" or "p95") of the per-revolution `quantity` is larger
    (expected = +1) or smaller (−1) at case `high` than at case `low`. `table`: per-revolution
    rows of both cases (sim.analysis.revolutions.revolution_table)."""
    differences = replicates(table, high, quantity, name, boot) - replicates(
        table, low, quantity, name, boot
    )
    bounds = interval(differences, boot.level)
    estimate = float(
        statistic(members_matrix(table[table.case == high], quantity).ravel(), name)
        - statistic(members_matrix(table[table.case == low], quantity).ravel(), name)
    )
    return Comparison(
        quantity=quantity,
        statistic=name,
        low=low,
        high=high,
        expected=expected,
        estimate=estimate,
        interval=bounds,
        level=boot.level,
        verdict=decide(bounds, expected),
    )


def trend(
    table: pd.DataFrame,
    ordered_cases: list[str],
    quantities: dict[str, int],
    boot: Bootstrap,
    statistics: tuple[str, ...] = ("median", "p95"),
) -> list[Comparison]:
    """Every component of a monotone-trend claim: each pair of neighbouring cases (in
    `ordered_cases`, the setting increasing), each quantity with its expected sign, each
    statistic."""
    return [
        compare(table, low, high, quantity, name, sign, boot)
        for low, high in itertools.pairwise(ordered_cases)
        for quantity, sign in quantities.items()
        for name in statistics
    ]


def combine(verdicts: list[str]) -> str:
    """A claim's verdict from its components' (intersection–union, Berger 1982), "mixed" when
    they are decided both ways."""
    if not verdicts:
        return NOT_EVALUATED
    if all(v == SUPPORTED for v in verdicts):
        return SUPPORTED
    if NOT_SUPPORTED in verdicts:
        return MIXED if SUPPORTED in verdicts else NOT_SUPPORTED
    return UNDECIDED


def consistent(first: list[str], second: list[str]) -> bool:
    """Whether two judgements of one claim (e.g. from two ensembles), given as the verdicts of
    the same components in the same order, agree: no component is supported in one and decided
    against in the other (undecided agrees with either). The claims' verdicts then agree too,
    "mixed" at most against "not supported" where its supported components are undecided."""
    if len(first) != len(second):
        raise ValueError(f"{len(first)} against {len(second)} components: not the same claim")
    return all({a, b} != {SUPPORTED, NOT_SUPPORTED} for a, b in zip(first, second, strict=True))


def intervals_text(components: list[Comparison]) -> str:
    """The components with their intervals, for the report."""
    if not components:
        return ""
    level = components[0].level
    return f"{level:.0%} intervals: " + "; ".join(c.describe() for c in components)

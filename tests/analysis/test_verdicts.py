"""Distributions of per-revolution peaks (sim.analysis.revolutions) and the claims' tests on
them (sim.analysis.verdicts), on synthetic ensembles whose truth is known."""

import numpy as np
import pandas as pd
import pytest

from sim.analysis.revolutions import Bootstrap, members_matrix, resample, summarise
from sim.analysis.verdicts import (
    MIXED,
    NOT_SUPPORTED,
    SUPPORTED,
    UNDECIDED,
    combine,
    compare,
    consistent,
    decide,
    trend,
)

BOOT = Bootstrap(resamples=1000, level=0.95, seed=5)


def ensemble(case: str, level: float, members: int, revolutions: int, seed: int) -> pd.DataFrame:
    """Per-revolution peaks of a synthetic chaotic run: log-normal about `level` with 20 %
    spread, correlated from one revolution to the next (AR(1), coefficient 0.5)."""
    rng = np.random.default_rng(seed)
    rows = []
    for member in range(members):
        z = 0.0
        for revolution in range(revolutions):
            z = 0.5 * z + np.sqrt(1 - 0.25) * rng.standard_normal()
            value = level * np.exp(0.2 * z)
            rows.append(
                {
                    "case": case,
                    "member": member,
                    "seed": seed + member,
                    "revolution": revolution + 1,
                    "slider_acceleration": value,
                    "drive_torque": value / 10.0,
                    "contact_events": round(200 - value / 20),
                }
            )
    return pd.DataFrame(rows)


def test_resampling_is_seeded_and_keeps_the_shape():
    table = ensemble("a", 1000.0, 3, 25, seed=1)
    values = members_matrix(table, "slider_acceleration")
    assert values.shape == (3, 25)
    first = resample(values, BOOT, BOOT.rng("a"))
    again = resample(values, BOOT, BOOT.rng("a"))
    np.testing.assert_array_equal(first, again)
    assert first.shape == (BOOT.resamples, 75)
    assert set(np.unique(first)) <= set(values.ravel())
    assert BOOT.block_length(25) == 3 and BOOT.block_length(2) == 1


def test_summary_intervals_hold_the_estimates():
    table = ensemble("a", 1000.0, 3, 40, seed=2)
    summary = summarise(table, BOOT).set_index("quantity")
    for quantity in ("slider_acceleration", "drive_torque", "contact_events"):
        row = summary.loc[quantity]
        assert row.members == 3 and row.revolutions_per_member == 40
        for name in ("median", "p95"):
            assert row[f"{name}_low"] <= row[name] <= row[f"{name}_high"]
        assert row.p95 <= row["max"]
    assert summary.loc["slider_acceleration", "median"] == pytest.approx(1000.0, rel=0.15)
    pd.testing.assert_frame_equal(summarise(table, BOOT), summarise(table, BOOT))


@pytest.mark.parametrize(
    ("interval", "expected", "verdict"),
    [
        ((1.0, 2.0), +1, SUPPORTED),
        ((-2.0, -1.0), +1, NOT_SUPPORTED),
        ((-1.0, 2.0), +1, UNDECIDED),
        ((-2.0, -1.0), -1, SUPPORTED),
        ((1.0, 2.0), -1, NOT_SUPPORTED),
    ],
)
def test_a_component_is_decided_by_its_interval(interval, expected, verdict):
    assert decide(interval, expected) == verdict


def test_claims_combine_as_an_intersection_union_test():
    assert combine([SUPPORTED, SUPPORTED]) == SUPPORTED
    assert combine([SUPPORTED, UNDECIDED]) == UNDECIDED
    assert combine([NOT_SUPPORTED, UNDECIDED]) == NOT_SUPPORTED
    # decided both ways: part of the claim holds, part is contradicted
    assert combine([SUPPORTED, NOT_SUPPORTED, UNDECIDED]) == MIXED


def test_two_judgements_agree_when_no_component_flips():
    assert consistent([SUPPORTED, UNDECIDED], [UNDECIDED, UNDECIDED])
    # mixed against not supported: the supported component became undecided
    assert consistent([SUPPORTED, NOT_SUPPORTED], [UNDECIDED, NOT_SUPPORTED])
    assert not consistent([SUPPORTED, NOT_SUPPORTED], [NOT_SUPPORTED, SUPPORTED])
    assert not consistent([SUPPORTED], [NOT_SUPPORTED])
    with pytest.raises(ValueError, match="not the same claim"):
        consistent([SUPPORTED], [SUPPORTED, SUPPORTED])


def test_clear_differences_are_decided_both_ways():
    table = pd.concat(
        [ensemble("small", 1000.0, 3, 25, seed=3), ensemble("large", 1600.0, 3, 25, seed=4)]
    )
    grows = compare(table, "small", "large", "slider_acceleration", "median", +1, BOOT)
    assert grows.verdict == SUPPORTED
    assert grows.interval[0] <= grows.estimate <= grows.interval[1]
    assert "supported" in grows.describe()
    shrinks = compare(table, "small", "large", "slider_acceleration", "p95", -1, BOOT)
    assert shrinks.verdict == NOT_SUPPORTED
    events = compare(table, "small", "large", "contact_events", "median", -1, BOOT)
    assert events.verdict == SUPPORTED


def test_no_difference_is_undecided():
    table = pd.concat(
        [ensemble("one", 1000.0, 3, 25, seed=5), ensemble("two", 1000.0, 3, 25, seed=6)]
    )
    components = trend(table, ["one", "two"], {"slider_acceleration": +1}, BOOT)
    assert [c.verdict for c in components] == [UNDECIDED, UNDECIDED]


# The quick configuration's compared cases: clearance-size (3 members × 25 revolutions after
# the transient) and speed (3 members × 2 revolutions), at effects from none to large.
QUICK_CASES = {"clearance-size": (3, 25), "speed": (3, 2)}


@pytest.mark.parametrize("study", list(QUICK_CASES))
@pytest.mark.parametrize("effect", [1.0, 1.05, 1.2, 2.0, 0.8])
def test_two_ensembles_with_different_seeds_agree(study, effect):
    """The judgements of a claim from two ensembles drawn with different seeds agree: no
    component supported by one and decided against by the other (issue 17)."""
    members, revolutions = QUICK_CASES[study]
    judgements = []
    for seed in (100, 200):
        table = pd.concat(
            [
                ensemble("low", 1000.0, members, revolutions, seed=seed),
                ensemble("high", 1000.0 * effect, members, revolutions, seed=seed + 50),
            ]
        )
        boot = Bootstrap(resamples=1000, level=0.95, seed=seed)
        quantities = {"slider_acceleration": +1, "drive_torque": +1}
        judgements.append([c.verdict for c in trend(table, ["low", "high"], quantities, boot)])
    assert consistent(*judgements), judgements
    verdicts = [combine(j) for j in judgements]
    if effect == 2.0 and study == "clearance-size":
        assert verdicts == [SUPPORTED, SUPPORTED]

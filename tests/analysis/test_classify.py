"""Per-channel verdicts (sim.analysis.classify): only decided indicators vote."""

import math

import pytest

from sim.analysis.classify import MIN_GROWTH_PER_TIME_SCALE, SIGNIFICANCE, classify, lyapunov_vote
from sim.analysis.section import SectionEvidence

#: the flagship's crank period at 150 rpm (s)
PERIOD = 0.4


@pytest.mark.parametrize(
    ("exponent", "stderr", "vote"),
    [
        (120.0, 8.0, "chaotic"),  # 15 standard errors above zero
        (-0.83, 11.4, None),  # the flagship's A.x: cannot be told from zero
        (1.18, 8.5, None),
        (20.0, 11.0, None),  # positive, but within SIGNIFICANCE standard errors of zero
        (-3.0, 0.5, "regular"),  # its upper bound, -2 1/s, is below any growth
        (math.nan, 1.0, None),
        (1.0, math.nan, None),
    ],
)
def test_an_exponent_votes_only_when_its_interval_decides(exponent, stderr, vote):
    assert lyapunov_vote(exponent, stderr, PERIOD) == vote


def test_the_regular_vote_needs_the_whole_interval_below_the_least_growth():
    """On either side of the least practical growth, by one part in a thousand of it."""
    least = MIN_GROWTH_PER_TIME_SCALE / PERIOD
    stderr = 0.01
    below = least - SIGNIFICANCE * stderr
    assert lyapunov_vote(below * 0.999, stderr, PERIOD) == "regular"
    assert lyapunov_vote(below * 1.001, stderr, PERIOD) is None


def _verdict(section_period=0, held=False, state_period=0, **kw):
    args = dict(
        lyapunov_exponent=math.nan,
        lyapunov_stderr=math.nan,
        zero_one_K=math.nan,
        time_scale=PERIOD,
    )
    distance = 1e-3 if section_period else 0.5
    section = SectionEvidence(section_period, distance, held, state_period, 0.3)
    return classify(section=section, **{**args, **kw})


def test_an_undecided_exponent_leaves_the_verdict_to_the_zero_one_test():
    """The flagship's A.x of one full run: −0.83 ± 11.4 1/s beside K = 0.997 is chaotic, not
    quasi-periodic, and all the decided indicators agree with it."""
    v = _verdict(lyapunov_exponent=-0.83, lyapunov_stderr=11.4, zero_one_K=0.997)
    assert v.verdict == "chaotic"
    assert v.evidence["lyapunov_vote"] == "none"
    assert v.agreement == 1.0


def test_no_decided_indicator_gives_undecided():
    v = _verdict(lyapunov_exponent=5.0, lyapunov_stderr=10.0)
    assert v.verdict == "undecided"
    assert "no chaos indicator is decided" in v.evidence["reason"]


def test_the_model_exponent_comes_first_and_the_section_period_before_all():
    chaotic_model = dict(model_exponent=150.0, model_stderr=10.0)
    v = _verdict(zero_one_K=0.1, **chaotic_model)
    assert v.verdict == "chaotic"
    assert v.agreement == pytest.approx(2 / 3)  # the section and the model, not K
    assert _verdict(zero_one_K=0.1).verdict == "quasi-periodic"
    assert _verdict(section_period=1, **chaotic_model).verdict == "periodic"


def test_a_channel_held_by_its_wall_is_periodic_only_when_the_state_returns():
    """A slider resting on its wall at the section repeats there whatever the mechanism does:
    with the state not returning, neither its section nor the 0-1 test on its pinned values
    votes, and a decided exponent gives the verdict; with the state returning, it is periodic."""
    pinned = dict(section_period=1, held=True, zero_one_K=0.02)
    chaotic = _verdict(model_exponent=212.0, model_stderr=5.0, **pinned)
    assert chaotic.verdict == "chaotic"
    assert chaotic.evidence["zero_one_vote"] == "none"
    reason = chaotic.evidence["reason"]
    assert "resting on its clearance bound" in reason and "does not return" in reason
    assert "model exponent 212 ± 5 1/s votes chaotic" in reason
    assert "0–1 test K = 0.02 not read" in reason
    assert _verdict(**pinned).verdict == "undecided"
    assert _verdict(state_period=2, **pinned).verdict == "periodic"
    # a channel that no wall holds keeps its section's verdict, as before
    assert _verdict(section_period=1, model_exponent=212.0, model_stderr=5.0).verdict == "periodic"

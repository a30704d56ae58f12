"""Periodic, quasi-periodic, chaotic or undecided: one verdict per channel from its indicators."""

import math
from collections.abc import Sequence
from dataclasses import dataclass

from sim.analysis.section import SectionEvidence

#: an exponent counts as positive when it exceeds this many standard errors …
SIGNIFICANCE = 2.0
#: … and grows separations by at least this fraction (in e-folds) per time scale: an exponent
#: of 1e-4 per forcing period is zero for any practical purpose, however small its error
MIN_GROWTH_PER_TIME_SCALE = 0.01
#: K above this is a chaotic vote of the 0–1 test (K tends to 0 or 1)
ZERO_ONE_THRESHOLD = 0.5

VERDICTS = ("periodic", "quasi-periodic", "chaotic", "undecided")


@dataclass(frozen=True)
class Verdict:
    """Verdict on one channel.

    Attributes:
        verdict: 'periodic', 'quasi-periodic' or 'chaotic'.
        evidence: the indicator values and votes (numbers or short strings) and ``reason``, a
            sentence saying why.
        agreement: fraction of the available indicators consistent with the verdict.
    """

    verdict: str
    evidence: dict[str, float | int | str]
    agreement: float


def lyapunov_vote(exponent: float, stderr: float, time_scale: float) -> str | None:
    """The vote of an exponent λ ± s (1/s) over a time scale T (s).

    'chaotic' when λ is significantly positive (λ > SIGNIFICANCE · s) and grows separations by
    more than ``MIN_GROWTH_PER_TIME_SCALE`` e-folds per T; 'regular' when even its upper bound
    λ + SIGNIFICANCE · s grows them by less than that; None when the interval straddles the
    threshold (the exponent cannot be told from zero) or the exponent is unknown. An undecided
    exponent does not vote: −0.8 ± 11 1/s says nothing about regularity.
    """
    if not (math.isfinite(exponent) and math.isfinite(stderr)):
        return None
    least = MIN_GROWTH_PER_TIME_SCALE / time_scale
    if exponent > SIGNIFICANCE * stderr and exponent > least:
        return "chaotic"
    if exponent + SIGNIFICANCE * stderr < least:
        return "regular"
    return None


def zero_one_vote(K: float) -> str | None:
    """'chaotic' for K above ``ZERO_ONE_THRESHOLD``, 'regular' otherwise, None if unknown."""
    if not math.isfinite(K):
        return None
    return "chaotic" if K > ZERO_ONE_THRESHOLD else "regular"


def _consistent(vote: str, verdict: str) -> bool:
    return (vote == "chaotic") == (verdict == "chaotic")


def classify(
    *,
    section: SectionEvidence,
    lyapunov_exponent: float,
    lyapunov_stderr: float,
    zero_one_K: float,
    time_scale: float,
    model_exponent: float = math.nan,
    model_stderr: float = math.nan,
) -> Verdict:
    """Verdict on one channel from its Poincaré section, the Lyapunov exponents and the 0–1 test.

    Explanation of the method:
        The indicators answer different questions. The Poincaré section tells periodic motion
        (points repeat every k crossings, see :mod:`sim.analysis.poincare`) from the rest; it
        cannot tell a closed curve (quasi-periodic) from a scatter (chaos) on its own. The
        largest Lyapunov exponent and the 0–1 test tell chaos (exponential divergence,
        diffusive walk) from regular motion. So:

        - section points repeat → 'periodic', unless the channel is held at its clearance
          bound at the section while the mechanism's state does not return
          (:class:`sim.analysis.section.SectionEvidence`): then the wall, not the motion, sets
          the section value, and neither the section nor the 0–1 test on those values votes;
        - otherwise the first DECIDED chaos vote, in this order, gives 'chaotic' or
          'quasi-periodic': the model's own exponent (Benettin on the linkage, when given), the
          channel's time-series exponent, the 0–1 test;
        - 'undecided' when none of them is decided.

        An exponent votes only when its interval λ ± ``SIGNIFICANCE`` · s lies on one side of
        the least practical growth (:func:`lyapunov_vote`); K votes chaotic above 0.5 and
        regular below. The model exponent comes first because it is the linkage's own and the
        quantity the literature reports; when a decided vote disagrees with the verdict,
        ``agreement`` drops below 1 and the reason says so. The reason names every indicator
        read, its value and its vote.

    Choosing the parameters:
        time_scale: the forcing period (the crank period for the linkage), in the exponents'
            inverse units.

    References:
        G. A. Gottwald, I. Melbourne, SIAM J. Appl. Dyn. Syst. 8 (2009) 129–145 (K threshold).
        T. S. Parker, L. O. Chua, "Practical Numerical Algorithms for Chaotic Systems",
        Springer (1989) (periodic, quasi-periodic and chaotic steady states).

    Args:
        section: what the Poincaré section says about the channel.
        lyapunov_exponent: the channel's largest exponent (NaN when it could not be estimated).
        lyapunov_stderr: its standard error.
        zero_one_K: K of the 0–1 test on the section points (NaN when unknown).
        time_scale: the forcing period.
        model_exponent, model_stderr: the model's largest exponent and its standard error
            (NaN: not computed).

    Returns:
        A :class:`Verdict`.
    """
    pinned = section.period > 0 and not section.periodic
    model = lyapunov_vote(model_exponent, model_stderr, time_scale)
    series = lyapunov_vote(lyapunov_exponent, lyapunov_stderr, time_scale)
    zero_one = None if pinned else zero_one_vote(zero_one_K)
    decided = model or series or zero_one
    if section.periodic:
        verdict, why = "periodic", "the section points repeat"
    elif decided == "chaotic":
        verdict, why = "chaotic", "the motion diverges"
    elif decided == "regular":
        verdict, why = "quasi-periodic", "the motion does not diverge"
    else:
        verdict, why = "undecided", "no chaos indicator is decided"

    votes = [vote for vote in (model, series, zero_one) if vote is not None]
    consistent = sum(_consistent(vote, verdict) for vote in votes) + 1  # + the section
    agreement = consistent / (len(votes) + 1)
    read = [f"section: {section.text()}" + ("; not read as periodic" if pinned else "")]
    if not math.isnan(model_exponent):
        read.append(
            f"model exponent {model_exponent:.3g} ± {model_stderr:.2g} 1/s votes "
            f"{model or 'nothing'}"
        )
    read.append(
        "series exponent not estimated"
        if math.isnan(lyapunov_exponent)
        else f"series exponent {lyapunov_exponent:.3g} ± {lyapunov_stderr:.2g} 1/s votes "
        f"{series or 'nothing'}"
    )
    if math.isnan(zero_one_K):
        read.append("0–1 test not estimated")
    elif pinned:
        read.append(f"0–1 test K = {zero_one_K:.2f} not read (the wall sets the section values)")
    else:
        read.append(f"0–1 test K = {zero_one_K:.2f} votes {zero_one or 'nothing'}")
    basis = _basis(
        section,
        pinned,
        (model, series, zero_one),
        (model_exponent, model_stderr),
        (lyapunov_exponent, lyapunov_stderr),
        zero_one_K,
    )
    reason = (
        f"{verdict}: {why}. Read: "
        + "; ".join(read)
        + ("; the indicators disagree" if agreement != 1.0 else "")
        + "."
    )
    evidence: dict[str, float | int | str] = {
        "model_exponent": model_exponent,
        "model_stderr": model_stderr,
        "model_vote": model or "none",
        "lyapunov_exponent": lyapunov_exponent,
        "lyapunov_stderr": lyapunov_stderr,
        "lyapunov_vote": series or "none",
        "zero_one_K": zero_one_K,
        "zero_one_vote": zero_one or "none",
        "section_period": section.period,
        "section_return_distance": section.return_distance,
        "section_held": int(section.held),
        "state_period": section.state_period,
        "agreement": agreement,
        "basis": basis,
        "reason": reason,
    }
    return Verdict(verdict=verdict, evidence=evidence, agreement=agreement)


def _basis(
    section: SectionEvidence,
    pinned: bool,
    votes: tuple[str | None, str | None, str | None],
    model: tuple[float, float],
    series: tuple[float, float],
    zero_one_K: float,
) -> str:
    """What decided a verdict, in a few words: the section, or the first decided chaos vote
    (model exponent, series exponent, 0–1 test), or nothing; a channel its wall holds says so."""
    if section.periodic:
        whole = " with the whole state" if section.held else ""
        return f"Poincaré points repeat every {section.period}{whole}"
    texts = (
        f"model exponent {model[0]:.3g} ± {model[1]:.2g} 1/s",
        f"series exponent {series[0]:.3g} ± {series[1]:.2g} 1/s",
        f"0–1 test K = {zero_one_K:.2f}",
    )
    decided = next((text for vote, text in zip(votes, texts, strict=True) if vote), None)
    held = "; its wall holds the section value" if pinned else ""
    return (decided or "no indicator decided") + held


def _exponent_vote(verdict: Verdict) -> str:
    """The verdict's decided exponent vote: the model's, else the time series', else 'none'."""
    model = verdict.evidence["model_vote"]
    return model if model != "none" else str(verdict.evidence["lyapunov_vote"])


def indicator_agreement(verdicts: Sequence[Verdict]) -> dict[str, float]:
    """Agreement between the indicators over many channels (or runs of a sweep).

    Returns:
        ``mean_agreement``: mean of the per-channel agreement; ``lyapunov_zero_one``: fraction
        of the channels where a decided exponent vote (the model's, else the time series') and
        the 0–1 vote both exist and agree (NaN if none has both).
    """
    if not verdicts:
        return {"mean_agreement": math.nan, "lyapunov_zero_one": math.nan}
    both = [
        _exponent_vote(v) == v.evidence["zero_one_vote"]
        for v in verdicts
        if _exponent_vote(v) != "none" and v.evidence["zero_one_vote"] != "none"
    ]
    return {
        "mean_agreement": sum(v.agreement for v in verdicts) / len(verdicts),
        "lyapunov_zero_one": sum(both) / len(both) if both else math.nan,
    }

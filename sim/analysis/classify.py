"""Periodic, quasi-periodic or chaotic: one verdict per channel from three indicators."""

import math
from collections.abc import Sequence
from dataclasses import dataclass

#: an exponent counts as positive when it exceeds this many standard errors …
SIGNIFICANCE = 2.0
#: … and grows separations by at least this fraction (in e-folds) per time scale: an exponent
#: of 1e-4 per forcing period is zero for any practical purpose, however small its error
MIN_GROWTH_PER_TIME_SCALE = 0.01
#: K above this is a chaotic vote of the 0–1 test (K tends to 0 or 1)
ZERO_ONE_THRESHOLD = 0.5

VERDICTS = ("periodic", "quasi-periodic", "chaotic")


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
    """'chaotic' for a significantly positive exponent, 'regular' otherwise, None if unknown."""
    if not math.isfinite(exponent):
        return None
    positive = (
        exponent > SIGNIFICANCE * stderr and exponent * time_scale > MIN_GROWTH_PER_TIME_SCALE
    )
    return "chaotic" if positive else "regular"


def zero_one_vote(K: float) -> str | None:
    """'chaotic' for K above ``ZERO_ONE_THRESHOLD``, 'regular' otherwise, None if unknown."""
    if not math.isfinite(K):
        return None
    return "chaotic" if K > ZERO_ONE_THRESHOLD else "regular"


def _consistent(vote: str, verdict: str) -> bool:
    return (vote == "chaotic") == (verdict == "chaotic")


def classify(
    *,
    lyapunov_exponent: float,
    lyapunov_stderr: float,
    zero_one_K: float,
    section_period: int,
    section_return_distance: float,
    time_scale: float,
) -> Verdict:
    """Verdict on one channel from its Lyapunov exponent, 0–1 test and Poincaré section.

    Explanation of the method:
        The three indicators answer different questions. The Poincaré section tells periodic
        motion (points repeat every k crossings, see :mod:`sim.analysis.poincare`) from the
        rest; it cannot tell a closed curve (quasi-periodic) from a scatter (chaos) on its
        own. The largest Lyapunov exponent and the 0–1 test tell chaos (exponential divergence,
        diffusive walk) from regular motion. So:

        - section points repeat → 'periodic';
        - otherwise, the Lyapunov vote decides (the 0–1 vote when the exponent is unknown):
          'chaotic' if it says chaotic, 'quasi-periodic' if it says regular.

        The exponent is primary because it is the quantity the linkage literature reports; when
        the 0–1 test disagrees, ``agreement`` drops below 1 and the reason says so. An exponent
        votes chaotic when it exceeds ``SIGNIFICANCE`` (2) standard errors and its growth per
        ``time_scale`` exceeds ``MIN_GROWTH_PER_TIME_SCALE`` (0.01 e-folds); K votes chaotic
        above 0.5.

    Choosing the parameters:
        time_scale: the forcing period (the crank period for the linkage), in the exponent's
            inverse units.

    References:
        G. A. Gottwald, I. Melbourne, SIAM J. Appl. Dyn. Syst. 8 (2009) 129–145 (K threshold).
        T. S. Parker, L. O. Chua, "Practical Numerical Algorithms for Chaotic Systems",
        Springer (1989) (periodic, quasi-periodic and chaotic steady states).

    Args:
        lyapunov_exponent: largest exponent (NaN when it could not be estimated).
        lyapunov_stderr: its standard error.
        zero_one_K: K of the 0–1 test on the section points (NaN when unknown).
        section_period: period of the section points, 0 when they do not repeat.
        section_return_distance: normalised return distance at that period.
        time_scale: the forcing period.

    Returns:
        A :class:`Verdict`.
    """
    lyap = lyapunov_vote(lyapunov_exponent, lyapunov_stderr, time_scale)
    zero_one = zero_one_vote(zero_one_K)
    if section_period > 0:
        verdict = "periodic"
        why = f"the Poincaré points repeat every {section_period} crossing(s)"
    elif (lyap or zero_one) == "chaotic":
        verdict = "chaotic"
        why = "the section points do not repeat and the motion diverges"
    else:
        verdict = "quasi-periodic"
        why = "the section points do not repeat but the motion does not diverge"

    votes = [vote for vote in (lyap, zero_one) if vote is not None]
    consistent = sum(_consistent(vote, verdict) for vote in votes) + 1  # + the section
    agreement = consistent / (len(votes) + 1)
    reason = (
        f"{verdict}: {why} (return distance {section_return_distance:.2g} of the orbit size); "
        f"exponent {lyapunov_exponent:.3g} ± {lyapunov_stderr:.2g} 1/s votes {lyap or 'nothing'}, "
        f"0–1 test K = {zero_one_K:.2f} votes {zero_one or 'nothing'}"
        + ("" if agreement == 1.0 else "; the indicators disagree")
        + "."
    )
    evidence: dict[str, float | int | str] = {
        "lyapunov_exponent": lyapunov_exponent,
        "lyapunov_stderr": lyapunov_stderr,
        "lyapunov_vote": lyap or "none",
        "zero_one_K": zero_one_K,
        "zero_one_vote": zero_one or "none",
        "section_period": section_period,
        "section_return_distance": section_return_distance,
        "agreement": agreement,
        "reason": reason,
    }
    return Verdict(verdict=verdict, evidence=evidence, agreement=agreement)


def indicator_agreement(verdicts: Sequence[Verdict]) -> dict[str, float]:
    """Agreement between the indicators over many channels (or runs of a sweep).

    Returns:
        ``mean_agreement``: mean of the per-channel agreement; ``lyapunov_zero_one``: fraction
        of the channels where both chaos votes exist and agree (NaN if none has both).
    """
    if not verdicts:
        return {"mean_agreement": math.nan, "lyapunov_zero_one": math.nan}
    both = [
        v.evidence["lyapunov_vote"] == v.evidence["zero_one_vote"]
        for v in verdicts
        if v.evidence["lyapunov_vote"] != "none" and v.evidence["zero_one_vote"] != "none"
    ]
    return {
        "mean_agreement": sum(v.agreement for v in verdicts) / len(verdicts),
        "lyapunov_zero_one": sum(both) / len(both) if both else math.nan,
    }

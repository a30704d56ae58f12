"""The chaos of each case of a study, as the front page's comparison sections show it (the
contact laws, sim.law_section; the oil film, sim.lubrication_section): the model exponent
over the ensemble's members on each link model the study takes it on, and claim 5's reading
of the case's chaos analysis (the flagship's channels: A x, A y and B x chaotic, B y periodic;
sim.claims.flagship_verdicts)."""

from collections.abc import Mapping
from pathlib import Path
from typing import NamedTuple

import xarray as xr

from sim.claims import exponents_by_case, flagship_verdicts, members_summary


class CaseChaos(NamedTuple):
    """One case: its model exponents [(links, primary, summary)], the primary first; claim 5's
    verdict on it, and its channels' verdicts with B y's section period in a few words."""

    exponents: list[tuple[str, bool, str]]
    verdict: str
    channels: str


def case_chaos(inputs: Mapping[str, object], role: str) -> dict[str, CaseChaos]:
    """Each case of the study in landing role `role`, in its order: from the landing inputs
    `<role>_analyses` (every case's chaos analysis, named by its case) and
    `<role>_model_exponents` (sim.studies.config.LANDING_INPUTS)."""
    exponents = {}
    if f"{role}_model_exponents" in inputs:
        exponents = dict(exponents_by_case(inputs[f"{role}_model_exponents"]))
    out = {}
    for path in inputs.get(f"{role}_analyses", []):
        case = Path(path).stem
        with xr.open_dataset(path) as analysis:
            verdict, verdicts, period = flagship_verdicts(analysis.load())
        channels = ", ".join(f"{channel} {v}" for channel, v in verdicts.items())
        # claim 5 also asks that B y's Poincaré map be a single point
        by_period = period.get("B.y", 0)
        points = "no repeat" if by_period == 0 else f"period {by_period}"
        out[case] = CaseChaos(
            [(str(r.links), bool(r.primary), members_summary(r)) for r in exponents.get(case, [])],
            verdict,
            f"{channels}; B y's section: {points}",
        )
    return out


def exponents_text(chaos: CaseChaos) -> str:
    """A case's model exponents in one cell: each link model's, the primary marked."""
    parts = [f"{links}{' (primary)' * primary}: {text}" for links, primary, text in chaos.exponents]
    return "; ".join(parts) or "not computed"

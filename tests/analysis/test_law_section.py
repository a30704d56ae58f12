"""The front page's section on the contact laws (sim.law_section) on synthetic analyses, model
exponent tables and clearance diagrams: each law's row reads its own case's files, and the
closing sentence says whether the chaos claims hold under every law and where chaos appears."""

import numpy as np
import pandas as pd
import xarray as xr
from test_claims import _sweep_table

from sim.analysis.verdicts import MIXED, SUPPORTED
from sim.law_section import law_rows, law_section

CHANNELS = ["A.x", "A.y", "B.x", "B.y"]


def _analysis(path, verdicts: list[str]) -> str:
    """A chaos analysis of the flagship with these channel verdicts (B y's period 1 when
    periodic)."""
    xr.Dataset(
        {
            "lyapunov_exponent": ("channel", [80.0, 60.0, 40.0, -5.0]),
            "verdict": ("channel", verdicts),
            "section_period": ("channel", [0 if v != "periodic" else 1 for v in verdicts]),
        },
        coords={"channel": CHANNELS, "revolution": np.arange(50)},
        attrs={"transient_revolutions": 20},
    ).to_netcdf(path)
    return str(path)


def _exponents(path, medians: dict[str, float]) -> str:
    """A model-exponent table: each case's median over 4 members on modal links (primary) and
    rigid links beside it."""
    rows = [
        {
            "case": case,
            "links": links,
            "primary": links == "modal",
            "members": 4,
            "median_exponent_per_s": median * scale,
            "interval_low_per_s": 0.9 * median * scale,
            "interval_high_per_s": 1.1 * median * scale,
            "interval_coverage": 0.875,
            "mean_member_stderr_per_s": 5.0,
            "revolutions": 30,
            "transient_revolutions": 10,
        }
        for case, median in medians.items()
        for links, scale in (("modal", 1.0), ("rigid", 0.25))
    ]
    pd.DataFrame(rows).to_csv(path, index=False)
    return str(path)


def _inputs(tmp_path, tsuji_verdicts: list[str], tsuji_by_y: list[str]) -> tuple[dict, dict]:
    chaotic = ["chaotic", "chaotic", "chaotic", "periodic"]
    (tmp_path / "analysis").mkdir(parents=True)
    inputs = {
        "contact_laws_analyses": [
            _analysis(tmp_path / "analysis/lankarani-nikravesh.nc", chaotic),
            _analysis(tmp_path / "analysis/tsuji.nc", tsuji_verdicts),
        ],
        "contact_laws_model_exponents": _exponents(
            tmp_path / "exponents.csv", {"lankarani-nikravesh": 280.0, "tsuji": 190.0}
        ),
        "bifurcation_clearance_table": _sweep_table(tmp_path, "ln", ["periodic"] * 6),
        "bifurcation_clearance_memoryless_table": _sweep_table(tmp_path, "tsuji", tsuji_by_y),
    }
    laws = {
        "contact_laws": {
            "lankarani-nikravesh": {"law": "lankarani-nikravesh", "lubricated": []},
            "tsuji": {"law": "tsuji", "lubricated": []},
        },
        "bifurcation_clearance": {"sweep": {"law": "lankarani-nikravesh", "lubricated": []}},
        "bifurcation_clearance_memoryless": {"sweep": {"law": "tsuji", "lubricated": []}},
    }
    return inputs, laws


def test_each_law_s_row_reads_its_own_case(tmp_path):
    inputs, laws = _inputs(
        tmp_path, ["chaotic", "chaotic", "periodic", "periodic"], ["periodic"] * 6
    )
    ln, tsuji = law_rows(inputs, laws)
    assert (ln["law"], ln["memory"], tsuji["law"], tsuji["memory"]) == (
        "lankarani-nikravesh",
        True,
        "tsuji",
        False,
    )
    assert ln["chaos"].exponents[0] == ("modal", True, "280 [252, 308] 1/s")
    assert ln["chaos"].exponents[1] == ("rigid", False, "70 [63, 77] 1/s")
    assert ln["chaos"].verdict == SUPPORTED
    assert tsuji["chaos"][1:] == (
        MIXED,
        "A.x chaotic, A.y chaotic, B.x periodic, B.y periodic; B y's section: period 1",
    )
    # the synthetic diagrams turn chaotic from their 4th point, 0.4 mm
    assert ln["clearance"] == (SUPPORTED, ln["clearance"][1], "from 0.4 mm")


def test_the_sentence_says_where_a_law_parts_from_the_claims(tmp_path):
    held, laws = _inputs(tmp_path / "held", ["chaotic"] * 3 + ["periodic"], ["periodic"] * 6)
    text = law_section(held, laws)
    assert text.startswith("Does the chaos depend on the contact law?\n")
    assert (
        "hold under every law run here (under lankarani-nikravesh chaos appears from 0.4 mm;"
        in text
    )
    parted, laws = _inputs(
        tmp_path / "parted", ["chaotic"] * 3 + ["periodic"], ["periodic"] * 5 + ["chaotic"]
    )
    text = law_section(parted, laws)
    assert "do not hold under every law: claim 5 is supported under lankarani-nikravesh" in text
    assert "claim 6 (clearance) is mixed under tsuji" in text


def test_no_study_no_section():
    assert law_section({}, {}) == ""

"""The front page's section on the oil film (sim.lubrication_section) on synthetic analyses,
per-revolution peaks and a viscosity sweep: the force change's interval is the bootstrap's of
the medians, and the sentence says whether the film removes the chaos."""

import pandas as pd
from test_law_section import _analysis, _exponents
from test_verdicts import ensemble

from sim.analysis.revolutions import Bootstrap
from sim.lubrication_section import lubrication_section

BOOT = Bootstrap(resamples=500, level=0.95, seed=1)
CONTACTS = {"lubrication": {"dry": {"lubricated": []}, "lubricated": {"lubricated": ["A"]}}}


def _inputs(tmp_path, oiled_verdicts: list[str], oiled_force: float) -> dict:
    """The dry case chaotic with a peak force at A near 10 kN; the lubricated one as given."""
    (tmp_path / "analysis").mkdir(parents=True)
    revolutions = pd.concat(
        [
            ensemble(case, level, 3, 40, seed=k).assign(
                contact_force_A=lambda t: 10 * t.drive_torque
            )
            for k, (case, level) in enumerate((("dry", 10000.0), ("lubricated", oiled_force)))
        ]
    )
    revolutions.to_csv(tmp_path / "revolutions.csv", index=False)
    sweep = pd.DataFrame(
        [
            {
                "joints.A.lubricant.viscosity": mu,
                "channel": channel,
                "model_lyapunov_exponent_per_s": 200.0 - 100.0 * k,
                "model_lyapunov_stderr_per_s": 8.0,
                "verdict": "chaotic" if k == 0 else "periodic",
            }
            for k, mu in enumerate((0.006, 0.6))
            for channel in ("A.x", "B.y")
        ]
    )
    sweep.to_csv(tmp_path / "sweep.csv", index=False)
    chaotic = ["chaotic", "chaotic", "chaotic", "periodic"]
    return {
        "lubrication_analyses": [
            _analysis(tmp_path / "analysis/dry.nc", chaotic),
            _analysis(tmp_path / "analysis/lubricated.nc", oiled_verdicts),
        ],
        "lubrication_model_exponents": _exponents(
            tmp_path / "exponents.csv", {"dry": 280.0, "lubricated": 150.0}
        ),
        "lubrication_revolutions": str(tmp_path / "revolutions.csv"),
        "lubrication_viscosity_table": str(tmp_path / "sweep.csv"),
    }


def test_a_film_that_keeps_the_chaos_and_lowers_the_force(tmp_path):
    inputs = _inputs(tmp_path, ["chaotic", "periodic", "periodic", "periodic"], 4000.0)
    text = lubrication_section(inputs, CONTACTS, BOOT)
    assert text.startswith("Does lubrication remove the chaos?\n")
    assert "lubricated (oil in A)" in text and "dry (dry)" in text
    # the medians' difference of peaks drawn about 10 and 4 kN is near −6 kN, −60 %, decided
    assert "lubricated against dry: joint A: -6" in text
    assert "supported that the film lowers it" in text
    assert "0.006 Pa s" in text and "2 of 2 channels chaotic" in text
    assert "0.6 Pa s" in text and "0 of 2 channels chaotic" in text
    assert (
        "The oil film does not remove the chaos: lubricated keeps chaotic channels (model "
        "exponents: dry 280 [252, 308] 1/s; lubricated 150 [135, 165] 1/s)."
    ) in text


def test_a_film_that_removes_the_chaos(tmp_path):
    inputs = _inputs(tmp_path, ["periodic"] * 4, 9800.0)
    text = lubrication_section(inputs, CONTACTS, BOOT)
    assert "The oil film removes the chaos" in text
    assert "undecided that the film lowers it" in text


def test_no_study_no_section():
    assert lubrication_section({}, {}, BOOT) == ""

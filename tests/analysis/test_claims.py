"""The landing page's judges (sim.claims) on synthetic tables of the peaks studies."""

import numpy as np
import pandas as pd
import pytest
import xarray as xr
from test_verdicts import ensemble

from sim.analysis.revolutions import Bootstrap
from sim.analysis.verdicts import NOT_EVALUATED, SUPPORTED, UNDECIDED
from sim.claims import claim_flagship_chaos, exponent_comparison, judge_all

BOOT = Bootstrap(resamples=500, level=0.95, seed=1)


def _study(tmp_path, name: str, setting: str, cases: dict[str, tuple[float, float]]) -> dict:
    """peaks.csv and revolutions.csv of a study whose cases have a setting and a peak level."""
    peaks = pd.DataFrame(
        [
            {
                "case": case,
                setting: value,
                "peak_slider_acceleration_m_s2": 1.3 * level,
                "peak_drive_torque_N_m": 0.13 * level,
                "peak_contact_force_A_N": 10 * level,
                "contact_events_per_revolution": 200 - level / 20,
            }
            for case, (value, level) in cases.items()
        ]
    )
    revolutions = pd.concat(
        [
            ensemble(case, level, 3, 25, seed=i).assign(
                contact_force_A=lambda t: 10 * t.drive_torque
            )
            for i, (case, (_, level)) in enumerate(cases.items())
        ]
    )
    (tmp_path / name).mkdir()
    peaks.to_csv(tmp_path / name / "peaks.csv", index=False)
    revolutions.to_csv(tmp_path / name / "revolutions.csv", index=False)
    role = name.replace("-", "_")
    return {
        f"{role}_peaks": str(tmp_path / name / "peaks.csv"),
        f"{role}_revolutions": str(tmp_path / name / "revolutions.csv"),
    }


def test_peak_claims_are_tests_with_intervals(tmp_path):
    inputs = _study(
        tmp_path,
        "clearance-size",
        "clearance_A_mm",
        {"clearance-0.4mm": (0.4, 1700.0), "clearance-0.1mm": (0.1, 1000.0)},
    )
    inputs |= _study(
        tmp_path,
        "speed",
        "speed_rpm",
        {"speed-30rpm": (30.0, 1000.0), "speed-60rpm": (60.0, 1000.0)},
    )
    claims, meta = judge_all(inputs, BOOT)
    by_claim = {row["claim"]: row for row in claims}
    larger = by_claim["Larger clearance gives larger acceleration and torque peaks."]
    assert larger["verdict"] == SUPPORTED
    assert "95% intervals" in larger["intervals"]
    assert "clearance-0.4mm − clearance-0.1mm" in larger["intervals"]
    assert "3 members × 25 revolutions" in larger["evidence"]
    impacts = by_claim["Smaller clearance gives more frequent, smaller impacts."]
    assert impacts["verdict"] == SUPPORTED
    assert "contact force A" in impacts["intervals"]
    speed = by_claim["Higher speed gives larger acceleration and torque peaks."]
    assert speed["verdict"] == UNDECIDED
    # studies not run are not evaluated, and say so
    assert by_claim[claims[0]["claim"]]["verdict"] == NOT_EVALUATED
    assert meta == {}
    fields = {"claim", "short", "verdict", "key", "intervals", "evidence"}
    assert all(set(row) == fields for row in claims)


def test_nothing_run_evaluates_nothing():
    claims, _ = judge_all({}, BOOT)
    assert {row["verdict"] for row in claims} == {NOT_EVALUATED}


def _sweep_table(tmp_path, name: str, by_y: list[str]) -> str:
    """bifurcation_lyapunov.csv of a 6-point sweep: A.x periodic with a negative model exponent
    over the lower half, chaotic with a positive one over the upper half; B.y as given."""
    rows = []
    for k, verdict in enumerate(by_y):
        chaotic = k >= 3
        exponent = 40.0 if chaotic else -5.0
        for channel, channel_verdict in (
            ("A.x", "chaotic" if chaotic else "periodic"),
            ("B.y", verdict),
        ):
            rows.append(
                {
                    "joints.A.clearance": 1e-4 * (k + 1),
                    "channel": channel,
                    "model_lyapunov_exponent_per_s": exponent,
                    "model_lyapunov_stderr_per_s": 2.0,
                    "zero_one_K": 0.9 if channel_verdict == "chaotic" else 0.05,
                    "section_period": 1 if channel_verdict == "periodic" else 0,
                    "verdict": channel_verdict,
                }
            )
    path = tmp_path / f"{name}.csv"
    pd.DataFrame(rows).to_csv(path, index=False)
    return str(path)


def test_bifurcation_claim_compares_the_ends_of_the_dense_sweeps(tmp_path):
    """Chaos at the highest third against the lowest, and B y periodic at every point: both
    sweeps so, supported; B y chaotic at one point of one sweep, mixed."""
    periodic = ["periodic"] * 6
    inputs = {
        "bifurcation_clearance_table": _sweep_table(tmp_path, "clearance", periodic),
        "bifurcation_speed_table": _sweep_table(tmp_path, "speed", periodic),
    }
    row = next(r for r in judge_all(inputs, BOOT)[0] if r["claim"].startswith("Chaos grows"))
    assert row["verdict"] == SUPPORTED
    assert "0.0001 to 0.0002 (2 points): 0.00 of the channels chaotic" in row["evidence"]
    assert "B y periodic at 6 of 6 points" in row["evidence"]
    onset = "chaos starts at 0.0004: 3 of 3 points from there on have a chaotic channel;"
    assert onset in row["evidence"]
    one_off = ["periodic"] * 4 + ["chaotic", "periodic"]
    inputs["bifurcation_speed_table"] = _sweep_table(tmp_path, "speed2", one_off)
    row = next(r for r in judge_all(inputs, BOOT)[0] if r["claim"].startswith("Chaos grows"))
    assert row["verdict"] == "mixed"
    assert "periodic at 5 of 6 points (not at 0.0005)" in row["evidence"]


def test_the_onset_of_chaos_names_the_windows_after_it(tmp_path):
    """Chaotic at the 2nd, 5th and 7th of 8 points: chaos starts at the 2nd, and the points
    without a chaotic channel after it are reported as stretches (3rd–4th, 6th, 8th)."""
    pattern = [False, True, False, False, True, False, True, False]
    rows = [
        {
            "speed": 30.0 * (k + 1),
            "channel": "A.x",
            "model_lyapunov_exponent_per_s": 40.0 if chaotic else -5.0,
            "model_lyapunov_stderr_per_s": 2.0,
            "zero_one_K": 0.9 if chaotic else 0.05,
            "section_period": 0 if chaotic else 1,
            "verdict": "chaotic" if chaotic else "periodic",
        }
        for k, chaotic in enumerate(pattern)
    ]
    path = tmp_path / "speed.csv"
    pd.DataFrame(rows).to_csv(path, index=False)
    row = next(
        r
        for r in judge_all({"bifurcation_speed_table": str(path)}, BOOT)[0]
        if r["claim"].startswith("Chaos grows")
    )
    assert (
        "chaos starts at 60: 3 of 7 points from there on have a chaotic channel, "
        "none at 90–120, 180, 240"
    ) in row["evidence"]


def test_flagship_chaos_leads_with_the_model_exponent(tmp_path):
    """With the model-based exponent in the analysis, the evidence gives it first and the
    per-channel exponents beside it; the claim's signs are still judged per channel."""
    import numpy as np
    import xarray as xr

    channels = ["A.x", "A.y", "B.x", "B.y"]
    analysis = xr.Dataset(
        {
            "lyapunov_exponent": ("channel", [80.0, 60.0, 40.0, -5.0]),
            "verdict": ("channel", ["chaotic", "chaotic", "chaotic", "periodic"]),
            "section_period": ("channel", [0, 0, 0, 1]),
            "model_lyapunov_exponent": ((), 120.0),
            "model_lyapunov_stderr": ((), 4.0),
        },
        coords={"channel": channels, "revolution": np.arange(180)},
        attrs={"transient_revolutions": 20},
    )
    path = tmp_path / "analysis.nc"
    analysis.to_netcdf(path)
    claims, _ = judge_all({"flagship_analysis": str(path)}, BOOT)
    row = next(r for r in claims if r["claim"].startswith("At 0.5 mm"))
    assert row["verdict"] == SUPPORTED
    assert row["evidence"].startswith("model-based largest exponent of the linkage")
    assert "120 ± 4 1/s" in row["evidence"]
    assert "B.y: λ = -5 1/s (periodic, section period 1)" in row["evidence"]
    analysis.drop_vars(["model_lyapunov_exponent", "model_lyapunov_stderr"]).to_netcdf(
        tmp_path / "plain.nc"
    )
    claims, _ = judge_all({"flagship_analysis": str(tmp_path / "plain.nc")}, BOOT)
    row = next(r for r in claims if r["claim"].startswith("At 0.5 mm"))
    assert row["evidence"].startswith("A.x: λ = 80 1/s")


def test_flagship_chaos_leads_with_the_model_exponent_over_members(tmp_path):
    """With the study's model-exponent table, the evidence leads with the median over members
    and its interval (the table's numbers, as written), then the per-channel exponents and the
    sentence on why they differ; one member gives its own error and says there is no interval."""
    import numpy as np
    import xarray as xr

    from sim.claims import MODEL_AND_CHANNEL_EXPONENTS

    channels = ["A.x", "A.y", "B.x", "B.y"]
    xr.Dataset(
        {
            "lyapunov_exponent": ("channel", [80.0, 60.0, 40.0, -5.0]),
            "verdict": ("channel", ["chaotic", "chaotic", "chaotic", "periodic"]),
            "section_period": ("channel", [0, 0, 0, 1]),
        },
        coords={"channel": channels, "revolution": np.arange(180)},
        attrs={"transient_revolutions": 20},
    ).to_netcdf(tmp_path / "analysis.nc")
    row = {
        "case": "clearance-0.5mm",
        "members": 4,
        "median_exponent_per_s": 118.0,
        "interval_low_per_s": 104.0,
        "interval_high_per_s": 131.0,
        "interval_coverage": 0.875,
        "mean_member_stderr_per_s": 6.2,
        "revolutions": 60,
        "transient_revolutions": 20,
        "links": "rigid",
        "rtol": 1e-8,
    }
    pd.DataFrame([row]).to_csv(tmp_path / "members.csv", index=False)
    inputs = {
        "flagship_analysis": str(tmp_path / "analysis.nc"),
        "flagship_model_exponents": str(tmp_path / "members.csv"),
    }
    claims, _ = judge_all(inputs, BOOT)
    evidence = next(r for r in claims if r["claim"].startswith("At 0.5 mm"))["evidence"]
    lead = (
        "model-based largest exponent of the linkage (Benettin on the model's own integrator): "
        "median over 4 members 118 1/s, interval [104, 131] 1/s (87.5% distribution-free "
        "coverage of the median), mean member standard error 6.2 1/s (rigid links, "
        "60 revolutions, 20 transient)."
    )
    assert evidence.startswith(lead)
    assert evidence.index("A.x: λ = 80 1/s") > len(lead)
    assert evidence.endswith(MODEL_AND_CHANNEL_EXPONENTS)
    pd.DataFrame([{**row, "members": 1}]).to_csv(tmp_path / "one.csv", index=False)
    inputs["flagship_model_exponents"] = str(tmp_path / "one.csv")
    claims, _ = judge_all(inputs, BOOT)
    evidence = next(r for r in claims if r["claim"].startswith("At 0.5 mm"))["evidence"]
    assert "118 ± 6.2 1/s (one member: no interval over members" in evidence


@pytest.mark.parametrize(
    ("a_x", "expected"),
    [("chaotic", SUPPORTED), ("undecided", UNDECIDED), ("quasi-periodic", "mixed")],
)
def test_flagship_chaos_reads_the_channel_verdicts(tmp_path, a_x, expected):
    """The claim follows each channel's verdict, not the sign of its time-series exponent:
    A x at −0.83 1/s with a chaotic verdict supports it; an undecided A x leaves the claim
    undecided; a quasi-periodic A x beside chaotic A y and B x makes it mixed."""
    import numpy as np
    import xarray as xr

    path = tmp_path / "analysis.nc"
    xr.Dataset(
        {
            "lyapunov_exponent": ("channel", [-0.83, 60.0, 40.0, -5.0]),
            "verdict": ("channel", [a_x, "chaotic", "chaotic", "periodic"]),
            "section_period": ("channel", [0, 0, 0, 1]),
        },
        coords={"channel": ["A.x", "A.y", "B.x", "B.y"], "revolution": np.arange(180)},
        attrs={"transient_revolutions": 20},
    ).to_netcdf(path)
    claims, _ = judge_all({"flagship_analysis": str(path)}, BOOT)
    row = next(r for r in claims if r["claim"].startswith("At 0.5 mm"))
    assert row["verdict"] == expected
    assert f"A.x: λ = -0.83 1/s ({a_x}, section period 0)" in row["evidence"]


def test_the_exponent_of_the_flexible_and_the_rigid_mechanism_side_by_side(tmp_path):
    """A study's model-exponent table with two link models: the flagship claim leads with the
    primary one and gives the other beside it; the landing page's comparison has one row per
    case of every study, the primary link model first whatever the table's order."""

    def row(case: str, links: str, primary: bool, median: float) -> dict:
        return {
            "case": case,
            "links": links,
            "primary": primary,
            "members": 4,
            "median_exponent_per_s": median,
            "interval_low_per_s": median - 10.0,
            "interval_high_per_s": median + 10.0,
            "interval_coverage": 0.875,
            "mean_member_stderr_per_s": 3.0,
            "revolutions": 30,
            "transient_revolutions": 10,
        }

    pd.DataFrame([row("c-0.5", "rigid", False, 57.0), row("c-0.5", "modal", True, 271.0)]).to_csv(
        tmp_path / "flagship.csv", index=False
    )
    pd.DataFrame(
        [
            row("c-0.1", "modal", True, 150.0),
            row("c-0.1", "rigid", False, 40.0),
            row("c-0.4", "modal", True, 250.0),
            row("c-0.4", "rigid", False, 60.0),
        ]
    ).to_csv(tmp_path / "size.csv", index=False)
    inputs = {
        "flagship_model_exponents": str(tmp_path / "flagship.csv"),
        "clearance_size_model_exponents": str(tmp_path / "size.csv"),
    }
    rows = exponent_comparison(inputs)
    assert [(r["role"], r["case"]) for r in rows] == [
        ("flagship", "c-0.5"),
        ("clearance size", "c-0.1"),
        ("clearance size", "c-0.4"),
    ]
    assert [(links, primary) for links, primary, _ in rows[0]["exponents"]] == [
        ("modal", True),
        ("rigid", False),
    ]
    assert rows[0]["exponents"][1][2].startswith("median over 4 members 57 1/s, interval [47, 67]")

    analysis = tmp_path / "analysis.nc"
    xr.Dataset(
        {
            "lyapunov_exponent": ("channel", [80.0, 60.0, 40.0, -5.0]),
            "verdict": ("channel", ["chaotic", "chaotic", "chaotic", "periodic"]),
            "section_period": ("channel", [0, 0, 0, 1]),
        },
        coords={"channel": ["A.x", "A.y", "B.x", "B.y"], "revolution": np.arange(20)},
        attrs={"transient_revolutions": 2},
    ).to_netcdf(analysis)
    evidence = claim_flagship_chaos(
        {
            "flagship_analysis": str(analysis),
            "flagship_model_exponents": inputs["flagship_model_exponents"],
        }
    )["evidence"]
    primary = evidence.index("median over 4 members 271 1/s")
    beside = evidence.index("; beside it, median over 4 members 57 1/s")
    assert primary < beside < evidence.index("A.x: λ = 80 1/s")


def test_the_cross_check_claim_reads_the_differences_over_the_peak_as_written(tmp_path):
    """The summary's raw `max` is already the largest difference over the peak
    (sim.crosscheck.compare.error_norms): the claim quotes it as it is, not over the peak
    again."""
    import json

    def norms(share: float, peak: float) -> dict:
        return {"raw": {"max": share, "rms": share / 3, "peak": peak}}

    case = {
        "clearance": False,
        "deterministic": {
            "displacement": norms(1.5e-8, 0.12),
            "velocity": norms(2e-6, 1.9),
            "acceleration": norms(4e-4, 150.0),
            "drive_torque": norms(6e-4, 80.0),
        },
    }
    path = tmp_path / "crosscheck.json"
    path.write_text(json.dumps({"ran": True, "cases": {"rigid-ideal": case}}))
    claims, _ = judge_all({"cross_check_summary": str(path)}, BOOT)
    row = next(r for r in claims if r["claim"].startswith("The model agrees with ADAMS"))
    assert row["verdict"] == SUPPORTED
    assert (
        "displacement 1.5e-08, velocity 2e-06, acceleration 0.0004, drive torque 0.0006"
        in (row["key"])
    )

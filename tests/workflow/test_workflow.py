"""The Snakemake workflow: a dry run and lint of the full configuration (fast), and the quick
configuration end to end with the report (slow), checking that every expected file exists and
opens."""

import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
SNAKEMAKE = shutil.which("snakemake") or str(Path(sys.executable).with_name("snakemake"))


def _snakemake(*args: str, cwd: Path = ROOT, timeout: float = 600) -> subprocess.CompletedProcess:
    return subprocess.run(
        [SNAKEMAKE, *args], cwd=cwd, capture_output=True, text=True, timeout=timeout
    )


def test_dry_run_full_config():
    done = _snakemake("-n", "--quiet", "rules")
    assert done.returncode == 0, done.stderr
    for rule in (
        "compile_kernels",
        "run",
        "run_member",
        "run_ideal",
        "run_tolerant",
        "analyze",
        "sweep_batch",
        "combine_sweep",
        "revolution_table",
        "model_exponent",
        "model_exponent_table",
        "landing",
    ):
        assert rule in done.stdout + done.stderr


def test_lint_full_config():
    done = _snakemake("--lint")
    assert done.returncode == 0, done.stdout + done.stderr
    assert "Congratulations" in done.stdout + done.stderr


def test_invalid_config_is_rejected(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("model: {links: wooden, elements: 2, flexible_bodies: [rod2]}\n")
    done = _snakemake("-n", "--configfile", str(bad))
    assert done.returncode != 0
    assert "wooden" in done.stdout + done.stderr


def test_members_shorter_than_the_transient_are_rejected_before_any_job(tmp_path):
    bad = tmp_path / "short.yaml"
    bad.write_text("defaults: {ensemble: {members: 1, seed: 1, revolutions: 10}}\n")
    done = _snakemake("-n", "--configfile", str(bad))
    assert done.returncode != 0
    out = done.stdout + done.stderr
    assert "ensemble.revolutions" in out and "must exceed the study's transient, 20" in out


def test_every_rule_has_its_files_named_once():
    # workflow/rules/paths.smk names every file: each rule's log and benchmark (JOBS), and
    # no two names share a pattern (one file, one name).
    names: dict = {}
    exec((ROOT / "workflow/rules/paths.smk").read_text(), names)
    paths, jobs = names["PATHS"], names["JOBS"]
    assert len(set(paths.values())) == len(paths)
    assert len(set(jobs.values())) == len(jobs)
    done = _snakemake("--list-rules")
    assert done.returncode == 0, done.stderr
    rules = set(done.stdout.split()) - {"all"}
    assert rules == set(jobs), rules ^ set(jobs)
    assert names["path"]("member", study="s", case="c", member=2) == "results/s/run/c/member-2.nc"


def _check_file(path: Path) -> None:
    assert path.exists(), path
    assert path.stat().st_size > 0, path
    if path.suffix == ".nc":
        import xarray as xr

        with xr.open_dataset(path) as ds:
            assert ds.sizes, path
    elif path.suffix == ".png":
        from matplotlib.image import imread

        assert imread(path).size > 0, path
    elif path.suffix == ".csv":
        import pandas as pd

        assert len(pd.read_csv(path)) > 0, path
    elif path.suffix == ".json":
        json.loads(path.read_text())


def _check_bifurcation(work: Path) -> None:
    """Each quick sweep point has its model exponent, and each clearance channel its K (a
    correlation, in [-1, 1]) and a verdict; the clearance-0 point has no channels; the model
    is named."""
    import numpy as np
    import xarray as xr

    with xr.open_dataset(work / "results/bifurcation-clearance/bifurcation.nc") as ds:
        np.testing.assert_array_equal(ds.parameter.values, [0.0, 5e-4, 1e-3])
        assert np.isfinite(ds.model_lyapunov_exponent).all()
        K = ds.zero_one_K.sel(parameter=[5e-4, 1e-3]).values
        assert np.all(np.abs(K) <= 1)  # a correlation
        assert (ds.verdict.sel(parameter=0.0) == "").all()
        model = "modal links rod2, rod3, rod4 (1 bending mode), dopri5 rtol 1e-06"
        assert ds.attrs["model"] == model


def _check_ensembles(work: Path) -> None:
    """Every member of the quick configuration's peaks studies is recorded with its index,
    seed and perturbation, and the claims on peaks are tests with intervals."""
    import pandas as pd
    import xarray as xr

    from sim.analysis.verdicts import MIXED, NOT_SUPPORTED, SUPPORTED, UNDECIDED

    table = pd.read_csv(work / "results/clearance-size/tables/revolutions.csv")
    assert sorted(table.member.unique()) == [0, 1, 2]
    assert (table.groupby(["case", "member"]).size() == 25).all()
    with xr.open_dataset(work / "results/clearance-size/run/clearance-0.1mm/member-1.nc") as run:
        assert run.attrs["ensemble_member"] == 1
        assert run.attrs["ensemble_seed"] == 20261124
        assert 0 < abs(run.attrs["perturbation_shift_deg"]) < 1e-7
        assert "revolution_peak_acceleration" in run
    claims = pd.read_csv(work / "results/report/claims.csv").set_index("claim")
    peaks = claims.loc["Larger clearance gives larger acceleration and torque peaks."]
    assert peaks.verdict in (SUPPORTED, NOT_SUPPORTED, MIXED, UNDECIDED)
    assert "95% intervals" in peaks.intervals


def _check_exponent_comparison(work: Path) -> None:
    """The members' exponents on both link models of the quick configuration (`links: rigid`,
    `compare: [modal]`): a row per case and model in the study's table, the primary one marked,
    and both side by side on the landing page."""
    import pandas as pd

    table = pd.read_csv(work / "results/clearance-size/tables/model_exponent.csv")
    assert sorted(zip(table.case, table.links, table.primary, strict=True)) == [
        ("clearance-0.1mm", "modal", False),
        ("clearance-0.1mm", "rigid", True),
        ("clearance-0.4mm", "modal", False),
        ("clearance-0.4mm", "rigid", True),
    ]
    assert (table.members == 3).all()
    landing = (work / "results/report/landing.rst").read_text()
    section = landing[landing.index("Chaos of the flexible and the rigid mechanism") :]
    section = section[: section.index("Accelerometer data used")]
    for case in ("clearance-0.5mm", "clearance-0.1mm", "clearance-0.4mm"):
        assert case in section
    assert section.count("**rigid** (primary)") == section.count("**modal**:") == 3


def _check_budget(work: Path) -> None:
    """benchmarks/workflow_budget.py --measured books every job's benchmark to its study."""
    import importlib.util

    import pandas as pd

    spec = importlib.util.spec_from_file_location("budget", ROOT / "benchmarks/workflow_budget.py")
    budget = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(budget)
    table, counts, _ = budget.measured_table(work / "results")
    files = list((work / "results/benchmarks").rglob("*.tsv"))
    assert sum(sum(kinds.values()) for kinds in counts.values()) == len(files)
    seconds = sum(pd.read_csv(f, sep="\t")["s"].iloc[0] for f in files)
    assert sum(sum(kinds.values()) for kinds in table.values()) == pytest.approx(seconds)
    assert {"flagship", "speed", "bifurcation-speed", "fidelity", "report"} <= set(table)
    assert {"run", "member", "ideal", "model-exponent"} <= set(table["clearance-size"])


def _workflow_copy(tmp_path: Path) -> Path:
    """A copy of the workflow (Snakefile, config, rules, report, data) to run in."""
    work = tmp_path / "repo"
    work.mkdir()
    for item in ("Snakefile", "config", "workflow", "report", "data"):
        source = ROOT / item
        if source.is_dir():
            shutil.copytree(source, work / item)
        else:
            shutil.copy(source, work / item)
    return work


@pytest.mark.slow
def test_quick_workflow_end_to_end(tmp_path):
    """The quick configuration in a copy of the workflow, then the report."""
    work = _workflow_copy(tmp_path)
    done = _snakemake("-j2", "--configfile", "config/quick.yaml", cwd=work, timeout=3600)
    assert done.returncode == 0, done.stderr[-4000:]
    targets = _snakemake(
        "-n", "--configfile", "config/quick.yaml", "--forceall", "--quiet", "all", cwd=work
    )
    assert targets.returncode == 0
    expected = [
        path
        for path in (work / "results").rglob("*")
        # Snakemake marks a directory output (a sweep batch) with an empty timestamp file
        if path.is_file() and "benchmarks" not in path.parts and path.name != ".snakemake_timestamp"
    ]
    kinds = {path.suffix for path in expected}
    assert {".nc", ".png", ".csv", ".html", ".json", ".rst"} <= kinds
    for path in expected:
        _check_file(path)
    for name in (
        "results/flagship/tables/lyapunov_clearance-0.5mm.csv",
        "results/clearance-size/tables/peaks.csv",
        "results/speed/tables/peaks.csv",
        "results/clearance-size/run/clearance-0.4mm/member-2.nc",
        "results/clearance-size/tables/revolutions.csv",
        "results/clearance-size/tables/revolution_statistics.csv",
        "results/speed/tables/revolution_statistics.html",
        "results/bifurcation-clearance/figures/bifurcation.png",
        "results/bifurcation-speed/figures/bifurcation.png",
        "results/bifurcation-clearance/tables/bifurcation_lyapunov.csv",
        "results/fidelity/figures/work_precision.png",
        "results/extremes/tables/extremes.csv",
        "results/report/landing.rst",
        "results/report/claims.csv",
    ):
        _check_file(work / name)
    _check_ensembles(work)
    _check_exponent_comparison(work)
    _check_bifurcation(work)
    _check_budget(work)
    report = _snakemake(
        "--configfile", "config/quick.yaml", "--report", "report.html", cwd=work, timeout=300
    )
    assert report.returncode == 0, report.stderr[-4000:]
    html = (work / "report.html").read_text()
    assert "Claims of the paper" in html
    assert "Synthetic recording" in html or "Measured recording" in html


FOURBAR_STUDY = """
studies:
  fourbar:
    title: Crank-rocker four-bar, flexible coupler, 0.3 mm clearance at Q
    scene: fourbar.yaml
    model: {links: beam, elements: 2, flexible_bodies: [coupler], solver: {method: dopri5}}
    cases:
      clearance-0.3mm: {}
    analyses: [responses, trajectories, chaos, peaks]
"""


@pytest.mark.slow
def test_quick_workflow_runs_a_four_bar_study(tmp_path):
    """A study of a linkage that is not the six-bar (tests/workflow/fourbar.yaml: its own body
    and joint names, no slider) through the quick workflow to its target: its figures and
    tables are made, its coupler is the flexible link its study names, and no key of the
    six-bar's studies (its link model's bodies, its operating point) reaches its runs."""
    import xarray as xr

    work = _workflow_copy(tmp_path)
    shutil.copy(ROOT / "tests/workflow/fourbar.yaml", work / "fourbar.yaml")
    (work / "fourbar-study.yaml").write_text(FOURBAR_STUDY)
    args = ("results/fourbar/done", "--configfile", "config/quick.yaml", "fourbar-study.yaml")
    plan = _snakemake("-n", "--printshellcmds", *args, cwd=work)
    assert plan.returncode == 0, plan.stderr[-4000:]
    output = plan.stdout + plan.stderr
    commands = [line for line in output.splitlines() if "sim run" in line]
    assert commands and all("fourbar.yaml" in line for line in commands)
    for six_bar_key in ("rod2", "slider", "joints.A", "joints.B", "drive.speed_rpm"):
        assert not any(six_bar_key in line for line in commands), six_bar_key
    done = _snakemake("-j2", *args, cwd=work, timeout=3600)
    assert done.returncode == 0, done.stderr[-4000:]
    study = work / "results/fourbar"
    for name in (
        "figures/responses_clearance-0.3mm.png",
        "tables/peaks.csv",
        "tables/revolutions.csv",
        "figures/trajectories_clearance-0.3mm.png",
        "figures/phase_clearance-0.3mm.png",
        "figures/poincare_clearance-0.3mm.png",
        "tables/lyapunov_clearance-0.3mm.csv",
        "tables/model_exponent.csv",
        "run/clearance-0.3mm.nc",
    ):
        _check_file(study / name)
    with xr.open_dataset(study / "run/clearance-0.3mm.nc") as run:
        scene = json.loads(run.attrs["scene"])
        assert list(run.joint.values) == ["Q"]  # the one clearance joint
    assert set(scene["bodies"]) == {"crank", "coupler", "rocker"}
    assert scene["bodies"]["coupler"]["kind"] == "beam"
    assert scene["bodies"]["rocker"]["kind"] == "rigid"
    # the scene's own operating point, not the six-bar studies' 150 rpm and friction 0.15
    assert scene["drive"]["speed_rpm"] == 120.0
    assert scene["contact"]["friction"] == 0.1

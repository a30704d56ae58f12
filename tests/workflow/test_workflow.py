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
        "study_section",
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
    and both side by side in the paper's section."""
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
    numbers = landing[landing.index("The exponents in numbers") :]
    for case in ("clearance-0.5mm", "clearance-0.1mm", "clearance-0.4mm", "tsuji", "dry"):
        assert case in numbers
    # a row per ensemble case of every study the front page reads, on each link model
    studies = ("flagship", "clearance-size", "contact-laws", "lubrication")
    cases = sum(
        pd.read_csv(work / f"results/{study}/tables/model_exponent.csv").case.nunique()
        for study in studies
    )
    assert cases == 1 + 2 + 5 + 2
    assert numbers.count(">rigid (primary)<") == numbers.count(">modal<") == cases


def _check_comparison_sections(work: Path) -> None:
    """The front page's sections on the contact laws and the oil film, after the paper's: a row
    per law and per case, and their closing sentences."""
    landing = (work / "results/report/landing.rst").read_text()
    laws = landing[landing.index("Does the chaos depend on the contact law?") :]
    for law in ("lankarani-nikravesh", "hunt-crossley", "flores", "gonthier-carvalho", "tsuji"):
        assert f"{law} (" in laws
    assert "The paper&#x27;s chaos claims " in laws
    oil = landing[landing.index("Does lubrication remove the chaos?") :]
    assert "dry (dry)" in oil and "lubricated (oil in A)" in oil
    assert "Peak contact force, median over revolutions and members, lubricated minus dry" in oil
    assert "The oil film " in oil or "The dry mechanism " in oil


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


#: a user's own linkage in the quick run: the offset slider-crank press (tests/workflow/press.yaml)
#: as a study with chaos and as a two-point sweep
PRESS_STUDIES = """
studies:
  press:
    title: Offset slider-crank press with clearance at the crank-rod joint and the slider
    scene: press.yaml
    cases:
      clearance: {}
    analyses: [responses, trajectories, chaos]
  press-speed:
    title: The offset press against its crank speed
    scene: press.yaml
    sweep: {keys: [drive.speed_rpm], label: speed, unit: rpm, values: [120.0, 200.0], batch: 2,
            lyapunov_alignment: 1}
    analyses: [bifurcation]
"""
#: words of the six-bar's studies that no other study's section may hold
SIX_BAR_WORDS = ("six-bar", "Xiao", "rod2", "rod3", "rod4", "Table 3", "flagship", "paper")


@pytest.fixture(scope="module")
def quick_workflow(tmp_path_factory) -> Path:
    """The quick configuration with the press's studies, in a copy of the workflow, then the
    report of everything: the copy's folder."""
    work = _workflow_copy(tmp_path_factory.mktemp("quick"))
    shutil.copy(ROOT / "tests/workflow/press.yaml", work / "press.yaml")
    (work / "press-studies.yaml").write_text(PRESS_STUDIES)
    config = ("--configfile", "config/quick.yaml", "press-studies.yaml")
    done = _snakemake("-j2", *config, cwd=work, timeout=3600)
    assert done.returncode == 0, done.stderr[-4000:]
    report = _snakemake(*config, "--report", "report.html", cwd=work, timeout=300)
    assert report.returncode == 0, report.stderr[-4000:]
    return work


def _check_report(work: Path) -> None:
    """The report holds the paper's section and every study's, each study's title and
    figures, and no six-bar wording in the press's sections."""
    front = (work / "report.html").read_text()
    assert "The paper&#x27;s claims" in front or "The paper's claims" in front
    assert "Synthetic recording" in front or "Measured recording" in front
    for study in ("press", "press-speed"):
        section = (work / f"results/{study}/report/section.rst").read_text()
        assert section.count("data:image/png;base64,") >= 1  # its figures, embedded
        for word in SIX_BAR_WORDS:
            assert word not in section, (study, word)
        # the section as written is in the report: its title and its first paragraph
        title = section.splitlines()[0]
        assert title in front
        first = section[section.index("<p>") + 3 : section.index("</p>")]
        assert first.replace('"', '\\"') in front
    press = (work / "results/press/report/section.rst").read_text()
    assert "Offset slider-crank press with clearance" in press
    assert "decided by" in press and "model exponent" in press
    assert press.count("data:image/png;base64,") == 4  # responses, trajectories, phase, Poincaré
    sweep = (work / "results/press-speed/report/section.rst").read_text()
    assert "A sweep of drive.speed_rpm: 2 values from 120 to 200 rpm" in sweep


@pytest.mark.slow
def test_quick_workflow_end_to_end(quick_workflow):
    """The quick configuration in a copy of the workflow, then the report."""
    work = quick_workflow
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
        "results/press/report/section.rst",
        "results/press-speed/figures/bifurcation.png",
    ):
        _check_file(work / name)
    _check_ensembles(work)
    _check_exponent_comparison(work)
    _check_comparison_sections(work)
    _check_bifurcation(work)
    _check_budget(work)
    _check_report(work)


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
    # the report of the one study that ran: its section, and the others named as not in it
    report = _snakemake("--report", "report.html", *args, cwd=work, timeout=300)
    assert report.returncode == 0, report.stderr[-4000:]
    html = (work / "report.html").read_text()
    section = (study / "report/section.rst").read_text()
    assert section.startswith("Crank-rocker four-bar, flexible coupler, 0.3 mm clearance at Q\n")
    assert "beams coupler (2 elements)" in section
    for word in SIX_BAR_WORDS:
        assert word not in section, word
    assert "Crank-rocker four-bar, flexible coupler" in html
    assert "Configured but not in this report: all-joints, flagship" in html
    assert "sim-paper" not in html  # the paper's section: its studies did not run


#: the front page's layout, measured in the browser: the front's width, every table that is
#: shown (not folded) with its columns' widths in characters of its font and its tallest row,
#: the images (all, loaded, and those of the paper's section shown unfolded), and any "nan" or
#: "inf" in its text
MEASURE = """
(() => {
  const front = document.querySelector('.sim-front');
  const charWidth = (cell) => {
    const probe = document.createElement('span');
    probe.textContent = '0'.repeat(40);
    probe.style.font = getComputedStyle(cell).font;
    probe.style.position = 'absolute';
    probe.style.visibility = 'hidden';
    document.body.appendChild(probe);
    const width = probe.getBoundingClientRect().width / 40;
    probe.remove();
    return width;
  };
  const shown = [...front.querySelectorAll('table')].filter(t => t.getClientRects().length > 0);
  const columns = shown.map(t => {
    const unit = charWidth(t.rows[t.rows.length - 1].cells[0]);
    return [...t.rows[0].cells].map(cell => cell.getBoundingClientRect().width / unit);
  });
  const rows = shown.flatMap(t => [...t.rows].map(r => r.getBoundingClientRect().height));
  const images = [...front.querySelectorAll('img')];
  const paper = document.querySelector('.sim-paper');
  const unfolded = paper
    ? [...paper.querySelectorAll('img')].filter(i => !i.closest('details'))
    : [];
  return {
    front: front.getBoundingClientRect().width,
    tables: shown.length,
    narrowest: Math.min(...columns.flat()),
    tallest: Math.max(...rows),
    screen: window.innerHeight,
    images: images.length,
    loaded: images.filter(i => i.complete && i.naturalWidth > 0).length,
    headline: unfolded.filter(i => i.complete && i.naturalWidth > 0).length,
    missing: (front.innerText.match(/\\b(nan|inf)\\b/gi) || []).length,
  };
})()
"""


@pytest.fixture(scope="module")
def chromium_binary() -> str:
    """The installed Chromium; the test skips, saying so, where there is none."""
    from browser import chromium

    binary = chromium()
    if binary is None:
        pytest.skip(
            "no Chromium installed (Debian: apt-get install -y chromium): the front page's "
            "layout in a browser is not checked"
        )
    return binary


@pytest.mark.slow
def test_the_front_page_in_a_browser(chromium_binary, quick_workflow):
    """The quick report's front page in headless Chromium at 1000 and 1400 px: no table column
    narrower than 25 characters, no row taller than the screen (900 px), every figure loaded,
    the paper's three headline figures shown unfolded, no "nan" or "inf" in the text.
    Screenshots of the first screen and of the page (5000 px tall) are kept beside the
    report, their paths printed."""
    from browser import Browser

    url = (quick_workflow / "report.html").as_uri()
    shots = quick_workflow / "screenshots"
    shots.mkdir(exist_ok=True)
    with Browser(chromium_binary) as browser:
        for width in (1000, 1400):
            browser.open(url, width, 900)
            browser.wait_for(".sim-front")
            layout = browser.evaluate(MEASURE)
            print(f"{width} px: {layout}")
            assert layout["front"] >= 0.6 * width  # wider than the report's 512 px column
            assert layout["tables"] >= 2  # the verdicts, and the press's channels
            assert layout["narrowest"] >= 25 - 0.5  # the CSS's 25ch, less rounding
            assert layout["tallest"] <= layout["screen"]
            assert layout["images"] >= 8 and layout["loaded"] == layout["images"]
            assert layout["headline"] == 3  # exponents, sweeps, the flagship against ideal
            assert layout["missing"] == 0
            first = browser.screenshot(shots / f"front-{width}px-first-screen.png")
            browser.open(url, width, 5000)
            browser.wait_for(".sim-front")
            page = browser.screenshot(shots / f"front-{width}px-5000px.png")
            print(f"screenshots: {first}, {page}")

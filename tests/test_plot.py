"""`sim plot`: a run, an analysis and a sweep drawn by the workflow's figure code, as PNG or
SVG, and what it refuses before drawing."""

import xml.etree.ElementTree as ET

import pytest
from matplotlib.image import imread

from sim.cli import main

#: the four-bar's clearance joint B, 27 revolutions: the least `sim sweep --indicators` takes
#: with a transient of 1 (1 + 25 section points) and a few seconds of integration
SHORT = ["--set", "simulation.revolutions=27", "--set", "simulation.output_per_revolution=40"]


@pytest.fixture(scope="module")
def files(tmp_path_factory):
    """A run of the four-bar, its ideal reference (as the workflow makes it), its analysis and
    a two-point clearance sweep with its indicators."""
    folder = tmp_path_factory.mktemp("plot")
    run, ideal = folder / "run.nc", folder / "ideal.nc"
    assert main(["run", "fourbar", "-q", "-o", str(run), *SHORT]) == 0
    assert main(["run", "fourbar", "-q", "-o", str(ideal), "--ideal", "--rigid", *SHORT]) == 0
    assert main(["analyze", str(run), "-o", str(folder / "analysis.nc"), "--transient", "1"]) == 0
    sweep = ["sweep", "fourbar", "-q", *SHORT, "--transient", "1", "--indicators"]
    sweep += ["--key", "joints.B.clearance", "--values", "2e-4", "3e-4"]
    assert main([*sweep, "--out-dir", str(folder / "runs"), "-o", str(folder / "sweep.nc")]) == 0
    return folder


@pytest.mark.parametrize(
    ("name", "kind", "suffix"),
    [
        ("run", None, "png"),  # responses
        ("run", "trajectories", "svg"),
        ("analysis", None, "svg"),  # phase portraits
        ("analysis", "poincare", "png"),
        ("sweep", None, "png"),  # the bifurcation diagram, the exponent and K beneath
    ],
)
def test_each_kind_is_drawn(files, tmp_path, capsys, name, kind, suffix):
    out = tmp_path / f"figure.{suffix}"
    argv = ["plot", str(files / f"{name}.nc"), "-o", str(out)] + (["--kind", kind] * bool(kind))
    assert main(argv) == 0
    drawn = kind or {"run": "responses", "analysis": "phase", "sweep": "bifurcation"}[name]
    assert capsys.readouterr().out.startswith(f"{out}: {drawn} of the {name} ")
    if suffix == "png":
        height, width, _ = imread(out).shape
        assert height > 300 and width > 300
    else:
        assert ET.parse(out).getroot().tag.endswith("svg")
    assert [p.name for p in tmp_path.iterdir()] == [out.name]  # no temporary left


def test_the_ideal_reference_is_simulated_as_the_workflow_runs_it(files):
    """Without --ideal the responses are drawn against the run's scene simulated with every
    joint ideal and every link rigid: the ideal run of `sim run --ideal --rigid`, to the float32
    precision its file stores."""
    from sim.cli.plot import _ideal_of
    from sim.results import open_run

    run, written = open_run(files / "run.nc"), open_run(files / "ideal.nc")
    simulated = _ideal_of(run, None)
    # the file stores float32 (relative precision 6e-8): 1e-6 of the peak leaves a factor 16
    for name in ("position", "velocity", "drive_torque"):
        scale = float(abs(written[name]).max())
        assert float(abs(simulated[name] - written[name]).max()) < 1e-6 * scale, name


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["run.nc", "-o", "x.pdf"], "--output 'x.pdf': give a file ending in .png or .svg"),
        (["analysis.nc", "--kind", "responses"], "is drawn as phase or poincare"),
        (["sweep.nc", "--kind", "phase"], "is drawn as bifurcation"),
        (["analysis.nc", "--ideal", "ideal.nc"], "only the responses take an ideal reference"),
        (["runs", "-o", "x.png"], "file 'runs' is a directory"),
        (["missing.nc"], "file 'missing.nc' does not exist"),
    ],
)
def test_what_cannot_be_drawn_is_refused_before_drawing(
    files, tmp_path, capsys, argv, message, monkeypatch
):
    monkeypatch.chdir(files)
    argv = [*argv, "-o", str(tmp_path / "x.png")] if "-o" not in argv else argv
    assert main(["plot", *argv]) == 2
    assert message in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []

"""The front page's pieces: a study's section (sim.sections) from a real run of the four-bar, the
paper's section (sim.paper_section) from what ran, and the HTML pieces they share
(sim.front_page); each renders with docutils, as Snakemake renders the report, without a
warning, and says what is missing in words."""

import io
import re
from html import unescape

import numpy as np
import pandas as pd
import pytest
from docutils.core import publish_parts

from sim import front_page as page
from sim.analysis.revolutions import Bootstrap
from sim.claims import judge_all
from sim.cli import main
from sim.paper_section import paper_section
from sim.sections import StudyFiles, study_section

SHORT = ["--set", "simulation.revolutions=27", "--set", "simulation.output_per_revolution=40"]
#: docutils drops any line longer than this (its line_length_limit)
LINE_LIMIT = 10_000


def render(rst: str) -> str:
    """The HTML docutils makes of ``rst``; AssertionError on any warning or error it reports."""
    warnings = io.StringIO()
    html = publish_parts(rst, writer="html", settings_overrides={"warning_stream": warnings})[
        "html_body"
    ]
    assert warnings.getvalue() == "", warnings.getvalue()
    assert max(map(len, rst.splitlines())) < LINE_LIMIT
    return html


@pytest.fixture(scope="module")
def fourbar(tmp_path_factory):
    """A four-bar run with its clearance at B, its analysis and a figure of it."""
    folder = tmp_path_factory.mktemp("fourbar")
    run, analysis = folder / "run.nc", folder / "analysis.nc"
    assert main(["run", "fourbar", "-q", "-o", str(run), *SHORT]) == 0
    assert main(["analyze", str(run), "-o", str(analysis), "--transient", "1"]) == 0
    assert (
        main(["plot", str(run), "-o", str(folder / "trajectories.png"), "--kind", "trajectories"])
        == 0
    )
    return folder


SETTINGS = {
    "title": "Crank-rocker with 0.3 mm clearance at the coupler-rocker joint",
    "scene": "fourbar",
    "revolutions": 27,
    "transient": 1,
    "overrides": {"simulation.output_per_revolution": 40},
    "cases": {"clearance-0.3mm": {}},
    "analyses": ["trajectories", "chaos"],
}


def test_a_study_s_section_says_what_ran_and_what_it_found(fourbar):
    files = StudyFiles(
        runs=[str(fourbar / "run.nc")],
        analyses=[str(fourbar / "analysis.nc")],
        figures=[str(fourbar / "trajectories.png")],
    )
    rst = study_section("my-fourbar", SETTINGS, files)
    assert rst.startswith(f"{SETTINGS['title']}\n{'-' * len(SETTINGS['title'])}\n")
    html = render(rst)
    text = unescape(re.sub(r"<[^>]+>", " ", html))
    assert "Study my-fourbar on scene fourbar (fourbar)" in text
    assert "Links: rigid links, dopri5 rtol 1e-06" in text  # the scene's own rtol
    assert "model exponent not computed: the channels' own indicators decide" in text
    for channel in ("B.x", "B.y"):
        assert f">{channel}</td>" in html
    assert html.count("data:image/png;base64,") == 1
    assert "Assumed values of scene fourbar (7)" in text  # the scene's seven assumptions
    assert not re.search(r"\b(nan|inf)\b", text)
    ours = text[: text.index("Assumed values of scene")]  # the scene's own words come after
    for word in ("six-bar", "rod2", "slider", "Xiao", "flagship"):
        assert word not in ours, word


def test_a_study_s_section_gives_the_model_exponent_its_verdicts_read(fourbar, tmp_path):
    """With the model exponent in the analysis (as `sim analyze --model-exponent` writes it),
    the section states it with its standard error, and over the members beside it."""
    import xarray as xr

    with xr.open_dataset(fourbar / "analysis.nc") as analysis:
        with_model = analysis.load().assign(
            model_lyapunov_exponent=((), 41.26), model_lyapunov_stderr=((), 3.14)
        )
    with_model.to_netcdf(tmp_path / "analysis.nc")
    members = pd.DataFrame(
        [
            {
                "case": "clearance-0.3mm",
                "links": "rigid",
                "members": 3,
                "primary": True,
                "median_exponent_per_s": 40.0,
                "interval_low_per_s": 35.5,
                "interval_high_per_s": np.nan,
                "interval_coverage": 0.75,
                "mean_member_stderr_per_s": 3.0,
            }
        ]
    )
    members.to_csv(tmp_path / "model_exponent.csv", index=False)
    files = StudyFiles(
        runs=[str(fourbar / "run.nc")],
        analyses=[str(tmp_path / "analysis.nc")],
        exponents=str(tmp_path / "model_exponent.csv"),
    )
    text = unescape(re.sub(r"<[^>]+>", " ", render(study_section("my-fourbar", SETTINGS, files))))
    assert "model exponent 41.3 ± 3.14 1/s" in text
    # a bound it lacks is said in words, not as nan
    assert "over the members: 40 1/s (no interval) on rigid links (3 members)" in text


def test_the_paper_s_section_of_nothing_run_says_so():
    claims, meta = judge_all({}, Bootstrap(resamples=10, level=0.95, seed=1))
    rst = paper_section({}, claims, meta, {}, {"level": 0.95, "resamples": 10}, {})
    html = render(rst)
    text = unescape(re.sub(r"<[^>]+>", " ", html))
    assert text.count("not evaluated") == len(claims) == 9
    assert "The experiment study was not run." in text
    assert "data:image" not in html  # no headline figure without its tables
    assert not re.search(r"\b(nan|inf)\b", text)


def test_numbers_keep_three_digits_and_say_what_is_missing():
    assert page.number(212.345, "1/s") == "212 1/s"
    assert page.number(float("nan"), "1/s", "not estimated") == "not estimated"
    assert page.number(float("inf")) == "not computed"
    assert page.interval(0.12345, 0.6789, "mm") == "[0.123, 0.679] mm"
    assert page.interval(1.0, float("nan")) == "no interval"


def test_a_large_figure_is_cut_into_lines_docutils_keeps():
    big = bytes(range(256)) * 4000  # a 1 MB image's bytes
    rst = page.raw(page.image(big, "big"))
    html = render(rst)
    assert max(map(len, rst.splitlines())) < 200  # 76 characters of base64, or the tag
    encoded = html[html.index("base64,") + 7 : html.index('"', html.index("base64,"))]
    import base64

    assert base64.b64decode("".join(encoded.split())) == big

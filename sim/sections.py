"""A study's section of the report's front page, from the study's own files: its title, scene,
link model and cases, its chaos verdicts with the model exponent and what decided each, its
sweep's diagram and its figures, its scene's assumptions.

Any study gets one, on any scene: nothing here knows the six-bar. The section is rst with raw
HTML blocks (sim.front_page): what a reader takes in at a glance stays visible, the rest is
folded beneath it.
"""

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import quote

import pandas as pd
import xarray as xr

from sim import front_page as page
from sim.claims import members_summary
from sim.results import scene_of
from sim.scene import load_scene
from sim.studies.config import case_names, case_overrides, sweep_points
from sim.studies.sweep import model_text

#: the link models of a study's exponents (`model_lyapunov.links`) in words
_LINKS = {"rigid": "rigid links", "modal": "modal links"}
RUN_LINKS = "the run's links"
#: a study with more cases than this lists their names only (their settings are in its config)
LISTED_CASES = 6


@dataclass(frozen=True)
class StudyFiles:
    """The files a study's section reads (workflow/rules/paths.smk names them).

    Attributes:
        runs: the nominal run of each case, in case order (none for a sweep).
        analyses: the chaos analysis of each case, in case order (studies with `chaos`).
        exponents: the study's model exponent table (`model_exponent.csv`), if it has one.
        sweep: the combined bifurcation dataset of a sweep study.
        figures: every figure of the study (PNG), its headline first.
    """

    runs: Sequence[str] = ()
    analyses: Sequence[str] = ()
    exponents: str | None = None
    sweep: str | None = None
    figures: Sequence[str] = field(default_factory=list)


def _open(path: str) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def _overrides_text(overrides: Mapping) -> str:
    """Scene overrides as `key = value` pairs."""
    return ", ".join(
        f"{key} = {value:g}" if isinstance(value, float) else f"{key} = {value}"
        for key, value in overrides.items()
    )


def _setting_text(name: str, settings: Mapping, scene: dict, model: str) -> str:
    """What the study ran, in one paragraph."""
    description = f": {scene['description'].strip()}" if scene.get("description") else ""
    own = settings.get("overrides") or {}
    own_links = any(
        key.startswith("solver.") or (key.startswith("bodies.") and key.endswith(".kind"))
        for changes in settings.get("cases", {}).values()
        for key in changes
    )
    parts = [
        f"Study {name} on scene {scene['name']} ({settings['scene']}){description}",
        f"Links: each case's own; the first case's {model}" if own_links else f"Links: {model}",
    ]
    if own:
        parts.append(f"Every run sets {_overrides_text(own)}")
    if "sweep" in settings:
        values = [value for _, value in sweep_points(settings)]
        unit = settings["sweep"]["unit"]
        parts.append(
            f"A sweep of {', '.join(settings['sweep']['keys'])}: {len(values)} values from "
            f"{min(values):g} to {max(values):g} {unit}"
        )
    elif len(settings["cases"]) > LISTED_CASES:
        parts.append(f"{len(settings['cases'])} cases: {', '.join(settings['cases'])}")
    else:
        cases = "; ".join(
            f"{case} ({_overrides_text(changes)})" if changes else case
            for case, changes in settings["cases"].items()
        )
        parts.append(f"Cases: {cases}")
    parts.append(
        f"{settings['revolutions']:g} crank revolutions a run, the first "
        f"{settings['transient']} dropped before the analyses"
    )
    return ". ".join(parts) + "."


def _exponent_rows(path: str | None) -> dict[str, pd.DataFrame]:
    """The model exponent table's rows by case (every link model), the primary first."""
    if path is None:
        return {}
    table = pd.read_csv(path)
    return {
        str(case): part.sort_values("primary", ascending=False, kind="stable")
        for case, part in table.groupby("case", sort=False)
    }


def _chaos_html(cases: Sequence[str], analyses: Sequence[str], exponents: str | None) -> str:
    """Per case: the model exponent the verdicts read, a table of each channel's verdict and
    what decided it, and every reason folded beneath."""
    rows_by_case = _exponent_rows(exponents)
    parts, reasons = [], []
    for case, path in zip(cases, analyses, strict=True):
        analysis = _open(path)
        if "model_lyapunov_exponent" in analysis:
            model = (
                f"model exponent {page.number(float(analysis.model_lyapunov_exponent))} ± "
                f"{page.number(float(analysis.model_lyapunov_stderr), '1/s')} (Benettin on "
                "the linkage, the nominal run's scene): the first chaos vote of every channel"
            )
        else:
            model = "model exponent not computed: the channels' own indicators decide"
        beside = rows_by_case.get(case)
        if beside is not None:
            model += "; over the members: " + "; ".join(
                f"{members_summary(row)} on {_LINKS.get(row.links, RUN_LINKS)} "
                f"({int(row.members)} member{'s' * (int(row.members) > 1)})"
                for _, row in beside.iterrows()
            )
        parts.append(page.paragraph(f"Case {case}: {model}."))
        basis = analysis.get("verdict_basis")
        parts.append(
            page.table(
                ["channel", "verdict", "decided by"],
                [
                    [
                        str(channel),
                        str(analysis.verdict.values[i]),
                        str(basis.values[i]) if basis is not None else "",
                    ]
                    for i, channel in enumerate(analysis.channel.values)
                ],
            )
        )
        reasons += [
            f"<li>{page.escaped(case)}, {page.escaped(channel)}: "
            f"{page.escaped(analysis.verdict_reason.values[i])}</li>"
            for i, channel in enumerate(analysis.channel.values)
        ]
    parts.append(
        page.details("Why each verdict (every indicator read)", f"<ul>{''.join(reasons)}</ul>")
    )
    return "".join(parts)


def _sweep_html(path: str) -> str:
    """The sweep's verdicts per point in a few words, each channel's share of chaotic points."""
    combined = _open(path)
    verdicts = combined.verdict.to_series() if "verdict" in combined else pd.Series(dtype=str)
    verdicts = verdicts[verdicts != ""]
    if verdicts.empty:
        return page.paragraph("No clearance channel at any point: nothing to judge.")
    chaotic = (verdicts == "chaotic").groupby(level=["joint", "axis"]).mean()
    shares = ", ".join(f"{j}.{a} {share:.0%}" for (j, a), share in chaotic.items())
    model = combined.attrs.get("model", "links not recorded")
    return page.paragraph(
        f"{combined.sizes['parameter']} points drawn on {model}; share of the points judged "
        f"chaotic per channel: {shares}."
    )


def _category_link(name: str) -> str:
    """HTML: a link to the study's category in the report's navigation."""
    return f"<a href=\"javascript:app.showCategory('{quote(name)}')\">{page.escaped(name)}</a>"


def study_section(name: str, settings: Mapping, files: StudyFiles) -> str:
    """The rst section of study ``name`` (its resolved settings, sim.studies.config) from its
    files: heading (its title), what it ran, its chaos verdicts or sweep, its headline figure,
    the rest of its figures and its scene's assumptions folded."""
    if files.runs:
        scene = scene_of(_open(files.runs[0]))
    else:  # the first case's scene as the workflow runs it
        first = case_overrides(settings, case_names(settings)[0])
        scene = load_scene(settings["scene"], [f"{k}={v}" for k, v in first.items()])
    if files.sweep is not None:
        model = str(_open(files.sweep).attrs.get("model", "not recorded"))
    else:
        model = model_text(scene)
    body = [page.paragraph(_setting_text(name, settings, scene, model))]
    cases = case_names(settings)
    if files.analyses:
        body.append(_chaos_html(cases, files.analyses, files.exponents))
    if files.sweep is not None:
        body.append(_sweep_html(files.sweep))
    figures = list(files.figures)
    if figures:
        body.append(page.figure(figures[0], f"{name}: {Path(figures[0]).stem}", "70%"))
    if figures[1:]:
        folded = "".join(
            f"<p>{page.escaped(Path(path).stem)}</p>{page.figure(path, Path(path).stem)}"
            for path in figures[1:]
        )
        body.append(page.details(f"Its other figures ({len(figures) - 1})", folded))
    assumptions = scene.get("assumptions") or []
    body.append(
        page.details(
            f"Assumed values of scene {scene['name']} ({len(assumptions)})",
            "<ul>" + "".join(f"<li>{page.escaped(a)}</li>" for a in assumptions) + "</ul>"
            if assumptions
            else page.paragraph("The scene lists none."),
        )
    )
    body.append(
        f"<p>Every figure and table of the study: category {_category_link(name)} of this "
        "report.</p>"
    )
    title = settings.get("title") or name
    return page.heading(title, "-") + page.raw(f'<div class="sim-study">{"".join(body)}</div>')

"""The workflow's study resolver: the settings of every study from the workflow config
(config/config.yaml, validated against workflow/schemas/config.schema.yaml with its defaults
filled in), as pure functions of the config mapping.

A study's settings are, later winning: the defaults (`defaults`, or `quick_defaults` when
`quick`), the study's entry, and, when quick, the entry's `quick:` block; `ensemble`,
`model_lyapunov`, `model` and `case_grid` merge key by key, every other key is replaced
whole. The scene overrides of one case are, later winning: the link model (`model`), the
duration, the default overrides, the study's `overrides`, the case's (or the sweep point's
swept keys). The config's `model` and `defaults.overrides` describe the default scene
(`defaults.scene`): they apply to the studies on that scene only, so a study on a scene of
its own gets its own `model:` and `overrides:` and nothing else. `force_model: true` puts the
config's link model (`links`, `elements`, `modes`, `solver`) over every study's own.

Kept free of heavy imports: the workflow reads it on every parse (workflow/rules/common.smk).
"""

from collections.abc import Mapping
from decimal import Decimal
from functools import cache
from typing import Any, NamedTuple

from sim.studies.grid import sweep_grid

#: a study's keys that fall back to the defaults' when the study does not set them
DEFAULTED_KEYS = ("scene", "revolutions", "output_per_revolution", "transient", "timeout_s")
#: a study's keys merged key by key over the defaults' (and by the `quick:` block)
MERGED_KEYS = ("ensemble", "model_lyapunov")
#: keys an ideal reference run does not take: it is all ideal and rigid (`--ideal --rigid`),
#: and runs the scene's own integrator, DOPRI5, the better one for rigid links
IDEAL_IGNORED = (".clearance", ".kind", ".elements", "solver.method", "solver.rho_inf")
#: keys of the config's link model that `force_model` puts over a study's own
FORCED_MODEL_KEYS = ("links", "elements", "modes", "axial_modes", "solver")
#: the integrator of a member's exponent on rigid or modal links (`model_lyapunov.links` and
#: `compare`): the explicit method, exact for the first and cheapest for both
REDUCED_LINKS_METHOD = "dopri5"


class ConfigError(ValueError):
    """A workflow config that cannot be planned; the message names the config key."""


def is_quick(config: Mapping) -> bool:
    """Whether the config asks for the quick variant (`--config quick=true` passes text)."""
    return str(config.get("quick", False)).lower() == "true"


def defaults(config: Mapping) -> dict:
    """The defaults of this variant: `quick_defaults` when quick, else `defaults`."""
    return config["quick_defaults"] if is_quick(config) else config["defaults"]


def enabled_studies(config: Mapping) -> list[str]:
    """The names of the studies to run, in config order."""
    return [name for name, entry in config["studies"].items() if entry.get("enabled", True)]


def format_rtol(rtol: float) -> str:
    """A tolerance as a case name writes it: 1e-3, 5e-12."""
    mantissa, exponent = f"{rtol:e}".split("e")
    return f"{mantissa.rstrip('0').rstrip('.')}e{int(exponent)}"


def grid_cases(grid: Mapping) -> dict[str, dict]:
    """The cases of a `case_grid`: for each series, each of its link models and tolerances,
    the case `<prefix><links><suffix>-<rtol>` with every body of `bodies` given the link
    model's keys, the series' `overrides`, `solver.rtol` and `solver.atol` = rtol / 100
    (exactly: the decimal of rtol shifted by two places)."""
    cases = {}
    for series in grid["series"]:
        for links in series["links"]:
            model = grid["links"][links]
            for rtol in series["rtol"]:
                name = f"{series.get('prefix', '')}{links}{series.get('suffix', '')}"
                case = {
                    f"bodies.{body}.{key}": value
                    for body in grid["bodies"]
                    for key, value in model.items()
                }
                case.update(series.get("overrides", {}))
                case["solver.rtol"] = rtol
                case["solver.atol"] = float(Decimal(repr(rtol)).scaleb(-2))
                cases[f"{name}-{format_rtol(rtol)}"] = case
    return cases


def _with_cases(block: Mapping, grid: Mapping | None = None) -> dict:
    """`block` (a study entry or its quick block) with its `case_grid` turned into `cases`;
    a quick block's grid is merged key by key over the entry's (`grid`)."""
    out = dict(block)
    if "case_grid" in out:
        out["cases"] = grid_cases({**(grid or {}), **out.pop("case_grid")})
    return out


def link_model(config: Mapping, entry: Mapping, quick_block: Mapping, scene: str) -> dict:
    """The link model of a study: the config's `model` if the study is on the default scene,
    the study's own `model:` (and its quick block's) on top; `force_model` puts the config's
    link keys back on top. Empty: the scene's own links and integrator."""
    own = {**entry.get("model", {}), **quick_block.get("model", {})}
    on_default_scene = scene == defaults(config)["scene"]
    if on_default_scene:
        model = {**config["model"], **own}
    elif own:
        base = {k: v for k, v in config["model"].items() if k != "flexible_bodies"}
        model = {"flexible_bodies": [], **base, **own}
    else:
        model = {}
    if config.get("force_model") and model:
        model.update({k: config["model"][k] for k in FORCED_MODEL_KEYS if k in config["model"]})
    return model


def study_settings(config: Mapping, name: str) -> dict:
    """The resolved settings of study `name` (module docstring: precedence)."""
    raw = config["studies"][name]
    entry = _with_cases(raw)
    quick = is_quick(config)
    quick_block = _with_cases(raw.get("quick", {}), raw.get("case_grid")) if quick else {}
    base = defaults(config)
    settings = {key: value for key, value in entry.items() if key not in ("quick", "case_grid")}
    settings.update(quick_block)
    settings.pop("case_grid", None)
    for key in DEFAULTED_KEYS:
        settings.setdefault(key, base[key])
    for key in MERGED_KEYS:
        settings[key] = {**base.get(key, {}), **entry.get(key, {}), **quick_block.get(key, {})}
    settings["model"] = link_model(config, entry, quick_block, settings["scene"])
    on_default_scene = settings["scene"] == base["scene"]
    settings["default_overrides"] = dict(base.get("overrides", {})) if on_default_scene else {}
    _check(name, settings)
    return settings


def _check(name: str, settings: Mapping) -> None:
    """Refuse settings that cannot run, naming the config key."""
    model = settings["model"]
    if model and model["links"] != "rigid" and not model.get("flexible_bodies"):
        bodies = ", ".join(scene_kinds(settings["scene"]))
        raise ConfigError(
            f"config: studies.{name}.model.flexible_bodies: links: {model['links']} needs the "
            f"bodies of scene {settings['scene']!r} it makes flexible (its bodies: {bodies}); "
            "a study on a scene of its own gets no flexible bodies from the config's `model`"
        )
    exponent = settings["model_lyapunov"]
    if not 0 <= exponent["transient"] < exponent["revolutions"]:
        raise ConfigError(
            f"config: studies.{name}.model_lyapunov (or the defaults'): transient = "
            f"{exponent['transient']} must lie in [0, revolutions = {exponent['revolutions']})"
        )
    length = settings["ensemble"].get("revolutions")
    if ensemble_size(settings) > 1 and length is not None and not length > settings["transient"]:
        raise ConfigError(
            f"config: studies.{name}.ensemble.revolutions (or the defaults'): {length} must "
            f"exceed the study's transient, {settings['transient']} revolutions"
        )


def resolve(config: Mapping) -> dict[str, dict]:
    """The settings of every enabled study, resolved once."""
    return {name: study_settings(config, name) for name in enabled_studies(config)}


# ---------------------------------------------------------------- cases and sweep points
def point_name(sweep: Mapping, value: float) -> str:
    """File name of one sweep point, e.g. clearance-0.0005m or speed-120rpm."""
    return f"{sweep['label']}-{value:g}{sweep['unit']}"


def sweep_points(settings: Mapping) -> list[tuple[str, float]]:
    """(point name, value) of every point of a sweep study."""
    sweep = settings["sweep"]
    return [(point_name(sweep, value), value) for value in sweep_grid(sweep)]


def case_names(settings: Mapping) -> list[str]:
    """The cases of a study: its `cases`, or the points of its sweep."""
    if "sweep" in settings:
        return [point for point, _ in sweep_points(settings)]
    return list(settings["cases"])


def sweep_batches(settings: Mapping) -> list[list[tuple[str, float]]]:
    """The points of a sweep study in batches of `sweep.batch` consecutive points."""
    points = sweep_points(settings)
    size = int(settings["sweep"]["batch"])
    return [points[k : k + size] for k in range(0, len(points), size)]


def sweep_batch(settings: Mapping, batch: int | str) -> list[tuple[str, float]]:
    """The points of one batch of a sweep study (`sweep_batches`)."""
    return sweep_batches(settings)[int(batch)]


def batch_files(settings: Mapping) -> list[tuple[str, dict]]:
    """(file name, wildcards) of every batch directory of a sweep study."""
    return [("sweep_batch", {"batch": k}) for k in range(len(sweep_batches(settings)))]


def sweep_parameter(settings: Mapping) -> str:
    """The swept scene keys, comma-separated (`sim sweep-collect --parameter`)."""
    return ",".join(settings["sweep"]["keys"])


def link_overrides(model: Mapping) -> dict[str, Any]:
    """Scene keys of a link model and its integrator (config `model`)."""
    out = {f"solver.{key}": value for key, value in model.get("solver", {}).items()}
    if not model:
        return out
    if model["links"] == "rigid":
        out.update({f"bodies.{body}.kind": "rigid" for body in model["flexible_bodies"]})
        return out
    for body in model["flexible_bodies"]:
        out[f"bodies.{body}.kind"] = model["links"]
        if model["links"] == "modal":
            # else the scene schema's defaults (sim.scene, bodies.<name>.modes, .axial_modes)
            for key in ("modes", "axial_modes"):
                if key in model:
                    out[f"bodies.{body}.{key}"] = model[key]
        else:
            out[f"bodies.{body}.elements"] = model["elements"]
    return out


def case_overrides(settings: Mapping, case: str) -> dict[str, Any]:
    """Every scene override of one case, in order of precedence (later wins): link model,
    duration, default overrides, study, case (or sweep point)."""
    out = link_overrides(settings["model"])
    out["simulation.revolutions"] = settings["revolutions"]
    out["simulation.output_per_revolution"] = settings["output_per_revolution"]
    out.update(settings["default_overrides"])
    out.update(settings.get("overrides", {}))
    if "sweep" in settings:
        value = dict(sweep_points(settings))[case]
        out.update({key: value for key in settings["sweep"]["keys"]})
    else:
        out.update(settings["cases"][case])
    return out


def crank_rpm(settings: Mapping, case: str) -> float:
    """The crank speed (rpm) of one case's run."""
    return case_overrides(settings, case)["drive.speed_rpm"]


def ideal_reference(settings: Mapping, case: str) -> list[tuple[str, dict]]:
    """(file name, wildcards) of the ideal run a case is compared with: only the study's
    `ideal_reference` case has one (clearance 0 must reproduce the ideal joint)."""
    return [("ideal", {"case": case})] if settings.get("ideal_reference") == case else []


def ideal_overrides(settings: Mapping, case: str) -> dict[str, Any]:
    """A case's overrides for its ideal reference run (`--ideal --rigid` ignores the
    clearance and link keys, so changing them does not rerun the reference)."""
    overrides = case_overrides(settings, case)
    return {k: v for k, v in overrides.items() if not k.endswith(IDEAL_IGNORED)}


def sweep_base_overrides(settings: Mapping) -> dict[str, Any]:
    """The overrides shared by every point of a sweep: a point's without the swept keys."""
    keys = settings["sweep"]["keys"]
    overrides = case_overrides(settings, sweep_points(settings)[0][0])
    return {key: value for key, value in overrides.items() if key not in keys}


# ---------------------------------------------------------------- ensemble members
def ensemble_size(settings: Mapping) -> int:
    """Members per case: the study's ensemble if it has statistics over members, on the peaks
    or on the chaos (the model exponent's median and interval), else 1."""
    statistics = {"peaks", "chaos"} & set(settings["analyses"])
    return int(settings["ensemble"]["members"]) if statistics else 1


def member_overrides(settings: Mapping, case: str) -> dict[str, Any]:
    """A further member's scene overrides: its case's, its length the ensemble's
    `revolutions` (transient included) where that is shorter than the case's."""
    overrides = case_overrides(settings, case)
    length = settings["ensemble"].get("revolutions")
    if length is not None:
        overrides["simulation.revolutions"] = min(overrides["simulation.revolutions"], length)
    return overrides


def member_file(case: str, member: int | str) -> tuple[str, dict]:
    """(file name, wildcards) of member `member`'s run of a case: member 0 is the case's
    nominal run."""
    if int(member) == 0:
        return "run", {"case": case}
    return "member", {"case": case, "member": member}


def member_files(settings: Mapping) -> list[tuple[str, dict]]:
    """`member_file` of every member of every case, case by case."""
    members = range(ensemble_size(settings))
    return [member_file(case, k) for case in case_names(settings) for k in members]


def member_draw(settings: Mapping, member: int) -> dict[str, Any]:
    """Arguments of sim.ensemble.member for one member: index, base seed and, if the config
    states it, the perturbation's size (deg; else sim.ensemble's default)."""
    ensemble = settings["ensemble"]
    draw = {"index": int(member), "base_seed": int(ensemble["seed"])}
    if "size_deg" in ensemble:
        draw["size_deg"] = float(ensemble["size_deg"])
    return draw


def has_flexible_links(settings: Mapping) -> bool:
    """Whether some case of a study runs a beam or a modal link (its scene's bodies, with the
    link model's and the case's `bodies.<name>.kind` overrides)."""
    kinds = scene_kinds(settings["scene"])
    for case in case_names(settings):
        overrides = case_overrides(settings, case)
        case_kinds = {
            body: overrides.get(f"bodies.{body}.kind", kind) for body, kind in kinds.items()
        }
        if any(kind != "rigid" for kind in case_kinds.values()):
            return True
    return False


def exponent_links(settings: Mapping) -> list[str]:
    """The link models the members' exponents are taken on: the study's `model_lyapunov.links`
    (the one its verdicts and claims read) first, then those of `compare` in their order, each
    only where the study's mechanism has it: without flexible links there is no modal one, and
    the run's links are the rigid ones (the first of the two named is kept)."""
    exponent = settings["model_lyapunov"]
    named = list(dict.fromkeys([exponent["links"], *exponent.get("compare", [])]))
    if has_flexible_links(settings):
        return named
    # `run` and `rigid` are then one mechanism: the first named, else that of `modal`
    return [links for links in named if links != "modal"][:1] or ["rigid"]


def exponent_files(settings: Mapping) -> list[tuple[str, dict]]:
    """(file name, wildcards) of every member's exponent, case by case, then link model by
    link model (`exponent_links`)."""
    return [
        ("model_exponent", {"case": case, "links": links, "member": k})
        for case in case_names(settings)
        for links in exponent_links(settings)
        for k in range(ensemble_size(settings))
    ]


# ---------------------------------------------------------------- integrators
@cache
def loaded_scene(scene: str) -> dict:
    """A scene (name or path) loaded once per process: the plan reads it for every study and
    case (never modified: overrides make a copy, sim.scene.with_overrides)."""
    from sim.scene import load_scene

    return load_scene(scene)


def scene_kinds(scene: str) -> dict[str, str]:
    """Each body of a scene (name or path) and its link model (`kind`) as the scene gives it."""
    return {name: body["kind"] for name, body in loaded_scene(scene)["bodies"].items()}


def scene_method(scene: str) -> str:
    """The integrator (`solver.method`) a scene names when no override sets it."""
    return loaded_scene(scene)["solver"]["method"]


def override_texts(overrides: Mapping[str, Any]) -> list[str]:
    """Scene overrides as `sim run --set` takes them, `key=value` (None as YAML's null)."""
    return [f"{key}={'null' if value is None else value}" for key, value in overrides.items()]


def case_contacts(settings: Mapping) -> dict[str, dict]:
    """How each case of a study makes contact, from its scene with the case's overrides: the
    scene-wide damping law (`contact.law`) and the joints with an oil film
    (`joints.<name>.lubricant`); a sweep, whose points share them, as one entry named
    `sweep`. Joints that override the law for themselves (`joints.<name>.law`) are not
    followed here."""
    from sim.scene import with_overrides

    def contacts(overrides: Mapping) -> dict:
        scene = settings["scene"]
        resolved = with_overrides(loaded_scene(scene), override_texts(overrides), scene)
        oiled = [name for name, joint in resolved["joints"].items() if joint.get("lubricant")]
        return {"law": resolved["contact"]["law"], "lubricated": oiled}

    if "sweep" in settings:
        return {"sweep": contacts(sweep_base_overrides(settings))}
    return {case: contacts(case_overrides(settings, case)) for case in case_names(settings)}


#: the landing page's roles whose contacts its sections on the laws and the oil film name
CONTACT_ROLES = (
    "contact_laws",
    "bifurcation_clearance",
    "bifurcation_clearance_memoryless",
    "lubrication",
)


def landing_contacts(config: Mapping, studies: Mapping[str, Mapping]) -> dict[str, dict]:
    """{role: case_contacts} of the studies that config `report` names for CONTACT_ROLES and
    that run."""
    roles = config["report"]
    return {
        role: case_contacts(studies[roles[role]])
        for role in CONTACT_ROLES
        if roles.get(role) in studies
    }


def run_method(settings: Mapping, overrides: Mapping) -> str:
    """The integrator of a run of the study with these scene overrides: theirs, else the
    scene's own."""
    return overrides.get("solver.method", scene_method(settings["scene"]))


def ideal_method(settings: Mapping) -> str:
    """The integrator of an ideal reference run: the scene's own (`IDEAL_IGNORED`)."""
    return scene_method(settings["scene"])


def case_method(settings: Mapping, case: str) -> str:
    """The integrator of one case's run (a sweep point's, an ensemble member's)."""
    return run_method(settings, case_overrides(settings, case))


def sweep_method(settings: Mapping) -> str:
    """The integrator a sweep's points share: its first point's."""
    return case_method(settings, sweep_points(settings)[0][0])


def exponent_method(settings: Mapping, case: str, links: str) -> str:
    """The integrator of a member's exponent on `links` (`exponent_links`): the member's own
    on `run`, REDUCED_LINKS_METHOD on rigid or modal links."""
    return case_method(settings, case) if links == "run" else REDUCED_LINKS_METHOD


# ---------------------------------------------------------------- fidelity study
def fidelity_long_cases(settings: Mapping) -> list[str]:
    """Cases of a fidelity study long enough for the chaos analysis (`sim analyze` needs the
    transient and sim.analysis.poincare.MIN_REVOLUTIONS more): they feed the long-horizon
    statistics (peaks, Lyapunov exponents, Poincaré distances)."""
    from sim.analysis.poincare import MIN_REVOLUTIONS

    need = settings["transient"] + MIN_REVOLUTIONS
    return [
        case
        for case in case_names(settings)
        if case_overrides(settings, case)["simulation.revolutions"] >= need
    ]


def fidelity_settings(settings: Mapping) -> dict[str, Any]:
    """Reference cases, the long-horizon cases, short-horizon window and transient of a
    fidelity study (figures.py's work_precision)."""
    return {
        "reference": settings["reference"],
        "long_cases": fidelity_long_cases(settings),
        "window": settings["window"],
        "long_reference": settings.get("long_reference"),
        "transient": settings["transient"],
    }


# ---------------------------------------------------------------- experiment study
def synthetic_overrides(settings: Mapping) -> dict[str, Any]:
    """Scene overrides of the synthetic recording's higher-fidelity run: the study's first
    case with the `experiment.synthetic.overrides` on top."""
    overrides = case_overrides(settings, case_names(settings)[0])
    overrides.update(settings["experiment"]["synthetic"].get("overrides", {}))
    return overrides


def synthetic_method(settings: Mapping) -> str:
    """The integrator of the synthetic recording's run."""
    return run_method(settings, synthetic_overrides(settings))


def synthetic_sensor(settings: Mapping) -> str | None:
    """The sensor file the synthetic recording is measured with, if the study names one."""
    return settings["experiment"]["synthetic"].get("sensor")


# ---------------------------------------------------------------- extremes and cross-check
def extreme_checks(settings: Mapping) -> dict[str, Any]:
    """The bounds each run of an extremes study must keep (energy error, constraint violation,
    ...: config `checks`; none when the study sets none)."""
    return settings.get("checks", {})


def exudyn_settings(settings: Mapping, case: str) -> dict[str, Any]:
    """The cross-check's Exudyn settings of one case (none: the defaults)."""
    return settings["crosscheck"]["exudyn"].get(case, {})


# ---------------------------------------------------------------- the plan's scenes
def planned_scenes(studies: Mapping[str, Mapping]) -> list[tuple[str, str, str, dict]]:
    """(study, case, scene, overrides) of every run the studies plan: each case (each sweep
    point) and the experiment's synthetic recording."""
    out = []
    for name, settings in studies.items():
        for case in case_names(settings):
            out.append((name, case, settings["scene"], case_overrides(settings, case)))
        if "experiment" in settings["analyses"]:
            out.append((name, "synthetic", settings["scene"], synthetic_overrides(settings)))
    return out


def check_scenes(studies: Mapping[str, Mapping]) -> None:
    """Load and validate every planned scene with its overrides, as `sim scene` does, and
    drive its ideal, rigid linkage through a full crank turn, as `sim run` does before it
    integrates; refuse the plan at the first that cannot run (ConfigError naming the study,
    the case and, for a linkage that locks, the crank angle).

    Each scene file is read once (loaded_scene); with_overrides applies a case's overrides to
    it, fills its defaults in again and validates it, which this does per case
    (0.4 ms a case). The turn is driven once per distinct geometry
    (sim.model.mobility.kinematic_key): the cases of a study usually differ in clearances,
    link models or speed only."""
    from sim.model.assembly import AssemblyError
    from sim.model.mobility import drive_through_turn, kinematic_key
    from sim.scene import SceneError, with_overrides

    turned: set[str] = set()
    for name, case, scene, overrides in planned_scenes(studies):
        texts = override_texts(overrides)
        try:
            resolved = with_overrides(loaded_scene(scene), texts, scene)
            key = kinematic_key(resolved)
            if key not in turned:
                drive_through_turn(resolved)
                turned.add(key)
        except (SceneError, AssemblyError) as exc:
            raise ConfigError(
                f"config: studies.{name}, case {case}: its scene {scene!r} with the study's "
                f"overrides cannot run: {exc}"
            ) from None


# ---------------------------------------------------------------- targets
#: the final files (workflow/rules/paths.smk) of each analysis a study may list, per case
CASE_TARGETS = {
    "responses": ("responses",),
    "trajectories": ("trajectories",),
    "chaos": ("phase", "poincare", "lyapunov_csv", "lyapunov_html"),
    "experiment": ("comparison_json",),
}
#: ... and per study
STUDY_TARGETS = {
    "peaks": (
        "peaks_csv",
        "peaks_html",
        "revolutions",
        "revolution_statistics_csv",
        "revolution_statistics_html",
    ),
    "bifurcation": (
        "bifurcation",
        "bifurcation_figure",
        "bifurcation_lyapunov_csv",
        "bifurcation_lyapunov_html",
    ),
    "work_precision": ("work_precision_csv", "work_precision_html", "work_precision_figure"),
    "extremes": ("extremes_csv", "extremes_html"),
    "chaos": ("model_exponent_csv", "model_exponent_html"),
    "crosscheck": ("crosscheck_csv", "crosscheck_html", "crosscheck_summary"),
}


#: the figures (workflow/rules/paths.smk) a study's front-page section shows, in order: the
#: first one a study has is its headline; each is per case unless per study
SECTION_FIGURES = (
    ("bifurcation", "bifurcation_figure", False),
    ("responses", "responses", True),
    ("trajectories", "trajectories", True),
    ("chaos", "phase", True),
    ("chaos", "poincare", True),
    ("work_precision", "work_precision_figure", False),
    ("experiment", "comparison_overlay", True),
    ("experiment", "comparison_spectra", True),
)


#: the analyses that read each case's nominal run (so that a section may read it too)
RUN_ANALYSES = ("responses", "trajectories", "chaos", "peaks", "experiment")


def section_files(name: str, settings: Mapping) -> dict[str, list[tuple[str, dict]]]:
    """(file name, wildcards) of what study `name`'s section of the front page reads
    (sim.sections.StudyFiles): its cases' runs, their chaos analyses, its model exponent
    table, its sweep's dataset and its figures (`SECTION_FIGURES`)."""
    analyses = settings["analyses"]
    study = {"study": name}
    cases = [{"study": name, "case": case} for case in case_names(settings)]
    sweep = "sweep" in settings
    figures = [
        (file, wildcards)
        for analysis, file, per_case in SECTION_FIGURES
        if analysis in analyses
        for wildcards in (cases if per_case else [study])
    ]
    with_runs = not sweep and any(a in analyses for a in RUN_ANALYSES)
    return {
        "runs": [("run", wildcards) for wildcards in cases] if with_runs else [],
        "analyses": [("analysis", w) for w in cases] if "chaos" in analyses else [],
        "exponents": [("model_exponent_csv", study)] if "chaos" in analyses else [],
        "sweep": [("bifurcation", study)] if "bifurcation" in analyses else [],
        "figures": figures,
    }


def analysis_exponent(settings: Mapping, case: str) -> list[tuple[str, dict]]:
    """(file name, wildcards) of the model exponent a case's chaos analysis reads: its
    nominal run's (member 0) on the study's primary link model, for a study with `chaos`
    (whose members' exponents are computed); none otherwise."""
    if "chaos" not in settings["analyses"]:
        return []
    links = exponent_links(settings)[0]
    return [("model_exponent", {"case": case, "links": links, "member": 0})]


def has_clearance(settings: Mapping, case: str) -> bool:
    """Whether a case's overrides give some joint a clearance."""
    return any(
        key.endswith(".clearance") and float(value) > 0
        for key, value in case_overrides(settings, case).items()
    )


def study_files(name: str, settings: Mapping, crosscheck: bool) -> list[tuple[str, dict]]:
    """(file name, wildcards) of every final file of study `name`; `crosscheck`: whether
    the cross-check's case files are made (Exudyn importable). A clearance case under Exudyn's
    own contact law (`builtin_contact`) is compared impact by impact, without statistics."""
    cases = case_names(settings)
    out = []
    for analysis in settings["analyses"]:
        for case in cases:
            out += [(f, {"study": name, "case": case}) for f in CASE_TARGETS.get(analysis, ())]
        out += [(f, {"study": name}) for f in STUDY_TARGETS.get(analysis, ())]
    if "crosscheck" in settings["analyses"] and crosscheck:
        out += [("crosscheck_overlay", {"study": name, "case": case}) for case in cases]
        out += [
            ("crosscheck_statistics", {"study": name, "case": case})
            for case in cases
            if has_clearance(settings, case)
            and not exudyn_settings(settings, case).get("builtin_contact", False)
        ]
    return out


# ---------------------------------------------------------------- the landing page's inputs
class LandingInput(NamedTuple):
    """One named input of the landing page (sim.claims reads it as `<role>_<name>`): the
    file (workflow/rules/paths.smk) of the study that config `report.<role>` names, if
    that study lists `analysis` (None: any study); `cases` says whose: FIRST_CASE's, EVERY_CASE's
    (a list, in the study's order of cases) or the study's own (STUDY_FILE)."""

    role: str
    analysis: str | None
    name: str
    file: str
    cases: str


STUDY_FILE, FIRST_CASE, EVERY_CASE = "study", "first", "every"

#: every input of the landing page but the experiment's recording metadata, in input order:
#: the roles that share their inputs, then (analysis, name, file, cases) of each input;
#: sim.claims and sim.law_section judge the claims on these names
_LANDING_GROUPS = (
    (
        ("flagship", "all_joints"),
        (
            (None, "run", "run", FIRST_CASE),
            (None, "ideal", "ideal", FIRST_CASE),
            ("chaos", "analysis", "analysis", FIRST_CASE),
            ("chaos", "model_exponents", "model_exponent_csv", STUDY_FILE),
        ),
    ),
    (
        ("clearance_size", "speed"),
        (
            ("peaks", "peaks", "peaks_csv", STUDY_FILE),
            ("peaks", "revolutions", "revolutions", STUDY_FILE),
            ("chaos", "model_exponents", "model_exponent_csv", STUDY_FILE),
        ),
    ),
    (
        (
            "bifurcation_clearance",
            "bifurcation_speed",
            "bifurcation_clearance_memoryless",
            "lubrication_viscosity",
        ),
        (
            ("bifurcation", "table", "bifurcation_lyapunov_csv", STUDY_FILE),
            ("bifurcation", "dataset", "bifurcation", STUDY_FILE),
        ),
    ),
    (
        ("contact_laws", "lubrication"),
        (
            ("chaos", "analyses", "analysis", EVERY_CASE),
            ("chaos", "model_exponents", "model_exponent_csv", STUDY_FILE),
            ("peaks", "revolutions", "revolutions", STUDY_FILE),
        ),
    ),
    (("cross_check",), (("crosscheck", "summary", "crosscheck_summary", STUDY_FILE),)),
    (("experiment",), (("experiment", "comparison", "comparison_json", FIRST_CASE),)),
)
LANDING_INPUTS = tuple(
    LandingInput(role, *item)
    for roles, items in _LANDING_GROUPS
    for role in roles
    for item in items
)


def landing_inputs(
    config: Mapping, studies: Mapping[str, Mapping]
) -> list[tuple[str, str, dict | list[dict]]]:
    """(input name, file name, wildcards) of every landing input that the enabled
    `studies` (resolved settings) provide; the wildcards of an EVERY_CASE input are a list,
    one per case."""
    roles = config["report"]
    out = []
    for item in LANDING_INPUTS:
        name = roles.get(item.role)
        if name not in studies:
            continue
        settings = studies[name]
        if item.analysis is not None and item.analysis not in settings["analyses"]:
            continue
        cases = [{"study": name, "case": case} for case in case_names(settings)]
        wildcards = {STUDY_FILE: {"study": name}, FIRST_CASE: cases[0], EVERY_CASE: cases}
        out.append((f"{item.role}_{item.name}", item.file, wildcards[item.cases]))
    return out

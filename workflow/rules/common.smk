"""Helpers of the workflow: the resolved study settings and rule inputs.

Every study is a config entry (config/config.yaml); this file turns entries into file lists and
`sim` arguments. Rules call these functions by name (no lambdas inside rules). File names are
those of paths.smk (`PATHS`, `path`), included before this file.
"""

import functools
import importlib.util
import shlex
from pathlib import Path

from snakemake.utils import validate

from sim.scene import load_scene
from sim.studies.grid import sweep_grid

validate(config, schema="../schemas/config.schema.yaml")

QUICK = str(config.get("quick", False)).lower() == "true"
DEFAULTS = config["quick_defaults"] if QUICK else config["defaults"]
DURATION_KEYS = ("scene", "revolutions", "output_per_revolution", "transient")
STUDIES = [name for name, entry in config["studies"].items() if entry.get("enabled", True)]
# keys an ideal reference run does not take: it is all ideal and rigid (`--ideal --rigid`),
# and runs the scene's own integrator, DOPRI5, the better one for rigid links
IDEAL_IGNORED = (".clearance", ".kind", ".elements", "solver.method", "solver.rho_inf")


wildcard_constraints:
    study="[A-Za-z0-9_-]+",
    case="[A-Za-z0-9_.+-]+",
    member="[1-9][0-9]*",


def study(name):
    """The settings of study `name`: its entry, its `quick:` block on top when quick, and
    the defaults for what it does not set."""
    entry = config["studies"][name]
    settings = {key: value for key, value in entry.items() if key != "quick"}
    if QUICK:
        settings.update(entry.get("quick", {}))
    for key in DURATION_KEYS:
        settings.setdefault(key, DEFAULTS[key])
    # the study's ensemble keys on top of the defaults' (quick: on top of the study's)
    settings["ensemble"] = {
        **DEFAULTS.get("ensemble", {}),
        **entry.get("ensemble", {}),
        **(entry.get("quick", {}).get("ensemble", {}) if QUICK else {}),
    }
    return settings


def point_name(sweep, value):
    """File name of one sweep point, e.g. clearance-0.0005m or speed-120rpm."""
    return f"{sweep['label']}-{value:g}{sweep['unit']}"


def sweep_points(name):
    """(point name, value) of every point of a sweep study."""
    sweep = study(name)["sweep"]
    return [(point_name(sweep, value), value) for value in sweep_grid(sweep)]


def case_names(name):
    """The cases of a study: its `cases`, or the points of its sweep."""
    settings = study(name)
    if "sweep" in settings:
        return [point for point, _ in sweep_points(name)]
    return list(settings["cases"])


def has(name, analysis):
    return analysis in study(name)["analyses"]


def link_overrides():
    """Scene keys of the link model switch and its integrator (config `model`)."""
    model = config["model"]
    out = {f"solver.{key}": value for key, value in model.get("solver", {}).items()}
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


def case_overrides(name, case):
    """Every scene override of one case, in order of precedence (later wins): link model,
    duration, defaults, study, case (or sweep point)."""
    settings = study(name)
    out = dict(link_overrides())
    out["simulation.revolutions"] = settings["revolutions"]
    out["simulation.output_per_revolution"] = settings["output_per_revolution"]
    out.update(DEFAULTS.get("overrides", {}))
    out.update(settings.get("overrides", {}))
    if "sweep" in settings:
        value = dict(sweep_points(name))[case]
        out.update({key: value for key in settings["sweep"]["keys"]})
    else:
        out.update(settings["cases"][case])
    return out


def format_sets(overrides):
    return " ".join(f"--set {shlex.quote(f'{key}={value}')}" for key, value in overrides.items())


def run_sets(wildcards):
    """`--set` arguments of a case's run."""
    return format_sets(case_overrides(wildcards.study, wildcards.case))


def ideal_sets(wildcards):
    """`--set` arguments of a case's ideal reference run (clearance and link keys dropped:
    `--ideal --rigid` ignores them, so changing them does not rerun the reference)."""
    overrides = case_overrides(wildcards.study, wildcards.case)
    kept = {k: v for k, v in overrides.items() if not k.endswith(IDEAL_IGNORED)}
    return format_sets(kept)


def scene_name(wildcards):
    return study(wildcards.study)["scene"]


def transient(wildcards):
    return study(wildcards.study)["transient"]


def crank_rpm(wildcards):
    return case_overrides(wildcards.study, wildcards.case)["drive.speed_rpm"]


def run_timeout(wildcards):
    return study(wildcards.study).get("timeout_s", 120 if QUICK else 1800)


def extreme_checks(wildcards):
    return study(wildcards.study).get("checks", {})


# ---------------------------------------------------------------- files of a study (paths.smk)
def member_file(name, case, member):
    """Run of ensemble member `member` of a case: member 0 is the nominal run."""
    if int(member) == 0:
        return path("run", study=name, case=case)
    return path("member", study=name, case=case, member=member)


def ensemble_size(name):
    """Members per case: the study's ensemble if it has statistics on peaks, else 1."""
    return int(study(name)["ensemble"].get("members", 1)) if has(name, "peaks") else 1


def members_of_study(wildcards):
    """Every member's run of every case of a study, case by case."""
    name = wildcards.study
    return [
        member_file(name, case, k)
        for case in case_names(name)
        for k in range(ensemble_size(name))
    ]


def member_draw(wildcards):
    """Arguments of sim.ensemble.member for one member: index, base seed and, if the config
    states it, the perturbation's size (deg; else sim.ensemble's default)."""
    ensemble = study(wildcards.study)["ensemble"]
    draw = {"index": int(wildcards.member), "base_seed": int(ensemble.get("seed", 0))}
    if "size_deg" in ensemble:
        draw["size_deg"] = float(ensemble["size_deg"])
    return draw


def member_overrides(wildcards):
    """A further member's scene overrides as `key=value` texts (as `sim run --set` takes them):
    its case's, its length the ensemble's `revolutions` (transient included) where that is
    shorter than the case's."""
    name = wildcards.study
    overrides = case_overrides(name, wildcards.case)
    settings = study(name)
    length = settings["ensemble"].get("revolutions")
    if length is not None:
        if not length > settings["transient"]:
            raise ValueError(
                f"config: studies.{name}.ensemble.revolutions (or the defaults'): {length} must "
                f"exceed the study's transient, {settings['transient']} revolutions"
            )
        overrides["simulation.revolutions"] = min(overrides["simulation.revolutions"], length)
    return [f"{key}={value}" for key, value in overrides.items()]


def bootstrap_settings(wildcards=None):
    """The bootstrap of the statistics and verdicts (config `statistics`)."""
    return dict(config.get("statistics", {}))


def runs_of_study(wildcards):
    return paths_of_study("run", wildcards.study, case_names(wildcards.study))


def ideals_of_study(wildcards):
    return paths_of_study("ideal", wildcards.study, case_names(wildcards.study))


def analyses_of_study(wildcards):
    return paths_of_study("analysis", wildcards.study, case_names(wildcards.study))


def statuses_of_study(wildcards):
    return paths_of_study("status", wildcards.study, case_names(wildcards.study))


def ideal_reference_of_case(wildcards):
    """The ideal run a tolerant case is compared with: only for the study's
    `ideal_reference` case (clearance 0 must reproduce the ideal joint)."""
    if study(wildcards.study).get("ideal_reference") == wildcards.case:
        return [path("ideal", study=wildcards.study, case=wildcards.case)]
    return []


def sweep_values(wildcards):
    return [value for _, value in sweep_points(wildcards.study)]


def sweep_parameter(wildcards):
    return ",".join(study(wildcards.study)["sweep"]["keys"])


#: revolutions `sim analyze` needs after the transient (sim.analysis.run.MIN_REVOLUTIONS)
ANALYSIS_REVOLUTIONS = 25


def fidelity_long_cases(name):
    """Cases of a fidelity study long enough for the chaos analysis: they feed the
    long-horizon statistics (peaks, Lyapunov exponents, Poincaré distances)."""
    need = study(name)["transient"] + ANALYSIS_REVOLUTIONS
    return [
        case
        for case in case_names(name)
        if case_overrides(name, case)["simulation.revolutions"] >= need
    ]


def fidelity_analyses(wildcards):
    return paths_of_study("analysis", wildcards.study, fidelity_long_cases(wildcards.study))


def fidelity_settings(wildcards):
    """Reference cases, the long-horizon cases (in the order of `fidelity_analyses`),
    short-horizon window and transient of a fidelity study."""
    settings = study(wildcards.study)
    return {
        "reference": settings["reference"],
        "long_cases": fidelity_long_cases(wildcards.study),
        "window": settings.get("window", 2.0),
        "long_reference": settings.get("long_reference"),
        "transient": settings["transient"],
    }


# ---------------------------------------------------------------- cross-check (Exudyn)
#: the cross-check study's runs need Exudyn (pip install -e '.[crosscheck]'); without it the
#: study writes only its table, which says so
EXUDYN = importlib.util.find_spec("exudyn") is not None


def crosscheck_overrides(wildcards):
    """Scene overrides of a cross-check case (as a dict, for load_scene)."""
    return case_overrides(wildcards.study, wildcards.case)


def crosscheck_exudyn(wildcards):
    """Exudyn's integration settings of a cross-check case (sim.crosscheck.run.ExudynSettings)."""
    return study(wildcards.study)["crosscheck"].get("exudyn", {}).get(wildcards.case, {})


def crosscheck_lowpass(wildcards):
    return study(wildcards.study)["crosscheck"]["lowpass_hz"]


def crosscheck_has_clearance(name, case):
    """Whether a cross-check case has a clearance joint (its statistics figure is made)."""
    return any(
        key.endswith(".clearance") and float(value) > 0
        for key, value in case_overrides(name, case).items()
    )


def crosscheck_metrics(wildcards):
    """Metrics of every case of a cross-check study; none when Exudyn is not importable."""
    if not EXUDYN:
        return []
    return paths_of_study("crosscheck_metrics", wildcards.study, case_names(wildcards.study))


# ---------------------------------------------------------------- experiment data
def recording_file(wildcards):
    """The measured recording of the study if it exists, else the synthetic one."""
    measured = study(wildcards.study)["experiment"].get("recording")
    if measured and Path(measured).exists():
        return measured
    return path("synthetic_recording", study=wildcards.study)


def recording_meta(wildcards):
    """The metadata beside the recording (data/experiment/README.md: <name>.meta.yaml)."""
    csv = recording_file(wildcards)
    return csv[: -len(".csv")] + ".meta.yaml"


def synthetic_overrides(wildcards):
    """Scene overrides of the synthetic recording's higher-fidelity run: the study's first
    case with the `experiment.synthetic.overrides` on top."""
    overrides = case_overrides(wildcards.study, case_names(wildcards.study)[0])
    overrides.update(study(wildcards.study)["experiment"]["synthetic"].get("overrides", {}))
    return overrides


def synthetic_sets(wildcards):
    """`--set` arguments of the synthetic recording's run."""
    return format_sets(synthetic_overrides(wildcards))


def synthetic_seed(wildcards):
    return study(wildcards.study)["experiment"]["synthetic"]["seed"]


def sensor_option(wildcards):
    sensor = study(wildcards.study)["experiment"]["synthetic"].get("sensor")
    return f"--sensor {shlex.quote(sensor)}" if sensor else ""


# ---------------------------------------------------------------- targets
#: the final files of each analysis a study may list (config `analyses`), per case or per study
CASE_TARGETS = {
    "responses": ("responses",),
    "trajectories": ("trajectories",),
    "chaos": ("phase", "poincare", "lyapunov_csv", "lyapunov_html"),
    "experiment": ("comparison_json",),
}
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


def study_targets(name):
    """Every final file of one study."""
    cases = case_names(name)
    out = []
    for analysis in study(name)["analyses"]:
        for case in cases:
            out += [path(f, study=name, case=case) for f in CASE_TARGETS.get(analysis, ())]
        out += [path(f, study=name) for f in STUDY_TARGETS.get(analysis, ())]
    if has(name, "crosscheck") and EXUDYN:
        out += paths_of_study("crosscheck_overlay", name, cases)
        out += [
            path("crosscheck_statistics", study=name, case=case)
            for case in cases
            if crosscheck_has_clearance(name, case)
        ]
    return out


def all_targets():
    out = [target for name in STUDIES for target in study_targets(name)]
    return out + [PATHS["landing"], PATHS["claims"]]


def landing_inputs(wildcards):
    """Named inputs of the landing page: the results each claim of docs/studies.md is judged on,
    for the studies of config `report` that are enabled."""
    roles = config.get("report", {})
    out = {}

    def enabled(role):
        name = roles.get(role)
        return name if name in STUDIES else None

    for role in ("flagship", "all_joints"):
        name = enabled(role)
        if name:
            case = case_names(name)[0]
            out[f"{role}_run"] = path("run", study=name, case=case)
            out[f"{role}_ideal"] = path("ideal", study=name, case=case)
            if has(name, "chaos"):
                out[f"{role}_analysis"] = path("analysis", study=name, case=case)
                out[f"{role}_model_exponents"] = path("model_exponent_csv", study=name)
    for role in ("clearance_size", "speed"):
        name = enabled(role)
        if name and has(name, "peaks"):
            out[f"{role}_peaks"] = path("peaks_csv", study=name)
            out[f"{role}_revolutions"] = path("revolutions", study=name)
    for role in ("bifurcation_clearance", "bifurcation_speed"):
        name = enabled(role)
        if name and has(name, "bifurcation"):
            out[f"{role}_table"] = path("bifurcation_lyapunov_csv", study=name)
            out[f"{role}_dataset"] = path("bifurcation", study=name)
    name = enabled("cross_check")
    if name and has(name, "crosscheck"):
        out["cross_check_summary"] = path("crosscheck_summary", study=name)
    name = enabled("experiment")
    if name and has(name, "experiment"):
        case = case_names(name)[0]
        out["experiment_comparison"] = path("comparison_json", study=name, case=case)
        out["experiment_meta"] = landing_recording(wildcards)["meta"]
    return out


def landing_page():
    """The report's front page: the generated claims page once it exists."""
    return PATHS["landing"] if Path(PATHS["landing"]).exists() else "report/pending.rst"


def sweep_settings(wildcards):
    return study(wildcards.study)["sweep"]


def study_cases(wildcards):
    return case_names(wildcards.study)


def landing_recording(wildcards):
    """The recording the experiment study compares with, and its metadata file."""
    name = config.get("report", {}).get("experiment")
    if name not in STUDIES:
        return {}
    fake = type("Wildcards", (), {"study": name})()
    return {"csv": recording_file(fake), "meta": recording_meta(fake)}


# ---------------------------------------------------------------- sweep batches
def sweep_batches(name):
    """The points of a sweep study in batches of `sweep.batch` consecutive points."""
    points = sweep_points(name)
    size = int(study(name)["sweep"].get("batch", 1))
    return [points[k : k + size] for k in range(0, len(points), size)]


def batch_dirs_of_study(wildcards):
    """The folder of every batch of a sweep study (its run files and batch.nc)."""
    count = len(sweep_batches(wildcards.study))
    return [path("sweep_batch", study=wildcards.study, batch=k) for k in range(count)]


def batch_points(wildcards):
    """(point name, value) of the points of one batch."""
    return sweep_batches(wildcards.study)[int(wildcards.batch)]


def sweep_base_overrides(wildcards):
    """The scene overrides shared by every point of a sweep (`key=value` texts): a point's
    overrides without the swept keys, which the batch sets per point."""
    name = wildcards.study
    keys = study(name)["sweep"]["keys"]
    overrides = case_overrides(name, sweep_points(name)[0][0])
    return [f"{key}={value}" for key, value in overrides.items() if key not in keys]


# ---------------------------------------------------------------- model exponent over members
def model_lyapunov_settings(wildcards):
    """Duration (revolutions, transient) and, if set, solver tolerances of the model exponent
    of a chaos study's members: the study's `model_lyapunov` on top of the defaults' (quick:
    its `quick:` block's on top)."""
    entry = config["studies"][wildcards.study]
    settings = {
        **DEFAULTS["model_lyapunov"],
        **entry.get("model_lyapunov", {}),
        **(entry.get("quick", {}).get("model_lyapunov", {}) if QUICK else {}),
    }
    if not 0 <= settings["transient"] < settings["revolutions"]:
        raise ValueError(
            f"config: studies.{wildcards.study}.model_lyapunov (or the defaults'): transient = "
            f"{settings['transient']} must lie in [0, revolutions = {settings['revolutions']})"
        )
    return settings


def model_exponent_run(wildcards):
    """The run file of the member whose exponent is computed (member 0: the case's run)."""
    return member_file(wildcards.study, wildcards.case, wildcards.member)


def model_exponents_of_study(wildcards):
    """Every member's exponent file of every case of a study, case by case."""
    name = wildcards.study
    return [
        path("model_exponent", study=name, case=case, member=k)
        for case in case_names(name)
        for k in range(ensemble_size(name))
    ]


# ---------------------------------------------------------------- compiled kernels
@functools.cache
def scene_method(scene):
    """The integrator (`solver.method`) a scene names when no override sets it."""
    return load_scene(scene)["solver"]["method"]


def kernels(name, overrides):
    """The marker of rule compile_kernels for the integrator that a run of study `name` with
    these scene overrides uses. Its age does not count (`ancient`): it only makes that
    integrator's kernels compile once, before its first run."""
    method = overrides.get("solver.method", scene_method(study(name)["scene"]))
    return ancient(path("kernels", method=method))


def case_kernels(wildcards):
    """The compiled kernels a case's run (and its members) uses."""
    return kernels(wildcards.study, case_overrides(wildcards.study, wildcards.case))


def ideal_kernels(wildcards):
    """An ideal reference runs the scene's own integrator (IDEAL_IGNORED)."""
    return kernels(wildcards.study, {})


def sweep_kernels(wildcards):
    """A sweep's points share their integrator: its first point's."""
    first = sweep_points(wildcards.study)[0][0]
    return kernels(wildcards.study, case_overrides(wildcards.study, first))


def synthetic_kernels(wildcards):
    """The compiled kernels of the synthetic recording's run."""
    return kernels(wildcards.study, synthetic_overrides(wildcards))


def model_exponent_kernels(wildcards):
    """The member's own integrator, or DOPRI5 for the rigid-link exponent
    (workflow/scripts/model_exponent.py)."""
    if model_lyapunov_settings(wildcards).get("links", "run") == "rigid":
        return kernels(wildcards.study, {"solver.method": "dopri5"})
    return case_kernels(wildcards)

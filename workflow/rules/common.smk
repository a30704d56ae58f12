"""Wildcard adapters: the rules' inputs and params from the resolved study settings.

Every study is a config entry (config/config.yaml, config/README.md); sim.studies.config
resolves them once (precedence, quick merge, case grids) and checks every planned scene.
Rules call these functions by name (no lambdas inside rules). File names are those of
paths.smk (`PATHS`, `path`), included before this file.
"""

import functools
import importlib.util
import shlex
from pathlib import Path

from snakemake.utils import validate

from sim.scene import load_scene
from sim.studies import config as resolver

validate(config, schema="../schemas/config.schema.yaml", set_default=True)

QUICK = resolver.is_quick(config)
DEFAULTS = resolver.defaults(config)
SETTINGS = resolver.resolve(config)
STUDIES = list(SETTINGS)
resolver.check_scenes(SETTINGS)


wildcard_constraints:
    study="[A-Za-z0-9_-]+",
    case="[A-Za-z0-9_.+-]+",
    member="[1-9][0-9]*",


def setting(key):
    """An adapter giving the study's resolved setting `key`."""
    return lambda wildcards: SETTINGS[wildcards.study][key]


def files_of_cases(file):
    """An adapter giving the file `file` (paths.smk) of every case of the study."""
    return lambda wildcards: paths_of_study(file, wildcards.study, case_names(wildcards.study))


scene_name = setting("scene")
transient = setting("transient")
run_timeout = setting("timeout_s")
sweep_settings = setting("sweep")
model_lyapunov_settings = setting("model_lyapunov")
runs_of_study = files_of_cases("run")
ideals_of_study = files_of_cases("ideal")
statuses_of_study = files_of_cases("status")


def extreme_checks(wildcards):
    return SETTINGS[wildcards.study].get("checks", {})


def case_names(name):
    return resolver.case_names(SETTINGS[name])


def has(name, analysis):
    return analysis in SETTINGS[name]["analyses"]


def case_overrides(name, case):
    return resolver.case_overrides(SETTINGS[name], case)


def format_sets(overrides):
    return " ".join(f"--set {shlex.quote(f'{key}={value}')}" for key, value in overrides.items())


def as_texts(overrides):
    """Overrides as `key=value` texts, as `sim run --set` takes them."""
    return [f"{key}={value}" for key, value in overrides.items()]


def run_sets(wildcards):
    return format_sets(case_overrides(wildcards.study, wildcards.case))


def ideal_sets(wildcards):
    return format_sets(resolver.ideal_overrides(SETTINGS[wildcards.study], wildcards.case))


def crank_rpm(wildcards):
    return case_overrides(wildcards.study, wildcards.case)["drive.speed_rpm"]


def study_cases(wildcards):
    return case_names(wildcards.study)


def bootstrap_settings(wildcards=None):
    return config["statistics"]


# ---------------------------------------------------------------- runs and ensemble members
def member_file(name, case, member):
    """Run of ensemble member `member` of a case: member 0 is the nominal run."""
    if int(member) == 0:
        return path("run", study=name, case=case)
    return path("member", study=name, case=case, member=member)


def ensemble_size(name):
    return resolver.ensemble_size(SETTINGS[name])


def members_of_study(wildcards):
    name = wildcards.study
    k_all = range(ensemble_size(name))
    return [member_file(name, case, k) for case in case_names(name) for k in k_all]


def member_draw(wildcards):
    return resolver.member_draw(SETTINGS[wildcards.study], wildcards.member)


def member_overrides(wildcards):
    return as_texts(resolver.member_overrides(SETTINGS[wildcards.study], wildcards.case))


def ideal_reference_of_case(wildcards):
    """The ideal run a tolerant case is compared with: only for the study's
    `ideal_reference` case (clearance 0 must reproduce the ideal joint)."""
    if SETTINGS[wildcards.study].get("ideal_reference") == wildcards.case:
        return [path("ideal", study=wildcards.study, case=wildcards.case)]
    return []


# ---------------------------------------------------------------- sweeps


def sweep_parameter(wildcards):
    return ",".join(SETTINGS[wildcards.study]["sweep"]["keys"])


def batch_dirs_of_study(wildcards):
    count = len(resolver.sweep_batches(SETTINGS[wildcards.study]))
    return [path("sweep_batch", study=wildcards.study, batch=k) for k in range(count)]


def batch_points(wildcards):
    return resolver.sweep_batches(SETTINGS[wildcards.study])[int(wildcards.batch)]


def sweep_base_overrides(wildcards):
    return as_texts(resolver.sweep_base_overrides(SETTINGS[wildcards.study]))


# ---------------------------------------------------------------- fidelity
def fidelity_analyses(wildcards):
    cases = resolver.fidelity_long_cases(SETTINGS[wildcards.study])
    return paths_of_study("analysis", wildcards.study, cases)


def fidelity_settings(wildcards):
    return resolver.fidelity_settings(SETTINGS[wildcards.study])


# ---------------------------------------------------------------- model exponent over members


def model_exponent_run(wildcards):
    return member_file(wildcards.study, wildcards.case, wildcards.member)


def exponent_links(wildcards):
    return resolver.exponent_links(SETTINGS[wildcards.study])


def model_exponents_of_study(wildcards):
    """Every member's exponent file, case by case, then link model by link model."""
    name = wildcards.study
    return [
        path("model_exponent", study=name, case=case, links=links, member=k)
        for case in case_names(name)
        for links in exponent_links(wildcards)
        for k in range(ensemble_size(name))
    ]


# ---------------------------------------------------------------- cross-check (Exudyn)
#: the cross-check study's runs need Exudyn (pip install -e '.[crosscheck]'); without it the
#: study writes only its table, which says so
EXUDYN = importlib.util.find_spec("exudyn") is not None


def crosscheck_overrides(wildcards):
    return case_overrides(wildcards.study, wildcards.case)


def crosscheck_exudyn(wildcards):
    return SETTINGS[wildcards.study]["crosscheck"]["exudyn"].get(wildcards.case, {})


def crosscheck_lowpass(wildcards):
    return SETTINGS[wildcards.study]["crosscheck"]["lowpass_hz"]


def crosscheck_metrics(wildcards):
    """Metrics of every case of a cross-check study; none when Exudyn is not importable."""
    if not EXUDYN:
        return []
    return paths_of_study("crosscheck_metrics", wildcards.study, case_names(wildcards.study))


# ---------------------------------------------------------------- experiment data
def recording_file(wildcards):
    """The measured recording of the study if it exists, else the synthetic one."""
    measured = SETTINGS[wildcards.study]["experiment"].get("recording")
    if measured and Path(measured).exists():
        return measured
    return path("synthetic_recording", study=wildcards.study)


def recording_meta(wildcards):
    """The metadata beside the recording (data/experiment/README.md: <name>.meta.yaml)."""
    return recording_file(wildcards)[: -len(".csv")] + ".meta.yaml"


def synthetic_overrides(wildcards):
    return resolver.synthetic_overrides(SETTINGS[wildcards.study])


def synthetic_sets(wildcards):
    return format_sets(synthetic_overrides(wildcards))


def synthetic_seed(wildcards):
    return SETTINGS[wildcards.study]["experiment"]["synthetic"]["seed"]


def sensor_option(wildcards):
    sensor = SETTINGS[wildcards.study]["experiment"]["synthetic"].get("sensor")
    return f"--sensor {shlex.quote(sensor)}" if sensor else ""


# ---------------------------------------------------------------- targets
def study_targets(name):
    """Every final file of one study (sim.studies.config.study_files)."""
    files = resolver.study_files(name, SETTINGS[name], crosscheck=EXUDYN)
    return [path(file, **wildcards) for file, wildcards in files]


def study_done_targets(wildcards):
    """Rule study: every final file of the study `wildcards.study`."""
    return study_targets(wildcards.study)


def all_targets():
    out = [target for name in STUDIES for target in study_targets(name)]
    return out + [PATHS["landing"], PATHS["claims"]]


def landing_inputs(wildcards):
    """Named inputs of the landing page (sim.studies.config.LANDING_INPUTS) and the
    experiment's recording metadata."""
    out = {
        key: path(file, **names) for key, file, names in resolver.landing_inputs(config, SETTINGS)
    }
    if "experiment_comparison" in out:
        out["experiment_meta"] = landing_recording(wildcards)["meta"]
    return out


def landing_page():
    """The report's front page: the generated claims page once it exists."""
    return PATHS["landing"] if Path(PATHS["landing"]).exists() else "report/pending.rst"


def landing_recording(wildcards):
    """The recording the experiment study compares with, and its metadata file."""
    name = config["report"].get("experiment")
    if name not in STUDIES:
        return {}
    fake = type("Wildcards", (), {"study": name})()
    return {"csv": recording_file(fake), "meta": recording_meta(fake)}


# ---------------------------------------------------------------- compiled kernels
@functools.cache
def scene_method(scene):
    """The integrator (`solver.method`) a scene names when no override sets it."""
    return load_scene(scene)["solver"]["method"]


def kernels(name, overrides):
    """The marker of rule compile_kernels for the integrator that a run of study `name` with
    these scene overrides uses. Its age does not count (`ancient`): it only makes that
    integrator's kernels compile once, before its first run."""
    method = overrides.get("solver.method", scene_method(SETTINGS[name]["scene"]))
    return ancient(path("kernels", method=method))


def case_kernels(wildcards):
    return kernels(wildcards.study, case_overrides(wildcards.study, wildcards.case))


def ideal_kernels(wildcards):
    """An ideal reference runs the scene's own integrator (resolver.IDEAL_IGNORED)."""
    return kernels(wildcards.study, {})


def sweep_kernels(wildcards):
    """A sweep's points share their integrator: its first point's."""
    settings = SETTINGS[wildcards.study]
    first = resolver.sweep_points(settings)[0][0]
    return kernels(wildcards.study, resolver.case_overrides(settings, first))


def synthetic_kernels(wildcards):
    return kernels(wildcards.study, synthetic_overrides(wildcards))


def model_exponent_kernels(wildcards):
    """The member's own integrator, or DOPRI5 for the exponent on rigid or modal links
    (workflow/scripts/model_exponent.py)."""
    if wildcards.links == "run":
        return case_kernels(wildcards)
    return kernels(wildcards.study, {"solver.method": "dopri5"})

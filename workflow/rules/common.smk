"""Wildcard adapters: the rules' inputs and params from the resolved study settings.

Every study is a config entry (config/config.yaml, config/README.md); sim.studies.config
resolves them once (precedence, quick merge, case grids) and checks every planned scene.
Rules call these functions by name (no lambdas inside rules). File names are those of
paths.smk (`PATHS`, `path`), included before this file.
"""

import importlib.util
import shlex
from functools import reduce
from operator import getitem
from pathlib import Path

from snakemake.utils import validate

from sim.studies import config as resolver

validate(config, schema="../schemas/config.schema.yaml", set_default=True)

QUICK = resolver.is_quick(config)
DEFAULTS = resolver.defaults(config)
SETTINGS = resolver.resolve(config)
STUDIES = list(SETTINGS)
resolver.check_scenes(SETTINGS)
#: the cross-check study's runs need Exudyn (pip install -e '.[crosscheck]'); without it the
#: study writes only its table, which says so
EXUDYN = importlib.util.find_spec("exudyn") is not None


wildcard_constraints:
    study="[A-Za-z0-9_-]+",
    case="[A-Za-z0-9_.+-]+",
    member="[1-9][0-9]*",


def setting(*keys):
    """An adapter giving the study's resolved setting at the nested `keys`."""
    return lambda wildcards: reduce(getitem, keys, SETTINGS[wildcards.study])


def resolved(function, *names):
    """An adapter giving resolver `function` of the study's settings and the wildcards
    `names` (e.g. resolved(resolver.member_draw, "member"))."""
    return lambda wildcards: function(
        SETTINGS[wildcards.study], *(getattr(wildcards, name) for name in names)
    )


def files_of_cases(file):
    """An adapter giving the file `file` (paths.smk) of every case of the study."""
    return lambda wildcards: paths_of_study(file, wildcards.study, case_names(wildcards.study))


def as_texts(function, *names):
    """An adapter giving the overrides of resolver `function` (as `resolved`) as `key=value`
    texts, as `sim run --set` takes them."""
    overrides = resolved(function, *names)
    return lambda wildcards: [f"{key}={value}" for key, value in overrides(wildcards).items()]


def as_sets(function, *names):
    """An adapter giving the overrides of resolver `function` as `sim` command-line options."""
    texts = as_texts(function, *names)
    return lambda wildcards: " ".join(f"--set {shlex.quote(text)}" for text in texts(wildcards))


def case_names(name):
    return resolver.case_names(SETTINGS[name])


def ensemble_size(name):
    return resolver.ensemble_size(SETTINGS[name])


scene_name = setting("scene")
transient = setting("transient")
run_timeout = setting("timeout_s")
sweep_settings = setting("sweep")
model_lyapunov_settings = setting("model_lyapunov")
crosscheck_lowpass = setting("crosscheck", "lowpass_hz")
synthetic_seed = setting("experiment", "synthetic", "seed")
study_cases = resolved(resolver.case_names)
runs_of_study = files_of_cases("run")
ideals_of_study = files_of_cases("ideal")
statuses_of_study = files_of_cases("status")
case_overrides = resolved(resolver.case_overrides, "case")
run_sets = as_sets(resolver.case_overrides, "case")
ideal_sets = as_sets(resolver.ideal_overrides, "case")
member_draw = resolved(resolver.member_draw, "member")
sweep_base_overrides = as_texts(resolver.sweep_base_overrides)
member_overrides = as_texts(resolver.member_overrides, "case")
fidelity_settings = resolved(resolver.fidelity_settings)
exponent_links = resolved(resolver.exponent_links)
synthetic_overrides = resolved(resolver.synthetic_overrides)
synthetic_sets = as_sets(resolver.synthetic_overrides)


def extreme_checks(wildcards):
    return SETTINGS[wildcards.study].get("checks", {})


def crank_rpm(wildcards):
    return case_overrides(wildcards)["drive.speed_rpm"]


def bootstrap_settings(wildcards=None):
    return config["statistics"]


# ---------------------------------------------------------------- runs and ensemble members
def member_file(name, case, member):
    """Run of ensemble member `member` of a case: member 0 is the nominal run."""
    if int(member) == 0:
        return path("run", study=name, case=case)
    return path("member", study=name, case=case, member=member)


def members_of_study(wildcards):
    name = wildcards.study
    k_all = range(ensemble_size(name))
    return [member_file(name, case, k) for case in case_names(name) for k in k_all]


def ideal_reference_of_case(wildcards):
    """The ideal run a tolerant case is compared with: only for the study's
    `ideal_reference` case (clearance 0 must reproduce the ideal joint)."""
    if SETTINGS[wildcards.study].get("ideal_reference") == wildcards.case:
        return [path("ideal", study=wildcards.study, case=wildcards.case)]
    return []


# ---------------------------------------------------------------- sweeps, fidelity, exponents
def sweep_parameter(wildcards):
    return ",".join(SETTINGS[wildcards.study]["sweep"]["keys"])


def batch_dirs_of_study(wildcards):
    count = len(resolver.sweep_batches(SETTINGS[wildcards.study]))
    return [path("sweep_batch", study=wildcards.study, batch=k) for k in range(count)]


def batch_points(wildcards):
    return resolver.sweep_batches(SETTINGS[wildcards.study])[int(wildcards.batch)]


def fidelity_analyses(wildcards):
    cases = resolver.fidelity_long_cases(SETTINGS[wildcards.study])
    return paths_of_study("analysis", wildcards.study, cases)


def model_exponent_run(wildcards):
    return member_file(wildcards.study, wildcards.case, wildcards.member)


def model_exponents_of_study(wildcards):
    """Every member's exponent file, case by case, then link model by link model."""
    name = wildcards.study
    return [
        path("model_exponent", study=name, case=case, links=links, member=k)
        for case in case_names(name)
        for links in exponent_links(wildcards)
        for k in range(ensemble_size(name))
    ]


# ---------------------------------------------------------------- cross-check and experiment
def crosscheck_exudyn(wildcards):
    return SETTINGS[wildcards.study]["crosscheck"]["exudyn"].get(wildcards.case, {})


def crosscheck_metrics(wildcards):
    """Metrics of every case of a cross-check study; none when Exudyn is not importable."""
    if not EXUDYN:
        return []
    return paths_of_study("crosscheck_metrics", wildcards.study, case_names(wildcards.study))


def recording_file(wildcards):
    """The measured recording of the study if it exists, else the synthetic one."""
    measured = SETTINGS[wildcards.study]["experiment"].get("recording")
    if measured and Path(measured).exists():
        return measured
    return path("synthetic_recording", study=wildcards.study)


def recording_meta(wildcards):
    """The metadata beside the recording (data/experiment/README.md: <name>.meta.yaml)."""
    return recording_file(wildcards)[: -len(".csv")] + ".meta.yaml"


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
def kernels(method):
    """The marker of rule compile_kernels for integrator `method`. Its age does not count
    (`ancient`): it only makes that integrator's kernels compile once, before its first run."""
    return ancient(path("kernels", method=method))


def case_kernels(wildcards):
    return kernels(resolver.case_method(SETTINGS[wildcards.study], wildcards.case))


def ideal_kernels(wildcards):
    """An ideal reference runs the scene's own integrator (resolver.IDEAL_IGNORED)."""
    return kernels(resolver.scene_method(SETTINGS[wildcards.study]["scene"]))


def sweep_kernels(wildcards):
    return kernels(resolver.sweep_method(SETTINGS[wildcards.study]))


def synthetic_kernels(wildcards):
    return kernels(resolver.run_method(SETTINGS[wildcards.study], synthetic_overrides(wildcards)))


def model_exponent_kernels(wildcards):
    links = wildcards.links
    return kernels(resolver.exponent_method(SETTINGS[wildcards.study], wildcards.case, links))

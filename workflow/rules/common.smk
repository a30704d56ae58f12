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


def files(function, *names):
    """An adapter giving the paths of the (file name, wildcards) pairs that resolver
    `function` (as `resolved`) lists for the study."""
    pairs = resolved(function, *names)
    return lambda wildcards: [
        path(file, study=wildcards.study, **more) for file, more in pairs(wildcards)
    ]


def files_of_cases(file, cases=resolver.case_names):
    """An adapter giving the file `file` (paths.smk) of every case of the study (or of the
    resolver's `cases` of it)."""
    return lambda wildcards: paths_of_study(file, wildcards.study, cases(SETTINGS[wildcards.study]))


def as_texts(function, *names):
    """An adapter giving the overrides of resolver `function` (as `resolved`) as `key=value`
    texts, as `sim run --set` takes them."""
    overrides = resolved(function, *names)
    return lambda wildcards: resolver.override_texts(overrides(wildcards))


def as_sets(function, *names):
    """An adapter giving the overrides of resolver `function` as `sim` command-line options."""
    texts = as_texts(function, *names)
    return lambda wildcards: " ".join(f"--set {shlex.quote(text)}" for text in texts(wildcards))


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
members_of_study = files(resolver.member_files)
model_exponents_of_study = files(resolver.exponent_files)
analysis_exponent = files(resolver.analysis_exponent, "case")
sweep_base_overrides = as_texts(resolver.sweep_base_overrides)
member_overrides = as_texts(resolver.member_overrides, "case")
fidelity_settings = resolved(resolver.fidelity_settings)
exponent_links = resolved(resolver.exponent_links)
synthetic_overrides = resolved(resolver.synthetic_overrides)
synthetic_sets = as_sets(resolver.synthetic_overrides)
extreme_checks = resolved(resolver.extreme_checks)
crank_rpm = resolved(resolver.crank_rpm, "case")
ideal_reference_of_case = files(resolver.ideal_reference, "case")
sweep_parameter = resolved(resolver.sweep_parameter)
batch_points = resolved(resolver.sweep_batch, "batch")
batch_dirs_of_study = files(resolver.batch_files)
fidelity_analyses = files_of_cases("analysis", resolver.fidelity_long_cases)
crosscheck_exudyn = resolved(resolver.exudyn_settings, "case")


def exponent_option(wildcards):
    """`sim analyze --model-exponent FILE` when the case has a model exponent, else nothing."""
    exponent = analysis_exponent(wildcards)
    return f"--model-exponent {shlex.quote(exponent[0])}" if exponent else ""


def bootstrap_settings(wildcards=None):
    return config["statistics"]


def model_exponent_run(wildcards):
    """The member's run, whose exponent model_exponent takes."""
    file, more = resolver.member_file(wildcards.case, wildcards.member)
    return path(file, study=wildcards.study, **more)


# ---------------------------------------------------------------- cross-check and experiment
def crosscheck_metrics(wildcards):
    """Metrics of every case of a cross-check study; none when Exudyn is not importable."""
    return files_of_cases("crosscheck_metrics")(wildcards) if EXUDYN else []


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
    sensor = resolver.synthetic_sensor(SETTINGS[wildcards.study])
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
    sections = paths_of_studies("study_section", STUDIES)
    return out + sections + [PATHS["landing"], PATHS["claims"]]


def section_inputs(wildcards):
    """Named inputs of a study's section (sim.studies.config.section_files)."""
    files = resolver.section_files(wildcards.study, SETTINGS[wildcards.study])
    return {key: [path(file, **more) for file, more in items] for key, items in files.items()}


def study_settings(wildcards):
    """The resolved settings of the study (sim.studies.config)."""
    return SETTINGS[wildcards.study]


def landing_inputs(wildcards):
    """Named inputs of the landing page (sim.studies.config.LANDING_INPUTS) and the
    experiment's recording metadata."""
    out = {
        key: (
            [path(file, **case) for case in names]
            if isinstance(names, list)
            else path(file, **names)
        )
        for key, file, names in resolver.landing_inputs(config, SETTINGS)
    }
    if "experiment_comparison" in out:
        out["experiment_meta"] = landing_recording(wildcards)["meta"]
    return out


def landing_contacts(wildcards):
    """The contact law and oiled joints of each case the landing page's sections read."""
    return resolver.landing_contacts(config, SETTINGS)


def landing_recording(wildcards):
    """The recording the experiment study compares with, and its metadata file."""
    name = config["report"].get("experiment")
    if name not in STUDIES:
        return {}
    fake = type("Wildcards", (), {"study": name})()
    return {"csv": recording_file(fake), "meta": recording_meta(fake)}


# ---------------------------------------------------------------- compiled kernels
def kernels_of(function, *names):
    """An adapter giving the marker of rule compile_kernels for the integrator that resolver
    `function` (as `resolved`) names. The marker's age does not count (`ancient`): it only
    makes that integrator's kernels compile once, before its first run."""
    method = resolved(function, *names)
    return lambda wildcards: ancient(path("kernels", method=method(wildcards)))


case_kernels = kernels_of(resolver.case_method, "case")
ideal_kernels = kernels_of(resolver.ideal_method)
sweep_kernels = kernels_of(resolver.sweep_method)
synthetic_kernels = kernels_of(resolver.synthetic_method)
model_exponent_kernels = kernels_of(resolver.exponent_method, "case", "links")

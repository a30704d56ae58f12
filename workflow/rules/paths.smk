"""Every file the workflow writes, named once.

`PATHS` maps a name to its pattern, with Snakemake's wildcards {study}, {case}, {member}, ...:
rules give the pattern itself (`output: PATHS["run"]`), helpers fill it in with `path(name,
study=..., case=...)`, and scripts receive the files through `snakemake.input` and
`snakemake.output`, never a literal. `JOBS` names each rule's log (logs/<stem>.log) and
benchmark (results/benchmarks/<stem>.tsv).
"""

RESULTS = "results"
STUDY = f"{RESULTS}/{{study}}"

PATHS = {
    # stage 0: each integrator's kernels compiled once (simulate.smk); deleted after the run
    "kernels": f"{RESULTS}/kernels/{{method}}.txt",
    # stage 1: runs (workflow/rules/simulate.smk)
    "run": f"{STUDY}/run/{{case}}.nc",
    "member": f"{STUDY}/run/{{case}}/member-{{member}}.nc",
    "ideal": f"{STUDY}/ideal/{{case}}.nc",
    "status": f"{STUDY}/status/{{case}}.json",
    # stage 2: chaos analysis (analyze.smk)
    "analysis": f"{STUDY}/analysis/{{case}}.nc",
    # the model-based exponent of every member (member 0 included: the nominal run) on each
    # link model the study's model_lyapunov names ({links}: run, rigid or modal)
    "model_exponent": f"{STUDY}/model-exponent/{{case}}/{{links}}/member-{{member}}.nc",
    # stage 3: sweeps (sweep.smk): a batch folder holds its points' run files and batch.nc
    "sweep_batch": f"{STUDY}/sweep/batch-{{batch}}",
    "bifurcation": f"{STUDY}/bifurcation.nc",
    # stage 4: experiment (experiment.smk)
    "synthetic_recording": f"{STUDY}/recording/synthetic.csv",
    "synthetic_meta": f"{STUDY}/recording/synthetic.meta.yaml",
    "comparison_json": f"{STUDY}/comparison/{{case}}/comparison.json",
    "comparison_netcdf": f"{STUDY}/comparison/{{case}}/comparison.nc",
    "comparison_overlay": f"{STUDY}/comparison/{{case}}/overlay.png",
    "comparison_spectra": f"{STUDY}/comparison/{{case}}/spectra.png",
    # cross-check (crosscheck.smk)
    "crosscheck_sim": f"{STUDY}/crosscheck/{{case}}/sim.nc",
    "crosscheck_exudyn": f"{STUDY}/crosscheck/{{case}}/exudyn.nc",
    "crosscheck_metrics": f"{STUDY}/crosscheck/{{case}}/metrics.json",
    "crosscheck_overlay": f"{STUDY}/crosscheck/{{case}}/overlay.png",
    "crosscheck_statistics": f"{STUDY}/crosscheck/{{case}}/statistics.png",
    "crosscheck_csv": f"{STUDY}/tables/crosscheck.csv",
    "crosscheck_html": f"{STUDY}/tables/crosscheck.html",
    "crosscheck_summary": f"{STUDY}/tables/crosscheck.json",
    # stage 5: figures and tables (figures.smk)
    "responses": f"{STUDY}/figures/responses_{{case}}.png",
    "trajectories": f"{STUDY}/figures/trajectories_{{case}}.png",
    "phase": f"{STUDY}/figures/phase_{{case}}.png",
    "poincare": f"{STUDY}/figures/poincare_{{case}}.png",
    "lyapunov_csv": f"{STUDY}/tables/lyapunov_{{case}}.csv",
    "lyapunov_html": f"{STUDY}/tables/lyapunov_{{case}}.html",
    "peaks_csv": f"{STUDY}/tables/peaks.csv",
    "peaks_html": f"{STUDY}/tables/peaks.html",
    "revolutions": f"{STUDY}/tables/revolutions.csv",
    "revolution_statistics_csv": f"{STUDY}/tables/revolution_statistics.csv",
    "revolution_statistics_html": f"{STUDY}/tables/revolution_statistics.html",
    "bifurcation_lyapunov_csv": f"{STUDY}/tables/bifurcation_lyapunov.csv",
    "bifurcation_lyapunov_html": f"{STUDY}/tables/bifurcation_lyapunov.html",
    "bifurcation_figure": f"{STUDY}/figures/bifurcation.png",
    "work_precision_csv": f"{STUDY}/tables/work_precision.csv",
    "work_precision_html": f"{STUDY}/tables/work_precision.html",
    "work_precision_figure": f"{STUDY}/figures/work_precision.png",
    "extremes_csv": f"{STUDY}/tables/extremes.csv",
    "extremes_html": f"{STUDY}/tables/extremes.html",
    "model_exponent_csv": f"{STUDY}/tables/model_exponent.csv",
    "model_exponent_html": f"{STUDY}/tables/model_exponent.html",
    # stage 6: report (report.smk); a study's target, every final file of the study built
    "study_done": f"{STUDY}/done",
    # a study's section of the report's front page (report/front.rst includes it)
    "study_section": f"{STUDY}/report/section.rst",
    # the paper's section of the front page: its claims judged, with their figures
    "landing": f"{RESULTS}/report/landing.rst",
    "claims": f"{RESULTS}/report/claims.csv",
}

JOBS = {
    "compile_kernels": "kernels/{method}",
    "run": "{study}/run/{case}",
    "run_member": "{study}/run/{case}/member-{member}",
    "run_ideal": "{study}/ideal/{case}",
    "run_tolerant": "{study}/status/{case}",
    "analyze": "{study}/analysis/{case}",
    "model_exponent": "{study}/model-exponent/{case}/{links}/member-{member}",
    "sweep_batch": "{study}/sweep/batch-{batch}",
    "combine_sweep": "{study}/bifurcation",
    "synthesize_recording": "{study}/recording/synthetic",
    "compare_experiment": "{study}/comparison/{case}",
    "crosscheck_case": "{study}/crosscheck/{case}",
    "crosscheck_statistics": "{study}/crosscheck/{case}_statistics",
    "crosscheck_table": "{study}/tables/crosscheck",
    "responses": "{study}/figures/responses_{case}",
    "trajectories": "{study}/figures/trajectories_{case}",
    "phase": "{study}/figures/phase_{case}",
    "poincare": "{study}/figures/poincare_{case}",
    "lyapunov_table": "{study}/tables/lyapunov_{case}",
    "peaks_table": "{study}/tables/peaks",
    "revolution_table": "{study}/tables/revolutions",
    "bifurcation_table": "{study}/tables/bifurcation_lyapunov",
    "bifurcation_figure": "{study}/figures/bifurcation",
    "work_precision": "{study}/tables/work_precision",
    "extremes_table": "{study}/tables/extremes",
    "model_exponent_table": "{study}/tables/model_exponent",
    "landing": "report/landing",
    "study_section": "{study}/report/section",
    "study": "{study}/done",
}


def path(name, **wildcards):
    """The file `name` of PATHS with its wildcards filled in, e.g. path("run", study="speed",
    case="speed-30rpm")."""
    return PATHS[name].format(**wildcards)


def log_file(job):
    """Log pattern of the rule `job`."""
    return f"logs/{JOBS[job]}.log"


def benchmark_file(job):
    """Benchmark pattern of the rule `job`."""
    return f"{RESULTS}/benchmarks/{JOBS[job]}.tsv"


def paths_of_studies(name, studies):
    """The file `name` of every study of `studies`."""
    return [path(name, study=study) for study in studies]


def paths_of_study(name, study_name, cases):
    """The file `name` for every case of a study."""
    return [path(name, study=study_name, case=case) for case in cases]

# Stage 6: the report's landing page. It judges each claim of docs/studies.md on our results and
# states the assumed geometry and values and which accelerometer data was used. It is the
# report's front page (Snakefile `report:`); `snakemake --report report.html` renders it.


localrules:
    landing,
    study,


# One study's target: `snakemake -j2 results/<study>/done` builds every final file of the study
# (config/README.md).
rule study:
    input:
        study_done_targets,
    output:
        touch(PATHS["study_done"]),
    log:
        log_file("study"),


rule landing:
    input:
        unpack(landing_inputs),
        template="report/landing.rst.jinja",
    output:
        rst=PATHS["landing"],
        csv=report(
            PATHS["claims"],
            caption="../report/claims.rst",
            category="0 claims",
        ),
    log:
        log_file("landing"),
    benchmark:
        benchmark_file("landing")
    conda:
        "../envs/sim.yaml"
    params:
        quick=QUICK,
        studies=STUDIES,
        model=config["model"],
        recording=landing_recording,
        statistics=bootstrap_settings,
        ensemble=DEFAULTS.get("ensemble", {}),
    script:
        "../scripts/landing.py"

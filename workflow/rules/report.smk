# Stage 6: the report's front page (report/front.rst, the Snakefile's `report:`), which
# `snakemake --report report.html` renders from the sections of the studies in the report: each
# study's own section, and the paper's (its claims judged on our results, the assumed geometry
# and values, the accelerometer data used) when the paper's studies ran.


localrules:
    landing,
    study_section,
    study,


# One study's target: `snakemake -j2 results/<study>/done` builds every final file of the study
# and its section of the front page (config/README.md).
rule study:
    input:
        study_done_targets,
        section=PATHS["study_section"],
    output:
        touch(PATHS["study_done"]),
    log:
        log_file("study"),


rule study_section:
    input:
        unpack(section_inputs),
    output:
        PATHS["study_section"],
    log:
        log_file("study_section"),
    benchmark:
        benchmark_file("study_section")
    conda:
        "../envs/sim.yaml"
    params:
        settings=study_settings,
    script:
        "../scripts/study_section.py"


rule landing:
    input:
        unpack(landing_inputs),
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
        recording=landing_recording,
        contacts=landing_contacts,
        statistics=bootstrap_settings,
        ensemble=DEFAULTS.get("ensemble", {}),
    script:
        "../scripts/landing.py"

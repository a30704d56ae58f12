# The cross-check study: every case run by sim and by Exudyn in one job (their wall
# times compare), the agreement measured, and a summary table saying whether it ran. The case
# rules are requested only when Exudyn is importable (EXUDYN, common.smk); the table always.


localrules:
    crosscheck_statistics,
    crosscheck_table,


rule crosscheck_case:
    input:
        kernels=case_kernels,
    output:
        sim=PATHS["crosscheck_sim"],
        exudyn=PATHS["crosscheck_exudyn"],
        metrics=PATHS["crosscheck_metrics"],
        overlay=report(
            PATHS["crosscheck_overlay"],
            caption="../report/crosscheck_overlay.rst",
            category="{study}",
            subcategory="{case}",
        ),
    log:
        log_file("crosscheck_case"),
    benchmark:
        benchmark_file("crosscheck_case")
    conda:
        "../envs/sim.yaml"
    threads: 1
    resources:
        mem_mb=4000,
        runtime=240,
    params:
        scene=scene_name,
        overrides=case_overrides,
        exudyn=crosscheck_exudyn,
        lowpass_hz=crosscheck_lowpass,
        transient=transient,
    script:
        "../scripts/crosscheck.py"


rule crosscheck_statistics:
    input:
        sim=PATHS["crosscheck_sim"],
        exudyn=PATHS["crosscheck_exudyn"],
    output:
        report(
            PATHS["crosscheck_statistics"],
            caption="../report/crosscheck_statistics.rst",
            category="{study}",
            subcategory="{case}",
        ),
    log:
        log_file("crosscheck_statistics"),
    benchmark:
        benchmark_file("crosscheck_statistics")
    conda:
        "../envs/sim.yaml"
    params:
        transient=transient,
    script:
        "../scripts/crosscheck.py"


rule crosscheck_table:
    input:
        metrics=crosscheck_metrics,
    output:
        csv=report(
            PATHS["crosscheck_csv"],
            caption="../report/crosscheck_table.rst",
            category="{study}",
        ),
        html=PATHS["crosscheck_html"],
        summary=PATHS["crosscheck_summary"],
    log:
        log_file("crosscheck_table"),
    benchmark:
        benchmark_file("crosscheck_table")
    conda:
        "../envs/sim.yaml"
    params:
        cases=study_cases,
    script:
        "../scripts/crosscheck.py"

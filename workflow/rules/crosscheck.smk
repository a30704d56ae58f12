# The cross-check study (issue 8): every case run by sim and by Exudyn in one job (their wall
# times compare), the agreement measured, and a summary table saying whether it ran. The case
# rules are requested only when Exudyn is importable (EXUDYN, common.smk); the table always.


localrules:
    crosscheck_statistics,
    crosscheck_table,


rule crosscheck_case:
    output:
        sim="results/{study}/crosscheck/{case}/sim.nc",
        exudyn="results/{study}/crosscheck/{case}/exudyn.nc",
        metrics="results/{study}/crosscheck/{case}/metrics.json",
        overlay=report(
            "results/{study}/crosscheck/{case}/overlay.png",
            caption="../report/crosscheck_overlay.rst",
            category="{study}",
            subcategory="{case}",
        ),
    params:
        scene=scene_name,
        overrides=crosscheck_overrides,
        exudyn=crosscheck_exudyn,
        lowpass_hz=crosscheck_lowpass,
        transient=transient,
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/crosscheck/{case}.log",
    benchmark:
        "results/benchmarks/{study}/crosscheck/{case}.tsv"
    threads: 1
    resources:
        mem_mb=4000,
        runtime=240,
    script:
        "../scripts/crosscheck.py"


rule crosscheck_statistics:
    input:
        sim="results/{study}/crosscheck/{case}/sim.nc",
        exudyn="results/{study}/crosscheck/{case}/exudyn.nc",
    output:
        report(
            "results/{study}/crosscheck/{case}/statistics.png",
            caption="../report/crosscheck_statistics.rst",
            category="{study}",
            subcategory="{case}",
        ),
    params:
        transient=transient,
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/crosscheck/{case}_statistics.log",
    benchmark:
        "results/benchmarks/{study}/crosscheck/{case}_statistics.tsv"
    script:
        "../scripts/crosscheck.py"


rule crosscheck_table:
    input:
        metrics=crosscheck_metrics,
    output:
        csv=report(
            "results/{study}/tables/crosscheck.csv",
            caption="../report/crosscheck_table.rst",
            category="{study}",
        ),
        html="results/{study}/tables/crosscheck.html",
        summary="results/{study}/tables/crosscheck.json",
    params:
        cases=study_cases,
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/tables/crosscheck.log",
    benchmark:
        "results/benchmarks/{study}/tables/crosscheck.tsv"
    script:
        "../scripts/crosscheck.py"

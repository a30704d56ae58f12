# Stage 5: figures and tables (small, local jobs). Every figure is a report item with a
# caption (workflow/report/*.rst), filed under its study (category) and case (subcategory).


localrules:
    responses,
    trajectories,
    phase,
    poincare,
    lyapunov_table,
    peaks_table,
    revolution_table,
    bifurcation_figure,
    bifurcation_table,
    work_precision,
    extremes_table,


rule responses:
    input:
        run="results/{study}/run/{case}.nc",
        ideal="results/{study}/ideal/{case}.nc",
    output:
        report(
            "results/{study}/figures/responses_{case}.png",
            caption="../report/responses.rst",
            category="{study}",
            subcategory="{case}",
        ),
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/figures/responses_{case}.log",
    benchmark:
        "results/benchmarks/{study}/figures/responses_{case}.tsv"
    script:
        "../scripts/figures.py"


rule trajectories:
    input:
        run="results/{study}/run/{case}.nc",
    output:
        report(
            "results/{study}/figures/trajectories_{case}.png",
            caption="../report/trajectories.rst",
            category="{study}",
            subcategory="{case}",
        ),
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/figures/trajectories_{case}.log",
    benchmark:
        "results/benchmarks/{study}/figures/trajectories_{case}.tsv"
    script:
        "../scripts/figures.py"


rule phase:
    input:
        analysis="results/{study}/analysis/{case}.nc",
    output:
        report(
            "results/{study}/figures/phase_{case}.png",
            caption="../report/phase.rst",
            category="{study}",
            subcategory="{case}",
        ),
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/figures/phase_{case}.log",
    benchmark:
        "results/benchmarks/{study}/figures/phase_{case}.tsv"
    script:
        "../scripts/figures.py"


rule poincare:
    input:
        analysis="results/{study}/analysis/{case}.nc",
    output:
        report(
            "results/{study}/figures/poincare_{case}.png",
            caption="../report/poincare.rst",
            category="{study}",
            subcategory="{case}",
        ),
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/figures/poincare_{case}.log",
    benchmark:
        "results/benchmarks/{study}/figures/poincare_{case}.tsv"
    script:
        "../scripts/figures.py"


rule lyapunov_table:
    input:
        analysis="results/{study}/analysis/{case}.nc",
    output:
        csv="results/{study}/tables/lyapunov_{case}.csv",
        html=report(
            "results/{study}/tables/lyapunov_{case}.html",
            caption="../report/lyapunov.rst",
            category="{study}",
            subcategory="{case}",
        ),
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/tables/lyapunov_{case}.log",
    benchmark:
        "results/benchmarks/{study}/tables/lyapunov_{case}.tsv"
    script:
        "../scripts/figures.py"


rule peaks_table:
    input:
        runs=runs_of_study,
        ideals=ideals_of_study,
    output:
        csv="results/{study}/tables/peaks.csv",
        html=report(
            "results/{study}/tables/peaks.html",
            caption="../report/peaks.rst",
            category="{study}",
            subcategory="tables",
        ),
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/tables/peaks.log",
    benchmark:
        "results/benchmarks/{study}/tables/peaks.tsv"
    script:
        "../scripts/figures.py"


rule revolution_table:
    input:
        runs=members_of_study,
    output:
        revolutions="results/{study}/tables/revolutions.csv",
        csv="results/{study}/tables/revolution_statistics.csv",
        html=report(
            "results/{study}/tables/revolution_statistics.html",
            caption="../report/revolution_statistics.rst",
            category="{study}",
            subcategory="tables",
        ),
    params:
        cases=study_cases,
        transient=transient,
        statistics=bootstrap_settings,
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/tables/revolutions.log",
    benchmark:
        "results/benchmarks/{study}/tables/revolutions.tsv"
    script:
        "../scripts/revolutions.py"


rule bifurcation_table:
    input:
        combined="results/{study}/bifurcation.nc",
    output:
        csv="results/{study}/tables/bifurcation_lyapunov.csv",
        html=report(
            "results/{study}/tables/bifurcation_lyapunov.html",
            caption="../report/bifurcation_lyapunov.rst",
            category="{study}",
            subcategory="tables",
        ),
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/tables/bifurcation_lyapunov.log",
    benchmark:
        "results/benchmarks/{study}/tables/bifurcation_lyapunov.tsv"
    script:
        "../scripts/figures.py"


rule bifurcation_figure:
    input:
        combined="results/{study}/bifurcation.nc",
    output:
        report(
            "results/{study}/figures/bifurcation.png",
            caption="../report/bifurcation.rst",
            category="{study}",
            subcategory="figures",
        ),
    params:
        sweep=sweep_settings,
        transient=transient,
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/figures/bifurcation.log",
    benchmark:
        "results/benchmarks/{study}/figures/bifurcation.tsv"
    script:
        "../scripts/figures.py"


rule work_precision:
    input:
        runs=runs_of_study,
        analyses=fidelity_analyses,
    output:
        csv="results/{study}/tables/work_precision.csv",
        html=report(
            "results/{study}/tables/work_precision.html",
            caption="../report/work_precision_table.rst",
            category="{study}",
            subcategory="tables",
        ),
        figure=report(
            "results/{study}/figures/work_precision.png",
            caption="../report/work_precision.rst",
            category="{study}",
            subcategory="figures",
        ),
    params:
        cases=study_cases,
        fidelity=fidelity_settings,
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/tables/work_precision.log",
    benchmark:
        "results/benchmarks/{study}/tables/work_precision.tsv"
    script:
        "../scripts/figures.py"


rule extremes_table:
    input:
        statuses=statuses_of_study,
    output:
        csv="results/{study}/tables/extremes.csv",
        html=report(
            "results/{study}/tables/extremes.html",
            caption="../report/extremes.rst",
            category="{study}",
            subcategory="tables",
        ),
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/tables/extremes.log",
    benchmark:
        "results/benchmarks/{study}/tables/extremes.tsv"
    script:
        "../scripts/figures.py"

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
        run=PATHS["run"],
        ideal=PATHS["ideal"],
    output:
        report(
            PATHS["responses"],
            caption="../report/responses.rst",
            category="{study}",
            subcategory="{case}",
        ),
    log:
        log_file("responses"),
    benchmark:
        benchmark_file("responses")
    conda:
        "../envs/sim.yaml"
    script:
        "../scripts/figures.py"


rule trajectories:
    input:
        run=PATHS["run"],
    output:
        report(
            PATHS["trajectories"],
            caption="../report/trajectories.rst",
            category="{study}",
            subcategory="{case}",
        ),
    log:
        log_file("trajectories"),
    benchmark:
        benchmark_file("trajectories")
    conda:
        "../envs/sim.yaml"
    script:
        "../scripts/figures.py"


rule phase:
    input:
        analysis=PATHS["analysis"],
    output:
        report(
            PATHS["phase"],
            caption="../report/phase.rst",
            category="{study}",
            subcategory="{case}",
        ),
    log:
        log_file("phase"),
    benchmark:
        benchmark_file("phase")
    conda:
        "../envs/sim.yaml"
    script:
        "../scripts/figures.py"


rule poincare:
    input:
        analysis=PATHS["analysis"],
    output:
        report(
            PATHS["poincare"],
            caption="../report/poincare.rst",
            category="{study}",
            subcategory="{case}",
        ),
    log:
        log_file("poincare"),
    benchmark:
        benchmark_file("poincare")
    conda:
        "../envs/sim.yaml"
    script:
        "../scripts/figures.py"


rule lyapunov_table:
    input:
        analysis=PATHS["analysis"],
    output:
        csv=PATHS["lyapunov_csv"],
        html=report(
            PATHS["lyapunov_html"],
            caption="../report/lyapunov.rst",
            category="{study}",
            subcategory="{case}",
        ),
    log:
        log_file("lyapunov_table"),
    benchmark:
        benchmark_file("lyapunov_table")
    conda:
        "../envs/sim.yaml"
    script:
        "../scripts/figures.py"


rule peaks_table:
    input:
        runs=runs_of_study,
        ideals=ideals_of_study,
    output:
        csv=PATHS["peaks_csv"],
        html=report(
            PATHS["peaks_html"],
            caption="../report/peaks.rst",
            category="{study}",
            subcategory="tables",
        ),
    log:
        log_file("peaks_table"),
    benchmark:
        benchmark_file("peaks_table")
    conda:
        "../envs/sim.yaml"
    params:
        cases=study_cases,
    script:
        "../scripts/figures.py"


rule revolution_table:
    input:
        runs=members_of_study,
    output:
        revolutions=PATHS["revolutions"],
        csv=PATHS["revolution_statistics_csv"],
        html=report(
            PATHS["revolution_statistics_html"],
            caption="../report/revolution_statistics.rst",
            category="{study}",
            subcategory="tables",
        ),
    log:
        log_file("revolution_table"),
    benchmark:
        benchmark_file("revolution_table")
    conda:
        "../envs/sim.yaml"
    params:
        cases=study_cases,
        transient=transient,
        statistics=bootstrap_settings,
    script:
        "../scripts/revolutions.py"


rule model_exponent_table:
    input:
        model_exponents_of_study,
    output:
        csv=PATHS["model_exponent_csv"],
        html=report(
            PATHS["model_exponent_html"],
            caption="../report/model_exponent.rst",
            category="{study}",
            subcategory="tables",
        ),
    log:
        log_file("model_exponent_table"),
    benchmark:
        benchmark_file("model_exponent_table")
    conda:
        "../envs/sim.yaml"
    params:
        cases=study_cases,
        links=exponent_links,
        statistics=bootstrap_settings,
    script:
        "../scripts/model_exponent_table.py"


rule bifurcation_table:
    input:
        combined=PATHS["bifurcation"],
    output:
        csv=PATHS["bifurcation_lyapunov_csv"],
        html=report(
            PATHS["bifurcation_lyapunov_html"],
            caption="../report/bifurcation_lyapunov.rst",
            category="{study}",
            subcategory="tables",
        ),
    log:
        log_file("bifurcation_table"),
    benchmark:
        benchmark_file("bifurcation_table")
    conda:
        "../envs/sim.yaml"
    script:
        "../scripts/figures.py"


rule bifurcation_figure:
    input:
        combined=PATHS["bifurcation"],
    output:
        report(
            PATHS["bifurcation_figure"],
            caption="../report/bifurcation.rst",
            category="{study}",
            subcategory="figures",
        ),
    log:
        log_file("bifurcation_figure"),
    benchmark:
        benchmark_file("bifurcation_figure")
    conda:
        "../envs/sim.yaml"
    params:
        sweep=sweep_settings,
        transient=transient,
    script:
        "../scripts/figures.py"


rule work_precision:
    input:
        runs=runs_of_study,
        analyses=fidelity_analyses,
    output:
        csv=PATHS["work_precision_csv"],
        html=report(
            PATHS["work_precision_html"],
            caption="../report/work_precision_table.rst",
            category="{study}",
            subcategory="tables",
        ),
        figure=report(
            PATHS["work_precision_figure"],
            caption="../report/work_precision.rst",
            category="{study}",
            subcategory="figures",
        ),
    log:
        log_file("work_precision"),
    benchmark:
        benchmark_file("work_precision")
    conda:
        "../envs/sim.yaml"
    params:
        cases=study_cases,
        fidelity=fidelity_settings,
    script:
        "../scripts/figures.py"


rule extremes_table:
    input:
        statuses=statuses_of_study,
    output:
        csv=PATHS["extremes_csv"],
        html=report(
            PATHS["extremes_html"],
            caption="../report/extremes.rst",
            category="{study}",
            subcategory="tables",
        ),
    log:
        log_file("extremes_table"),
    benchmark:
        benchmark_file("extremes_table")
    conda:
        "../envs/sim.yaml"
    script:
        "../scripts/figures.py"

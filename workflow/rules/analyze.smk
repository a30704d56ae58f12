# Stage 2: chaos analysis of one run (phase portraits, Poincaré points, Lyapunov exponents); in a
# study with model exponents, the verdicts read the nominal run's first.


rule analyze:
    input:
        run=PATHS["run"],
        exponent=analysis_exponent,
    output:
        PATHS["analysis"],
    log:
        log_file("analyze"),
    benchmark:
        benchmark_file("analyze")
    conda:
        "../envs/sim.yaml"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=30,
    params:
        transient=transient,
        exponent=exponent_option,
    shell:
        "sim analyze {input.run} -o {output} --transient {params.transient} {params.exponent} "
        "> {log} 2>&1"


# The model-based largest Lyapunov exponent (Benettin on the linkage) of every ensemble member
# of a chaos study, over `model_lyapunov.revolutions` (config: cheaper than the run's length).
rule model_exponent:
    input:
        run=model_exponent_run,
        kernels=model_exponent_kernels,
    output:
        PATHS["model_exponent"],
    log:
        log_file("model_exponent"),
    benchmark:
        benchmark_file("model_exponent")
    wildcard_constraints:
        member="[0-9]+",
        links="run|rigid|modal",
    conda:
        "../envs/sim.yaml"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=240,
    params:
        settings=model_lyapunov_settings,
    script:
        "../scripts/model_exponent.py"

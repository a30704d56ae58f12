# Stage 2: chaos analysis of one run (phase portraits, Poincaré points, Lyapunov exponents).


rule analyze:
    input:
        PATHS["run"],
    output:
        PATHS["analysis"],
    params:
        transient=transient,
    conda:
        "../envs/sim.yaml"
    log:
        log_file("analyze"),
    benchmark:
        benchmark_file("analyze")
    threads: 1
    resources:
        mem_mb=2000,
        runtime=30,
    shell:
        "sim analyze {input} -o {output} --transient {params.transient} > {log} 2>&1"

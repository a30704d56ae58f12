# Stage 2: chaos analysis of one run (phase portraits, Poincaré points, Lyapunov exponents).


rule analyze:
    input:
        "results/{study}/run/{case}.nc",
    output:
        "results/{study}/analysis/{case}.nc",
    params:
        transient=transient,
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/analysis/{case}.log",
    benchmark:
        "results/benchmarks/{study}/analysis/{case}.tsv"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=30,
    shell:
        "sim analyze {input} -o {output} --transient {params.transient} > {log} 2>&1"

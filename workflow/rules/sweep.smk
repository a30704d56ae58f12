# Stage 3: parameter sweeps. Every sweep point is its own `run` job (rule run, so a cluster
# spreads them); this combines their Poincaré samples into one bifurcation dataset.


localrules:
    combine_sweep,


rule combine_sweep:
    input:
        runs=runs_of_study,
    output:
        "results/{study}/bifurcation.nc",
    params:
        parameter=sweep_parameter,
        values=sweep_values,
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/bifurcation.log",
    benchmark:
        "results/benchmarks/{study}/bifurcation.tsv"
    script:
        "../scripts/combine_sweep.py"

# Stage 3: parameter sweeps. A sweep study's points are run in batches: each `sweep_batch` job
# runs `batch` consecutive points on its threads (sim.studies.batch; continuation along each
# thread's chunk if the sweep asks), writes their run files and, per point, the model-based
# exponent, the 0-1 K, the section period and the verdict of every channel; `combine_sweep`
# stacks the batches into one bifurcation dataset.


localrules:
    combine_sweep,


rule sweep_batch:
    output:
        directory("results/{study}/sweep/batch-{batch}"),
    params:
        scene=scene_name,
        overrides=sweep_base_overrides,
        points=batch_points,
        sweep=sweep_settings,
        transient=transient,
    wildcard_constraints:
        batch="[0-9]+",
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/sweep/batch-{batch}.log",
    benchmark:
        "results/benchmarks/{study}/sweep/batch-{batch}.tsv"
    threads: 2
    resources:
        mem_mb=3000,
        runtime=240,
    script:
        "../scripts/sweep_batch.py"


rule combine_sweep:
    input:
        batches=batch_dirs_of_study,
    output:
        "results/{study}/bifurcation.nc",
    params:
        parameter=sweep_parameter,
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/bifurcation.log",
    benchmark:
        "results/benchmarks/{study}/bifurcation.tsv"
    script:
        "../scripts/combine_sweep.py"

# Stage 3: parameter sweeps. A sweep study's points are run in batches: each `sweep_batch` job
# runs `batch` consecutive points on its cores (sim.studies.batch: a worker process per core;
# continuation along each worker's chunk if the sweep asks), writes their run files and, per
# point, the model-based exponent, the 0-1 K, the section period and the verdict of every
# channel; `combine_sweep` stacks the batches into one bifurcation dataset.


localrules:
    combine_sweep,


rule sweep_batch:
    input:
        kernels=sweep_kernels,
    output:
        directory(PATHS["sweep_batch"]),
    log:
        log_file("sweep_batch"),
    benchmark:
        benchmark_file("sweep_batch")
    wildcard_constraints:
        batch="[0-9]+",
    conda:
        "../envs/sim.yaml"
    threads: 2
    resources:
        mem_mb=3000,
        runtime=240,
    params:
        scene=scene_name,
        overrides=sweep_base_overrides,
        points=batch_points,
        sweep=sweep_settings,
        transient=transient,
    script:
        "../scripts/sweep_batch.py"


rule combine_sweep:
    input:
        batches=batch_dirs_of_study,
    output:
        PATHS["bifurcation"],
    log:
        log_file("combine_sweep"),
    benchmark:
        benchmark_file("combine_sweep")
    conda:
        "../envs/sim.yaml"
    params:
        parameter=sweep_parameter,
    script:
        "../scripts/combine_sweep.py"

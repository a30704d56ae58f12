# Stage 3: parameter sweeps. A sweep study's points are run in batches: each `sweep_batch` job
# runs `batch` consecutive points on its threads (sim.studies.batch; continuation along each
# thread's chunk if the sweep asks), writes their run files and, per point, the model-based
# exponent, the 0-1 K, the section period and the verdict of every channel; `combine_sweep`
# stacks the batches into one bifurcation dataset.


localrules:
    combine_sweep,


def sweep_batches(name):
    """The points of a sweep study in batches of `sweep.batch` consecutive points."""
    points = sweep_points(name)
    size = int(study(name)["sweep"].get("batch", 1))
    return [points[k : k + size] for k in range(0, len(points), size)]


def batch_dirs_of_study(wildcards):
    """The folder of every batch of a sweep study (its run files and batch.nc)."""
    count = len(sweep_batches(wildcards.study))
    return [f"results/{wildcards.study}/sweep/batch-{k}" for k in range(count)]


def batch_points(wildcards):
    """(point name, value) of the points of one batch."""
    return sweep_batches(wildcards.study)[int(wildcards.batch)]


def sweep_base_overrides(wildcards):
    """The scene overrides shared by every point of a sweep (`key=value` texts): a point's
    overrides without the swept keys, which the batch sets per point."""
    name = wildcards.study
    keys = study(name)["sweep"]["keys"]
    overrides = case_overrides(name, sweep_points(name)[0][0])
    return [f"{key}={value}" for key, value in overrides.items() if key not in keys]


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

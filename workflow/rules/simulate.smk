# Stage 1: one `sim run` per case (and per sweep point), the further members of its ensemble
# (sim/ensemble.py; member 0 is the case's run), its ideal reference, and the tolerant runs of
# the extremes study. Threads and memory here are defaults; profiles may
# override them (workflow/profiles/*/config.yaml).


rule run:
    output:
        "results/{study}/run/{case}.nc",
    params:
        scene=scene_name,
        sets=run_sets,
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/run/{case}.log",
    benchmark:
        "results/benchmarks/{study}/run/{case}.tsv"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=240,
    shell:
        "sim run {params.scene} -o {output} -q {params.sets} > {log} 2>&1"


rule run_member:
    output:
        "results/{study}/run/{case}/member-{member}.nc",
    params:
        scene=scene_name,
        overrides=run_overrides,
        draw=member_draw,
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/run/{case}/member-{member}.log",
    benchmark:
        "results/benchmarks/{study}/run/{case}/member-{member}.tsv"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=240,
    script:
        "../scripts/run_member.py"


rule run_ideal:
    output:
        "results/{study}/ideal/{case}.nc",
    params:
        scene=scene_name,
        sets=ideal_sets,
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/ideal/{case}.log",
    benchmark:
        "results/benchmarks/{study}/ideal/{case}.tsv"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=30,
    shell:
        "sim run {params.scene} -o {output} -q --ideal --rigid {params.sets} > {log} 2>&1"


rule run_tolerant:
    input:
        ideal=ideal_reference_of_case,
    output:
        "results/{study}/status/{case}.json",
    params:
        scene=scene_name,
        sets=run_sets,
        timeout=run_timeout,
        checks=extreme_checks,
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/status/{case}.log",
    benchmark:
        "results/benchmarks/{study}/status/{case}.tsv"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=60,
    script:
        "../scripts/run_tolerant.py"

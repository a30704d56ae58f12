# Stage 1: one `sim run` per case (and per sweep point), the further members of its ensemble
# (sim/ensemble.py; member 0 is the case's run), its ideal reference, and the tolerant runs of
# the extremes study. Threads and memory here are defaults; profiles may
# override them (workflow/profiles/*/config.yaml).


rule run:
    output:
        PATHS["run"],
    params:
        scene=scene_name,
        sets=run_sets,
    conda:
        "../envs/sim.yaml"
    log:
        log_file("run"),
    benchmark:
        benchmark_file("run")
    threads: 1
    resources:
        mem_mb=2000,
        runtime=240,
    shell:
        "sim run {params.scene} -o {output} -q {params.sets} > {log} 2>&1"


rule run_member:
    output:
        PATHS["member"],
    params:
        scene=scene_name,
        overrides=member_overrides,
        draw=member_draw,
    conda:
        "../envs/sim.yaml"
    log:
        log_file("run_member"),
    benchmark:
        benchmark_file("run_member")
    threads: 1
    resources:
        mem_mb=2000,
        runtime=240,
    script:
        "../scripts/run_member.py"


rule run_ideal:
    output:
        PATHS["ideal"],
    params:
        scene=scene_name,
        sets=ideal_sets,
    conda:
        "../envs/sim.yaml"
    log:
        log_file("run_ideal"),
    benchmark:
        benchmark_file("run_ideal")
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
        PATHS["status"],
    params:
        scene=scene_name,
        sets=run_sets,
        timeout=run_timeout,
        checks=extreme_checks,
    conda:
        "../envs/sim.yaml"
    log:
        log_file("run_tolerant"),
    benchmark:
        benchmark_file("run_tolerant")
    threads: 1
    resources:
        mem_mb=2000,
        runtime=60,
    script:
        "../scripts/run_tolerant.py"

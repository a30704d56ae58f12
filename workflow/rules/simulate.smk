# Stage 1: one `sim run` per case (and per sweep point), the further members of its ensemble
# (sim/ensemble.py; member 0 is the case's run), its ideal reference, and the tolerant runs of
# the extremes study. Threads and memory here are defaults; profiles may
# override them (workflow/profiles/*/config.yaml).


# Stage 0: each integrator's kernels compiled once, before its first run (sim.studies.kernels);
# without it the two jobs that -j2 starts together would both compile them. Every simulating
# rule takes its integrator's marker as an `ancient` input; the marker is deleted once they ran.
rule compile_kernels:
    output:
        temp(PATHS["kernels"]),
    log:
        log_file("compile_kernels"),
    benchmark:
        benchmark_file("compile_kernels")
    wildcard_constraints:
        method="dopri5|generalized_alpha",
    conda:
        "../envs/sim.yaml"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=30,
    script:
        "../scripts/compile_kernels.py"


rule run:
    input:
        kernels=case_kernels,
    output:
        PATHS["run"],
    log:
        log_file("run"),
    benchmark:
        benchmark_file("run")
    conda:
        "../envs/sim.yaml"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=240,
    params:
        scene=scene_name,
        sets=run_sets,
    shell:
        "sim run {params.scene} -o {output} -q {params.sets} > {log} 2>&1"


rule run_member:
    input:
        kernels=case_kernels,
    output:
        PATHS["member"],
    log:
        log_file("run_member"),
    benchmark:
        benchmark_file("run_member")
    conda:
        "../envs/sim.yaml"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=240,
    params:
        scene=scene_name,
        overrides=member_overrides,
        draw=member_draw,
    script:
        "../scripts/run_member.py"


rule run_ideal:
    input:
        kernels=ideal_kernels,
    output:
        PATHS["ideal"],
    log:
        log_file("run_ideal"),
    benchmark:
        benchmark_file("run_ideal")
    conda:
        "../envs/sim.yaml"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=30,
    params:
        scene=scene_name,
        sets=ideal_sets,
    shell:
        "sim run {params.scene} -o {output} -q --ideal --rigid {params.sets} > {log} 2>&1"


rule run_tolerant:
    input:
        ideal=ideal_reference_of_case,
        kernels=case_kernels,
    output:
        PATHS["status"],
    log:
        log_file("run_tolerant"),
    benchmark:
        benchmark_file("run_tolerant")
    conda:
        "../envs/sim.yaml"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=60,
    params:
        scene=scene_name,
        sets=run_sets,
        timeout=run_timeout,
        checks=extreme_checks,
    script:
        "../scripts/run_tolerant.py"

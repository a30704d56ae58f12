# Stage 4: the experiment study. A measured recording in data/experiment/ is used when it
# exists (config experiment.recording); otherwise the workflow writes a synthetic one.


rule synthesize_recording:
    input:
        kernels=synthetic_kernels,
    output:
        csv=PATHS["synthetic_recording"],
        meta=PATHS["synthetic_meta"],
    log:
        log_file("synthesize_recording"),
    benchmark:
        benchmark_file("synthesize_recording")
    conda:
        "../envs/sim.yaml"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=240,
    params:
        scene=scene_name,
        sets=synthetic_sets,
        seed=synthetic_seed,
        sensor=sensor_option,
    shell:
        "sim experiment synthesize {params.scene} {params.sets} --seed {params.seed} "
        "{params.sensor} -o {output.csv} > {log} 2>&1"


rule compare_experiment:
    input:
        recording=recording_file,
        meta=recording_meta,
        run=PATHS["run"],
    output:
        json=PATHS["comparison_json"],
        netcdf=PATHS["comparison_netcdf"],
        overlay=report(
            PATHS["comparison_overlay"],
            caption="../report/experiment_overlay.rst",
            category="{study}",
            subcategory="{case}",
        ),
        spectra=report(
            PATHS["comparison_spectra"],
            caption="../report/experiment_spectra.rst",
            category="{study}",
            subcategory="{case}",
        ),
    log:
        log_file("compare_experiment"),
    benchmark:
        benchmark_file("compare_experiment")
    conda:
        "../envs/sim.yaml"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=30,
    params:
        rpm=crank_rpm,
        out_dir=subpath(output.json, parent=True),
    shell:
        "sim experiment compare {input.recording} {input.run} --crank-rpm {params.rpm} "
        "--out-dir {params.out_dir} > {log} 2>&1"

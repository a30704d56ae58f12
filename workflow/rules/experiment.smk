# Stage 4: the experiment study. A measured recording in data/experiment/ is used when it
# exists (config experiment.recording); otherwise the workflow writes a synthetic one.


rule synthesize_recording:
    output:
        csv="results/{study}/recording/synthetic.csv",
        meta="results/{study}/recording/synthetic.meta.yaml",
    params:
        scene=scene_name,
        sets=synthetic_sets,
        seed=synthetic_seed,
        sensor=sensor_option,
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/recording/synthetic.log",
    benchmark:
        "results/benchmarks/{study}/recording/synthetic.tsv"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=240,
    shell:
        "sim experiment synthesize {params.scene} {params.sets} --seed {params.seed} "
        "{params.sensor} -o {output.csv} > {log} 2>&1"


rule compare_experiment:
    input:
        recording=recording_file,
        meta=recording_meta,
        run="results/{study}/run/{case}.nc",
    output:
        json="results/{study}/comparison/{case}/comparison.json",
        netcdf="results/{study}/comparison/{case}/comparison.nc",
        overlay=report(
            "results/{study}/comparison/{case}/overlay.png",
            caption="../report/experiment_overlay.rst",
            category="{study}",
            subcategory="{case}",
        ),
        spectra=report(
            "results/{study}/comparison/{case}/spectra.png",
            caption="../report/experiment_spectra.rst",
            category="{study}",
            subcategory="{case}",
        ),
    params:
        rpm=crank_rpm,
        out_dir=subpath(output.json, parent=True),
    conda:
        "../envs/sim.yaml"
    log:
        "logs/{study}/comparison/{case}.log",
    benchmark:
        "results/benchmarks/{study}/comparison/{case}.tsv"
    threads: 1
    resources:
        mem_mb=2000,
        runtime=30,
    shell:
        "sim experiment compare {input.recording} {input.run} --crank-rpm {params.rpm} "
        "--out-dir {params.out_dir} > {log} 2>&1"

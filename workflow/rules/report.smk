# Stage 6: the report's landing page. It judges each claim of docs/studies.md on our results and
# states the assumed geometry and values and which accelerometer data was used. It is the
# report's front page (Snakefile `report:`); `snakemake --report report.html` renders it.


localrules:
    landing,


rule landing:
    input:
        unpack(landing_inputs),
        template="report/landing.rst.jinja",
    output:
        rst="results/report/landing.rst",
        csv=report(
            "results/report/claims.csv",
            caption="../report/claims.rst",
            category="0 claims",
        ),
    params:
        quick=QUICK,
        studies=STUDIES,
        model=config["model"],
        recording=landing_recording,
        statistics=bootstrap_settings,
        ensemble=DEFAULTS.get("ensemble", {}),
    conda:
        "../envs/sim.yaml"
    log:
        "logs/report/landing.log",
    benchmark:
        "results/benchmarks/report/landing.tsv"
    script:
        "../scripts/landing.py"

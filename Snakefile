# Reproduction of every study of docs/studies.md: `snakemake -j2` (full),
# `snakemake -j2 --configfile config/quick.yaml` (quick), `snakemake --report report.html`
# (after some studies only: `snakemake --report report.html results/<study>/done ...`).
# Studies are entries of config/config.yaml; the rules are grouped by stage in workflow/rules.


import os


configfile: "config/config.yaml"


# the repository, for the pip entries of workflow/envs/sim.yaml (--software-deployment-method conda)
os.environ.setdefault("SIM_ROOT", workflow.basedir)


include: "workflow/rules/paths.smk"
include: "workflow/rules/common.smk"
include: "workflow/rules/simulate.smk"
include: "workflow/rules/analyze.smk"
include: "workflow/rules/sweep.smk"
include: "workflow/rules/experiment.smk"
include: "workflow/rules/crosscheck.smk"
include: "workflow/rules/figures.smk"
include: "workflow/rules/report.smk"


report: "report/front.rst"


rule all:
    default_target: True
    input:
        all_targets(),

"""The report's landing page: each claim of docs/studies.md judged on our results.

The judging is sim.claims (tested); this script reads the rule's inputs, renders
report/landing.rst.jinja and writes claims.csv.
"""

import json
from pathlib import Path

import jinja2
import pandas as pd
import xarray as xr

from sim.analysis.revolutions import Bootstrap
from sim.claims import exponent_comparison, judge_all
from sim.results import scene_of


def main(sm) -> None:
    inp = {key: value for key, value in sm.input.items() if key != "template"}
    claims, meta = judge_all(inp, Bootstrap(**sm.params.statistics))
    table = pd.DataFrame(claims)
    table.to_csv(sm.output.csv, index=False)

    scene, assumptions, versions = {}, [], {}
    if "flagship_run" in inp:
        with xr.open_dataset(inp["flagship_run"]) as ds:
            scene = scene_of(ds)
            assumptions = json.loads(ds.attrs["assumptions"])
            versions = {"sim": ds.attrs["sim_version"]} | json.loads(
                ds.attrs.get("library_versions", "{}")
            )
    template = jinja2.Template(Path(sm.input.template).read_text())
    page = template.render(
        claims=claims,
        exponents=exponent_comparison(inp),
        quick=sm.params.quick,
        studies=sm.params.studies,
        model=sm.params.model,
        assumptions=assumptions,
        scene=scene,
        versions=versions,
        recording=sm.params.recording,
        recording_meta=meta,
        statistics=sm.params.statistics,
        ensemble=sm.params.ensemble,
    )
    if "{{" in page or "{%" in page:
        raise ValueError("landing page would be re-rendered by Snakemake's Jinja: remove braces")
    Path(sm.output.rst).write_text(page)
    with open(sm.log[0], "w") as log:
        log.write(table.to_string() + "\n")


main(snakemake)  # noqa: F821 (injected by Snakemake)

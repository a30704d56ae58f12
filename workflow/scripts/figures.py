"""Figures and tables of the workflow: one function per rule of workflow/rules/figures.smk,
chosen by the rule's name; the drawing itself lives in sim.plots."""

import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

import xarray as xr

from sim.plots import bifurcation, chaos, responses, style, tables, trajectories


def _open(path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def rule_responses(sm) -> None:
    fig = responses.plot_responses(_open(sm.input.run), _open(sm.input.ideal))
    style.save(fig, sm.output[0])


def rule_trajectories(sm) -> None:
    style.save(trajectories.plot_trajectories(_open(sm.input.run)), sm.output[0])


def rule_phase(sm) -> None:
    style.save(chaos.plot_phase(_open(sm.input.analysis)), sm.output[0])


def rule_poincare(sm) -> None:
    style.save(chaos.plot_poincare(_open(sm.input.analysis)), sm.output[0])


def rule_lyapunov_table(sm) -> None:
    analysis = _open(sm.input.analysis)
    note = (
        f"{analysis.attrs['transient_revolutions']} transient revolutions dropped, "
        f"{analysis.sizes['revolution']} analysed"
    )
    title = f"Largest Lyapunov exponent per joint and axis: {sm.wildcards.case}"
    tables.write_table(chaos.lyapunov_table(analysis), sm.output.csv, sm.output.html, title, note)


def rule_peaks_table(sm) -> None:
    runs = [_open(path) for path in sm.input.runs]
    ideals = [_open(path) for path in sm.input.ideals]
    table = tables.peaks_table(list(sm.params.cases), runs, ideals)
    tables.write_table(table, sm.output.csv, sm.output.html, f"Peak values: {sm.wildcards.study}")


def rule_bifurcation_table(sm) -> None:
    combined = _open(sm.input.combined)
    table = bifurcation.indicators_table(combined)
    parameter = combined.parameter.attrs.get("name", "parameter")
    title = f"Model exponent, 0-1 K and verdicts against {parameter}"
    tables.write_table(table, sm.output.csv, sm.output.html, title)


def rule_bifurcation_figure(sm) -> None:
    sweep = sm.params.sweep
    fig = bifurcation.plot_bifurcation(
        _open(sm.input.combined),
        label=sweep["label"],
        unit=sweep["unit"],
        transient=int(sm.params.transient),
    )
    style.save(fig, sm.output[0])


def rule_work_precision(sm) -> None:
    settings = sm.params.fidelity
    runs = [_open(path) for path in sm.input.runs]
    analyses = {
        case: _open(path)
        for case, path in zip(settings["long_cases"], sm.input.analyses, strict=True)
    }
    table = tables.work_precision_table(
        list(sm.params.cases),
        runs,
        reference=settings["reference"],
        window=settings["window"],
        analyses=analyses,
        long_reference=settings["long_reference"],
        transient=settings["transient"],
    )
    note = (
        f"short horizon: first {settings['window']:g} revolutions against "
        f"{settings['reference']}; long horizon: {len(analyses)} runs against "
        f"{settings['long_reference']} after {settings['transient']} transient revolutions"
    )
    tables.write_table(table, sm.output.csv, sm.output.html, "Work against precision", note)
    style.save(tables.plot_work_precision(table, settings["window"]), sm.output.figure)


def rule_extremes_table(sm) -> None:
    statuses = [json.loads(Path(path).read_text()) for path in sm.input.statuses]
    table = tables.extremes_table(statuses)
    counts = table.result.value_counts().to_dict()
    note = ", ".join(f"{n} {result}" for result, n in counts.items())
    tables.write_table(table, sm.output.csv, sm.output.html, "Extremes: numerical stability", note)


def main(sm) -> None:
    with open(sm.log[0], "w") as log:
        globals()[f"rule_{sm.rule}"](sm)
        log.write(f"{sm.rule}: wrote {', '.join(map(str, sm.output))}\n")


main(snakemake)  # noqa: F821 (injected by Snakemake)

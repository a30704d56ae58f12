"""A study's section of the report's front page (sim.sections), from the study's files."""

from pathlib import Path

from sim.atomic import write_atomically
from sim.sections import StudyFiles, study_section


def main(sm) -> None:
    files = StudyFiles(
        runs=list(sm.input.runs),
        analyses=list(sm.input.analyses),
        exponents=next(iter(sm.input.exponents), None),
        sweep=next(iter(sm.input.sweep), None),
        figures=list(sm.input.figures),
    )
    text = study_section(sm.wildcards.study, sm.params.settings, files)
    write_atomically(Path(sm.output[0]), lambda temporary: temporary.write_text(text))
    with open(sm.log[0], "w") as log:
        log.write(f"{sm.output[0]}: {len(text)} characters, {len(files.figures)} figures\n")


main(snakemake)  # noqa: F821 (injected by Snakemake)

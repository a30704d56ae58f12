"""Compile one integrator's kernels into numba's on-disk cache before its runs (rule
compile_kernels, sim.studies.kernels); the marker says how long it took and where the cache is."""

from pathlib import Path

from sim.atomic import write_atomically
from sim.jit import cache_directory
from sim.studies.kernels import compile_kernels


def main(sm) -> None:
    method = sm.wildcards.method
    seconds = compile_kernels(method)
    text = f"{method}: kernels ready in {seconds:.1f} s (numba cache {cache_directory()})\n"
    write_atomically(Path(sm.output[0]), lambda temporary: temporary.write_text(text))
    Path(sm.log[0]).write_text(text)


main(snakemake)  # noqa: F821 (injected by Snakemake)

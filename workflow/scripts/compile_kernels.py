"""Compile one integrator's kernels into numba's on-disk cache before its runs (rule
compile_kernels, sim.studies.kernels); the marker says how long it took and where the cache is."""

import os
from pathlib import Path

from sim.jit import cache_directory
from sim.studies.kernels import compile_kernels


def main(sm) -> None:
    method = sm.wildcards.method
    seconds = compile_kernels(method)
    text = f"{method}: kernels ready in {seconds:.1f} s (numba cache {cache_directory()})\n"
    marker = Path(sm.output[0])
    partial = marker.with_name(marker.name + ".part")
    partial.write_text(text)
    os.replace(partial, marker)
    Path(sm.log[0]).write_text(text)


main(snakemake)  # noqa: F821 (injected by Snakemake)

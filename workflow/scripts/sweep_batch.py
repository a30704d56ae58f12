"""Run one batch of sweep points on the job's cores (rule sweep_batch): each point's run file
and the batch's bifurcation dataset with every point's chaos indicators (batch.nc)."""

import time
from pathlib import Path

from sim.results import write_netcdf
from sim.studies.sweep import Indicators, run_sweep


def main(snakemake) -> None:
    sweep = snakemake.params.sweep
    points = snakemake.params.points
    out_dir = Path(snakemake.output[0])
    out_dir.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    combined = run_sweep(
        snakemake.params.scene,
        snakemake.params.overrides,
        sweep["keys"],
        [value for _, value in points],
        out_dir=out_dir,
        label=sweep["label"],
        transient_revolutions=int(snakemake.params.transient),
        continuation=bool(sweep.get("continuation", False)),
        workers=snakemake.threads,
        indicators=Indicators(alignment_revolutions=float(sweep["lyapunov_alignment"])),
        file_names=[f"{name}.nc" for name, _ in points],
    )
    write_netcdf(combined, out_dir / "batch.nc")
    wall = time.perf_counter() - start
    with open(snakemake.log[0], "w") as log:
        log.write(
            f"{len(points)} points on {snakemake.threads} worker processes in {wall:.1f} s "
            f"({wall / len(points):.2f} s per point)\n"
        )


main(snakemake)  # noqa: F821 (injected by Snakemake)

"""Run files written from threads of one process: the netCDF library underneath is not
thread-safe, so `sim.results.write_netcdf` serialises writes. Without that lock this script
crashed with a segmentation fault on every one of three tries (2 threads × 40 files)."""

import subprocess
import sys
import textwrap

import xarray as xr

WRITERS = 2
FILES_EACH = 30

SCRIPT = textwrap.dedent(
    """
    import sys
    from concurrent.futures import ThreadPoolExecutor

    import numpy as np
    import xarray as xr

    from sim.results import write_netcdf

    folder, writers, files_each = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])

    def write_files(writer):
        for k in range(files_each):
            values = np.full(2000, 1000.0 * writer + k)
            ds = xr.Dataset(
                {f"v{j}": ("time", values + j) for j in range(12)},
                coords={"time": np.arange(2000.0)},
            )
            write_netcdf(ds, f"{folder}/w{writer}_{k}.nc")

    with ThreadPoolExecutor(writers) as pool:
        list(pool.map(write_files, range(writers)))
    """
)


def test_threads_write_complete_files(tmp_path):
    done = subprocess.run(
        [sys.executable, "-c", SCRIPT, str(tmp_path), str(WRITERS), str(FILES_EACH)],
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr[-2000:]
    for writer in range(WRITERS):
        for k in range(FILES_EACH):
            with xr.open_dataset(tmp_path / f"w{writer}_{k}.nc") as ds:
                # every variable holds what its writer put there: no file mixes two writers
                assert float(ds["v3"][0]) == 1000.0 * writer + k + 3
    assert not list(tmp_path.glob(".*.tmp"))

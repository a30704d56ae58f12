"""The suite's set-up: both integrators' kernels compiled side by side before the first test.

From an empty numba cache (a fresh clone, CI, an edit of any kernel) the first run of each
integrator compiles its loop and its lockstep follower for up to a minute
(`sim.kernel_cache.COMPILE_SECONDS`); in one pytest process the two integrators' compiles come
one after the other on one core. `pytest_sessionstart` runs them at once in two processes, as the
workflow's `compile_kernels` rule does (`sim.studies.kernels`, whose order lets the two share
the kernels common to both methods), into the on-disk cache the tests then load. With the
kernels cached each process returns in about three seconds.

The tests then run on every core (pytest-xdist, ``-n auto`` in pyproject.toml): its workers
start after this set-up (xdist starts them in its own, last, session start) and skip it.
"""

import os
import subprocess
import sys
import time

#: the integrators the default suite runs, each with its lockstep follower
SUITE_METHODS = ("dopri5", "generalized_alpha")

COMPILE = "from sim.studies.kernels import compile_kernels; compile_kernels({!r})"


def pytest_sessionstart(session) -> None:
    if "PYTEST_XDIST_WORKER" in os.environ:
        return  # the controller compiled before starting the workers
    start = time.perf_counter()
    jobs = [
        (method, subprocess.Popen([sys.executable, "-c", COMPILE.format(method)]))
        for method in SUITE_METHODS
    ]
    failed = [method for method, job in jobs if job.wait() != 0]
    seconds = time.perf_counter() - start
    # A failed compile is not the suite's verdict: the tests that need the kernel compile it
    # again and report what fails.
    print(
        f"\nintegrator kernels ready in {seconds:.0f} s"
        + (f"; the warm-up failed for {', '.join(failed)}" if failed else ""),
        file=sys.stderr,
    )

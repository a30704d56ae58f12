"""Batched runs: independent integrations carried by the threads of one process.

The compiled kernels release the GIL (:mod:`sim.jit`, ``nogil``) and touch only the arrays of
their own :class:`sim.run.Integration`, so threads that each prepare and advance their own
integrations run them on separate cores at once, with no state shared between them: every
thread computes exactly what it would compute alone (bitwise; ``tests/analysis/test_batch.py``).
Only the Python between compiled calls (scene loading, the energy watch every quarter
revolution, writing the results) takes turns on the GIL. ``benchmarks/batch_throughput.py``
measures the throughput against running the same points one by one.
"""

import itertools
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from typing import TypeVar

T = TypeVar("T")


def contiguous_chunks(count: int, workers: int) -> list[range]:
    """``count`` items split into at most ``workers`` contiguous ranges whose lengths differ
    by at most one, so that continuation can run along each range."""
    if count < 0 or workers < 1:
        raise ValueError(f"contiguous_chunks: count = {count} must be ≥ 0, workers = {workers} ≥ 1")
    n = min(count, workers)
    bounds = [count * k // n for k in range(n + 1)] if n else [0]
    return [range(a, b) for a, b in itertools.pairwise(bounds)]


def run_batch(tasks: Sequence[Callable[[], T]], workers: int) -> list[T]:
    """Call every task on a pool of ``workers`` threads; their results in task order.

    The tasks must not share mutable state (each prepares its own integrations). The first
    exception of a task, in task order, is raised here once every task has finished.
    """
    if workers < 1:
        raise ValueError(f"run_batch: workers = {workers} must be at least 1")
    if workers == 1 or len(tasks) <= 1:
        return [task() for task in tasks]
    with ThreadPoolExecutor(max_workers=workers, thread_name_prefix="sim-batch") as pool:
        futures = [pool.submit(task) for task in tasks]
        return [future.result() for future in futures]

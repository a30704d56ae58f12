"""Batched runs: independent integrations carried by the worker processes of one job.

A batch (the points of one sweep job) is shared among ``workers`` processes forked from the
job's process: each integrates its own runs with its own arrays and writes its own run files,
and hands back only what the job gathers (each point's section variables and indicators). No
state is shared, so every process computes exactly what it would compute alone (bitwise;
``tests/analysis/test_batch.py``). Processes, not threads: the kernels release the GIL
(:mod:`sim.jit`, ``nogil``), but the Python between compiled calls does not, and a sweep point
with its model exponent pauses its run 32 times a revolution; two threads did 12 % more CPU
work than one by one and reached 1.73 × its throughput, two processes 2.0 ×
(``benchmarks/batch_throughput.py``, docs/performance.md).
"""

import itertools
import multiprocessing
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor
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
    """Call every task on a pool of ``workers`` processes, each task taken by whichever process
    is free; their results in task order.

    The tasks and their results must pickle (module-level functions, or ``functools.partial``
    of one, with plain arguments). The processes are forked, so they start with the job's
    imports and loaded kernels. The first exception of a task, in task order, is raised here
    once every task has finished. With one worker (or one task) the tasks run in this process.
    """
    if workers < 1:
        raise ValueError(f"run_batch: workers = {workers} must be at least 1")
    if workers == 1 or len(tasks) <= 1:
        return [task() for task in tasks]
    context = multiprocessing.get_context("fork")
    with ProcessPoolExecutor(max_workers=min(workers, len(tasks)), mp_context=context) as pool:
        futures = [pool.submit(task) for task in tasks]
        return [future.result() for future in futures]

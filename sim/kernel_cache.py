"""Whether the integrator's compiled loop is ready, and compiling it before a run's clock
starts.

numba compiles a kernel on its first call and keeps it in the on-disk cache (sim.jit): in a
fresh environment, or after an edit of any kernel, the first run of each method compiles for
up to a minute and prints nothing. `compile_integrator` compiles (or loads) the loop for a run's
argument types before it is timed, so the recorded wall time and real-time factor are those
of the integration alone, and says once, with an estimate, when the cache does not hold it.
Asking the cache is cheap: numba's own index of the cached signatures is read, nothing is
compiled.
"""

import sys
import time

import numba

from sim.solve import stepping

#: Compile time (s) of each method's integration loop with everything it calls, from an empty
#: cache on this project's 2-core reference machine, generalized-α's after DOPRI5's
#: (docs/performance.md, "Start-up"), rounded up; longer when other work shares the core.
COMPILE_SECONDS = {"dopri5": 50.0, "generalized_alpha": 40.0}


def _signature(args: tuple) -> tuple:
    return tuple(numba.typeof(a) for a in args)


def is_cached(dispatcher, args: tuple) -> bool:
    """Whether `dispatcher` (a `sim.jit.kernel`) is compiled for the types of `args` in this
    process or held by numba's on-disk cache for them (index of numba.core.caching)."""
    signature = _signature(args)
    if signature in dispatcher.overloads:
        return True
    cache = dispatcher._cache
    key = cache._index_key(signature, dispatcher.targetctx.codegen())
    return key in cache._cache_file._load_index()


def cached_signatures(dispatcher) -> int:
    """How many specialisations of `dispatcher` numba's on-disk cache holds: each argument
    type it was ever compiled for with the current kernel sources."""
    return len(dispatcher._cache._cache_file._load_index())


def compile_integrator(args: tuple, method: str) -> float:
    """Compile, or load from the cache, the integration loop (`stepping.integrate`) for the
    types of its arguments `args`; when the cache does not hold it, say so on stderr with
    the estimate of `COMPILE_SECONDS` for `method`. Returns the time it took (s; 0 when this
    process has it already)."""
    signature = _signature(args)
    if signature in stepping.integrate.overloads:
        return 0.0
    if not is_cached(stepping.integrate, args):
        print(
            f"compiling the integrator's kernels for {method} (numba; once per install or "
            f"change of the kernels, then cached): about {COMPILE_SECONDS[method]:.0f} s on an "
            "idle core",
            file=sys.stderr,
            flush=True,
        )
    start = time.perf_counter()
    stepping.integrate.compile(signature)
    return time.perf_counter() - start

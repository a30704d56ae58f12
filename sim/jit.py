"""The one way the hot loop is compiled.

Every kernel is numba's nopython compilation with the on-disk cache and without the numba
runtime (NRT). The kernels never allocate, and without the runtime numba also drops the atomic
reference counting it otherwise does on every array taken out of the `System` and `Work`
tuples: measured on the six-bar with A and B clearances, one right-hand side evaluation fell
from 5.6 µs to 2.3 µs and the clearance forces from 1.8 µs to 0.23 µs. A kernel that tried to
allocate fails to compile rather than allocating silently, which also enforces the
allocation-free rule. Division follows numpy's error model: a division by zero gives ±inf or
nan, which the integrator's finiteness checks catch, instead of a branch to a Python exception
after every division.

What a compile costs decides the four kinds of kernel (docs/performance.md, "Start-up").
numba compiles every kernel a compiled caller calls into a library of its own, then links that
library's code into the caller's and optimises and generates machine code for all of it
again: each library pays for everything beneath it, so a deep chain of libraries pays for its
leaves many times over. And a kernel Python can call carries a CPython wrapper that unboxes
every field of `System` and `Work`: a tenth of a second and more for each kernel. So:

- `entry`: a kernel that Python calls, such as the integration loop: a library with its
  wrapper.
- `kernel`: a kernel for compiled callers, one library without wrappers, linked into its
  callers: for what is large and called from several places (the right-hand side where
  it runs once, at an event or a sample; one sample row; generalized-α's step).
- `kernel_inline`: a small kernel for compiled callers, inlined into each by LLVM
  (``alwaysinline``), without wrappers: point kinematics, force laws, the evaluation's parts.
  Inlined, numba no longer passes `System` and `Work` to it field by field on the stack
  (hundreds of words), which made rigid runs 1.3 × slower when LLVM stopped inlining the
  point kinematics on its own. So is what runs at every stage or every step, however large:
  DOPRI5's step with its evaluation (`sim.solve.dae.rhs_inline`), the guide frame, the
  values recorded at each step's end.
- `spliced`: a part of the one or two kernels that call it, spliced into their body by numba
  before typing, so that it is no library at all: the integration loop's steps. Also what
  returns a view of an array (`sim.solve.dae.no_rotations`), which a library cannot without
  the runtime.

A `kernel` or `kernel_inline` called from Python (a test, a set-up computation) runs its
Python twin: the same function compiled with the wrappers under another name, so that the
on-disk cache keeps the two apart, built at that first call (`_Internal`).

The on-disk cache lives in a directory named for a digest of every module that
defines kernels (`cache_directory`): numba checks a cached function against its
own file only, so after an edit of a kernel it calls (or a `git pull`) it would
load the caller compiled against the old callee and silently compute with old
code. A new digest starts a fresh cache instead.

Kernels release the GIL (``nogil``): they touch only the arrays passed to them, so threads
of one process may integrate independent runs at once. The sweeps' batches use processes
instead (sim.studies.batch): the Python between compiled calls holds the GIL.
"""

import hashlib
import os
import shutil
import types
from collections.abc import Callable
from pathlib import Path

import numba
from numba.core.registry import CPUDispatcher

KEPT_CACHES = 4
"""Cache directories of earlier sources kept besides the current one."""

TWIN_SUFFIX = "__from_python"
"""Appended to a kernel's qualified name for its Python twin: numba names a function's cache
files after it, so the twin's never overwrite the kernel's."""


def cache_directory() -> Path:
    """numba's cache directory for the current kernel sources:
    sim-numba/<digest> under $NUMBA_CACHE_DIR if set, else under $XDG_CACHE_HOME
    (~/.cache)."""
    package = Path(__file__).parent
    digest = hashlib.sha256()
    for path in sorted(package.rglob("*.py")):
        text = path.read_bytes()
        if path == Path(__file__) or b"from sim.jit import" in text:
            digest.update(path.relative_to(package).as_posix().encode())
            digest.update(text)
    base = os.environ.get("NUMBA_CACHE_DIR") or os.environ.get("XDG_CACHE_HOME")
    return Path(base or Path.home() / ".cache") / "sim-numba" / digest.hexdigest()[:16]


def _prune(current: Path) -> None:
    """Remove all but the KEPT_CACHES most recent cache directories of earlier sources."""
    try:
        others = [p for p in current.parent.iterdir() if p.is_dir() and p != current]
    except OSError:
        return
    others.sort(key=lambda p: p.stat().st_mtime, reverse=True)
    for old in others[KEPT_CACHES:]:
        shutil.rmtree(old, ignore_errors=True)


# Set before any kernel is decorated: numba fixes a function's cache locator then.
numba.config.CACHE_DIR = str(cache_directory())
_prune(Path(numba.config.CACHE_DIR))

_OPTIONS = {"nogil": True, "_nrt": False, "error_model": "numpy"}
_INTERNAL = {"nopython": True, **_OPTIONS, "no_cpython_wrapper": True, "no_cfunc_wrapper": True}


class _Internal(CPUDispatcher):
    """A kernel compiled for compiled callers only, without wrappers. Called from Python, it
    runs its twin (module docstring)."""

    _twin: CPUDispatcher | None = None

    def __call__(self, *args, **kwargs):
        if self._twin is None:
            function = self.py_func
            twin = types.FunctionType(
                function.__code__,
                function.__globals__,
                function.__name__,
                function.__defaults__,
                function.__closure__,
            )
            twin.__qualname__ = function.__qualname__ + TWIN_SUFFIX
            twin.__module__ = function.__module__
            self._twin = entry(twin)
        return self._twin(*args, **kwargs)


def _internal(options: dict) -> Callable:
    """The decorator of an internal kind of kernel compiled with `options`."""

    def decorate(function: Callable) -> _Internal:
        dispatcher = _Internal(py_func=function, locals={}, targetoptions=options)
        dispatcher.enable_caching()
        return dispatcher

    return decorate


entry = numba.njit(cache=True, **_OPTIONS)
kernel = _internal({**_INTERNAL, "forceinline": False})
kernel_inline = _internal({**_INTERNAL, "forceinline": True})
spliced = numba.njit(cache=True, inline="always", **_OPTIONS)

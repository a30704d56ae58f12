"""The one way the hot loop is compiled.

`kernel` is numba's nopython compilation with the on-disk cache and without the
numba runtime (NRT). The kernels never allocate, and without the runtime numba
also drops the atomic reference counting it otherwise does on every array taken
out of the `System` and `Work` tuples: measured on the six-bar with A and B
clearances, one right-hand side evaluation fell from 5.6 µs to 2.3 µs and the
clearance forces from 1.8 µs to 0.23 µs. A kernel that tried to allocate fails
to compile rather than allocating silently, which also enforces the
allocation-free rule.

The on-disk cache lives in a directory named for a digest of every module that
defines kernels (`cache_directory`): numba checks a cached function against its
own file only, so after an edit of a kernel it calls (or a `git pull`) it would
load the caller compiled against the old callee and silently compute with old
code. A new digest starts a fresh cache instead.

`kernel_inline` inlines a kernel into its callers when numba compiles them. A kernel call
that is not inlined passes the `System` and `Work` tuples flattened, field by field, on the
stack (hundreds of words each); LLVM inlines a callee only while it is small, and stopped
doing so for the point kinematics and clearance helpers once `System` gained the modal-link
fields: rigid runs became 1.3 × slower. So what one right-hand side evaluation calls (its
forces, constraint terms and accelerations, down to the point kinematics) is inlined by
numba, whatever LLVM would decide; measured on the rigid flagship (docs/performance.md,
"Decisions kept"), 2.77 → 1.60 s for 20 revolutions, results bit for bit the same.
`rhs` itself is not inlined: its six calls per Runge–Kutta step would compile six copies.

Kernels release the GIL (``nogil``): they touch only the arrays passed to them, so threads
of one process may integrate independent runs at once. The sweeps' batches use processes
instead (sim.studies.batch): the Python between compiled calls holds the GIL.
"""

import hashlib
import os
import shutil
from pathlib import Path

import numba

KEPT_CACHES = 4
"""Cache directories of earlier sources kept besides the current one."""


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

kernel = numba.njit(cache=True, nogil=True, _nrt=False)
kernel_inline = numba.njit(cache=True, nogil=True, inline="always", _nrt=False)

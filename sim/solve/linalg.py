"""Small linear algebra for the compiled hot loop.

numpy.linalg allocates its results, which the integrator's step loop must not
do; these kernels work in place on caller-owned arrays. The systems solved here
are small (a few tens of unknowns). The symmetric positive definite ones are dense, where a
plain Cholesky factorisation is both the fastest and the simplest choice (Golub & Van Loan,
Matrix Computations, 4th ed., algorithm 4.2.1). The implicit integrator's Newton matrix is
sparse (a beam's or a body's block, the constraints' rows and columns): it is factored over a
fixed pattern of nonzeros (`LUPattern`) without pivoting, and by partial pivoting where that
fails.
"""

from typing import NamedTuple

import numpy as np

from sim.jit import kernel_inline

PIVOT_FLOOR = 1e-10
"""A pivot of the static-pattern LU below this share of the largest entry of its column below
it fails the factorisation, which the caller then does by partial pivoting: the elimination
without row exchanges would lose digits to its growth (Duff, Erisman & Reid, Direct Methods for
Sparse Matrices, 1986, section 5.4, whose threshold pivoting tests the same ratio). The Newton
matrix's mass block is positive definite and eliminated first, so its pivots never come near
(the crank's rotary inertia against the drive row's unit entry, 1e-3, is the smallest ratio on
the flexible flagship); a rank-deficient constraint set does."""


class LUPattern(NamedTuple):
    """Where the LU factors of a square matrix, eliminated in its own order without row
    exchanges, can be nonzero (fill-in included): for each pivot k, the rows i > k of L's
    column k and the columns j > k of U's row k, ascending, padded."""

    lower: np.ndarray  # (N, width) rows i > k with L[i, k] possibly nonzero
    n_lower: np.ndarray  # (N,) how many
    upper: np.ndarray  # (N, width) columns j > k with U[k, j] possibly nonzero
    n_upper: np.ndarray  # (N,) how many


def lu_pattern(nonzero: np.ndarray) -> LUPattern:
    """The `LUPattern` of a matrix whose entries can be nonzero where `nonzero` (bool,
    N × N) is True: symbolic Gaussian elimination, each pivot filling the product of its
    column below and its row right of it (George & Liu, Computer Solution of Large Sparse
    Positive Definite Systems, 1981, ch. 5)."""
    filled = np.array(nonzero, dtype=bool)
    size = filled.shape[0]
    lower, upper = [], []
    for k in range(size):
        rows = k + 1 + np.flatnonzero(filled[k + 1 :, k])
        cols = k + 1 + np.flatnonzero(filled[k, k + 1 :])
        filled[np.ix_(rows, cols)] = True
        lower.append(rows)
        upper.append(cols)
    width = max((len(r) for r in lower + upper), default=0)

    def padded(lists: list[np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
        table = np.zeros((size, width), dtype=np.int64)
        for k, entries in enumerate(lists):
            table[k, : len(entries)] = entries
        return table, np.array([len(e) for e in lists], dtype=np.int64)

    (low, n_low), (up, n_up) = padded(lower), padded(upper)
    return LUPattern(lower=low, n_lower=n_low, upper=up, n_upper=n_up)


@kernel_inline
def pattern_lu_in_place(a: np.ndarray, pattern) -> bool:
    """Overwrite the square matrix `a`, zero outside `pattern` (`LUPattern`), with its LU
    factors (unit lower L below the diagonal, U on and above), eliminated in its own order
    without row exchanges: only the entries the pattern holds are touched. Returns False
    when a pivot fails PIVOT_FLOOR (then `a` is spoilt: assemble it again)."""
    for k in range(a.shape[0]):
        pivot = a[k, k]
        largest = 0.0
        for r in range(pattern.n_lower[k]):
            largest = max(largest, abs(a[pattern.lower[k, r], k]))
        if not abs(pivot) >= PIVOT_FLOOR * largest or pivot == 0.0:
            return False
        for r in range(pattern.n_lower[k]):
            i = pattern.lower[k, r]
            f = a[i, k] / pivot
            a[i, k] = f
            for c in range(pattern.n_upper[k]):
                j = pattern.upper[k, c]
                a[i, j] -= f * a[k, j]
    return True


@kernel_inline
def pattern_lu_solve_in_place(lu: np.ndarray, pattern, b: np.ndarray) -> None:
    """Solve A x = b for x, overwriting b; A's factors from `pattern_lu_in_place`."""
    size = lu.shape[0]
    for k in range(size):
        bk = b[k]
        for r in range(pattern.n_lower[k]):
            i = pattern.lower[k, r]
            b[i] -= lu[i, k] * bk
    for k in range(size - 1, -1, -1):
        s = b[k]
        for c in range(pattern.n_upper[k]):
            j = pattern.upper[k, c]
            s -= lu[k, j] * b[j]
        b[k] = s / lu[k, k]


@kernel_inline
def cholesky_in_place(a: np.ndarray, m: int, first: np.ndarray) -> bool:
    """Overwrite the leading m×m block of the symmetric matrix `a` with its
    lower Cholesky factor L (a = L Lᵀ). Row i of the block is zero left of
    column first[i] (its envelope; zeros for a dense matrix), and so is row i of
    L, which has no fill-in outside the envelope (George & Liu, Computer Solution
    of Large Sparse Positive Definite Systems, 1981, ch. 4): the sums skip those
    exact zeros. Returns False if the block is not positive definite to working
    precision (a singular or rank-deficient constraint Jacobian shows up here)."""
    for j in range(m):
        s = a[j, j]
        for k in range(first[j], j):
            s -= a[j, k] * a[j, k]
        # The relative threshold separates a truly singular Schur complement
        # (redundant or locked constraints) from an ill-scaled but valid one.
        if s <= 1e-13 * abs(a[j, j]) or s <= 0.0:
            return False
        d = np.sqrt(s)
        a[j, j] = d
        for i in range(j + 1, m):
            if first[i] > j:
                continue
            s = a[i, j]
            for k in range(max(first[i], first[j]), j):
                s -= a[i, k] * a[j, k]
            a[i, j] = s / d
    return True


@kernel_inline
def cholesky_solve_in_place(l: np.ndarray, m: int, b: np.ndarray) -> None:
    """Solve (L Lᵀ) x = b for x, overwriting b; L from `cholesky_in_place`."""
    for i in range(m):
        s = b[i]
        for k in range(i):
            s -= l[i, k] * b[k]
        b[i] = s / l[i, i]
    for i in range(m - 1, -1, -1):
        s = b[i]
        for k in range(i + 1, m):
            s -= l[k, i] * b[k]
        b[i] = s / l[i, i]


@kernel_inline
def lu_in_place(a: np.ndarray, piv: np.ndarray) -> bool:
    """Overwrite the square matrix `a` with its LU factors (unit lower L below the
    diagonal, U on and above), partial pivoting by rows recorded in `piv`
    (Golub & Van Loan, algorithm 3.4.1). For the indefinite, unsymmetric Newton
    matrices of the implicit integrator. Returns False on an exactly zero pivot."""
    size = a.shape[0]
    for k in range(size):
        p = k
        big = abs(a[k, k])
        for i in range(k + 1, size):
            if abs(a[i, k]) > big:
                big = abs(a[i, k])
                p = i
        piv[k] = p
        if big == 0.0:
            return False
        if p != k:
            for j in range(size):
                tmp = a[k, j]
                a[k, j] = a[p, j]
                a[p, j] = tmp
        inv = 1.0 / a[k, k]
        for i in range(k + 1, size):
            f = a[i, k] * inv
            a[i, k] = f
            if f != 0.0:
                for j in range(k + 1, size):
                    a[i, j] -= f * a[k, j]
    return True


@kernel_inline
def lu_solve_in_place(lu: np.ndarray, piv: np.ndarray, b: np.ndarray) -> None:
    """Solve A x = b for x, overwriting b; A's factors from `lu_in_place`."""
    size = lu.shape[0]
    for k in range(size):
        p = piv[k]
        if p != k:
            tmp = b[k]
            b[k] = b[p]
            b[p] = tmp
    for i in range(size):
        s = b[i]
        for k in range(i):
            s -= lu[i, k] * b[k]
        b[i] = s
    for i in range(size - 1, -1, -1):
        s = b[i]
        for k in range(i + 1, size):
            s -= lu[i, k] * b[k]
        b[i] = s / lu[i, i]

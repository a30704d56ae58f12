"""Small dense linear algebra for the compiled hot loop.

numpy.linalg allocates its results, which the integrator's step loop must not
do; these kernels work in place on caller-owned arrays. The systems solved here
are small (a few tens of unknowns) and dense, where a plain Cholesky
factorisation is both the fastest and the simplest choice (Golub & Van Loan,
Matrix Computations, 4th ed., algorithm 4.2.1).
"""

import numpy as np

from sim.jit import kernel_inline


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

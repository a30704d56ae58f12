"""Small dense linear algebra for the compiled hot loop.

numpy.linalg allocates its results, which the integrator's step loop must not
do; these kernels work in place on caller-owned arrays. The systems solved here
are small (a few tens of unknowns) and dense, where a plain Cholesky
factorisation is both the fastest and the simplest choice (Golub & Van Loan,
Matrix Computations, 4th ed., algorithm 4.2.1).
"""

import numpy as np

from sim.jit import kernel


@kernel
def cholesky_in_place(a: np.ndarray, m: int) -> bool:
    """Overwrite the leading m×m block of the symmetric matrix `a` with its
    lower Cholesky factor L (a = L Lᵀ). Returns False if the block is not
    positive definite to working precision (a singular or rank-deficient
    constraint Jacobian shows up here)."""
    for j in range(m):
        s = a[j, j]
        for k in range(j):
            s -= a[j, k] * a[j, k]
        # The relative threshold separates a truly singular Schur complement
        # (redundant or locked constraints) from an ill-scaled but valid one.
        if s <= 1e-13 * abs(a[j, j]) or s <= 0.0:
            return False
        d = np.sqrt(s)
        a[j, j] = d
        for i in range(j + 1, m):
            s = a[i, j]
            for k in range(j):
                s -= a[i, k] * a[j, k]
            a[i, j] = s / d
    return True


@kernel
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

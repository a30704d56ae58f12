"""The finite journal bearing's film force, tabulated once from Reynolds' equation.

For 0.5 < L/D < 2 neither the short nor the long bearing holds (sim.model.lubrication). In the
frame turning at ω̄ the film is a pure squeeze at the relative velocity V (sim.model.
lubrication); with p = (12 μ R²/c³) |V| P, z̄ = z/R ∈ [−λ, λ], λ = L/D, the pressure solves

    ∂/∂ψ (H³ ∂P/∂ψ) + ∂/∂z̄ (H³ ∂P/∂z̄) = −(cos α cos ψ + sin α sin ψ),   H = 1 − ε cos ψ,

periodic in ψ, P = 0 at the bearing's ends z̄ = ±λ, α the angle of V from n (Frêne et al.,
Hydrodynamic Lubrication, 1997, ch. 8, without the wedge term in this frame). Cavitation:
half-Sommerfeld (Gümbel), P⁺ = max(P, 0); the film force on the journal is
F = −(12 μ R⁴/c³) |V| G(λ, ε, α), G = ∬ P⁺ (cos ψ, sin ψ) dψ dz̄ in (n, t). As λ → 0 it tends to
the short bearing's π-film (tests/model/test_lubrication.py).

The equation is solved by finite volumes on a grid uniform in the Sommerfeld angle γ
(cos γ = (cos ψ − ε)/(1 − ε cos ψ), dψ = H dγ/√(1 − ε²)), which gathers the points where the
film is thin: multiplied by dψ/dγ it reads
∂γ(H² √(1 − ε²) ∂γ P) + (H⁴/√(1 − ε²)) ∂²P/∂z̄² = −(H/√(1 − ε²)) (V̂·n_ψ).
Both sources (α = 0 and π/2) are solved once per (λ, ε); P for any α is their combination.

`python -m sim.model.finite_bearing` writes the table (G (1 − ε²)², the factor that keeps its
interpolation in ε accurate; single precision, 6e-8 of its values) on the grid that
sim.model.lubrication declares (FINITE_*) to sim.model.lubrication.FINITE_TABLE, which
`sim.model.lubrication.film_tables` reads (about 5 minutes on one core).
"""

import math

import numpy as np
from scipy.sparse import coo_matrix
from scipy.sparse.linalg import splu

from sim.model.lubrication import (
    FINITE_ANGLES,
    FINITE_ECCENTRICITIES,
    FINITE_RATIOS,
    FINITE_STEP_ANGLE,
    FINITE_STEP_U,
    FINITE_TABLE,
)

RATIOS = np.array(FINITE_RATIOS)
ECCENTRICITIES = 1.0 - np.exp(-FINITE_STEP_U * np.arange(FINITE_ECCENTRICITIES))
ANGLES = -math.pi + FINITE_STEP_ANGLE * np.arange(FINITE_ANGLES)
GRID = (256, 128)
"""Points around (γ) and across the length (z̄) of the table's solutions: doubling both changes
G at L/D = 1 by at most 5e-5 of its largest component at ε = 0.5, 3.3e-4 at 0.99 and 1.2e-3 at
0.9995 (the length's resolution dominates)."""


def pressure_fields(ratio: float, eps: float, grid: tuple[int, int] = GRID) -> tuple:
    """P for V along n and along t on the grid, (P_r, P_t) of shape (nγ, nz − 1), with the
    grid's cos ψ, sin ψ, dψ/dγ, Δγ and Δz̄."""
    n_g, n_z = grid
    s = 1.0 - eps * eps
    root = math.sqrt(s)
    gamma = 2.0 * math.pi * np.arange(n_g) / n_g
    dg = 2.0 * math.pi / n_g
    dz = 2.0 * ratio / n_z

    def film(g):
        return s / (1.0 + eps * np.cos(g))

    h = film(gamma)
    a_plus = film(gamma + 0.5 * dg) ** 2 * root / dg**2  # H²√s at γ_{i+½}, over Δγ²
    a_minus = np.roll(a_plus, 1)
    b = h**4 / root / dz**2
    m = n_z - 1
    index = np.arange(n_g * m).reshape(n_g, m)
    rows, cols, vals = [], [], []

    def add(r, c, v):
        rows.append(r.ravel())
        cols.append(c.ravel())
        vals.append(np.broadcast_to(v, r.shape).ravel())

    centre = -(a_plus + a_minus)[:, None] - 2.0 * b[:, None]
    add(index, index, centre)
    add(index, np.roll(index, -1, axis=0), a_plus[:, None])
    add(index, np.roll(index, 1, axis=0), a_minus[:, None])
    add(index[:, 1:], index[:, :-1], b[:, None])
    add(index[:, :-1], index[:, 1:], b[:, None])
    size = n_g * m
    matrix = coo_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))), shape=(size, size)
    ).tocsc()
    cos_psi = (np.cos(gamma) + eps) / (1.0 + eps * np.cos(gamma))
    sin_psi = root * np.sin(gamma) / (1.0 + eps * np.cos(gamma))
    jacobian = h / root  # dψ/dγ
    lu = splu(matrix)
    fields = []
    for direction in (cos_psi, sin_psi):
        rhs = np.repeat((-jacobian * direction)[:, None], m, axis=1)
        fields.append(lu.solve(rhs.ravel()).reshape(n_g, m))
    return fields[0], fields[1], cos_psi, sin_psi, jacobian, dg, dz


def force_integrals(ratio: float, eps: float, angles: np.ndarray, grid=GRID) -> np.ndarray:
    """G (n and t components, shape (len(angles), 2)) of a bearing of L/D `ratio` at ε for V
    at each angle α from n."""
    p_r, p_t, cos_psi, sin_psi, jacobian, dg, dz = pressure_fields(ratio, eps, grid)
    out = np.empty((len(angles), 2))
    for k, alpha in enumerate(angles):
        positive = np.maximum(math.cos(alpha) * p_r + math.sin(alpha) * p_t, 0.0)
        around = positive.sum(axis=1) * dz * jacobian * dg  # ∫ P⁺ dz̄ dψ at each γ
        out[k] = (around @ cos_psi, around @ sin_psi)
    return out


def tabulate() -> np.ndarray:
    """G (1 − ε²)² on RATIOS × ECCENTRICITIES × ANGLES × (n, t)."""
    table = np.empty((len(RATIOS), len(ECCENTRICITIES), len(ANGLES), 2))
    for i, ratio in enumerate(RATIOS):
        for k, eps in enumerate(ECCENTRICITIES):
            table[i, k] = force_integrals(ratio, eps, ANGLES) * (1.0 - eps * eps) ** 2
    return table


def main() -> None:
    np.savez_compressed(
        FINITE_TABLE,
        table=tabulate().astype(np.float32),
        ratios=RATIOS,
        eccentricities=ECCENTRICITIES,
        angles=ANGLES,
    )
    print(f"wrote {FINITE_TABLE}")


if __name__ == "__main__":
    main()

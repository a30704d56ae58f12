"""The Newton iteration matrix of the implicit integrator.

    [ c_M M + c_C C_t + c_K K_t   Φ_qᵀ ]
    [ Φ_q                         0    ]

with K_t = −∂Q/∂q and C_t = −∂Q/∂q̇ the tangent stiffness and damping of the
generalized forces Q (gravity is constant and adds nothing):
- beams: the analytic Jacobians of the elastic and damping forces
  (`sim.model.ancf`), block by block; modal links: their diagonal ω_k² and
  β ω_k² (`sim.model.modal`);
- clearance contacts: forward differences over the few coordinates the contact
  forces depend on (work.contact_coords), which is as cheap as it is simple
  here: a contact evaluation costs a fraction of a microsecond;
- the geometric stiffness of the constraint forces, ∂(Φ_qᵀλ)/∂q, is left out:
  for pins on rigid bodies it is λ times a lever (kN · 0.2 m), which c_K = β h²
  (≤ 3e-9 s² at h = 1e-4 s) makes a 1e-4 share of the inertia term. It slows
  the Newton contraction marginally and does not change the solution.
The constraint Jacobian Φ_q is read from work.jac, evaluated at the same state.
"""

import numpy as np

from sim.jit import kernel, kernel_inline
from sim.model import ancf, modal
from sim.solve.dae import contact_forces

FD_STEP_Q = 1e-10
"""Forward-difference step of positions (m) and angles (rad): far below the
penetrations that matter (> 1e-8 m) so that the δ^1.5 law is resolved."""
FD_STEP_QD = 1e-8
"""Forward-difference step of velocities (m/s, rad/s): far below the friction
tolerance v0 = 1e-4 m/s over which the friction coefficient ramps."""


def iteration_pattern(
    system, col_block: np.ndarray, jac_cols: np.ndarray, jac_ncols: np.ndarray, contact_coords
) -> np.ndarray:
    """Where `iteration_matrix` can write a nonzero, (n + m) × (n + m) bool: within each
    mass block (the mass matrix, a beam's tangents, a modal link's diagonal), between every
    two coordinates the contact forces depend on, and where Φ_q and Φ_qᵀ can be nonzero
    (`jac_cols`, `jac_ncols`: the columns of each row of Φ_q)."""
    n, m = system.n, system.m
    nonzero = np.zeros((n + m, n + m), dtype=bool)
    nonzero[:n, :n] = col_block[:, None] == col_block[None, :]
    nonzero[np.ix_(contact_coords, contact_coords)] = True
    for r in range(m):
        cols = jac_cols[r, : jac_ncols[r]]
        nonzero[n + r, cols] = True
        nonzero[cols, n + r] = True
    return nonzero


@kernel_inline
def _contact_force_acts(sys, work, mem, q: np.ndarray, qd: np.ndarray) -> bool:
    """The clearance contact forces at (q, q̇) into work.fd_base; whether any is nonzero."""
    contact_forces(sys, work, q, qd, mem, work.fd_base)
    for i in work.contact_coords:
        if work.fd_base[i] != 0.0:
            return True
    return False


@kernel
def _add_contact_tangent(sys, work, mat, mem, q, qd, x: np.ndarray, step: float, coef: float):
    """mat[i, c] −= coef ∂Q_i/∂x_c for the contact coordinates, x being q or q̇, the contact
    forces at (q, q̇) in work.fd_base."""
    coords = work.contact_coords
    for a in range(coords.shape[0]):
        c = coords[a]
        saved = x[c]
        x[c] = saved + step
        contact_forces(sys, work, q, qd, mem, work.fd_gen)
        x[c] = saved
        for b in range(coords.shape[0]):
            i = coords[b]
            mat[i, c] -= coef * (work.fd_gen[i] - work.fd_base[i]) / step


@kernel
def _add_beam_tangent(sys, work, mat, q, qd, c_c: float, c_k: float) -> None:
    """mat += c_K ∂F/∂q + c_C ∂F_d/∂q̇ (+ c_K ∂F_d/∂q) of every beam's elastic
    (and damping) forces F = −Q_beam."""
    for b in range(sys.beam_off.shape[0]):
        o = sys.beam_off[b]
        size = 4 * (sys.beam_nel[b] + 1)
        qb = q[o : o + size]
        kq = work.beam_kq[:size, :size]
        ancf.beam_elastic_jacobian(
            qb,
            sys.beam_dshape[b],
            sys.beam_axial_w[b],
            sys.beam_d2shape[b],
            sys.beam_bending_w[b],
            kq,
        )
        for i in range(size):
            for k in range(size):
                mat[o + i, o + k] += c_k * kq[i, k]
        beta = sys.beam[b].damping
        if beta > 0.0:
            kv = work.beam_kv[:size, :size]
            ancf.beam_damping_jacobians(
                qb,
                qd[o : o + size],
                sys.beam_dshape[b],
                sys.beam_axial_w[b],
                sys.beam_d2shape[b],
                sys.beam_bending_w[b],
                beta,
                kq,
                kv,
            )
            for i in range(size):
                for k in range(size):
                    mat[o + i, o + k] += c_k * kq[i, k] + c_c * kv[i, k]


@kernel
def iteration_matrix(
    sys, work, mat, mem, t: float, q: np.ndarray, qd: np.ndarray, c_m: float, c_c: float, c_k: float
) -> None:
    """Assemble the (n + m)² iteration matrix into mat."""
    n = sys.n
    m = sys.m
    mat[:, :] = 0.0
    for blk in range(sys.blk_start.shape[0]):
        for i in range(sys.blk_start[blk], sys.blk_end[blk]):
            for k in range(sys.blk_start[blk], sys.blk_end[blk]):
                mat[i, k] = c_m * sys.mass[i, k]
    _add_beam_tangent(sys, work, mat, q, qd, c_c, c_k)
    modal.add_modal_tangent(sys, mat, c_c, c_k)
    # without a contact force no clearance contact is closed (or within FD_STEP_Q of closing,
    # whose tangent, c_K times a Hertz stiffness at 1e-10 m, is 1e-5 of the inertia's): its
    # tangent is zero, and the 2 × contact-coordinates evaluations of the differences are saved
    if work.contact_coords.shape[0] > 0 and _contact_force_acts(sys, work, mem, q, qd):
        _add_contact_tangent(sys, work, mat, mem, q, qd, q, FD_STEP_Q, c_k)
        _add_contact_tangent(sys, work, mat, mem, q, qd, qd, FD_STEP_QD, c_c)
    for r in range(m):
        for i in range(n):
            mat[i, n + r] = work.jac[r, i]
            mat[n + r, i] = work.jac[r, i]

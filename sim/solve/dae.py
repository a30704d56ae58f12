"""The equations of motion as a first-order system for the integrator.

Lagrange multiplier form with Baumgarte stabilisation (Baumgarte, Comput. Meth.
Appl. Mech. Eng. 1, 1972; Nikravesh 1988, ch. 13):

    [ M   Φ_qᵀ ] [ q̈ ]   [ Q                         ]
    [ Φ_q  0   ] [ λ  ] = [ γ − 2α(Φ_q q̇ − ν) − β² Φ ]

Q collects gravity, contact and (negative) elastic forces. M is constant and
block diagonal, so the system is solved through the Schur complement
S = Φ_q M⁻¹ Φ_qᵀ (small, symmetric positive definite when Φ_q has full row rank):
S λ = Φ_q M⁻¹ Q − b, then q̈ = M⁻¹ (Q − Φ_qᵀ λ).

A mechanism of rigid bodies and modal links whose ideal joints form a tree (`System.tree`,
sim.model.tree) needs no multipliers: with q̇ = J ż and q̈ = J z̈ + a_b in the angles z of its
undriven bodies and the modal amplitudes of its modal links,

    (Jᵀ M J) z̈ = Jᵀ (Q − M a_b),        τ = J_dᵀ (M q̈ − Q)

(Kane & Levinson, Dynamics, 1985: the hinges' reactions do no work along J), J_d the
driven angle's column and τ the drive torque. It gives the same q̈ as the multiplier form
on the constraint manifold, without Φ, Φ_q, S or Baumgarte terms.

State y = (q, q̇, W_drive, E_dissipated): the last two are quadratures of the
drive power τ θ̇ and of the dissipated power, integrated with the motion so that
the energy audit uses the integrator's own accuracy.
"""

import numpy as np

from sim.jit import kernel, kernel_inline, spliced
from sim.model.beams import beam_damping_power, beam_forces
from sim.model.clearance import revolute_clearance_forces, translational_clearance_forces
from sim.model.constraints import constraint_terms
from sim.model.tree import tree_kinematics
from sim.solve.linalg import cholesky_in_place, cholesky_solve_in_place
from sim.solve.status import NONFINITE, OK, SINGULAR

# Scalars a right-hand side evaluation leaves behind, indices into Work.scalars.
SC_DRIVE_TORQUE, SC_DISSIPATED_POWER, SC_CONTACT_ENERGY = range(3)
N_SCALARS = 3


@kernel
def block_times(sys, matrix: np.ndarray, x: np.ndarray, out: np.ndarray) -> None:
    """out = A x for a matrix A with the mass matrix's block-diagonal pattern (M or M⁻¹)."""
    for b in range(sys.blk_start.shape[0]):
        s = sys.blk_start[b]
        e = sys.blk_end[b]
        for i in range(s, e):
            acc = 0.0
            for k in range(s, e):
                acc += matrix[i, k] * x[k]
            out[i] = acc


@spliced
def no_rotations(work) -> np.ndarray:
    """An empty table of rotations: the contact forces compute each body's (cos θ, sin θ)
    from q (sim.model.kinematics.frame_rotation). A view, so nothing is allocated."""
    return work.tree_rot[:0]


@kernel_inline
def generalized_forces(
    sys, work, t: float, q: np.ndarray, qd: np.ndarray, mem: np.ndarray, rot: np.ndarray
) -> None:
    """Q = gravity + contact − elastic − damping forces into work.gen; the dissipated power
    and the stored contact energy into work.scalars. rot: the bodies' (cos θ, sin θ) at q when
    the tree has them (work.tree_rot), else empty (`no_rotations`)."""
    gen = work.gen
    for i in range(sys.n):
        gen[i] = sys.gravity_force[i]
    pr, ur = revolute_clearance_forces(sys, q, qd, mem, gen, work.jout, rot)
    pt, ut = translational_clearance_forces(sys, q, qd, mem, gen, work.jout, rot)
    pb = beam_forces(sys, q, qd, gen, work.scratch)
    work.scalars[SC_DISSIPATED_POWER] = pr + pt + pb
    work.scalars[SC_CONTACT_ENERGY] = ur + ut


@kernel
def contact_forces(sys, work, q: np.ndarray, qd: np.ndarray, mem: np.ndarray, out) -> float:
    """The generalized clearance contact forces alone into `out` (N, N·m), their
    per-joint outputs discarded; returns the power their damping and friction
    dissipate (W). Leaves the evaluation that work holds intact."""
    out[:] = 0.0
    pr, _ = revolute_clearance_forces(sys, q, qd, mem, out, work.fd_jout, no_rotations(work))
    pt, _ = translational_clearance_forces(sys, q, qd, mem, out, work.fd_jout, no_rotations(work))
    return pr + pt


@kernel
def dissipated_power(sys, work, q: np.ndarray, qd: np.ndarray, mem: np.ndarray) -> float:
    """The power dissipated at (q, q̇) by contact damping, friction and beam
    damping (W), computed aside: the evaluation that work holds is left intact,
    and the beams' elastic forces, which dissipate nothing, are not evaluated."""
    return contact_forces(sys, work, q, qd, mem, work.fd_gen) + beam_damping_power(
        sys, q, qd, work.scratch
    )


@kernel
def rhs(sys, work, mem: np.ndarray, t: float, y: np.ndarray, ydot: np.ndarray) -> int:
    """`rhs_inline` compiled once and called: for the callers that evaluate once per step or
    sample (an event, a sample, a start)."""
    return rhs_inline(sys, work, mem, t, y, ydot)


@kernel_inline
def rhs_inline(sys, work, mem: np.ndarray, t: float, y: np.ndarray, ydot: np.ndarray) -> int:
    """ẏ = f(t, y); returns OK, SINGULAR (constraint Jacobian lost rank) or NONFINITE.
    Inlined into DOPRI5's stages (`sim.solve.dopri`), which evaluate it six times a step: a
    call passes `System` and `Work` field by field, which took 0.09 µs of the 0.62 µs of one
    evaluation of the rigid flagship."""
    if sys.tree.shape[0] > 0:
        return tree_accelerations(sys, work, mem, t, y, ydot)
    n = sys.n
    q = y[:n]
    qd = y[n : 2 * n]
    generalized_forces(sys, work, t, q, qd, mem, no_rotations(work))
    if sys.m > 0:
        constraint_terms(sys, t, q, qd, work.phi, work.jac, work.gamma, work.nu)
    return accelerations(sys, work, qd, ydot)


@kernel_inline
def accelerations(sys, work, qd: np.ndarray, ydot: np.ndarray) -> int:
    """ẏ from the forces and constraint terms that work holds for a state with
    velocities q̇: the Schur-complement solve of the module docstring."""
    if sys.m > 0 and factor_schur(sys, work) != OK:
        return SINGULAR
    return factored_accelerations(sys, work, qd, ydot)


@kernel
def factor_schur(sys, work) -> int:
    """M⁻¹ Φ_qᵀ into work.minv_jt and the Cholesky factor of the Schur complement
    S = Φ_q M⁻¹ Φ_qᵀ into work.schur, from the Φ_q that work holds. Φ_q is sparse
    (a row touches at most two bodies), so its products run over the nonzero
    columns of each row (work.jac_cols) only. OK, or SINGULAR when Φ_q has lost
    rank."""
    m = sys.m
    jac = work.jac
    cols = work.jac_cols
    y_mt = work.minv_jt
    y_mt[:, :] = 0.0
    for r in range(m):
        for c in range(work.jac_ncols[r]):
            k = cols[r, c]
            blk = work.col_block[k]
            for i in range(sys.blk_start[blk], sys.blk_end[blk]):
                y_mt[i, r] += sys.mass_inv[i, k] * jac[r, k]
    # Only the entries that can be nonzero (work.schur_pairs) are summed; the
    # others are exact zeros, so S is the same to the bit.
    schur = work.schur
    schur[:, :] = 0.0
    for p in range(work.schur_pairs.shape[0]):
        i = work.schur_pairs[p, 0]
        j = work.schur_pairs[p, 1]
        acc = 0.0
        for c in range(work.jac_ncols[i]):
            k = cols[i, c]
            acc += jac[i, k] * y_mt[k, j]
        schur[i, j] = acc
        schur[j, i] = acc
    return OK if cholesky_in_place(schur, m, work.schur_first) else SINGULAR


@kernel
def _velocity_residual(work, r: int, qd: np.ndarray) -> float:
    """Φ_q q̇ − ν of constraint row r."""
    vel = -work.nu[r]
    for c in range(work.jac_ncols[r]):
        k = work.jac_cols[r, c]
        vel += work.jac[r, k] * qd[k]
    return vel


@kernel
def project_velocities(sys, work, qd: np.ndarray) -> None:
    """q̇ ← q̇ − M⁻¹ Φ_qᵀ S⁻¹ (Φ_q q̇ − ν): the velocity nearest to q̇ in the
    kinetic-energy norm that satisfies the velocity constraints Φ_q q̇ = ν
    (a mass-orthogonal projection, e.g. Bayo & Ledesma, Nonlinear Dyn. 9, 1996).
    Needs `factor_schur` at the same Φ_q; uses work.rhs."""
    m = sys.m
    mu = work.rhs
    for r in range(m):
        mu[r] = _velocity_residual(work, r, qd)
    cholesky_solve_in_place(work.schur, m, mu)
    _less_constraint_term(sys, work, qd, mu, qd)


@kernel
def _less_constraint_term(sys, work, base: np.ndarray, mult: np.ndarray, out: np.ndarray) -> None:
    """out = base − M⁻¹ Φ_qᵀ mult, with M⁻¹ Φ_qᵀ from `factor_schur`; out may be base.
    Row i of M⁻¹ Φ_qᵀ is zero but for the rows of Φ_q in work.coord_rows."""
    for i in range(sys.n):
        acc = base[i]
        for c in range(work.coord_nrows[i]):
            r = work.coord_rows[i, c]
            acc -= work.minv_jt[i, r] * mult[r]
        out[i] = acc


@kernel_inline
def tree_accelerations(
    sys, work, mem: np.ndarray, t: float, y: np.ndarray, ydot: np.ndarray
) -> int:
    """ẏ of a tree mechanism (module docstring): its kinematics rebuilt from the angles
    that y holds, the forces there, and the projected equations of motion; the drive
    torque from the driven angle's column. q̇ in ẏ is the rebuilt one, so ẏ depends on y
    through the angles and their rates only. OK, SINGULAR or NONFINITE."""
    n = sys.n
    q = work.tree_q
    qd = work.tree_qd
    jac = work.tree_jac
    bias = work.tree_bias
    tree_kinematics(sys, t, y, q, qd, jac, bias, work.tree_rot)
    generalized_forces(sys, work, t, q, qd, mem, work.tree_rot)
    gen = work.gen
    mz = work.tree_mass
    zdd = work.tree_zdd
    free = zdd.shape[0]
    zdd[:] = 0.0
    mz[:, :] = 0.0
    # row by row, the lower triangle only (all the factorisation reads), over the columns
    # where the row can be nonzero (ascending, the driven angle's last): a body's rows are
    # zero in the columns of the bodies that do not move it
    cols = work.tree_cols
    for i in range(n):
        m_i = sys.mass[i, i]
        f_i = gen[i] - m_i * bias[i]
        for ka in range(work.tree_ncols[i]):
            a = cols[i, ka]
            if a == free:
                break
            j_ia = jac[i, a]
            zdd[a] += j_ia * f_i
            mj = m_i * j_ia
            for kb in range(ka + 1):
                b = cols[i, kb]
                mz[a, b] += mj * jac[i, b]
    if not cholesky_in_place(mz, free, work.tree_first):
        return SINGULAR
    cholesky_solve_in_place(mz, free, zdd)
    qdd = work.qdd
    torque = 0.0
    for i in range(n):
        acc = bias[i]
        j_drive = 0.0
        for ka in range(work.tree_ncols[i]):
            a = cols[i, ka]
            if a == free:
                j_drive = jac[i, a]
                break
            acc += jac[i, a] * zdd[a]
        qdd[i] = acc
        torque += j_drive * (sys.mass[i, i] * acc - gen[i])
    drive_power = torque * qd[sys.drive_coord]
    return _finish_derivative(sys, work, qd, torque, drive_power, ydot)


@kernel_inline
def _finish_derivative(sys, work, qd, torque: float, drive_power: float, ydot) -> int:
    """ẏ = (q̇, q̈, drive power, dissipated power) from work.qdd; the torque into
    work.scalars. NONFINITE if any entry is not finite, else OK."""
    n = sys.n
    work.scalars[SC_DRIVE_TORQUE] = torque
    for i in range(n):
        ydot[i] = qd[i]
        ydot[n + i] = work.qdd[i]
    ydot[2 * n] = drive_power
    ydot[2 * n + 1] = work.scalars[SC_DISSIPATED_POWER]
    for i in range(2 * n + 2):
        if not np.isfinite(ydot[i]):
            return NONFINITE
    return OK


@kernel_inline
def project_onto_tree(sys, work, t: float, y: np.ndarray) -> None:
    """Overwrite the absolute q and q̇ in y with those the tree's angles and rates give
    (and the driven angle with the drive's): the projection onto the constraint manifold
    at every start from a given state. A no-op without a tree. Inlined (sim.jit): once the
    tree carried modal links, LLVM stopped inlining it into the step, and the call, with
    `System` and `Work` passed field by field, made rigid runs 8 % slower."""
    if sys.tree.shape[0] == 0:
        return
    tree_kinematics(
        sys, t, y, work.tree_q, work.tree_qd, work.tree_jac, work.tree_bias, work.tree_rot
    )
    adopt_tree_state(sys, work, y)


@kernel_inline
def adopt_tree_state(sys, work, y: np.ndarray) -> None:
    """Overwrite the absolute q and q̇ in y with those the last evaluation rebuilt from the
    tree (work.tree_q, work.tree_qd): `project_onto_tree` without rebuilding them, when that
    evaluation was at y itself, as DOPRI5's last stage is at the step's end. A no-op without
    a tree."""
    if sys.tree.shape[0] == 0:
        return
    n = sys.n
    for i in range(n):
        y[i] = work.tree_q[i]
        y[n + i] = work.tree_qd[i]


@kernel_inline
def factored_accelerations(sys, work, qd: np.ndarray, ydot: np.ndarray) -> int:
    """`accelerations` with the Schur complement already factored (`factor_schur`)."""
    n = sys.n
    m = sys.m
    block_times(sys, sys.mass_inv, work.gen, work.minv_gen)
    qdd = work.qdd
    if m > 0:
        jac = work.jac
        alpha = sys.baumgarte[0]
        beta = sys.baumgarte[1]
        b = work.rhs
        for r in range(m):
            acc = 0.0
            for c in range(work.jac_ncols[r]):
                k = work.jac_cols[r, c]
                acc += jac[r, k] * work.minv_gen[k]
            vel = _velocity_residual(work, r, qd)
            b[r] = acc - (work.gamma[r] - 2.0 * alpha * vel - beta * beta * work.phi[r])
        cholesky_solve_in_place(work.schur, m, b)
        _less_constraint_term(sys, work, work.minv_gen, b, qdd)
    else:
        for i in range(n):
            qdd[i] = work.minv_gen[i]
    torque = 0.0
    drive_power = 0.0
    if sys.drive_row >= 0:
        # The drive row of Φ_q is the unit vector of the driven angle, so its
        # constraint force on that coordinate is −λ: the motor's torque.
        torque = -work.rhs[sys.drive_row]
        drive_power = torque * qd[sys.drive_coord]
    return _finish_derivative(sys, work, qd, torque, drive_power, ydot)


@kernel
def kinetic_energy(sys, work, qd: np.ndarray) -> float:
    """T = ½ q̇ᵀ M q̇ (J)."""
    momentum = work.scratch
    block_times(sys, sys.mass, qd, momentum)
    total = 0.0
    for i in range(sys.n):
        total += qd[i] * momentum[i]
    return 0.5 * total


@kernel
def potential_energy(sys, q: np.ndarray) -> float:
    """Gravitational potential V = −Q_gᵀ q (J): gravity is uniform, so its
    generalized force is constant and V is linear in q for rigid bodies and
    ANCF beams alike."""
    total = 0.0
    for i in range(sys.n):
        total -= sys.gravity_force[i] * q[i]
    return total

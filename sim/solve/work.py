"""The scratch arrays of one simulation, and the constant structure the kernels read with
them (sparsity patterns, the contact coordinates): `Work`, made once by `make_work`."""

from typing import NamedTuple

import numpy as np

from sim.model.constraints import constraint_terms
from sim.model.gaps import n_gaps
from sim.model.system import (
    N_JOINT_OUT,
    POINT_MODAL,
    POINT_NODE,
    POINT_RIGID,
    System,
    n_clearance_joints,
)
from sim.model.tree import tree_columns, tree_pattern
from sim.solve.dae import N_SCALARS
from sim.solve.linalg import LUPattern, lu_pattern
from sim.solve.tangent import iteration_pattern


class Work(NamedTuple):
    """Scratch arrays owned by one simulation; the compiled loop allocates nothing. Nothing
    here outlives a step: what one step hands to the next, and an integration method's own
    scratch, is the method's carry (`sim.solve.methods.make_carry`)."""

    phi: np.ndarray  # (m,) constraint values
    jac: np.ndarray  # (m, n) Φ_q
    gamma: np.ndarray  # (m,)
    nu: np.ndarray  # (m,)
    rhs: np.ndarray  # (m,) Schur right-hand side, then λ
    gen: np.ndarray  # (n,) generalized forces Q
    minv_gen: np.ndarray  # (n,) M⁻¹ Q
    minv_jt: np.ndarray  # (n, m) M⁻¹ Φ_qᵀ
    schur: np.ndarray  # (m, m)
    qdd: np.ndarray  # (n,)
    jout: np.ndarray  # (joints, N_JOINT_OUT) per clearance joint outputs
    scalars: np.ndarray  # (3,) what an evaluation leaves behind: sim.solve.dae's SC_*
    scratch: np.ndarray  # (n,) scratch: beam forces, momenta
    ydot_end: np.ndarray  # (ny,) ẏ at the step's end (DOPRI5's k7, FSAL)
    ytmp: np.ndarray  # (ny,)
    ynew: np.ndarray  # (ny,)
    yint: np.ndarray  # (ny,) interpolated state of an output sample
    dense: np.ndarray  # (5, ny) dense-output coefficients of the last step
    gaps: np.ndarray  # (ngaps,) every gap's δ at the end of a step (stepping._first_event)
    jac_cols: np.ndarray  # (m, k) the columns where each row of Φ_q can be nonzero
    jac_ncols: np.ndarray  # (m,) how many
    col_block: np.ndarray  # (n,) the mass block of each coordinate
    # The implicit method's iteration matrix (sim.solve.tangent):
    beam_kq: np.ndarray  # (s, s) one beam's stiffness Jacobian, s its largest size
    beam_kv: np.ndarray  # (s, s) one beam's damping Jacobian
    fd_base: np.ndarray  # (n,) contact forces at the unperturbed state
    fd_gen: np.ndarray  # (n,) contact forces at a perturbed state, or evaluated aside
    fd_jout: np.ndarray  # (joints, N_JOINT_OUT) their discarded outputs
    contact_coords: np.ndarray  # coordinates the clearance contact forces depend on
    newton_lu: LUPattern  # where the iteration matrix's LU factors can be nonzero
    # The sparsity of the Schur complement Φ_q M⁻¹ Φ_qᵀ (factor_schur):
    schur_pairs: np.ndarray  # (p, 2) rows (i, j ≤ i) of Φ_q that share a mass block
    schur_first: np.ndarray  # (m,) first column where row i of S (and of its factor) can be nonzero
    coord_rows: np.ndarray  # (n, k) the rows of Φ_q that touch each coordinate's mass block
    coord_nrows: np.ndarray  # (n,) how many
    # Minimal coordinates (System.tree, sim.model.tree); zero-sized without a tree:
    tree_q: np.ndarray  # (n,) absolute q rebuilt from the angles
    tree_qd: np.ndarray  # (n,) absolute q̇
    tree_jac: np.ndarray  # (n, columns) J = ∂q̇/∂ż, the driven angle's column last
    tree_bias: np.ndarray  # (n,) centripetal accelerations a_b
    tree_rot: np.ndarray  # (n, 2) (cos θ, sin θ) of each body, at its offset
    tree_mass: np.ndarray  # (columns − 1, columns − 1) Jᵀ M J, then its Cholesky factor
    tree_zdd: np.ndarray  # (columns − 1,) Jᵀ (Q − M a_b), then z̈
    tree_first: np.ndarray  # (columns − 1,) zeros: Jᵀ M J is dense
    tree_cols: np.ndarray  # (n, columns) the columns where each row of J can be nonzero
    tree_ncols: np.ndarray  # (n,) how many (sim.model.tree.tree_pattern)


def state_size(system: System) -> int:
    """Length of y: q, q̇ and the two energy quadratures."""
    return 2 * system.n + 2


def contact_coordinates(system: System) -> np.ndarray:
    """Sorted coordinates of the bodies and nodes that clearance joints touch (a
    modal link's frame and modes)."""
    coords = set()
    for pts in system.rj_pts:
        for k in pts:
            o = int(system.pt_off[k])
            if system.pt_kind[k] in (POINT_RIGID, POINT_MODAL):
                coords.update(range(o, o + 3 + int(system.pt_modes[k])))
            elif system.pt_kind[k] == POINT_NODE:
                coords.update(range(o, o + 2))
    for o in system.tj_off:
        coords.update(range(int(o), int(o) + 3))
    return np.array(sorted(coords), dtype=np.int64)


def jacobian_pattern(system: System) -> tuple[np.ndarray, np.ndarray]:
    """The columns where each row of Φ_q can be nonzero, from Φ_q at a generic
    state (angles and slopes away from the values where an entry vanishes)."""
    rng = np.random.default_rng(0)
    q = rng.uniform(0.1, 1.0, system.n)
    jac = np.zeros((system.m, system.n))
    scratch = np.zeros(system.m)
    constraint_terms(system, 0.0, q, q, scratch, jac, scratch.copy(), scratch.copy())
    rows = [np.flatnonzero(row) for row in jac]
    width = max((r.size for r in rows), default=0)
    cols = np.zeros((system.m, width), dtype=np.int64)
    for i, r in enumerate(rows):
        cols[i, : r.size] = r
    return cols, np.array([r.size for r in rows], dtype=np.int64)


def constraint_sparsity(
    jac_cols: np.ndarray, jac_ncols: np.ndarray, col_block: np.ndarray
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Where the products of `factor_schur` can be nonzero. M⁻¹ is block diagonal, so
    rows i and j of Φ_q couple in S = Φ_q M⁻¹ Φ_qᵀ only when they touch a common mass
    block (a chain of joints couples each row to few others), and row i of M⁻¹ Φ_qᵀ
    is nonzero only in the rows of Φ_q that touch coordinate i's block. Returns the
    entries (i, j ≤ i) of S that can be nonzero, the first of them in each row of S
    (its envelope, outside which a Cholesky factor has no fill-in), and per
    coordinate its rows of Φ_q (ascending) and how many."""
    blocks = [set(col_block[jac_cols[r, : jac_ncols[r]]].tolist()) for r in range(jac_ncols.size)]
    pairs = [(i, j) for i in range(len(blocks)) for j in range(i + 1) if blocks[i] & blocks[j]]
    first = [min(j for i, j in pairs if i == row) for row in range(len(blocks))]
    rows = [[r for r, b in enumerate(blocks) if col_block[k] in b] for k in range(col_block.size)]
    coord_rows = np.zeros((col_block.size, max(map(len, rows), default=0)), dtype=np.int64)
    for k, r in enumerate(rows):
        coord_rows[k, : len(r)] = r
    return (
        np.array(pairs, dtype=np.int64).reshape(-1, 2),
        np.array(first, dtype=np.int64),
        coord_rows,
        np.array([len(r) for r in rows], dtype=np.int64),
    )


def make_work(system: System) -> Work:
    """Allocate the scratch arrays for `system`."""
    n, m, ny = system.n, system.m, state_size(system)
    jac_cols, jac_ncols = jacobian_pattern(system)
    col_block = np.zeros(n, dtype=np.int64)
    for b, (start, end) in enumerate(zip(system.blk_start, system.blk_end, strict=True)):
        col_block[start:end] = b
    beam_size = 4 * (int(system.beam_nel.max()) + 1) if system.beam_nel.size else 0
    pairs, first, coord_rows, coord_nrows = constraint_sparsity(jac_cols, jac_ncols, col_block)
    contacts = contact_coordinates(system)
    columns = tree_columns(system.tree)
    free = max(columns - 1, 0)
    n_tree = n if columns else 0
    tree_cols, tree_ncols = tree_pattern(system.tree, n)
    return Work(
        phi=np.zeros(m),
        jac=np.zeros((m, n)),
        gamma=np.zeros(m),
        nu=np.zeros(m),
        rhs=np.zeros(m),
        gen=np.zeros(n),
        minv_gen=np.zeros(n),
        minv_jt=np.zeros((n, m)),
        schur=np.zeros((m, m)),
        qdd=np.zeros(n),
        jout=np.zeros((n_clearance_joints(system), N_JOINT_OUT)),
        scalars=np.zeros(N_SCALARS),
        scratch=np.zeros(n),
        ydot_end=np.zeros(ny),
        ytmp=np.zeros(ny),
        ynew=np.zeros(ny),
        yint=np.zeros(ny),
        dense=np.zeros((5, ny)),
        gaps=np.zeros(n_gaps(system)),
        jac_cols=jac_cols,
        jac_ncols=jac_ncols,
        col_block=col_block,
        beam_kq=np.zeros((beam_size, beam_size)),
        beam_kv=np.zeros((beam_size, beam_size)),
        fd_base=np.zeros(n),
        fd_gen=np.zeros(n),
        fd_jout=np.zeros((n_clearance_joints(system), N_JOINT_OUT)),
        contact_coords=contacts,
        newton_lu=lu_pattern(iteration_pattern(system, col_block, jac_cols, jac_ncols, contacts)),
        schur_pairs=pairs,
        schur_first=first,
        coord_rows=coord_rows,
        coord_nrows=coord_nrows,
        tree_q=np.zeros(n_tree),
        tree_qd=np.zeros(n_tree),
        tree_jac=np.zeros((n_tree, columns)),
        tree_bias=np.zeros(n_tree),
        tree_rot=np.zeros((n_tree, 2)),
        tree_mass=np.zeros((free, free)),
        tree_zdd=np.zeros(free),
        tree_first=np.zeros(free, dtype=np.int64),
        tree_cols=tree_cols,
        tree_ncols=tree_ncols,
    )

"""ANCF beams inside a system: gravity, reference point and the elastic and
damping forces of every beam (the element kernels live in `sim.model.ancf`), and
of every modal link (`sim.model.modal`), so that the equations of motion see one
call for the elastic links of either kind.

Cubic Hermite shape functions of the planar ANCF element (Shabana, Dynamics of
Multibody Systems, 3rd ed., 2005, ch. 7; the paper's eq. 20), ξ = x/l:
S1 = 1 − 3ξ² + 2ξ³, S2 = l(ξ − 2ξ² + ξ³), S3 = 3ξ² − 2ξ³, S4 = l(ξ³ − ξ²).
"""

import numpy as np

from sim.jit import kernel, kernel_inline
from sim.model import ancf, modal


def hermite_shape(xi: float, length: float) -> np.ndarray:
    """(S1, S2, S3, S4) at ξ for an element of length l (m)."""
    return np.array(
        [
            1.0 - 3.0 * xi**2 + 2.0 * xi**3,
            length * (xi - 2.0 * xi**2 + xi**3),
            3.0 * xi**2 - 2.0 * xi**3,
            length * (xi**3 - xi**2),
        ]
    )


def midpoint_shape(length: float, elements: int) -> tuple[int, np.ndarray]:
    """Element index and shape values of the beam's mid-length material point."""
    el_len = length / elements
    el = min(int(0.5 * length / el_len), elements - 1)
    return el, hermite_shape((0.5 * length - el * el_len) / el_len, el_len)


def beam_gravity_force(rho_a: float, length: float, elements: int, g: np.ndarray) -> np.ndarray:
    """Generalized gravity force ∫ ρA Sᵀ g dx of a beam (N): per element
    ρA (l/2, l²/12, l/2, −l²/12) on (r_i, r'_i, r_j, r'_j), each times g."""
    el_len = length / elements
    out = np.zeros(4 * (elements + 1))
    weights = rho_a * np.array([el_len / 2, el_len**2 / 12, el_len / 2, -(el_len**2) / 12])
    for e in range(elements):
        for k, w in enumerate(weights):
            out[4 * e + 2 * k : 4 * e + 2 * k + 2] += w * g
    return out


@kernel_inline
def beam_forces(sys, q: np.ndarray, qd: np.ndarray, gen: np.ndarray, scratch: np.ndarray):
    """Subtract the elastic forces (and the stiffness-proportional damping forces,
    where a link has a damping coefficient) of every beam and modal link from
    `gen`; return the power they dissipate (W). The strain energy is `strain_energy`'s: only
    the samples need it, not every evaluation."""
    p_diss = modal.modal_forces(sys, q, qd, gen)
    for b in range(sys.beam_off.shape[0]):
        o = sys.beam_off[b]
        size = 4 * (sys.beam_nel[b] + 1)
        qb = q[o : o + size]
        out = scratch[:size]
        dshape = sys.beam_dshape[b]
        axial_w = sys.beam_axial_w[b]
        d2shape = sys.beam_d2shape[b]
        bending_w = sys.beam_bending_w[b]
        ancf.beam_elastic_forces(qb, dshape, axial_w, d2shape, bending_w, out)
        for i in range(size):
            gen[o + i] -= out[i]
        if sys.beam[b].damping > 0.0:
            p_diss += _damping_forces(sys, b, q, qd, out)
            for i in range(size):
                gen[o + i] -= out[i]
    return p_diss


@kernel
def strain_energy(sys, q: np.ndarray) -> float:
    """The strain energy of every modal link and beam at q (J)."""
    strain = modal.modal_strain_energy(sys, q)
    for b in range(sys.beam_off.shape[0]):
        o = sys.beam_off[b]
        size = 4 * (sys.beam_nel[b] + 1)
        strain += ancf.beam_strain_energy(
            q[o : o + size],
            sys.beam_dshape[b],
            sys.beam_axial_w[b],
            sys.beam_d2shape[b],
            sys.beam_bending_w[b],
        )
    return strain


@kernel
def _damping_forces(sys, b: int, q: np.ndarray, qd: np.ndarray, out: np.ndarray) -> float:
    """The stiffness-proportional damping forces F_d of beam b into out (its
    coordinates, N); returns the power they dissipate, F_d · q̇ (W)."""
    o = sys.beam_off[b]
    size = 4 * (sys.beam_nel[b] + 1)
    qdb = qd[o : o + size]
    ancf.beam_damping_forces(
        q[o : o + size],
        qdb,
        sys.beam_dshape[b],
        sys.beam_axial_w[b],
        sys.beam_d2shape[b],
        sys.beam_bending_w[b],
        sys.beam[b].damping,
        out,
    )
    power = 0.0
    for i in range(size):
        power += out[i] * qdb[i]
    return power


@kernel
def beam_damping_power(sys, q: np.ndarray, qd: np.ndarray, scratch: np.ndarray) -> float:
    """The power dissipated by the damping of every beam and modal link at (q, q̇),
    W; the elastic forces, which dissipate nothing, are not evaluated."""
    power = modal.modal_damping_power(sys, qd)
    for b in range(sys.beam_off.shape[0]):
        if sys.beam[b].damping > 0.0:
            power += _damping_forces(sys, b, q, qd, scratch)
    return power

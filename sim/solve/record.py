"""One output sample: every reported quantity at (t, y), as one row of floats.

The quantities and their order are declared once, in `sim.quantities`; `column_layout`
places them in the row, `write_row` fills it in that order (each block marked with its
quantity's name) and `sim.results` decodes rows with the same layout.
"""

from collections.abc import Mapping
from functools import cache
from types import MappingProxyType

import numpy as np

from sim.jit import kernel
from sim.model import ancf
from sim.model.clearance import eccentricity, eccentricity_rate, guide_frame
from sim.model.constraints import constraint_terms
from sim.model.modal import modal_midspan_deflection
from sim.model.system import (
    OUT_FRICTION_FORCE,
    OUT_NORMAL_FORCE,
    OUT_PENETRATION,
    OUT_STATE,
)
from sim.quantities import PEAK, SAMPLE, recorded, shape
from sim.solve.dae import (
    SC_CONTACT_ENERGY,
    SC_DRIVE_TORQUE,
    SC_STRAIN_ENERGY,
    kinetic_energy,
    potential_energy,
    rhs,
)

Layout = Mapping[str, tuple[int, tuple[int, ...]]]  # read-only: the layouts are cached


def _blocks(quantities, n_bodies: int, n_joints: int, leading: int) -> Layout:
    """Name → (first column, shape) of consecutive blocks, one per quantity, in order; the
    first `leading` dimensions (time) are not part of a block."""
    layout = {}
    col = 0
    for q in quantities:
        block = shape(q.dims[leading:], n_bodies, n_joints)
        layout[q.name] = (col, block)
        col += int(np.prod(block, dtype=int))
    return MappingProxyType(layout)


@cache  # read at every energy audit, a quarter revolution apart: built once per size
def column_layout(n_bodies: int, n_joints: int) -> Layout:
    """Name → (first column, shape per sample) of every sampled quantity (`sim.quantities`,
    recorded SAMPLE), in the table's order, which `write_row` follows."""
    return _blocks(recorded(SAMPLE), n_bodies, n_joints, leading=1)


def _width(layout: Layout) -> int:
    return sum(int(np.prod(block, dtype=int)) for _, block in layout.values())


def row_width(n_bodies: int, n_joints: int) -> int:
    """Number of columns of one sample row."""
    return _width(column_layout(n_bodies, n_joints))


def peak_width(n_bodies: int, n_joints: int) -> int:
    """Number of entries of the integrator's vector of peaks (`peak_layout`)."""
    return _width(peak_layout(n_bodies, n_joints))


@cache
def peak_layout(n_bodies: int, n_joints: int) -> Layout:
    """Name → (first entry, shape) of every PEAK quantity in the integrator's vector of peaks
    (and in each row of its per-revolution peaks, the REVOLUTION_PEAK quantities in the same
    order), which `sim.solve.stepping._update_peaks` fills in the table's order."""
    return _blocks(recorded(PEAK), n_bodies, n_joints, leading=0)


@kernel
def reference_point(sys, b: int, x: np.ndarray, axis: int) -> float:
    """Component `axis` of body b's reference point, applied to q, q̇ or q̈ (x)."""
    acc = 0.0
    for k in range(4):
        acc += sys.ref_coef[b, k] * x[sys.ref_idx[b, k] + axis]
    return acc


@kernel
def beam_midspan_deflection(q: np.ndarray, sys, b: int) -> float:
    """Mid-span deflection (m) of body b, a beam, from the chord of its end nodes."""
    i0 = sys.ang_idx[b, 0]
    k = 0
    while sys.beam_off[k] != i0:
        k += 1
    size = 4 * (sys.beam_nel[k] + 1)
    return ancf.beam_midspan_deflection(
        q[i0 : i0 + size], sys.beam_nel[k], sys.beam[k].element_length
    )


@kernel
def record_row(sys, work, mem: np.ndarray, t: float, y: np.ndarray, row: np.ndarray) -> int:
    """Evaluate the model at (t, y) and write one sample row; returns the
    right-hand side status."""
    status = rhs(sys, work, mem, t, y, work.ytmp)
    if sys.tree.shape[0] > 0:
        # the tree's evaluation forms no Φ: the sample's constraint residual is taken here
        n = sys.n
        constraint_terms(sys, t, y[:n], y[n : 2 * n], work.phi, work.jac, work.gamma, work.nu)
    write_row(sys, work, y, row)
    return status


@kernel
def write_row(sys, work, y: np.ndarray, row: np.ndarray) -> None:
    """Write one sample row of the state y from the evaluation at y that work
    holds (accelerations work.qdd, forces, contact outputs, constraint residual). One block
    per sampled quantity of `sim.quantities`, in its order (tests/core/test_sample_row.py
    checks each block against an independent reference)."""
    n = sys.n
    q = y[:n]
    qd = y[n : 2 * n]
    nb = sys.ref_idx.shape[0]
    c = 0
    # crank_angle
    row[c] = q[sys.drive_coord] if sys.drive_coord >= 0 else 0.0
    c += 1
    # position, velocity, acceleration
    for src in range(3):
        x = q if src == 0 else (qd if src == 1 else work.qdd)
        for b in range(nb):
            for a in range(2):
                row[c] = reference_point(sys, b, x, a)
                c += 1
    # angle
    for b in range(nb):
        i0 = sys.ang_idx[b, 0]
        if sys.body_is_beam[b] == 1:
            i1 = sys.ang_idx[b, 1]
            row[c] = np.arctan2(q[i1 + 1] - q[i0 + 1], q[i1] - q[i0])
        else:
            row[c] = q[i0]
        c += 1
    # deflection
    for b in range(nb):
        row[c] = 0.0
        if sys.body_is_beam[b] == 1:
            row[c] = beam_midspan_deflection(q, sys, b)
        elif sys.body_modal[b] >= 0:
            row[c] = modal_midspan_deflection(sys, sys.body_modal[b], q)
        c += 1
    # drive_torque
    row[c] = work.scalars[SC_DRIVE_TORQUE]
    c += 1
    nr = sys.rj_pts.shape[0]
    nj = nr + sys.tj_off.shape[0]
    # eccentricity, eccentricity_rate
    for j in range(nj):
        if j < nr:
            ex, ey = eccentricity(sys, j, q)
            vx, vy = eccentricity_rate(sys, j, q, qd)
        else:
            # Slider centre relative to the guide's point: x across, y along.
            k = j - nr
            o = sys.tj_off[k]
            tx, ty, nx, ny = guide_frame(sys, k)
            dx = q[o] - sys.tj[k].px
            dy = q[o + 1] - sys.tj[k].py
            ex = dx * nx + dy * ny
            ey = dx * tx + dy * ty
            vx = qd[o] * nx + qd[o + 1] * ny
            vy = qd[o] * tx + qd[o + 1] * ty
        row[c + 2 * j] = ex
        row[c + 2 * j + 1] = ey
        row[c + 2 * nj + 2 * j] = vx
        row[c + 2 * nj + 2 * j + 1] = vy
    c += 4 * nj
    # penetration, normal_force, friction_force, in_contact
    for out in (OUT_PENETRATION, OUT_NORMAL_FORCE, OUT_FRICTION_FORCE, OUT_STATE):
        for j in range(nj):
            row[c] = work.jout[j, out]
            c += 1
    # constraint_violation
    viol = 0.0
    for i in range(sys.m):
        viol += work.phi[i] * work.phi[i]
    row[c] = np.sqrt(viol)
    row[c + 1] = kinetic_energy(sys, work, qd)  # kinetic_energy
    row[c + 2] = potential_energy(sys, q)  # potential_energy
    row[c + 3] = work.scalars[SC_STRAIN_ENERGY]  # strain_energy
    row[c + 4] = work.scalars[SC_CONTACT_ENERGY]  # contact_energy
    row[c + 5] = y[2 * n]  # drive_work
    row[c + 6] = y[2 * n + 1]  # dissipated_energy

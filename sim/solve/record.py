"""One output sample: every reported quantity at (t, y), as one row of floats.

The quantities and their order are declared once, in `sim.quantities`; `column_layout`
places them in the row, `write_row` fills it in that order (each block marked with its
quantity's name) and `sim.results` decodes rows with the same layout. The compiled code that
reads or writes single blocks (the interval means, `sim.solve.means`; the peaks,
`sim.solve.stepping._update_peaks`) finds them by name: `RowColumns`, `PeakSlots`.
"""

from collections.abc import Mapping
from functools import cache
from types import MappingProxyType
from typing import NamedTuple

import numpy as np

from sim.jit import kernel, kernel_inline
from sim.model import ancf
from sim.model.beams import strain_energy
from sim.model.clearance import eccentricity, eccentricity_rate, guide_frame
from sim.model.constraints import constraint_terms
from sim.model.kinematics import point_position, point_quadratic_acceleration, point_velocity
from sim.model.modal import modal_midspan_deflection
from sim.model.system import (
    OUT_FRICTION_FORCE,
    OUT_NORMAL_FORCE,
    OUT_PENETRATION,
    OUT_STATE,
)
from sim.quantities import BY_NAME, PEAK, SAMPLE, recorded, shape
from sim.solve.dae import (
    SC_CONTACT_ENERGY,
    SC_DRIVE_TORQUE,
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


class RowColumns(NamedTuple):
    """First column, in a sample row, of each block the compiled code reads or writes by
    name (`column_layout`)."""

    crank_angle: int
    velocity: int
    acceleration: int
    output_velocity: int
    output_acceleration: int
    angular_velocity: int
    angular_acceleration: int
    deflection: int
    drive_torque: int
    normal_force: int
    friction_force: int
    drive_work: int


@cache
def row_columns(n_bodies: int, n_joints: int) -> RowColumns:
    """The `RowColumns` of a system of n_bodies bodies and n_joints clearance joints."""
    layout = column_layout(n_bodies, n_joints)
    return RowColumns(**{name: layout[name][0] for name in RowColumns._fields})


class PeakSlots(NamedTuple):
    """First entry, in the vector of peaks (and each row of per-revolution peaks), of the
    peak of each sampled quantity (`peak_layout`), named by that quantity."""

    acceleration: int
    output_acceleration: int
    angular_velocity: int
    angular_acceleration: int
    drive_torque: int
    normal_force: int


@cache
def peak_slots(n_bodies: int, n_joints: int) -> PeakSlots:
    """The `PeakSlots` of a system of n_bodies bodies and n_joints clearance joints."""
    slots = {
        BY_NAME[name].source: first for name, (first, _) in peak_layout(n_bodies, n_joints).items()
    }
    assert set(slots) == set(PeakSlots._fields), "sim.quantities' peaks and PeakSlots differ"
    return PeakSlots(**slots)


@kernel
def reference_point(sys, b: int, x: np.ndarray, axis: int) -> float:
    """Component `axis` of body b's reference point, applied to q, q̇ or q̈ (x): a fixed
    linear combination of coordinates, so the same map takes q̇ to the point's velocity and
    q̈ to its acceleration."""
    acc = 0.0
    for k in range(4):
        acc += sys.ref_coef[b, k] * x[sys.ref_idx[b, k] + axis]
    return acc


@kernel_inline
def output_position(sys, q: np.ndarray) -> tuple[float, float]:
    """Global position (m) of the output point: point System.out_pt, or, for −1, the
    reference point of body System.out_body."""
    if sys.out_pt < 0:
        return reference_point(sys, sys.out_body, q, 0), reference_point(sys, sys.out_body, q, 1)
    return point_position(sys, sys.out_pt, q)


@kernel_inline
def output_velocity(sys, q: np.ndarray, qd: np.ndarray) -> tuple[float, float]:
    """Global velocity (m/s) of the output point: the linear map J(q) of the rates q̇."""
    if sys.out_pt < 0:
        return reference_point(sys, sys.out_body, qd, 0), reference_point(sys, sys.out_body, qd, 1)
    return point_velocity(sys, sys.out_pt, q, qd, 0.0, 0.0)


@kernel_inline
def output_acceleration(sys, q, qd, qdd) -> tuple[float, float]:
    """Global acceleration (m/s²) of the output point: J(q) q̈ (the velocity's map applied
    to the accelerations) plus the terms quadratic in q̇."""
    jx, jy = output_velocity(sys, q, qdd)
    if sys.out_pt < 0:
        return jx, jy  # a reference point is linear in q: no quadratic terms
    bx, by = point_quadratic_acceleration(sys, sys.out_pt, q, qd)
    return jx + bx, jy + by


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
def body_angle_rates(sys, b: int, q, qd, qdd) -> tuple[float, float, float]:
    """Body b's angle (rad), angular velocity (rad/s) and angular acceleration (rad/s²):
    of its angle coordinate (rigid bodies; modal links: the floating frame's), or of the
    chord d between a beam's end nodes, θ = atan2(d_y, d_x):
    θ̇ = (d × ḋ)/|d|², θ̈ = (d × d̈)/|d|² − 2 (d · ḋ) θ̇ / |d|²."""
    i0 = sys.ang_idx[b, 0]
    if sys.body_is_beam[b] == 0:
        return q[i0], qd[i0], qdd[i0]
    i1 = sys.ang_idx[b, 1]
    dx, dy = q[i1] - q[i0], q[i1 + 1] - q[i0 + 1]
    vx, vy = qd[i1] - qd[i0], qd[i1 + 1] - qd[i0 + 1]
    ax, ay = qdd[i1] - qdd[i0], qdd[i1 + 1] - qdd[i0 + 1]
    d2 = dx * dx + dy * dy
    rate = (dx * vy - dy * vx) / d2
    return (
        np.arctan2(dy, dx),
        rate,
        (dx * ay - dy * ax) / d2 - 2.0 * (dx * vx + dy * vy) * rate / d2,
    )


@kernel
def _reference_points(sys, x: np.ndarray, row: np.ndarray, c: int) -> None:
    """Every body's reference point applied to x (q, q̇ or q̈) into row[c:], (body, axis)."""
    for b in range(sys.ref_idx.shape[0]):
        for a in range(2):
            row[c + 2 * b + a] = reference_point(sys, b, x, a)


@kernel
def _deflections(sys, q: np.ndarray, row: np.ndarray, c: int) -> None:
    """Every body's mid-span deflection (0 for rigid bodies) into row[c:]."""
    for b in range(sys.ref_idx.shape[0]):
        row[c + b] = 0.0
        if sys.body_is_beam[b] == 1:
            row[c + b] = beam_midspan_deflection(q, sys, b)
        elif sys.body_modal[b] >= 0:
            row[c + b] = modal_midspan_deflection(sys, sys.body_modal[b], q)


@kernel
def _joint_output(work, out: int, row: np.ndarray, c: int) -> None:
    """Every clearance joint's contact output `out` (OUT_*) into row[c:]."""
    for j in range(work.jout.shape[0]):
        row[c + j] = work.jout[j, out]


@kernel
def crank_angle(sys, q: np.ndarray) -> float:
    """The driven crank's angle (rad; 0 without a drive)."""
    return q[sys.drive_coord] if sys.drive_coord >= 0 else 0.0


@kernel_inline
def write_fast_values(sys, work, y: np.ndarray, cols, row: np.ndarray) -> None:
    """Into row's blocks (`RowColumns` cols): the point values at the state y that work was
    evaluated at of the quantities whose peaks are kept or whose interval means are a
    quadrature over the steps: accelerations (the output point's too), angular velocities and
    accelerations, deflections, drive torque, contact normal and friction forces."""
    n = sys.n
    q = y[:n]
    qd = y[n : 2 * n]
    _reference_points(sys, work.qdd, row, cols.acceleration)
    ax, ay = output_acceleration(sys, q, qd, work.qdd)
    row[cols.output_acceleration] = ax
    row[cols.output_acceleration + 1] = ay
    for b in range(sys.ref_idx.shape[0]):
        _, rate, acc = body_angle_rates(sys, b, q, qd, work.qdd)
        row[cols.angular_velocity + b] = rate
        row[cols.angular_acceleration + b] = acc
    _deflections(sys, q, row, cols.deflection)
    row[cols.drive_torque] = work.scalars[SC_DRIVE_TORQUE]
    _joint_output(work, OUT_NORMAL_FORCE, row, cols.normal_force)
    _joint_output(work, OUT_FRICTION_FORCE, row, cols.friction_force)


@kernel_inline
def balance_work(sys, work, y: np.ndarray) -> float:
    """The drive work that the energy balance gives at the state y whose evaluation work
    holds (J): T + V + U_s + U_c + D, the stored energies and what contact, friction and
    damping dissipated, which differs from the drive's work W by a constant (the energy at
    the start) and the integration error. Its change over a window is the work the drive did
    there, as the mechanism's state measures it (`sim.solve.means`)."""
    n = sys.n
    q = y[:n]
    stored = kinetic_energy(sys, work, y[n : 2 * n]) + potential_energy(sys, q)
    return stored + strain_energy(sys, q) + work.scalars[SC_CONTACT_ENERGY] + y[2 * n + 1]


@kernel
def write_rate_sources(sys, y: np.ndarray, cols, row: np.ndarray) -> None:
    """Into row's blocks (`RowColumns` cols): the state quantities whose differences form
    interval means (`sim.quantities`' `source` and `per`), at the state y: reference-point
    and output-point velocities, angular velocities, drive work and crank angle. No
    evaluation needed."""
    n = sys.n
    q = y[:n]
    qd = y[n : 2 * n]
    _reference_points(sys, qd, row, cols.velocity)
    vx, vy = output_velocity(sys, q, qd)
    row[cols.output_velocity] = vx
    row[cols.output_velocity + 1] = vy
    for b in range(sys.ref_idx.shape[0]):
        _, rate, _ = body_angle_rates(sys, b, q, qd, qd)
        row[cols.angular_velocity + b] = rate
    row[cols.drive_work] = y[2 * n]
    row[cols.crank_angle] = crank_angle(sys, q)


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
    """Write one sample row of point values at the state y from the evaluation at y that
    work holds (accelerations work.qdd, forces, contact outputs, constraint residual). One
    block per sampled quantity of `sim.quantities`, in its order
    (tests/core/test_sample_row.py checks each block against an independent reference).
    The interval means replace the fast quantities' blocks later (`sim.solve.means`)."""
    n = sys.n
    q = y[:n]
    qd = y[n : 2 * n]
    nb = sys.ref_idx.shape[0]
    c = 0
    # crank_angle
    row[c] = crank_angle(sys, q)
    c += 1
    # position, velocity, acceleration
    _reference_points(sys, q, row, c)
    _reference_points(sys, qd, row, c + 2 * nb)
    _reference_points(sys, work.qdd, row, c + 4 * nb)
    c += 6 * nb
    # output_position, output_velocity, output_acceleration
    row[c], row[c + 1] = output_position(sys, q)
    row[c + 2], row[c + 3] = output_velocity(sys, q, qd)
    row[c + 4], row[c + 5] = output_acceleration(sys, q, qd, work.qdd)
    c += 6
    # angle, angular_velocity, angular_acceleration
    for b in range(nb):
        angle, rate, acc = body_angle_rates(sys, b, q, qd, work.qdd)
        row[c + b] = angle
        row[c + nb + b] = rate
        row[c + 2 * nb + b] = acc
    c += 3 * nb
    # deflection
    _deflections(sys, q, row, c)
    c += nb
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
        _joint_output(work, out, row, c)
        c += nj
    # constraint_violation
    viol = 0.0
    for i in range(sys.m):
        viol += work.phi[i] * work.phi[i]
    row[c] = np.sqrt(viol)
    row[c + 1] = kinetic_energy(sys, work, qd)  # kinetic_energy
    row[c + 2] = potential_energy(sys, q)  # potential_energy
    row[c + 3] = strain_energy(sys, q)  # strain_energy
    row[c + 4] = work.scalars[SC_CONTACT_ENERGY]  # contact_energy
    row[c + 5] = y[2 * n]  # drive_work
    row[c + 6] = y[2 * n + 1]  # dissipated_energy

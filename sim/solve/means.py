"""Interval means: the fast quantities of a sample row as the mean over the sample's window.

Sample i's window is the part inside the run of [t_i − Δt/2, t_i + Δt/2] (its ends halfway
to the neighbouring samples), a centred boxcar: it removes the content above the output rate
that a point sample folds into the recorded band, without delay (`sim.quantities` declares
which quantities are so recorded). The row is first written with point values at t_i
(`sim.solve.record.write_row`); when the integration passes the window's end, its
interval-mean blocks are replaced:

- a quantity with a `source` (acceleration: velocity; angular acceleration: angular
  velocity; drive torque: drive work per crank angle) from the integrator's state at the two
  ends of the window, read on the continuous extension of the step that holds each end: the
  mean of a rate is exactly its quantity's difference over the window divided by the
  window's length (the reference point is a fixed linear map of the coordinates,
  `sim.solve.record.reference_point`), and the mean drive torque is ΔW/Δθ, the drive work
  over the crank angle it turned through (the time mean for a constant-speed drive). Under
  generalized-α, W is the work the energy balance gives (`Means.balance`,
  `sim.solve.record.balance_work`: the change of T + V + U_s + U_c plus what was dissipated)
  rather than its integrated drive work: the trapezoid of the drive power over its steps
  samples the links' ringing, which its steps do not resolve, and read 4e-2 of the peak off
  the rigid torque on the flexible ideal six-bar, low-passed at 100 Hz;
- the others (deflections, contact forces) by the trapezoid rule over the values at every
  accepted step's end, with the window's ends on the straight line between the two step
  ends around them. The steps resolve the fastest dynamics the error control sees, so the
  quadrature's error is that of the motion between two steps.

A window of zero length (a run of one sample) keeps the point value.
"""

from typing import NamedTuple

import numpy as np

from sim.jit import kernel, kernel_inline, spliced
from sim.quantities import INTERVAL_MEAN, SAMPLE, recorded
from sim.solve.dense import interpolate
from sim.solve.record import (
    RowColumns,
    balance_work,
    column_layout,
    row_columns,
    write_rate_sources,
)

MEANS_CLOCK = np.dtype(
    [
        ("t_node", np.float64),  # s, time of the last quadrature node (`Means.node`)
        ("t_edge", np.float64),  # s, start of the open window
        ("window", np.int64),  # the sample whose window is open; all closed: the sample count
    ]
)


class Means(NamedTuple):
    """What the interval means carry through the integration (rows in the sample row's
    layout; only the blocks named below are used)."""

    clock: np.ndarray  # (1,) MEANS_CLOCK
    columns: RowColumns  # the blocks `write_rate_sources` and `write_fast_values` write
    quadrature: np.ndarray  # (k,) columns averaged by the trapezoid rule over the steps
    target: np.ndarray  # (d,) columns formed from a difference over the window ...
    source: np.ndarray  # (d,) ... of these columns ...
    per: np.ndarray  # (d,) ... per the difference of these (−1: per the window's length)
    node: np.ndarray  # (width,) quadrature columns at clock.t_node
    end: np.ndarray  # (width,) point values at the end of the step just accepted
    edge: np.ndarray  # (width,) source and per columns at the open window's start
    here: np.ndarray  # (width,) the same at the end of the window being closed
    integral: np.ndarray  # (width,) ∫ of the quadrature columns from t_edge to t_node
    # the drive torque's mean from the energy balance's drive work (`balance_work`) instead of
    # the integrated drive work: generalized-α's, whose windows end on its steps
    balance: bool


def make_means(
    width: int, n_bodies: int, n_joints: int, windows: bool, balance: bool = False
) -> Means:
    """The interval means of a run whose sample rows are `width` wide, to be started by its
    first sample row (`start_windows`); without `windows` (simulation.sampling: point) none is
    open. `balance`: the drive torque's mean from the energy balance (`Means.balance`)."""
    layout = column_layout(n_bodies, n_joints)
    columns = row_columns(n_bodies, n_joints)
    means = [q for q in recorded(SAMPLE) if q.sampling == INTERVAL_MEAN]
    quadrature = [q for q in means if not q.source]
    formed = [q for q in means if q.source]

    def block(name: str) -> list[int]:
        first, shape = layout[name]
        return list(range(first, first + int(np.prod(shape, dtype=int))))

    # the kernels write exactly these blocks (sim.solve.record.write_fast_values and
    # write_rate_sources): a new interval mean needs its lines there
    sources = {"velocity", "output_velocity", "angular_velocity", "drive_work", "crank_angle"}
    fast = {"deflection", "normal_force", "friction_force"}
    assert {q.source for q in formed} | {q.per for q in formed if q.per} <= sources
    assert {q.name for q in quadrature} <= fast
    target, source, per = [], [], []
    for q in formed:
        cols = block(q.name)
        target += cols
        source += block(q.source)
        per += block(q.per) * len(cols) if q.per else [-1] * len(cols)
    clock = np.zeros(1, dtype=MEANS_CLOCK)
    if not windows:
        clock[0]["window"] = np.iinfo(np.int64).max
    return Means(
        clock=clock,
        columns=columns,
        quadrature=np.array([c for q in quadrature for c in block(q.name)], dtype=np.int64),
        target=np.array(target, dtype=np.int64),
        source=np.array(source, dtype=np.int64),
        per=np.array(per, dtype=np.int64),
        node=np.zeros(width),
        end=np.zeros(width),
        edge=np.zeros(width),
        here=np.zeros(width),
        integral=np.zeros(width),
        balance=balance,
    )


@spliced
def start_windows(sys, work, means, y: np.ndarray, first_row: np.ndarray) -> None:
    """Start the interval means from the run's first sample row (point values at its start
    time, the first window's start), taken at the state y whose evaluation work holds."""
    for c in range(first_row.shape[0]):
        means.node[c] = first_row[c]
        means.end[c] = first_row[c]
        means.edge[c] = first_row[c]
        means.here[c] = first_row[c]
    if means.balance:
        means.edge[means.columns.drive_work] = balance_work(sys, work, y)


@kernel
def _window_end(out_t: np.ndarray, i: int) -> float:
    """End of sample i's window: halfway to the next sample, or the last sample itself."""
    if i + 1 < out_t.shape[0]:
        return 0.5 * (out_t[i] + out_t[i + 1])
    return out_t[i]


@kernel
def next_window_end(t: float, means, out_t: np.ndarray) -> float:
    """End of the open window when it lies after t, else ∞ (every window closed, point
    sampling, or the end at t itself)."""
    i = means.clock[0].window
    if i >= out_t.shape[0]:
        return np.inf
    b = _window_end(out_t, i)
    return b if b > t else np.inf


@kernel
def _integrate_to(means, t: float, t_end_step: float) -> None:
    """Advance the quadrature from clock.t_node to t (≤ t_end_step): the trapezoid on the
    straight line from the node's values to the step's end values (`Means.end`)."""
    clock = means.clock[0]
    span = t_end_step - clock.t_node
    frac = (t - clock.t_node) / span if span > 0.0 else 1.0
    for c in means.quadrature:
        value = means.node[c] + frac * (means.end[c] - means.node[c])
        means.integral[c] += 0.5 * (means.node[c] + value) * (t - clock.t_node)
        means.node[c] = value
    clock.t_node = t


@kernel_inline
def close_windows(sys, work, means, out_t: np.ndarray, out_rows: np.ndarray, t0: float, h: float):
    """After the accepted step from t0 to t0 + h (its end values in means.end, its
    continuous extension in work.dense, its samples recorded): close every window that ends
    in the step, replacing its sample's interval-mean blocks, and carry the quadrature to
    the step's end."""
    clock = means.clock[0]
    if clock.window >= out_t.shape[0]:
        return  # every window closed, or point sampling
    t1 = t0 + h
    slack = 1e-12 * max(1.0, abs(t1))  # a window ending on the step's end closes in it
    while clock.window < out_t.shape[0]:
        i = clock.window
        b = _window_end(out_t, i)
        if b > t1 + slack:
            break
        b = min(b, t1)
        _integrate_to(means, b, t1)
        interpolate(work, min(max((b - t0) / h, 0.0), 1.0), work.yint.shape[0], work.yint)
        write_rate_sources(sys, work.yint, means.columns, means.here)
        if means.balance:  # the window ends on the step's end, whose evaluation work holds
            means.here[means.columns.drive_work] = balance_work(sys, work, work.yint)
        length = b - clock.t_edge
        if length > 0.0:
            row = out_rows[i]
            for c in means.quadrature:
                row[c] = means.integral[c] / length
            for k in range(means.target.shape[0]):
                change = means.here[means.source[k]] - means.edge[means.source[k]]
                p = means.per[k]
                per = length if p < 0 else means.here[p] - means.edge[p]
                if per != 0.0:
                    row[means.target[k]] = change / per
        for c in means.quadrature:
            means.integral[c] = 0.0
        for k in range(means.source.shape[0]):
            means.edge[means.source[k]] = means.here[means.source[k]]
            if means.per[k] >= 0:
                means.edge[means.per[k]] = means.here[means.per[k]]
        clock.t_edge = b
        clock.window += 1
    _integrate_to(means, t1, t1)

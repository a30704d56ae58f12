"""The contact gaps every clearance joint monitors: their numbering and their memory.

Gap numbering: the nr revolute clearances come first, one gap each (revolute clearance j
is gap j); then each translational clearance j owns GAPS_PER_SLIDER gaps, one for each
corner i (0..3, `sim.model.clearance.CORNER_SX`) against each wall w (0: the +n_g side,
1: the −n_g side), gap nr + GAPS_PER_SLIDER j + 2 i + w. `gap_owner` and `slider_gap`
are the only places that know it.

Contact memory: an array (gaps, MEM_COLUMNS), one row per gap, whose columns are
  MEM_IN_CONTACT  1.0 while the gap is flagged in contact (flipped only at a located
                  crossing, by the integration loop), else 0.0;
  MEM_ONSET_RATE  δ̇⁻ (m/s), the penetration rate captured at the crossing (the memory the
                  Lankarani–Nikravesh law needs), 0 while apart;
  MEM_GRAZED      1.0 when a stage saw the gap penetrated before its crossing was located
                  (a contact that may come and go inside one step), cleared every step.
It is part of the trajectory (`sim.solve.state.Trajectory`): a restart point copies it.
"""

import numpy as np

from sim.jit import kernel_inline
from sim.model.system import System

MEM_IN_CONTACT, MEM_ONSET_RATE, MEM_GRAZED = range(3)
MEM_COLUMNS = 3

GAP_REVOLUTE, GAP_SLIDER_CORNER = 0, 1
CORNERS_PER_SLIDER = 4
GAPS_PER_SLIDER = 2 * CORNERS_PER_SLIDER  # four corners, each against both walls


def n_gaps(system: System) -> int:
    """Number of monitored contact gaps (one per revolute clearance, eight per slider)."""
    return system.rj_pts.shape[0] + GAPS_PER_SLIDER * system.tj_off.shape[0]


def contact_memory(system: System) -> np.ndarray:
    """A contact memory with every gap of `system` open (the assembled state's)."""
    return np.zeros((n_gaps(system), MEM_COLUMNS))


@kernel_inline
def gap_owner(sys, g: int) -> tuple[int, int, int, int]:
    """(kind, joint, corner, wall) of gap g: (GAP_REVOLUTE, j, 0, 0) for revolute clearance
    j, (GAP_SLIDER_CORNER, j, i, w) for corner i of translational clearance j against wall w.
    The joint is counted within its kind (sys.rj or sys.tj)."""
    nr = sys.rj_pts.shape[0]
    if g < nr:
        return GAP_REVOLUTE, g, 0, 0
    k = g - nr
    return GAP_SLIDER_CORNER, k // GAPS_PER_SLIDER, (k % GAPS_PER_SLIDER) // 2, k % 2


def gap_joints(system: System) -> np.ndarray:
    """The clearance joint of every gap, numbered as `n_clearance_joints` counts them
    (revolute first, then translational): (gaps,) int."""
    nr = system.rj_pts.shape[0]
    owners = (gap_owner(system, g) for g in range(n_gaps(system)))
    return np.array(
        [j if kind == GAP_REVOLUTE else nr + j for kind, j, _, _ in owners], dtype=np.int64
    )


@kernel_inline
def slider_gap(sys, j: int, i: int, w: int) -> int:
    """The gap of corner i of translational clearance j against wall w (`gap_owner`'s
    inverse)."""
    return sys.rj_pts.shape[0] + GAPS_PER_SLIDER * j + 2 * i + w

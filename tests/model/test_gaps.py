"""The gap numbering (sim/model/gaps.py): every gap has exactly one owner, and `slider_gap`
inverts `gap_owner` for every slider corner and wall."""

from typing import NamedTuple

import numpy as np

from sim.model.gaps import (
    CORNERS_PER_SLIDER,
    GAP_REVOLUTE,
    GAP_SLIDER_CORNER,
    GAPS_PER_SLIDER,
    MEM_COLUMNS,
    contact_memory,
    gap_owner,
    n_gaps,
    slider_gap,
)


class Joints(NamedTuple):
    """The two fields of sim.model.system.System the numbering reads."""

    rj_pts: np.ndarray  # (nr, 2)
    tj_off: np.ndarray  # (nt,)


# three revolute and two translational clearances
SYSTEM = Joints(rj_pts=np.zeros((3, 2), dtype=np.int64), tj_off=np.zeros(2, dtype=np.int64))
# The kernels run as Python: compiled for a type of this module, they would enter numba's
# on-disk index, which a process without the tests on its path then cannot read.
gap_owner = gap_owner.py_func
slider_gap = slider_gap.py_func


def test_every_gap_has_one_owner_and_every_owner_one_gap():
    owners = [gap_owner(SYSTEM, g) for g in range(n_gaps(SYSTEM))]
    assert len(owners) == 3 + 2 * GAPS_PER_SLIDER == 3 + 2 * 2 * CORNERS_PER_SLIDER
    assert len(set(owners)) == len(owners)
    assert owners[:3] == [(GAP_REVOLUTE, j, 0, 0) for j in range(3)]
    corners = {
        (GAP_SLIDER_CORNER, j, i, w)
        for j in range(2)
        for i in range(CORNERS_PER_SLIDER)
        for w in (0, 1)
    }
    assert set(owners[3:]) == corners


def test_slider_gap_inverts_gap_owner():
    for j in range(2):
        for i in range(CORNERS_PER_SLIDER):
            for w in (0, 1):
                g = slider_gap(SYSTEM, j, i, w)
                assert gap_owner(SYSTEM, g) == (GAP_SLIDER_CORNER, j, i, w)


def test_a_new_memory_has_every_gap_open():
    mem = contact_memory(SYSTEM)
    assert mem.shape == (n_gaps(SYSTEM), MEM_COLUMNS)
    assert not mem.any()

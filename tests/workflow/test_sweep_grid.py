"""The sweep grid the workflow and the benchmarks share (sim.studies.grid)."""

import itertools

import pytest

from sim.studies.grid import sweep_grid


def test_a_range_spans_its_ends_exactly_in_equal_steps():
    """The dense speed diagram's grid: 211 speeds from 30 to 240 rpm are 1 rpm apart, and
    both ends are exact (the point names are formatted from these values)."""
    grid = sweep_grid({"range": [30.0, 240.0, 211]})
    assert len(grid) == 211
    assert grid[0] == 30.0 and grid[-1] == 240.0
    assert all(b - a == pytest.approx(1.0, rel=1e-12) for a, b in itertools.pairwise(grid))


def test_given_values_are_kept_as_given_and_a_one_point_range_is_its_start():
    assert sweep_grid({"values": [120.0, 240]}) == [120.0, 240]
    assert sweep_grid({"range": [0.0, 1.0e-3, 1]}) == [0.0]

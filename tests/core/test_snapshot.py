"""Snapshot and restore of an integration (sim.run.Integration.snapshot / restore)."""

import numpy as np
import pytest

from sim.model.assembly import crank_period
from sim.run import Snapshot, prepare
from sim.scene import load_scene
from sim.solve.status import OK

CASE = ["joints.A.clearance=0.5e-3", "joints.B.clearance=0.5e-3"]


def _end_state(integ, t_end):
    assert integ.advance(t_end) == OK
    return integ.y.copy(), integ.mem.copy(), integ.trajectory.clock.copy()


@pytest.mark.parametrize(("method", "revolutions"), [("dopri5", 0.5), ("generalized_alpha", 0.1)])
def test_restored_snapshot_resumes_bit_for_bit(method, revolutions):
    # A snapshot with its carried step data (the FSAL derivative, the generalized-α start
    # data, the Newton factors) is a complete restart point: the integration from it repeats
    # every step, through contact events (counted below), to the last bit.
    scene = load_scene("sixbar", [*CASE, f"solver.method={method}"])
    integ = prepare(scene, revolutions=0)
    period = crank_period(scene)
    t_mid, t_end = 0.5 * revolutions * period, revolutions * period
    assert integ.advance(t_mid) == OK
    snap = integ.snapshot()
    events = integ.count("events")
    first = _end_state(integ, t_end)
    assert integ.count("events") > events  # the stretch compared passes contact events
    integ.restore(snap)
    assert integ.t == t_mid
    second = _end_state(integ, t_end)
    for a, b in zip(first, second, strict=True):
        assert a.tobytes() == b.tobytes()


def test_restart_without_carried_data_re_evaluates_the_start():
    # Restored without its carried data, the integration re-evaluates the derivative at the
    # restart point: one evaluation more. For DOPRI5 that derivative is the one the last step
    # carried (first same as last: the same function at the same t, y and contact memory), so
    # the integration then repeats every step to the last bit.
    scene = load_scene("sixbar", CASE)
    integ = prepare(scene, revolutions=0)
    period = crank_period(scene)
    assert integ.advance(0.1 * period) == OK
    snap = integ.snapshot()
    evaluations = integ.count("evaluations")
    first = _end_state(integ, 0.2 * period)
    carried = integ.count("evaluations") - evaluations
    integ.restore(Snapshot(snap.trajectory, carry=None))
    integ.carry.derivative[:] = np.nan  # what it holds is not used
    evaluations = integ.count("evaluations")
    second = _end_state(integ, 0.2 * period)
    assert integ.count("evaluations") - evaluations == carried + 1
    for a, b in zip(first, second, strict=True):
        assert a.tobytes() == b.tobytes()

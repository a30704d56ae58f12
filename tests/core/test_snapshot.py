"""Snapshot and restore of an integration (sim.run.Integration.snapshot / restore)."""

import numpy as np
import pytest

from sim.model.assembly import crank_period
from sim.run import prepare
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
    # restart point: one evaluation besides DOPRI5's six per step and one per contact event.
    scene = load_scene("sixbar", CASE)
    integ = prepare(scene, revolutions=0)
    assert integ.advance(0.1 * crank_period(scene)) == OK
    snap = integ.snapshot(carried=False)
    integ.carry.derivative[:] = np.nan  # what it holds is not used
    integ.restore(snap)
    names = ("evaluations", "accepted", "rejected", "events")
    before = {name: integ.count(name) for name in names}
    assert integ.advance(integ.t + 0.01 * crank_period(scene)) == OK
    assert np.isfinite(integ.y).all()
    done = {name: integ.count(name) - before[name] for name in names}
    assert done["evaluations"] == 1 + 6 * (done["accepted"] + done["rejected"]) + done["events"]

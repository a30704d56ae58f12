"""The cross-check's contact laws (sim.crosscheck.contact, written anew from docs/model.md) against
our compiled ones (sim.model.clearance) at random states, and against closed forms. Two
implementations of the same law must give the same generalized forces; neither needs Exudyn."""

import math

import numpy as np
import pytest

from sim.crosscheck import contact
from sim.model.assembly import build_system
from sim.model.clearance import revolute_clearance_forces, translational_clearance_forces
from sim.model.contact_laws import LAW_CODES, STIFFNESS_HERTZ
from sim.model.gaps import (
    CORNERS_PER_SLIDER,
    MEM_IN_CONTACT,
    MEM_ONSET_RATE,
    contact_memory,
    slider_gap,
)
from sim.model.initial import assemble
from sim.model.system import N_JOINT_OUT
from sim.scene import load_scene


@pytest.fixture(scope="module")
def sixbar():
    scene = load_scene("sixbar", ["joints.A.clearance=5e-4", "joints.B.clearance=5e-4"])
    system, layout = build_system(scene)
    q0, qd0 = assemble(scene)[:2]
    return system, layout, q0, qd0


def _ours(system, q, qd, mem):
    gen = np.zeros(system.n)
    jout = np.zeros((2, N_JOINT_OUT))
    computed = np.zeros((0, 2))  # no table of rotations: each body's from q
    revolute_clearance_forces(system, q, qd, mem, gen, jout, computed)
    translational_clearance_forces(system, q, qd, mem, gen, jout, computed)
    return gen


def _theirs(system, layout, q, qd, mem) -> np.ndarray:
    """The same forces from sim.crosscheck.contact, on the full coordinates (local = global)."""
    points = [
        contact.Point(contact.RIGID, int(system.pt_off[k]), tuple(system.pt_u[k]))
        for k in system.rj_pts[0]
    ]
    revolute = contact.RevoluteClearance.from_system(system, 0, *points)
    centre = contact.Point(contact.RIGID, layout.offset["slider"], (0.0, 0.0))
    slider = contact.SliderClearance.from_system(system, 0, centre)
    # the memories: gap 0 of ours is the revolute joint; the slider's corner i against wall w
    # is its gap 2 i + w (contact.SliderClearance.gaps)
    slider_gaps = [slider_gap(system, 0, i, w) for i in range(CORNERS_PER_SLIDER) for w in (0, 1)]
    for law_, gaps in ((revolute, [0]), (slider, slider_gaps)):
        for g_local, g in enumerate(gaps):
            law_.memory.flag[g_local] = mem[g, MEM_IN_CONTACT] > 0
            law_.memory.onset[g_local] = mem[g, MEM_ONSET_RATE]
    return revolute.force(q, qd) + slider.force(q, qd)


def test_both_implementations_give_the_same_forces(sixbar):
    """200 random states around the assembly: journal of A pushed 0–20 µm into its bearing
    in a random direction, the slider shifted and tilted so that none, one or two corners of
    either long edge penetrate, random velocities, random contact memories."""
    system, layout, q0, qd0 = sixbar
    rng = np.random.default_rng(8)
    o_crank, o_slider = layout.offset["crank"], layout.offset["slider"]
    clearance_a = system.rj[0]["clearance"]
    gap_b = 0.5 * (system.tj[0]["gap_width"] - system.tj[0]["width"])
    checked = 0
    for _ in range(200):
        q, qd = q0.copy(), qd0 + rng.normal(0.0, 0.05, q0.size)
        angle = rng.uniform(0, 2 * math.pi)
        depth = clearance_a + rng.uniform(-2e-6, 2e-5)
        q[o_crank : o_crank + 2] += depth * np.array([math.cos(angle), math.sin(angle)])
        q[o_slider] += rng.uniform(-1.2, 1.2) * gap_b
        q[o_slider + 2] += rng.uniform(-1.5, 1.5) * 2 * gap_b / system.tj[0]["length"]
        mem = contact_memory(system)
        mem[:, MEM_IN_CONTACT] = rng.integers(0, 2, mem.shape[0])
        mem[:, MEM_ONSET_RATE] = rng.uniform(0.0, 0.5, mem.shape[0])
        ours = _ours(system, q, qd, mem.copy())
        theirs = _theirs(system, layout, q, qd, mem)
        scale = max(np.max(np.abs(ours)), 1e-9)
        np.testing.assert_allclose(theirs, ours, rtol=0, atol=1e-9 * scale)
        checked += np.any(ours != 0.0)
    assert checked > 100  # most states are in contact


def test_revolute_hertz_force_closed_form():
    """A journal resting (zero rate) δ deep in its bearing: F = K δ^1.5 along −n on the
    journal, +n on the bearing, no friction at zero slip."""
    law = contact.Law(
        LAW_CODES["lankarani-nikravesh"], 0.75 * (1 - 0.9**2), 0.15, 1e-4, 1e-3, 1e-4, 1.5
    )
    joint = contact.RevoluteClearance(
        bearing=contact.Point(contact.NODE, 0),
        journal=contact.Point(contact.NODE, 2),
        r_bearing=0.015,
        r_journal=0.0145,
        clearance=5e-4,
        stiffness=1e10,
        stiffness_law=STIFFNESS_HERTZ,
        law=law,
    )
    delta = 1e-5
    x = np.array([0.0, 0.0, 0.6 * (5e-4 + delta), 0.8 * (5e-4 + delta)])
    force = joint.force(x, np.zeros(4))
    expected = 1e10 * delta**1.5
    np.testing.assert_allclose(force, expected * np.array([0.6, 0.8, -0.6, -0.8]), rtol=1e-12)


def test_memory_interpolates_the_onset_rate_to_the_crossing():
    """δ from −1 µm to +1 µm between two step starts with rates 0.3 and 0.1 m/s: the onset
    rate is the rate at δ = 0, halfway: 0.2 m/s; leaving contact clears the flag."""
    memory = contact.ContactMemory(1)
    memory.update([(-1e-6, 0.3)])
    memory.update([(1e-6, 0.1)])
    assert memory.flag[0]
    assert memory.onset[0] == pytest.approx(0.2)
    memory.update([(-1e-7, -0.1)])
    assert not memory.flag[0]

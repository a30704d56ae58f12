"""The system builder (sim/model/builder.py): errors that name the scene key, and clamps
added through it, checked against geometry and against Euler–Bernoulli beam theory."""

import math

import numpy as np
import pytest

from sim.model import ancf
from sim.model.builder import SystemBuilder
from sim.model.initial import constraint_values
from sim.model.system import CON_CLAMP, CON_CLAMP_NODE, SLIDER_LAW_PAPER, ContactLaw
from sim.scene import SceneError

CONTACT = ContactLaw(0.0, 1e-4, 1e-3, 1e-4, 1.5, SLIDER_LAW_PAPER)
G = 9.81
# A steel cantilever: 0.5 m, 20 mm × 20 mm.
LENGTH, SIDE, E, RHO = 0.5, 0.02, 2.1e11, 7800.0


def _builder(gravity=(0.0, -G)) -> SystemBuilder:
    return SystemBuilder(gravity, (0.0, 0.0), CONTACT, {"O": (0.0, 0.0)})


def test_unknown_names_are_errors_that_name_the_scene_key():
    b = _builder()
    b.add_rigid_body("crank", 1.0, 0.01, {"centre": (0.0, 0.0), "end": (0.1, 0.0)})
    b.add_beam("rod", 0.5, 2, 1.0, 1e6, 1.0, 0.0)
    where = "joints.A.points"
    with pytest.raises(SceneError, match=r"joints\.A\.points: unknown body 'rotor'"):
        b.add_point("rotor", "start", where)
    with pytest.raises(SceneError, match=r"joints\.A\.points: body 'crank' has no point 'tip'"):
        b.add_point("crank", "tip", where)
    with pytest.raises(SceneError, match=r"joints\.A\.points: the ground has no point 'P'"):
        b.add_point("ground", "P", where)
    with pytest.raises(SceneError, match=r"joints\.A\.points: beam 'rod' offers 'start' and"):
        b.add_point("rod", "centre", where)
    with pytest.raises(SceneError, match=r"drive\.body: unknown body 'rotor'"):
        b.add_drive("rotor", 0.0, 1.0)
    with pytest.raises(SceneError, match=r"bodies\.crank: added twice"):
        b.add_rigid_body("crank", 1.0, 0.01, {})
    with pytest.raises(SceneError, match=r"bodies\.ground: the name is reserved"):
        b.add_rigid_body("ground", 1.0, 0.01, {})


def test_rigid_clamp_holds_the_named_point_at_its_position():
    """A body clamped by its point u = (0.1, 0.05) m at (1, 2) m, turned 90°: its centre
    sits at (1, 2) − R(90°) u = (1.05, 1.9) m, where Φ vanishes (to round-off)."""
    b = _builder()
    b.add_rigid_body("crank", 1.0, 0.01, {"centre": (0.0, 0.0), "tip": (0.1, 0.05)})
    b.add_clamp("W", "crank", "tip", (1.0, 2.0), math.pi / 2)
    system, layout = b.freeze()
    assert system.con_type.tolist() == [CON_CLAMP]
    assert layout.constraint_rows == [("W", 0, 3)]
    phi, jac, _ = constraint_values(system, np.array([1.05, 1.9, math.pi / 2]), np.zeros(3), 0.0)
    assert np.abs(phi).max() < 1e-15
    np.testing.assert_array_equal(jac, np.eye(3))


def test_beam_clamp_gives_the_euler_bernoulli_cantilever():
    """A steel cantilever (two ANCF elements) clamped at its start node through the builder
    (CON_CLAMP_NODE, which no scene reaches: scenes weld rigid bodies only), sagging under
    its own weight: the static tip deflection and slope are Euler–Bernoulli's w L⁴/(8 EI)
    and w L³/(6 EI). Cubic Hermite elements with consistent loads are exact at the nodes
    for a uniform load, so what remains is the ANCF model's geometric nonlinearity, of
    order (δ/L)² ≈ 3e-8 here (measured −6e-8 and −3e-8); 1e-6 relative leaves room for
    round-off in a stiffness matrix whose EA/(EI/L²) ratio is 7.5e3."""
    elements = 2
    area, inertia = SIDE * SIDE, SIDE**4 / 12.0
    b = _builder()
    b.add_beam("rod", LENGTH, elements, RHO * area, E * area, E * inertia, 0.0)
    b.add_clamp("W", "rod", "start", (0.0, 0.0), 0.0)
    system, layout = b.freeze()
    assert system.con_type.tolist() == [CON_CLAMP_NODE]
    assert layout.constraint_rows == [("W", 0, 4)]

    n, m = system.n, system.m
    q = np.zeros(n)
    q[0::4] = np.linspace(0.0, LENGTH, elements + 1)
    q[2::4] = 1.0
    lam = np.zeros(m)
    consts = (
        system.beam_dshape[0],
        system.beam_axial_w[0],
        system.beam_d2shape[0],
        system.beam_bending_w[0],
    )
    for _ in range(20):
        phi, jac, _ = constraint_values(system, q, np.zeros(n), 0.0)
        force = np.zeros(n)
        stiffness = np.zeros((n, n))
        ancf.beam_elastic_forces(q, *consts, force)
        ancf.beam_elastic_jacobian(q, *consts, stiffness)
        residual = np.concatenate([force + jac.T @ lam - system.gravity_force, phi])
        step = np.linalg.solve(np.block([[stiffness, jac.T], [jac, np.zeros((m, m))]]), -residual)
        q += step[:n]
        lam += step[n:]
        if np.abs(step[:n]).max() < 1e-15:
            break
    w, ei = RHO * area * G, E * inertia
    tip = q[4 * elements : 4 * elements + 4]
    assert tip[1] == pytest.approx(-w * LENGTH**4 / (8.0 * ei), rel=1e-6)
    assert tip[3] / tip[2] == pytest.approx(-w * LENGTH**3 / (6.0 * ei), rel=1e-6)
    np.testing.assert_allclose(q[:4], [0.0, 0.0, 1.0, 0.0], atol=1e-15)

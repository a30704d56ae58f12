"""Minimal coordinates of tree mechanisms (sim.model.tree) against the multiplier form.

Reference: the engine's Lagrange-multiplier form with Baumgarte stabilisation
(sim.solve.dae), an independent solution of the same equations of motion. On the
constraint manifold (Φ = 0, Φ_q q̇ = ν) its stabilisation terms vanish, and both forms give
the same accelerations, drive torque and dissipated power up to round-off.
"""

import numpy as np
import pytest

from sim.model.assembly import build_system
from sim.model.clearance import (
    gap,
    gap_depths,
    revolute_clearance_forces,
    translational_clearance_forces,
)
from sim.model.gaps import MEM_IN_CONTACT
from sim.model.system import CON_REVOLUTE
from sim.run import prepare
from sim.scene import load_scene
from sim.solve.dae import SC_DRIVE_TORQUE, project_onto_tree, rhs
from sim.solve.status import OK
from sim.studies.model_lyapunov import linkage_lyapunov

FLAGSHIP = ["joints.A.clearance=0.5e-3", "joints.B.clearance=0.5e-3"]
RODS = ("rod2", "rod3", "rod4")
MODAL = tuple(f"bodies.{b}.kind=modal" for b in RODS)
AXIAL = tuple(f"bodies.{b}.axial_modes=1" for b in RODS)


def _scene(*overrides: str) -> dict:
    return load_scene("sixbar", [*FLAGSHIP, *overrides])


def test_the_flagship_is_a_tree_of_five_hinges_with_the_drive_last():
    system, layout = build_system(_scene())
    tree = system.tree
    assert tree.size == 5  # O, C, D2, D1, E: A and B have clearance
    assert tree.size == np.count_nonzero(system.con_type == CON_REVOLUTE)
    driven = [h for h in tree if h["column"] == tree.size - 1]
    assert [h["child"] for h in driven] == [layout.offset["crank"]]
    assert driven[0]["rate"] == pytest.approx(150.0 * 2 * np.pi / 60)
    # every parent is placed before its children
    placed = {-1}
    for hinge in tree:
        assert hinge["parent"] in placed
        placed.add(hinge["child"])
    assert sorted(hinge["column"] for hinge in tree) == list(range(tree.size))


@pytest.mark.parametrize(
    "overrides",
    [
        ("joints.A.clearance=0", "joints.B.clearance=0"),  # every joint ideal: loops
        ("joints.A.clearance=0",),  # A ideal closes the loop O-A-D1-D2-C
        ("bodies.rod2.kind=beam",),  # a beam is neither a rigid body nor a modal link
        ("solver.method=generalized_alpha",),  # its Newton iteration is built on Φ_q
        ("solver.coordinates=absolute",),
    ],
)
def test_no_tree_where_it_does_not_apply(overrides):
    system, _ = build_system(_scene(*overrides))
    assert system.tree.size == 0


def test_modal_links_add_their_amplitudes_before_the_driven_angle():
    system, layout = build_system(_scene(*MODAL, *AXIAL))
    tree = system.tree
    assert tree.size == 5
    # 4 undriven angles, then 2 amplitudes of each of the three rods, then the driven angle
    assert sorted(h["modal_column"] for h in tree if h["child_modes"]) == [4, 6, 8]
    assert {int(h["child_modes"]) for h in tree if h["child"] in system.md_off} == {2}
    driven = [h for h in tree if h["child"] == layout.offset["crank"]]
    assert driven[0]["column"] == 4 + 6


#: revolutions searched for a state with both joints in contact, and samples a revolution
#: looked at: the journal and the slider touch together for 0.4-7 % of the time (measured on
#: 3 revolutions at 600 samples a revolution, under three OpenBLAS kernels), in spells a few
#: samples long whose times move with the rounding of the chaotic run, so the search looks
#: densely and long enough to meet several spells on any machine
SEARCH_REVOLUTIONS, SEARCH_SAMPLES = 6, 1000
#: the largest acceleration (m/s², rad/s²) a state must have for the forms' comparison to
#: weigh the contact forces: 3.5 times the ideal motion's peak (143, a rod's angular one)
CONTACT_ACCELERATION = 500.0


def _contact_state(*links: str) -> tuple[float, np.ndarray, np.ndarray]:
    """A state of the multiplier form with both clearance joints in contact, pressed hard
    enough to accelerate some coordinate beyond CONTACT_ACCELERATION."""
    revolutions = f"simulation.revolutions={SEARCH_REVOLUTIONS}"
    integ = prepare(_scene(*links, "solver.coordinates=absolute", revolutions))
    n = integ.system.n
    period = 0.4
    for k in range(1, SEARCH_REVOLUTIONS * SEARCH_SAMPLES + 1):
        t = k * period / SEARCH_SAMPLES
        assert integ.advance(t) == OK
        closed = integ.mem[:, MEM_IN_CONTACT] > 0  # gap 0: joint A, then the slider's
        if not (closed[0] and closed[1:].any()):
            continue
        y, mem, ydot = integ.y.copy(), integ.mem.copy(), np.zeros_like(integ.y)
        assert rhs(integ.system, integ.work, mem.copy(), t, y, ydot) == OK
        if np.abs(ydot[n : 2 * n]).max() > CONTACT_ACCELERATION:
            return t, y, mem
    raise AssertionError("no state with both joints in contact")


@pytest.mark.parametrize("links", [(), MODAL, MODAL + AXIAL], ids=["rigid", "modal", "axial"])
def test_the_jacobian_pattern_holds_every_nonzero_and_leaves_out_the_unmoved(links):
    """The right-hand side sums J's rows over their pattern only (sim.model.tree.tree_pattern):
    at random states every nonzero of J must lie in it. A body's rows must leave out what does
    not move it: the crank's angle row holds its own column alone."""
    integ = prepare(_scene(*links, "simulation.revolutions=1"))
    system, work = integ.system, integ.work
    n, columns = work.tree_jac.shape
    pattern = np.zeros((n, columns), dtype=bool)
    for i in range(n):
        pattern[i, work.tree_cols[i, : work.tree_ncols[i]]] = True
    rng = np.random.default_rng(7)
    for _ in range(5):
        y = integ.y + rng.normal(size=integ.y.size)
        project_onto_tree(system, work, rng.uniform(0.0, 0.4), y)
        outside = np.argwhere((work.tree_jac != 0) & ~pattern)
        assert outside.size == 0, f"nonzeros of J outside the pattern: {outside.tolist()}"
    assert pattern.sum() < n * columns // 2  # sparse: no body moves with every column
    crank = system.drive_coord
    assert pattern[crank].tolist() == [c == columns - 1 for c in range(columns)]


@pytest.mark.parametrize("links", [(), MODAL, MODAL + AXIAL], ids=["rigid", "modal", "axial"])
def test_tree_and_multiplier_forms_agree_on_the_manifold(links):
    t, y, mem = _contact_state(*links)
    tree = prepare(_scene(*links, "simulation.revolutions=1"))
    absolute = prepare(_scene(*links, "solver.coordinates=absolute", "simulation.revolutions=1"))
    assert tree.system.tree.size == 5
    n = tree.system.n
    drift = y.copy()
    project_onto_tree(tree.system, tree.work, t, y)
    # the Baumgarte-stabilised state lies within its drift (~1e-8 m) of the manifold
    assert 0 < np.abs(y - drift)[:n].max() < 1e-6
    d_tree, d_abs = np.zeros_like(y), np.zeros_like(y)
    assert rhs(tree.system, tree.work, mem, t, y, d_tree) == OK
    assert rhs(absolute.system, absolute.work, mem, t, y, d_abs) == OK
    # round-off of two different linear solves of size ~15: 1e-13 relative measured,
    # bound 1e-9 (margin 1e4); contact forces make |q̈| ~1e3 here
    scale = np.abs(d_abs[n : 2 * n]).max()
    assert scale > CONTACT_ACCELERATION
    np.testing.assert_allclose(d_tree[n : 2 * n], d_abs[n : 2 * n], rtol=0, atol=1e-9 * scale)
    np.testing.assert_allclose(d_tree[: 2 * n], d_abs[: 2 * n], rtol=0, atol=1e-9 * scale)
    torque_tree = tree.work.scalars[SC_DRIVE_TORQUE]
    torque_abs = absolute.work.scalars[SC_DRIVE_TORQUE]
    assert torque_tree == pytest.approx(torque_abs, rel=1e-9, abs=1e-9)
    # drive power and dissipated power
    np.testing.assert_allclose(d_tree[2 * n :], d_abs[2 * n :], rtol=1e-9)


@pytest.mark.parametrize("links", [(), MODAL], ids=["rigid", "modal"])
def test_contact_forces_from_the_trees_rotations_equal_those_computed(links):
    # The tree's table holds each body's (cos θ, sin θ) at its offset; read at a wrong
    # offset, or stale, the forces of a state in contact would differ
    t, y, mem = _contact_state(*links)
    tree = prepare(_scene(*links, "simulation.revolutions=1"))
    system, work = tree.system, tree.work
    assert rhs(system, work, mem.copy(), t, y, np.zeros_like(y)) == OK
    q, qd = work.tree_q, work.tree_qd
    forces = []
    for rot in (work.tree_rot, np.zeros((0, 2))):
        gen = np.zeros(system.n)
        jout = np.zeros_like(work.jout)
        revolute_clearance_forces(system, q, qd, mem.copy(), gen, jout, rot)
        translational_clearance_forces(system, q, qd, mem.copy(), gen, jout, rot)
        forces.append((gen, jout))
    (gen_table, jout_table), (gen_computed, jout_computed) = forces
    assert np.abs(gen_computed).max() > 100.0  # contact forces of hundreds of newtons
    # the same cos and sin of the same angles: equal to the bit
    np.testing.assert_array_equal(gen_table, gen_computed)
    np.testing.assert_array_equal(jout_table, jout_computed)


def test_the_end_of_step_scan_gives_every_gaps_depth():
    _, y, mem = _contact_state()
    system, _ = build_system(_scene("solver.coordinates=absolute"))
    n = system.n
    depths = np.zeros(mem.shape[0])
    gap_depths(system, y[:n], depths)
    each = [gap(system, g, y[:n], y[n : 2 * n])[0] for g in range(mem.shape[0])]
    assert (depths > 0).any() and (depths < 0).any()
    np.testing.assert_array_equal(depths, each)


@pytest.mark.parametrize("links", [(), MODAL], ids=["rigid", "modal"])
def test_a_tree_run_keeps_its_constraints_and_closes_its_energy_audit(run, links):
    # restitution 1 and no friction: the only loss is the integrator's. The multiplier
    # form's audit on the same case is ~3e-5 (test_energy); the bound 1e-3 is the default
    # fidelity's (README, "Default fidelity").
    elastic = ("contact.restitution=1.0", "contact.friction=0.0", *links)
    ds = run("sixbar", *FLAGSHIP, *elastic, revolutions=2)
    assert ds.attrs["solver_contact_events"] > 50
    assert abs(ds.attrs["energy_error_relative"]) < 1e-3
    # each accepted step ends on the manifold: a sample inside a step is off it by the
    # continuous extension's error only, far below the Baumgarte drift of the multiplier form
    absolute = run("sixbar", *FLAGSHIP, *elastic, "solver.coordinates=absolute", revolutions=2)
    tree_violation = float(ds["constraint_violation"].max())
    assert tree_violation < 1e-9
    assert tree_violation < 0.1 * float(absolute["constraint_violation"].max())


def test_a_lyapunov_restart_near_resting_contact_passes_and_agrees_with_the_multiplier_form():
    """A member of the speed study's 30 rpm ensemble (0.2 mm, its crank shifted by 1.45e-9°),
    whose model exponent once stopped with a collapsed step at joint A (t = 2.79 s): the
    perturbed restarts left the manifold by d0 and the events read the gaps off it, while the
    forces read them from the angles. Both forms follow the same dynamics, so their exponents
    must agree within three combined standard errors (one recorded revolution: ±10-13 1/s)."""
    overrides = [
        "joints.A.clearance=2e-4",
        "joints.B.clearance=2e-4",
        "drive.speed_rpm=30",
        "drive.initial_angle_deg=1.449474094874856e-09",
    ]
    exponents = {}
    for coordinates in ("minimal", "absolute"):
        scene = load_scene("sixbar", [*overrides, f"solver.coordinates={coordinates}"])
        exponents[coordinates] = linkage_lyapunov(scene, revolutions=2, transient_revolutions=1)
    minimal, absolute = exponents["minimal"], exponents["absolute"]
    combined = np.hypot(minimal.stderr, absolute.stderr)
    assert abs(minimal.exponent - absolute.exponent) < 3.0 * combined

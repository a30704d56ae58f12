"""Assembly without hints and the full-turn check (sim/model/initial.py, sim/model/mobility.py):
a body without a hint is placed on a branch the search finds and names; a linkage whose crank
cannot turn fully is refused before integrating, at the closed-form locking angle."""

import math
import time

import numpy as np
import pytest

from sim.cli import main
from sim.model.assembly import AssemblyError, crank_period
from sim.model.initial import HINTED, assemble, constraint_values
from sim.model.mobility import check_full_turn
from sim.run import prepare
from sim.scene import load_scene

NO_HINTS = ["bodies.coupler.hint=null", "bodies.rocker.hint=null"]


def test_without_hints_the_search_finds_both_branches_and_names_the_one_it_takes():
    hinted = assemble(load_scene("fourbar"))
    searched = assemble(load_scene("fourbar", NO_HINTS))
    assert hinted.branch == HINTED
    # A four-bar closes in two ways at a given crank angle (B above or below the line A-C):
    # the search finds both and takes one, whose angles it states.
    assert "the first of 2 assembly branches" in searched.branch
    angles = {
        b: math.degrees(searched.q[searched.layout.offset[b] + 2]) % 360.0
        for b in ("coupler", "rocker")
    }
    assert f"coupler {angles['coupler']:.2f}°, rocker {angles['rocker']:.2f}°" in searched.branch
    # Closed form at crank angle 0 (A = (0.1, 0), C = (0.4, 0), |AC| = 0.3): B lies 0.35 m
    # from A and 0.3 m from C, at x = 0.1 + (0.35² − 0.3² + 0.3²)/(2·0.3) from O; the two
    # branches are ±y. Each found branch must be one of them (to Newton's 1e-13 m).
    x = 0.1 + 0.35**2 / 0.6
    y = math.sqrt(0.35**2 - (x - 0.1) ** 2)
    for q in (hinted.q, searched.q):
        theta = q[searched.layout.offset["rocker"] + 2]
        tip = (0.4 + 0.3 * math.cos(theta), 0.3 * math.sin(theta))
        assert tip[0] == pytest.approx(x, abs=1e-9)
        assert abs(tip[1]) == pytest.approx(y, abs=1e-9)


def test_the_branch_is_recorded_in_the_run(capsys):
    integ = prepare(load_scene("fourbar", NO_HINTS), ideal=True, rigid=True, revolutions=0.01)
    assert integ.assembly_branch.startswith("bodies without a hint assembled at angles coupler")


# Crank a = 0.28 m, coupler b = 0.35, rocker c = 0.30, ground d = 0.40: shortest + longest
# 0.68 > 0.65, not Grashof, the crank cannot turn fully. It stops where coupler and rocker
# line up, |AC| = b + c (|b − c| = 0.05 is out of reach): a² + d² − 2ad cos θ = (b + c)².
A, B, C, D = 0.28, 0.35, 0.30, 0.40
LOCK_DEG = math.degrees(math.acos((A * A + D * D - (B + C) ** 2) / (2.0 * A * D)))  # 145.27°
NON_GRASHOF = [f"bodies.crank.length={A}", *NO_HINTS]


def test_a_crank_that_cannot_turn_is_refused_at_its_locking_angle():
    scene = load_scene("fourbar", NON_GRASHOF)
    assembly = assemble(scene)
    start = time.perf_counter()
    with pytest.raises(AssemblyError) as refused:
        check_full_turn(assembly.system, assembly.layout, assembly.q, crank_period(scene), 0.0)
    elapsed = time.perf_counter() - start
    message = str(refused.value)
    locked = float(message.split("locks at crank angle ")[1].split("°")[0])
    # Margin 0.05°: the continuation stops when its step falls below 1e-5 turn (0.0036°) and
    # reports the last angle it assembled, so it lies below the lock by less than a few steps.
    assert LOCK_DEG - 0.05 < locked <= LOCK_DEG + 1e-6, (locked, LOCK_DEG)
    assert "the loop through joints O, A, B, C" in message
    # A turn's continuation costs 72 position analyses plus the halvings near the lock.
    assert elapsed < 1.0, elapsed


def test_the_run_is_refused_before_integrating(tmp_path, capsys):
    assemble(load_scene("fourbar"))  # numba's constraint kernels loaded (compiled) once
    out = tmp_path / "x.nc"
    args = ["run", "fourbar", "-q", "-o", str(out)]
    start = time.perf_counter()
    assert main([*args, *[f"--set={s}" for s in NON_GRASHOF]]) == 2
    elapsed = time.perf_counter() - start
    err = capsys.readouterr().err
    assert (
        "cannot be driven through a full crank turn" in err and "locks at crank angle 145." in err
    )
    assert not out.exists()
    # before the integrator: loading, assembly (two branches) and the turn well under a second
    assert elapsed < 1.0, elapsed


def test_the_six_bar_makes_a_full_turn_from_hints_and_without():
    for overrides in ([], [f"bodies.{b}.hint=null" for b in ("rod2", "rod3", "rod4", "slider")]):
        scene = load_scene("sixbar", overrides)
        assembly = assemble(scene)
        check_full_turn(assembly.system, assembly.layout, assembly.q, crank_period(scene), 0.0)


def test_far_hints_still_assemble():
    # Hints anywhere in the linkage's area: Newton from them may wander, the least-squares
    # closest approach then lands within its stopping tolerance of an assembly, and Newton from
    # there closes every loop (before, 21 of 150 such hint sets were refused).
    rng = np.random.default_rng(1)
    for _ in range(30):
        overrides = [
            f"bodies.{b}.hint={{position: [{x:.3f}, {y:.3f}], angle_deg: {a:.0f}}}"
            for b, (x, y, a) in zip(
                ("rod2", "rod3", "rod4", "slider"),
                rng.uniform((-0.3, -0.3, -180), (0.5, 0.5, 180), size=(4, 3)),
                strict=True,
            )
        ]
        assembly = assemble(load_scene("sixbar", overrides))
        phi, _, _ = constraint_values(assembly.system, assembly.q, 0.0 * assembly.q, 0.0)
        assert np.abs(phi).max() < 1e-12

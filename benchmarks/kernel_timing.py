"""Where one right-hand side evaluation spends its time (issue 2's profile, inside numba).

pyinstrument sees the compiled integrator as one opaque call, so this script times its
kernels one by one, each called in a compiled loop (no Python dispatch in the figure), on
the rigid six-bar with A and B clearances of 0.5 mm at 150 rpm, in a state with contact,
in absolute coordinates under multipliers (solver.coordinates: absolute):

  - rhs: one full evaluation ẏ = f(t, y);
  - the same evaluation in the scene's minimal coordinates (sim.model.tree), for comparison;
  - one DOPRI5 step there (six evaluations, the stage sums, the error estimate, the
    continuous extension), to set against six evaluations called one by one;
  - generalized forces: gravity, both clearance joints' contact forces (and beams, none here);
  - revolute / translational clearance forces alone;
  - constraint terms: Φ, Φ_q, γ, ν;
  - Cholesky factorisation and solve of the Schur complement Φ_q M⁻¹ Φ_qᵀ;
  - the rest of rhs (the products M⁻¹ Q, M⁻¹ Φ_qᵀ, Φ_q M⁻¹ Φ_qᵀ, q̈): the difference.

Usage: python benchmarks/kernel_timing.py [--calls N]
"""

import argparse
import time

import numpy as np

from sim.jit import kernel
from sim.model.clearance import revolute_clearance_forces, translational_clearance_forces
from sim.model.constraints import constraint_terms
from sim.model.gaps import MEM_IN_CONTACT
from sim.run import prepare
from sim.scene import load_scene
from sim.solve import dopri
from sim.solve.dae import generalized_forces, no_rotations, project_onto_tree, rhs
from sim.solve.linalg import cholesky_in_place, cholesky_solve_in_place
from sim.solve.status import OK

CASE = ["joints.A.clearance=0.5e-3", "joints.B.clearance=0.5e-3", "solver.rtol=1e-6"]
ABSOLUTE = "solver.coordinates=absolute"


@kernel
def _rhs_loop(sys, work, mem, t, y, ydot, calls):
    for _ in range(calls):
        rhs(sys, work, mem, t, y, ydot)


@kernel
def _step_loop(sys, work, carry, mem, t, h, y, options, tally, calls):
    for _ in range(calls):
        dopri.step(sys, work, carry, mem, t, h, y, options, tally)


@kernel
def _forces_loop(sys, work, mem, t, y, calls):
    n = sys.n
    for _ in range(calls):
        generalized_forces(sys, work, t, y[:n], y[n : 2 * n], mem, no_rotations(work))


@kernel
def _revolute_loop(sys, work, mem, y, calls):
    n = sys.n
    for _ in range(calls):
        revolute_clearance_forces(
            sys, y[:n], y[n : 2 * n], mem, work.gen, work.jout, no_rotations(work)
        )


@kernel
def _translational_loop(sys, work, mem, y, calls):
    n = sys.n
    for _ in range(calls):
        translational_clearance_forces(
            sys, y[:n], y[n : 2 * n], mem, work.gen, work.jout, no_rotations(work)
        )


@kernel
def _constraints_loop(sys, work, t, y, calls):
    n = sys.n
    for _ in range(calls):
        constraint_terms(sys, t, y[:n], y[n : 2 * n], work.phi, work.jac, work.gamma, work.nu)


@kernel
def _cholesky_loop(schur, factor, b, rhs_in, m, first, calls):
    # the copies (m² + m numbers) are part of the figure; they are small against the rest
    for _ in range(calls):
        for i in range(m):
            b[i] = rhs_in[i]
            for j in range(m):
                factor[i, j] = schur[i, j]
        cholesky_in_place(factor, m, first)
        cholesky_solve_in_place(factor, m, b)


def per_call_us(loop, *args, calls: int, repeats: int = 3) -> float:
    """Best of `repeats` timings of `calls` calls, in microseconds per call."""
    loop(*args, 10)  # compile or load from the cache
    best = np.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        loop(*args, calls)
        best = min(best, time.perf_counter() - t0)
    return 1e6 * best / calls


def contact_state(scene: dict, after: float = 0.0, revolutions: float = 5.0):
    """The integration of `scene` at the first chunk end (1/200 revolution apart) after
    `after` revolutions where the journal of A and a corner of the slider are both in contact
    (gap 0: the journal of A; gaps 1–8: the slider's corners against the guide walls), and
    its time (s)."""
    integ = prepare(scene, revolutions=revolutions)
    period = 60.0 / scene["drive"]["speed_rpm"]
    t = after * period
    if t > 0.0 and integ.advance(t) != OK:
        raise RuntimeError(f"integration failed before t = {t}")
    while t < revolutions * period:
        t += period / 200
        if integ.advance(t) != OK:
            raise RuntimeError(f"integration failed at t = {t}")
        closed = integ.mem[:, MEM_IN_CONTACT] > 0
        if closed[0] and closed[1:].any():
            return integ, t
    raise RuntimeError("no contact found")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=200_000)
    args = parser.parse_args()
    integ, t = contact_state(load_scene("sixbar", [*CASE, ABSOLUTE]))
    sys, work, mem, y = integ.system, integ.work, integ.mem, integ.y.copy()
    ydot = np.zeros_like(y)
    calls = args.calls
    closed = [int(g) for g in np.nonzero(integ.mem[:, MEM_IN_CONTACT] > 0)[0]]
    print(
        f"rigid six-bar, A+B 0.5 mm, state at t = {t:.4f} s (closed gaps {closed}), "
        f"n = {sys.n} coordinates, m = {sys.m} constraints; µs per call, best of 3 × {calls}:"
    )
    tree = prepare(load_scene("sixbar", CASE), revolutions=1.0)
    y_tree = y.copy()
    project_onto_tree(tree.system, tree.work, t, y_tree)
    _, _, carry, _, _, options, _, tallies = tree.arguments(t)
    rhs(tree.system, tree.work, mem, t, y_tree, carry.derivative)  # the step's k1
    tree_rhs = per_call_us(_rhs_loop, tree.system, tree.work, mem, t, y_tree, ydot, calls=calls)
    step_args = (tree.system, tree.work, carry, mem, t, 1e-5, y_tree, options, tallies[0])
    figures = {
        "rhs (one evaluation, multipliers)": per_call_us(
            _rhs_loop, sys, work, mem, t, y, ydot, calls=calls
        ),
        "rhs in minimal coordinates": tree_rhs,
        "  6 of them, called one by one": 6 * tree_rhs,
        "  one DOPRI5 step there (h = 10 µs)": per_call_us(
            _step_loop, *step_args, calls=calls // 4
        ),
        "generalized forces": per_call_us(_forces_loop, sys, work, mem, t, y, calls=calls),
        "  revolute clearance (A)": per_call_us(_revolute_loop, sys, work, mem, y, calls=calls),
        "  translational clearance (B)": per_call_us(
            _translational_loop, sys, work, mem, y, calls=calls
        ),
        "constraint terms": per_call_us(_constraints_loop, sys, work, t, y, calls=calls),
    }
    rhs(sys, work, mem, t, y, ydot)  # leaves the Schur matrix and its right-hand side
    m = sys.m
    # rhs factors work.schur in place; rebuild S = Φ_q M⁻¹ Φ_qᵀ from its own products
    schur = work.jac @ work.minv_jt
    figures["Schur Cholesky + solve"] = per_call_us(
        _cholesky_loop,
        schur,
        np.zeros((m, m)),
        np.zeros(m),
        work.rhs.copy(),
        m,
        work.schur_first,
        calls=calls,
    )
    parts = sum(figures[k] for k in ("generalized forces", "constraint terms"))
    # the rest is the multiplier form's
    figures["rest (M⁻¹ products, Schur assembly)"] = (
        figures["rhs (one evaluation, multipliers)"] - parts - figures["Schur Cholesky + solve"]
    )
    for name, value in figures.items():
        print(f"  {name:38s} {value:6.3f}")


if __name__ == "__main__":
    main()

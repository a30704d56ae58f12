"""Where one generalized-α step of the flexible flagship spends its time, part by part.

The flagship (A and B clearances of 0.5 mm, 150 rpm) on ANCF beams of two elements under
generalized-α at the scene's rtol 1e-5, integrated to the first state after 2 revolutions with
the journal of A and a corner of the slider in contact (`kernel_timing.contact_state`). From
that state each part is timed in a compiled loop (best of nine runs of N calls, µs per call)
by `benchmarks/kernel_timing.py`'s timer for DOPRI5's parts:

  - the step with the iteration matrix kept (`sim.solve.galpha.step`), and within it Newton's
    iteration, one residual (a force and constraint evaluation) and one solve with the factors;
  - forming the iteration matrix and its LU factors (`_factor`): the beams' tangents, the
    contact forces' forward differences, the LU over the fixed pattern;
  - the step's end: the Schur complement's factors, the velocity projection, the
    accelerations, the Hermite extension with the energy quadratures;
  - the loop's probe for grazes on the continuous extension.

Then the run's counts per revolution up to that state (steps, evaluations, iteration matrices)
and what they make of the parts: the time of a revolution they account for.

Usage: python benchmarks/galpha_timing.py [--calls N]
"""

import argparse
import functools

import numpy as np
from kernel_timing import contact_state, per_call_us

from sim.jit import kernel
from sim.scene import load_scene
from sim.solve import galpha
from sim.solve.dae import factor_schur, factored_accelerations, project_velocities
from sim.solve.dense import hermite_coefficients
from sim.solve.linalg import pattern_lu_in_place, pattern_lu_solve_in_place
from sim.solve.tangent import (
    _add_beam_tangent,
    _add_contact_tangent,
    _contact_force_acts,
    iteration_matrix,
)

SCENE = [
    "joints.A.clearance=5e-4",
    "joints.B.clearance=5e-4",
    *(f"bodies.{b}.kind=beam" for b in ("rod2", "rod3", "rod4")),
    "solver.method=generalized_alpha",
]
REPEATS = 9
"""Timings of each part, the best one kept."""
#: the iteration matrix's coefficients for the parts' timing: those of a step of 20 µs
C_M, C_C, C_K = 1.0, 1e-5, 1e-10


@kernel
def _step_loop(sys, work, carry, mem, t, h, y, options, tally, calls):
    for _ in range(calls):
        galpha.step(sys, work, carry, mem, t, h, y, options, tally)


@kernel
def _newton_loop(sys, work, carry, mem, t, h, y, rtol, atol, rho_inf, calls):
    for _ in range(calls):
        galpha._newton(sys, work, carry, mem, t, h, y, rtol, atol, rho_inf, False)


@kernel
def _residual_loop(sys, work, carry, mem, t, rtol, atol, calls):
    n = sys.n
    q = work.ynew[:n]
    v = work.ynew[n : 2 * n]
    for _ in range(calls):
        galpha._residual(
            sys, work, carry, mem, t, q, v, carry.xdd_new, carry.lam_new, 1e-10, rtol, atol
        )


@kernel
def _solve_loop(carry, work, x0, calls):
    x = carry.newton_rhs
    for _ in range(calls):
        for i in range(x0.shape[0]):
            x[i] = x0[i]
        pattern_lu_solve_in_place(carry.it_mat, work.newton_lu, x)


@kernel
def _matrix_loop(sys, work, carry, mem, t, y, calls):
    n = sys.n
    for _ in range(calls):
        iteration_matrix(sys, work, carry.it_mat, mem, t, y[:n], y[n : 2 * n], C_M, C_C, C_K)
        pattern_lu_in_place(carry.it_mat, work.newton_lu)


@kernel
def _beam_tangent_loop(sys, work, mat, y, calls):
    n = sys.n
    for _ in range(calls):
        _add_beam_tangent(sys, work, mat, y[:n], y[n : 2 * n], C_C, C_K)


@kernel
def _contact_tangent_loop(sys, work, mat, mem, y, calls):
    n = sys.n
    q = y[:n]
    qd = y[n : 2 * n]
    for _ in range(calls):
        _contact_force_acts(sys, work, mem, q, qd)
        _add_contact_tangent(sys, work, mat, mem, q, qd, q, 1e-10, C_K)
        _add_contact_tangent(sys, work, mat, mem, q, qd, qd, 1e-8, C_C)


@kernel
def _lu_loop(work, mat, assembled, calls):
    for _ in range(calls):
        for i in range(mat.shape[0]):
            for j in range(mat.shape[1]):
                mat[i, j] = assembled[i, j]
        pattern_lu_in_place(mat, work.newton_lu)


@kernel
def _schur_loop(sys, work, calls):
    for _ in range(calls):
        factor_schur(sys, work)


@kernel
def _projection_loop(sys, work, v0, calls):
    v = work.ytmp[: v0.shape[0]]
    for _ in range(calls):
        for i in range(v0.shape[0]):
            v[i] = v0[i]
        project_velocities(sys, work, v)


@kernel
def _accelerations_loop(sys, work, y, ydot, calls):
    n = sys.n
    for _ in range(calls):
        factored_accelerations(sys, work, y[n : 2 * n], ydot)


@kernel
def _quadratures_loop(sys, work, mem, h, y, k0, rtol, atol, calls):
    for _ in range(calls):
        hermite_coefficients(work, y, k0, h)
        galpha._energy_quadratures(sys, work, mem, h, y, k0, rtol, atol)


@kernel
def _grazes_loop(sys, work, mem, calls):
    for _ in range(calls):
        galpha.mark_grazes(sys, work, mem)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--calls", type=int, default=20_000)
    args = parser.parse_args()
    time_us = functools.partial(per_call_us, repeats=REPEATS)
    scene = load_scene("sixbar", SCENE)
    period = 60.0 / scene["drive"]["speed_rpm"]
    integ, t = contact_state(scene, after=2.0, revolutions=4.0)
    revolutions = t / period
    sys, work, carry, trajectory, _, options, _, tallies = integ.arguments(t)
    counts = {name: int(tallies[0][name]) for name in ("accepted", "rejected", "jacobians")}
    mem, y = trajectory.mem, trajectory.y.copy()
    n, calls, h = sys.n, args.calls, 2e-5
    rtol, atol, rho_inf = options.rtol, options.atol, options.method.rho_inf
    print(
        f"flexible flagship, state at t = {t:.4f} s, n = {sys.n}, m = {sys.m}, "
        f"h = {h * 1e6:.0f} µs; µs per call, best of {REPEATS} × {calls}:"
    )
    figures = {
        "step, iteration matrix kept": time_us(
            _step_loop, sys, work, carry, mem, t, h, y, options, tallies[0], calls=calls
        )
    }
    newton = (sys, work, carry, mem, t, h, y, rtol, atol, rho_inf)
    figures["  Newton's iteration"] = time_us(_newton_loop, *newton, calls=calls)
    _newton_loop(*newton, 1)  # leaves the converged state in work.ynew
    end = work.ynew.copy()
    figures["    one residual"] = time_us(
        _residual_loop, sys, work, carry, mem, t + h, rtol, atol, calls=5 * calls
    )
    figures["    one solve"] = time_us(
        _solve_loop, carry, work, carry.newton_rhs.copy(), calls=5 * calls
    )
    factor_schur(sys, work)
    figures["  end: Schur complement's factors"] = time_us(_schur_loop, sys, work, calls=5 * calls)
    figures["  end: velocity projection"] = time_us(
        _projection_loop, sys, work, end[n : 2 * n].copy(), calls=5 * calls
    )
    ydot = np.zeros_like(y)
    figures["  end: accelerations"] = time_us(
        _accelerations_loop, sys, work, end, ydot, calls=5 * calls
    )
    figures["  end: extension, energy quadratures"] = time_us(
        _quadratures_loop, sys, work, mem, h, y, carry.derivative, rtol, atol, calls=5 * calls
    )
    figures["loop: graze probes"] = time_us(_grazes_loop, sys, work, mem, calls=5 * calls)
    mat = carry.it_mat
    figures["iteration matrix and LU factors"] = time_us(
        _matrix_loop, sys, work, carry, mem, t + h, end, calls=calls
    )
    figures["  beams' tangents"] = time_us(_beam_tangent_loop, sys, work, mat, end, calls=calls)
    figures["  contact forces' differences"] = time_us(
        _contact_tangent_loop, sys, work, mat, mem, end, calls=calls
    )
    iteration_matrix(sys, work, mat, mem, t + h, end[:n], end[n : 2 * n], C_M, C_C, C_K)
    figures["  LU over the pattern (with a copy)"] = time_us(
        _lu_loop, work, np.empty_like(mat), mat.copy(), calls=calls
    )
    for name, value in figures.items():
        print(f"  {name:40s} {value:7.2f}")
    steps = (counts["accepted"] + counts["rejected"]) / revolutions
    matrices = counts["jacobians"] / revolutions
    step_ms = steps * figures["step, iteration matrix kept"] / 1e3
    matrix_ms = matrices * figures["iteration matrix and LU factors"] / 1e3
    print(
        f"per revolution up to t: {steps:.0f} steps (with rejected), {matrices:.0f} iteration "
        f"matrices: steps {step_ms:.0f} ms + matrices {matrix_ms:.0f} ms = "
        f"{step_ms + matrix_ms:.0f} ms of the revolution's {period * 1e3:.0f} ms simulated"
    )


if __name__ == "__main__":
    main()

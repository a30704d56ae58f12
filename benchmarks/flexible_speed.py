"""Benchmark of the flexible six-bar (issue 7): real-time factor per integrator.

The flagship case: A and B clearances of 0.5 mm, 150 rpm, rod2–rod4 as ANCF beams of
2 elements each, rtol 1e-6, on one core after compilation. Prints for each integrator
the real-time factor, steps, rejected steps, force evaluations, iteration matrices and
Newton failures, and where one implicit step's time goes (the compiled kernels timed
one by one, since a Python profiler cannot see inside them).

With --why it prints instead what sets the implicit method's step count: the natural
frequencies of the linearized flexible mechanism at the start, and the steps per
revolution of the flagship beside its parts (rigid links with the clearances, beams
with ideal joints) and beside the two ways of taking the ringing out (maximal numerical
damping ρ∞ = 0, and 1 % modal damping of the beams).

With --modal it prints the real-time factor of the flagship at the default fidelity (rtol
1e-5) with rod2–rod4 as modal links (DOPRI5; `--modes` modes each, the scene's default if
not given) beside the ANCF beams of 2 elements (generalized-α), issue 19's comparison.

Usage: python benchmarks/flexible_speed.py [--revolutions N] [--explicit-revolutions M]
       [--why] [--modal [--modes K]] [--set key=value ...]
"""

import argparse
import time

import numba
import numpy as np
import scipy.linalg

from sim.model.constraints import constraint_terms
from sim.run import prepare, simulate
from sim.scene import load_scene
from sim.solve import dae, galpha, linalg, tangent

FLAGSHIP = [
    "joints.A.clearance=0.5e-3",
    "joints.B.clearance=0.5e-3",
    "solver.rtol=1e-6",
    *(f"bodies.{b}.kind=beam" for b in ("rod2", "rod3", "rod4")),
    *(f"bodies.{b}.elements=2" for b in ("rod2", "rod3", "rod4")),
]


def run(method: str, revolutions: float, scene_sets: list[str]) -> dict:
    """One simulation of the six-bar with these overrides, after a short warm-up run
    (compilation); its statistics."""
    sets = [*scene_sets, f"solver.method={method}"]
    simulate(load_scene("sixbar", [*sets, "simulation.revolutions=0.005"]))
    ds = simulate(load_scene("sixbar", [*sets, f"simulation.revolutions={revolutions}"]))
    return ds.attrs


@numba.njit
def _time_residual(system, work, carry, mem, q, v, count):
    for _ in range(count):
        galpha._residual(system, work, mem, 0.0, q, v, carry.xdd, carry.lam, 1e-9, 1e-6, 1e-8)


@numba.njit
def _time_rhs(system, work, mem, y, count):
    for _ in range(count):
        dae.rhs(system, work, mem, 0.0, y, work.ydot_end)


@numba.njit
def _time_forces(system, work, mem, q, v, count):
    for _ in range(count):
        dae.generalized_forces(system, work, 0.0, q, v, mem, dae.no_rotations(work))
        constraint_terms(system, 0.0, q, v, work.phi, work.jac, work.gamma, work.nu)


@numba.njit
def _time_matrix(system, work, carry, mem, q, v, count):
    for _ in range(count):
        tangent.iteration_matrix(system, work, carry.it_mat, mem, 0.0, q, v, 1.0, 1e-5, 1e-9)
        linalg.lu_in_place(carry.it_mat, carry.it_piv)


@numba.njit
def _time_solve(work, carry, count):
    for _ in range(count):
        linalg.lu_solve_in_place(carry.it_mat, carry.it_piv, work.it_rhs)


def kernel_costs() -> dict[str, float]:
    """Microseconds per call of the kernels one implicit step is made of."""
    integ = prepare(load_scene("sixbar", FLAGSHIP))
    system, work, carry, mem, y = integ.system, integ.work, integ.carry, integ.mem, integ.y
    n = system.n
    q, v = y[:n].copy(), y[n : 2 * n].copy()
    cases = {
        "forces + constraints (one evaluation)": (_time_forces, (system, work, mem, q, v)),
        "Newton residual (evaluation + M q̈ + Φ_qᵀλ)": (
            _time_residual,
            (system, work, carry, mem, q, v),
        ),
        "equations of motion at the step's end (rhs)": (_time_rhs, (system, work, mem, y)),
        "iteration matrix + LU factorisation": (_time_matrix, (system, work, carry, mem, q, v)),
        "LU solve": (_time_solve, (work, carry)),
    }
    out = {}
    for name, (kernel, args) in cases.items():
        kernel(*args, 2)
        count = 2000
        start = time.perf_counter()
        kernel(*args, count)
        out[name] = 1e6 * (time.perf_counter() - start) / count
    return out


def natural_frequencies(sets: list[str]) -> np.ndarray:
    """Natural frequencies (Hz) of the mechanism linearized at its assembled start, with
    every joint ideal: K_t x = ω² M x on the null space of Φ_q (the iteration matrix's
    mass and stiffness blocks; the geometric stiffness of the constraint forces, which
    it leaves out, is left out here too)."""
    integ = prepare(load_scene("sixbar", [s for s in sets if not s.startswith("joints.")]))
    system, work, mem, y = integ.system, integ.work, integ.mem, integ.y
    n = system.n
    q, v = y[:n].copy(), np.zeros(n)
    constraint_terms(system, 0.0, q, v, work.phi, work.jac, work.gamma, work.nu)
    mat = integ.carry.it_mat
    tangent.iteration_matrix(system, work, mat, mem, 0.0, q, v, 1.0, 0.0, 0.0)
    mass = mat[:n, :n].copy()
    tangent.iteration_matrix(system, work, mat, mem, 0.0, q, v, 0.0, 0.0, 1.0)
    stiffness = mat[:n, :n].copy()
    basis = scipy.linalg.null_space(work.jac)
    omega2 = scipy.linalg.eigh(
        basis.T @ stiffness @ basis, basis.T @ mass @ basis, eigvals_only=True
    )
    return np.sqrt(np.clip(omega2, 0.0, None)) / (2.0 * np.pi)


def why(revolutions: float, extra: list[str]) -> None:
    """Print the spectrum and the steps per revolution of the flagship's variants."""
    sets = [*FLAGSHIP, *extra]
    freqs = natural_frequencies(sets)
    print("natural frequencies of the flexible mechanism, all joints ideal (kHz):")
    print("  " + " ".join(f"{f / 1e3:.2f}" for f in freqs))
    beams = [s for s in FLAGSHIP if s.startswith("bodies.")]
    joints = [s for s in FLAGSHIP if s.startswith("joints.")]
    modal = [f"bodies.{b}.damping={{kind: modal, ratio: 0.01}}" for b in ("rod2", "rod3", "rod4")]
    variants = {
        "rigid links, A + B clearances": [s for s in sets if s not in beams],
        "beams, all joints ideal": [s for s in sets if s not in joints],
        "flagship (beams, A + B clearances)": sets,
        "flagship, rho_inf = 0": [*sets, "solver.rho_inf=0.0"],
        "flagship, beams with 1 % modal damping": [*sets, *modal],
    }
    print(f"generalized-alpha, {revolutions:g} revolutions:")
    for name, variant in variants.items():
        st = run("generalized_alpha", revolutions, variant)
        steps = st["solver_accepted_steps"] / revolutions
        mean_step = 1e6 * st["crank_period"] / steps
        print(
            f"  {name:40s} {steps:8.0f} steps per revolution (mean {mean_step:6.1f} us), "
            f"real-time factor {st['real_time_factor']:.2f}"
        )


RODS = ("rod2", "rod3", "rod4")
FLAGSHIP_DEFAULT_FIDELITY = [
    "joints.A.clearance=0.5e-3",
    "joints.B.clearance=0.5e-3",
    "solver.rtol=1e-5",
    "solver.atol=1e-7",
]


def modal_against_beams(revolutions: float, modes: int | None, extra: list[str]) -> None:
    """Real-time factors of the flagship with modal rod2–rod4 (DOPRI5) and with ANCF beams
    (generalized-α), both at rtol 1e-5 (issue 19)."""
    modal = [f"bodies.{b}.kind=modal" for b in RODS]
    if modes is not None:
        modal += [f"bodies.{b}.modes={modes}" for b in RODS]
    beams = [f"bodies.{b}.kind=beam" for b in RODS] + [f"bodies.{b}.elements=2" for b in RODS]
    print(f"flagship: A + B 0.5 mm, 150 rpm, rtol 1e-5, {revolutions:g} revolutions")
    for label, method, sets in (
        (f"modal x {modes or 'default'} modes", "dopri5", modal),
        ("ANCF 2 elements", "generalized_alpha", beams),
    ):
        st = run(method, revolutions, [*FLAGSHIP_DEFAULT_FIDELITY, *sets, *extra])
        print(
            f"  {label:22s} {method:18s} real-time factor {st['real_time_factor']:.3f}, "
            f"wall {st['solver_wall_time_s']:.2f} s, steps {st['solver_accepted_steps']} "
            f"(+{st['solver_rejected_steps']} rejected), "
            f"{st['solver_accepted_steps'] / revolutions:.0f} steps per revolution, "
            f"energy error {st['energy_error_relative']:.2e}"
        )


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--revolutions", type=float, default=2.0)
    parser.add_argument(
        "--explicit-revolutions",
        type=float,
        default=0.1,
        help="DOPRI5 resolves the beams' axial modes and is slow: a shorter run",
    )
    parser.add_argument("--why", action="store_true", help="what sets the step count")
    parser.add_argument("--modal", action="store_true", help="modal links against ANCF beams")
    parser.add_argument("--modes", type=int, default=None, help="modes per modal link")
    parser.add_argument("--set", dest="extra", action="append", default=[])
    args = parser.parse_args()
    if args.why:
        why(args.revolutions, args.extra)
        return
    if args.modal:
        modal_against_beams(args.revolutions, args.modes, args.extra)
        return
    print("flagship: A + B 0.5 mm, 150 rpm, rod2-rod4 beams x 2 elements, rtol 1e-6")
    for method, revs in (
        ("generalized_alpha", args.revolutions),
        ("dopri5", args.explicit_revolutions),
    ):
        st = run(method, revs, [*FLAGSHIP, *args.extra])
        steps = st["solver_accepted_steps"] + st["solver_rejected_steps"]
        print(
            f"  {method:18s} {revs:g} rev: real-time factor {st['real_time_factor']:.3f}, "
            f"wall {st['solver_wall_time_s']:.2f} s, steps {st['solver_accepted_steps']} "
            f"(+{st['solver_rejected_steps']} rejected), evaluations "
            f"{st['solver_function_evaluations']}, iteration matrices "
            f"{st['solver_iteration_matrices']}, Newton failures {st['solver_newton_failures']}, "
            f"contact events {st['solver_contact_events']}, "
            f"{1e6 * st['solver_wall_time_s'] / steps:.1f} us per step"
        )
    print("where one implicit step's time goes (us per call):")
    for name, cost in kernel_costs().items():
        print(f"  {name:48s} {cost:8.2f}")


if __name__ == "__main__":
    main()

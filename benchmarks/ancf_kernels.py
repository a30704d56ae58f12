"""Time per call of the ANCF elastic force and tangent stiffness kernels (sim.model.ancf).

Run: ``python benchmarks/ancf_kernels.py``. Steel link of the six-bar (0.06 × 0.02 m section,
L = 0.35 m) meshed with 2 and 8 elements, deformed by a seeded random perturbation; timings are
taken after compilation, as the best of several repeats of many calls (one core). Two figures
per kernel: called from Python (includes numba's dispatch, ~0.2–0.3 µs) and called from a
compiled loop, as the assembler's hot loop will.
"""

import timeit

import numba
import numpy as np

from sim.model.ancf import (
    beam_constants,
    beam_elastic_forces,
    beam_elastic_jacobian,
    straight_beam_coordinates,
)

E = 207e9  # Pa
AREA = 1.2e-3  # m²
INERTIA = 4e-8  # m⁴
LENGTH = 0.35  # m
CALLS = 20_000
REPEATS = 5


def time_per_call(function, *arguments) -> float:
    """Best-of-REPEATS time (s) of one call from Python, averaged over CALLS calls."""
    function(*arguments)  # compile (or load from the cache) outside the timing
    return min(timeit.repeat(lambda: function(*arguments), number=CALLS, repeat=REPEATS)) / CALLS


@numba.njit
def _compiled_loop(kernel, q, dshape, axial_weight, d2shape, bending_weight, out, calls):
    for _ in range(calls):
        kernel(q, dshape, axial_weight, d2shape, bending_weight, out)


def time_per_compiled_call(kernel, q, constants, out) -> float:
    """Best-of-REPEATS time (s) of one call from compiled code, averaged over CALLS calls."""
    _compiled_loop(kernel, q, *constants, out, 1)  # compile outside the timing
    return (
        min(
            timeit.repeat(
                lambda: _compiled_loop(kernel, q, *constants, out, CALLS),
                number=1,
                repeat=REPEATS,
            )
        )
        / CALLS
    )


def main() -> None:
    rng = np.random.default_rng(0)
    for n in (2, 8):
        constants = beam_constants(LENGTH / n, E * AREA, E * INERTIA)
        q = straight_beam_coordinates(np.zeros(2), np.array([LENGTH, 0.0]), n)
        q += 1e-3 * rng.standard_normal(q.size)
        forces = np.empty(q.size)
        jacobian = np.empty((q.size, q.size))
        for kernel, out in ((beam_elastic_forces, forces), (beam_elastic_jacobian, jacobian)):
            from_python = time_per_call(kernel, q, *constants, out)
            compiled = time_per_compiled_call(kernel, q, constants, out)
            print(
                f"{n} elements ({q.size} coordinates), {kernel.__name__}: "
                f"{from_python * 1e6:.2f} µs from Python, {compiled * 1e6:.2f} µs compiled"
            )


if __name__ == "__main__":
    main()

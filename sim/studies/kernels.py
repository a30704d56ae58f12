"""Compile the integrator's kernels for one method before the runs that need them.

numba compiles a kernel on its first call and keeps it in the on-disk cache (:mod:`sim.jit`),
so in a fresh environment the first runs pay the compile: up to a minute for each method's
integration loop (`sim.kernel_cache.COMPILE_SECONDS`). Two processes that start at once both
compile what they share. The workflow's rule ``compile_kernels`` (and the test suite's set-up,
``tests/conftest.py``) runs :func:`compile_kernels` once per method, the two methods side by
side, before any run of that method.

The order inside it lets the two side-by-side compiles share the kernels common to both
methods, the right-hand side (`sim.solve.dae.rhs`) and the sample row
(`sim.solve.record.record_row`), instead of each compiling them. DOPRI5's run compiles them
first (its events and samples call them; its stages inline the evaluation). Generalized-α's
step calls neither, so it compiles its step first (`STEP_FIRST`), for longer than they take,
and then loads them from the cache (`benchmarks/compile_time.py` gives the per-kernel times).

One short run covers every scene of the studies: the compiled loop depends on the types of the
system's arrays, not on their sizes, so rigid, modal and beam links, ideal and clearance
joints, minimal and absolute coordinates all share it.
"""

import time

import numba
import numpy as np

from sim.model.assembly import build_system
from sim.model.gaps import contact_memory
from sim.run import prepare, simulate, solver_options
from sim.scene import load_scene
from sim.solve import lockstep
from sim.solve.methods import implementation, make_carry
from sim.solve.state import TALLY
from sim.solve.work import make_work, state_size

#: the run that compiles a method's kernels: the six-bar with clearance in A and B and
#: two-element beams, long enough for its first contact events
WARMUP_OVERRIDES = (
    "joints.A.clearance=5.0e-4",
    "joints.B.clearance=5.0e-4",
    "bodies.rod2.kind=beam",
    "bodies.rod3.kind=beam",
    "bodies.rod4.kind=beam",
    "simulation.revolutions=0.02",
    "simulation.output_per_revolution=200",
)


#: the methods whose own step compiles before the shared kernels: it calls none of them
STEP_FIRST = ("generalized_alpha",)


def compile_step(scene: dict) -> None:
    """Compile the step kernel of the scene's method (sim.solve.methods) for the argument
    types the integration loop passes it, without running anything."""
    system, _ = build_system(scene)
    options = solver_options(scene, system)
    tally = np.zeros(1, dtype=TALLY)[0]  # the loop's tallies[0]
    arguments = (
        system,
        make_work(system),
        make_carry(options.method, system.n, system.m),
        contact_memory(system),
        0.0,
        0.0,
        np.zeros(state_size(system)),
        options,
        tally,
    )
    implementation(options.method).step.compile(tuple(map(numba.typeof, arguments)))


def compile_kernels(method: str) -> float:
    """Compile (or load from numba's cache) every kernel a run with integrator ``method``
    (``solver.method``: ``dopri5`` or ``generalized_alpha``) calls: the method's step if in
    STEP_FIRST, then the built-in six-bar run for 0.02 revolution, then the lockstep follower of
    the model exponent (sim.solve.lockstep); returns the wall time in seconds."""
    start = time.perf_counter()
    scene = load_scene("sixbar", [*WARMUP_OVERRIDES, f"solver.method={method}"])
    if method in STEP_FIRST:
        compile_step(scene)
    simulate(scene)
    arguments = prepare(scene).follow_arguments(np.zeros(1), 0)
    lockstep.follow.compile(tuple(numba.typeof(a) for a in arguments))
    return time.perf_counter() - start

"""Compile the integrator's kernels for one method before the runs that need them.

numba compiles a kernel on its first call and keeps it in the on-disk cache (:mod:`sim.jit`),
so in a fresh environment the first runs pay the compile: about four minutes for each method's
integration loop on this project's reference machine. Two processes that start at once both
compile, and the workflow starts two at once: in a full run from an empty cache without
this rule the first two runs (both DOPRI5) each spent ~4.5 min compiling, and the next two
(both generalized-α) ~3.5 min. The workflow's rule ``compile_kernels`` runs
:func:`compile_kernels` once per method before any run of that method, so each method is
compiled once, the two methods side by side.

One short run covers every scene of the studies: the compiled loop depends on the types of the
system's arrays, not on their sizes, so rigid, modal and beam links, ideal and clearance
joints, minimal and absolute coordinates all share it.
"""

import time

import numba
import numpy as np

from sim.run import prepare, simulate
from sim.scene import load_scene
from sim.solve import lockstep

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


def compile_kernels(method: str) -> float:
    """Compile (or load from numba's cache) every kernel a run with integrator ``method``
    (``solver.method``: ``dopri5`` or ``generalized_alpha``) calls, by running the built-in
    six-bar for 0.02 revolution with it, and the lockstep follower of the model exponent
    (sim.solve.lockstep) for it; returns the wall time in seconds."""
    start = time.perf_counter()
    scene = load_scene("sixbar", [*WARMUP_OVERRIDES, f"solver.method={method}"])
    simulate(scene)
    arguments = prepare(scene).follow_arguments(np.zeros(1), 0)
    lockstep.follow.compile(tuple(numba.typeof(a) for a in arguments))
    return time.perf_counter() - start

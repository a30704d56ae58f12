"""The integration methods (solver.method) behind one kernel interface.

Each method module (`sim.solve.dopri`, `sim.solve.galpha`) owns its carry, the data one step
hands to the next (a NamedTuple `Carry` of arrays with at least `derivative`, ẏ at the step's
start, made by `make_carry(n, m)`), and implements the same kernels, with the same signatures:

- `start(sys, work, carry)`: prepare the step data from the evaluation at (t, y) just made
  (ẏ in carry.derivative; λ in work.rhs);
- `plan(t, h, t_end, buffers, tally)`: the step to take from t when the controller wants h;
- `step(sys, work, carry, mem, t, h, y, options, tally)`: one step: the new state in
  work.ynew, its derivative in work.ydot_end, the continuous extension in work.dense, the
  evaluations counted in tally; returns (status, error scaled to the tolerance, ∞ when the
  step failed);
- `mark_grazes(sys, work, mem)`: mark MEM_GRAZED (`sim.model.gaps`) the open gaps the step
  passed through;
- `accept(sys, work, carry)`: make the step just accepted the start of the next;
- `sample(sys, work, mem, t0, h, time, row)`: record the sample at `time` in (t0, t0 + h];
- `step_factor(err, err_old)`: ratio of the next step size to this one.

The method of a run is the type of Options.method (`Dopri5`, `GeneralizedAlpha`, which also
carry the method's own parameters). The kernels below take the options and resolve to the
method's kernel when the caller is compiled (numba `overload` on that type): the loop
(`sim.solve.stepping`) is compiled once per method, without a run-time branch, and numba's
on-disk cache keeps both (a loop built by a factory closing over the method's kernels would
miss the cache in every new process: numba issue #6264).
"""

from types import ModuleType
from typing import NamedTuple

import numpy as np
from numba.core import cgutils, types
from numba.extending import intrinsic

from sim.jit import spliced
from sim.solve import dopri, galpha
from sim.solve.control import FAC_MAX, FAC_MIN


class Dopri5(NamedTuple):
    """Dormand–Prince 5(4) (sim.solve.dopri): no parameters beyond the tolerances."""


class GeneralizedAlpha(NamedTuple):
    """Generalized-α (sim.solve.galpha)."""

    rho_inf: float  # spectral radius at infinity, in [0, 1]


def method_of(solver: dict) -> Dopri5 | GeneralizedAlpha:
    """Options.method for a scene's validated `solver` section."""
    if solver["method"] == "dopri5":
        return Dopri5()
    return GeneralizedAlpha(rho_inf=float(solver["rho_inf"]))


_MODULES = {Dopri5: dopri, GeneralizedAlpha: galpha}


def implementation(method: Dopri5 | GeneralizedAlpha) -> ModuleType:
    """The module that implements Options.method (sim.solve.dopri or sim.solve.galpha)."""
    return _MODULES[type(method)]


def make_carry(method: Dopri5 | GeneralizedAlpha, n: int, m: int) -> tuple:
    """The carry of Options.method for n coordinates and m constraints."""
    return implementation(method).make_carry(n, m)


def _module(options):
    """The method module of a numba Options type."""
    return _MODULES[options.types[options.fields.index("method")].instance_class]


@spliced
def grown_step(hs: float, err: float, facold: float, options) -> float:
    """The next step size after an accepted step of size hs with error err ≤ 1 (facold:
    the previous accepted step's)."""
    return hs * max(FAC_MIN, min(FAC_MAX, step_factor(err, facold, options)))


@spliced
def shrunk_step(hs: float, err: float, options) -> float:
    """The retry step size after a rejected step (err > 1, or ∞ when the step itself
    failed: a stage non-finite or Newton not converging): never longer than hs."""
    if not np.isfinite(err):
        return hs * FAC_MIN
    return hs * max(FAC_MIN, min(1.0, step_factor(err, 1.0, options)))


def _dispatched(name: str, options_at: int, passes_options: bool):
    """A compiled function taking the arguments of the method kernel `name` and the options
    (argument `options_at`), which calls the kernel `name` of the method module of the options
    with those arguments, the options among them only if `passes_options`. The kernel is
    resolved when the caller is compiled and called directly: no run-time branch, and no
    library in between (an `overload` compiles one around each call, which numba then
    optimises again with the method's code linked into it)."""

    @intrinsic
    def call(typingctx, *args):
        # numba hands the arguments over as one tuple (its vararg convention)
        packed = args[0] if len(args) == 1 and isinstance(args[0], types.StarArgTuple) else None
        args = tuple(packed.types) if packed else args
        keep = [i for i in range(len(args)) if passes_options or i != options_at]
        target = typingctx.resolve_value_type(getattr(_module(args[options_at]), name))
        signature = typingctx.resolve_function_type(target, tuple(args[i] for i in keep), {})

        def codegen(context, builder, _, values):
            items = cgutils.unpack_tuple(builder, values[0])
            return context.get_function(target, signature)(builder, [items[i] for i in keep])

        return signature.return_type(types.StarArgTuple(args)), codegen

    return call


start = _dispatched("start", 3, False)  # (sys, work, carry, options)
plan = _dispatched("plan", 5, False)  # (t, h, t_end, buffers, tally, options)
step = _dispatched("step", 7, True)  # (sys, work, carry, mem, t, h, y, options, tally)
mark_grazes = _dispatched("mark_grazes", 3, False)  # (sys, work, mem, options)
accept = _dispatched("accept", 3, False)  # (sys, work, carry, options)
sample = _dispatched("sample", 7, False)  # (sys, work, mem, t0, h, time, row, options)
step_factor = _dispatched("step_factor", 2, False)  # (err, err_old, options)

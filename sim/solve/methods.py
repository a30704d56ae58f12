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
from numba.extending import overload

from sim.jit import kernel
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
_JIT = {"_nrt": False}  # as sim.jit.kernel


def implementation(method: Dopri5 | GeneralizedAlpha) -> ModuleType:
    """The module that implements Options.method (sim.solve.dopri or sim.solve.galpha)."""
    return _MODULES[type(method)]


def make_carry(method: Dopri5 | GeneralizedAlpha, n: int, m: int) -> tuple:
    """The carry of Options.method for n coordinates and m constraints."""
    return implementation(method).make_carry(n, m)


def _module(options):
    """The method module of a numba Options type."""
    return _MODULES[options.types[options.fields.index("method")].instance_class]


@kernel
def grown_step(hs: float, err: float, facold: float, options) -> float:
    """The next step size after an accepted step of size hs with error err ≤ 1 (facold:
    the previous accepted step's)."""
    return hs * max(FAC_MIN, min(FAC_MAX, step_factor(err, facold, options)))


@kernel
def shrunk_step(hs: float, err: float, options) -> float:
    """The retry step size after a rejected step (err > 1, or ∞ when the step itself
    failed: a stage non-finite or Newton not converging): never longer than hs."""
    if not np.isfinite(err):
        return hs * FAC_MIN
    return hs * max(FAC_MIN, min(1.0, step_factor(err, 1.0, options)))


# The stubs below are what compiled callers call; their bodies never run.


def start(sys, work, carry, options) -> None:
    """The method's `start`."""
    raise NotImplementedError("compiled code only")


@overload(start, jit_options=_JIT)
def _start(sys, work, carry, options):
    impl = _module(options).start
    return lambda sys, work, carry, options: impl(sys, work, carry)


def plan(t, h, t_end, buffers, tally, options) -> float:
    """The method's `plan`."""
    raise NotImplementedError("compiled code only")


@overload(plan, jit_options=_JIT)
def _plan(t, h, t_end, buffers, tally, options):
    impl = _module(options).plan
    return lambda t, h, t_end, buffers, tally, options: impl(t, h, t_end, buffers, tally)


def step(sys, work, carry, mem, t, h, y, options, tally):
    """The method's `step`."""
    raise NotImplementedError("compiled code only")


@overload(step, jit_options=_JIT)
def _step(sys, work, carry, mem, t, h, y, options, tally):
    impl = _module(options).step
    return lambda sys, work, carry, mem, t, h, y, options, tally: impl(
        sys, work, carry, mem, t, h, y, options, tally
    )


def mark_grazes(sys, work, mem, options) -> None:
    """The method's `mark_grazes`."""
    raise NotImplementedError("compiled code only")


@overload(mark_grazes, jit_options=_JIT)
def _mark_grazes(sys, work, mem, options):
    impl = _module(options).mark_grazes
    return lambda sys, work, mem, options: impl(sys, work, mem)


def accept(sys, work, carry, options) -> None:
    """The method's `accept`."""
    raise NotImplementedError("compiled code only")


@overload(accept, jit_options=_JIT)
def _accept(sys, work, carry, options):
    impl = _module(options).accept
    return lambda sys, work, carry, options: impl(sys, work, carry)


def sample(sys, work, mem, t0, h, time, row, options) -> int:
    """The method's `sample`."""
    raise NotImplementedError("compiled code only")


@overload(sample, jit_options=_JIT)
def _sample(sys, work, mem, t0, h, time, row, options):
    impl = _module(options).sample
    return lambda sys, work, mem, t0, h, time, row, options: impl(sys, work, mem, t0, h, time, row)


def step_factor(err, err_old, options) -> float:
    """The method's `step_factor`."""
    raise NotImplementedError("compiled code only")


@overload(step_factor, jit_options=_JIT)
def _step_factor(err, err_old, options):
    impl = _module(options).step_factor
    return lambda err, err_old, options: impl(err, err_old)

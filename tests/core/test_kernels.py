"""The workflow's compile step (sim.studies.kernels): after it, a run of any link model with
the same integrator compiles nothing more, so the jobs that follow it only load the cache; and
a step it compiles ahead of the loop is the one the loop calls, not a second specialisation."""

import sys

import numba
import pytest

from sim.kernel_cache import cached_signatures
from sim.run import simulate
from sim.scene import load_scene
from sim.solve.methods import implementation, method_of
from sim.studies.kernels import STEP_FIRST, compile_kernels

SHORT = ["joints.A.clearance=5e-4", "joints.B.clearance=5e-4", "simulation.revolutions=0.02"]
LINKS = {
    "rigid": [],
    "modal": [f"bodies.rod{i}.kind=modal" for i in (2, 3, 4)],
    "one-element beams": [
        f"bodies.rod{i}.{key}" for i in (2, 3, 4) for key in ("kind=beam", "elements=1")
    ],
    "five clearances": [f"joints.{j}.clearance=3e-4" for j in ("C", "D1", "D2", "E")],
}


def compiled_signatures() -> int:
    """Number of compiled specialisations of every kernel of the package loaded so far."""
    return sum(
        len(value.signatures)
        for name, module in list(sys.modules.items())
        if name.startswith("sim.")
        for value in vars(module).values()
        if isinstance(value, numba.core.registry.CPUDispatcher)
    )


@pytest.mark.parametrize("method", ["dopri5", "generalized_alpha"])
def test_no_kernel_compiles_after_the_compile_step(method):
    compile_kernels(method)
    before = compiled_signatures()
    for name, overrides in LINKS.items():
        if method == "generalized_alpha" and name != "one-element beams":
            continue  # the studies run generalized-α on beams only
        scene = load_scene("sixbar", [*SHORT, *overrides, f"solver.method={method}"])
        simulate(scene)
        simulate(scene, ideal=True, rigid=True)
    assert compiled_signatures() == before
    if method in STEP_FIRST:
        # the step compiled ahead of the loop has the loop's argument types: had the loop
        # passed others, it would have compiled, and cached, a second specialisation
        step = implementation(method_of(scene["solver"])).step
        assert cached_signatures(step) == 1

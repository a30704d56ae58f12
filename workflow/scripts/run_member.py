"""One ensemble member of a case (sim/ensemble.py): the case's scene, started from the member's
perturbed initial state, written with its member index, seed and perturbation."""

from sim.ensemble import member
from sim.results import write_netcdf
from sim.run import simulate
from sim.scene import load_scene


def main(sm) -> None:
    who = member(**sm.params.draw)
    scene = load_scene(sm.params.scene, sm.params.overrides)
    write_netcdf(simulate(scene, member=who), sm.output[0])
    with open(sm.log[0], "w") as log:
        log.write(
            f"member {who.index}, seed {who.seed}, crank angle shift {who.shift_deg:.3g} deg\n"
        )


main(snakemake)  # noqa: F821 (injected by Snakemake)

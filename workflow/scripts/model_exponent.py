"""The model-based largest Lyapunov exponent of one ensemble member (Benettin on the linkage,
sim.studies.model_lyapunov) over the study's `model_lyapunov` duration, written atomically with
the member's index, seed and perturbation, and each clearance joint's share of the exponent's
stretch after its contact onsets (sim.studies.model_lyapunov.OnsetShares). The `links`
wildcard (one of the study's `model_lyapunov.links` and `compare`) takes it on the member's own
links (`run`), on rigid links, or with every flexible link a modal link (`modal`, the scene's
modes per link; docs/exponent.md, "Model convergence").

The member's run file holds its scene as run, perturbation included (sim.run.simulate records
the perturbed scene), so the exponent starts exactly where the member's run started."""

from sim.results import open_run, scene_of, write_netcdf
from sim.studies.config import REDUCED_LINKS_METHOD
from sim.studies.model_lyapunov import (
    DEFAULT_INTERVAL_REVOLUTIONS,
    exponent_tolerances,
    linkage_exponent,
    model_lyapunov_dataset,
    with_modal_links,
)

#: the run file's attributes that name the member (sim.ensemble.Member.attrs)
MEMBER_ATTRS = ("ensemble_member", "ensemble_seed", "perturbation", "perturbation_shift_deg")


def main(sm) -> None:
    settings = sm.params.settings
    run = open_run(sm.input.run)
    scene = scene_of(run)
    links = sm.wildcards.links
    # a run made rigid by `sim run --rigid` keeps its scene's flexible bodies: `run` follows it
    rigid = links == "rigid" or (links == "run" and bool(run.attrs.get("model_rigid", 0)))
    if links == "modal":
        scene = with_modal_links(scene)
    if rigid or links == "modal":
        scene["solver"]["method"] = REDUCED_LINKS_METHOD
    tolerances = settings.get("tolerances")
    rtol, atol = exponent_tolerances(scene, tolerances)
    result, shares = linkage_exponent(
        scene,
        revolutions=settings["revolutions"],
        transient_revolutions=settings["transient"],
        interval_revolutions=settings.get("interval_revolutions", DEFAULT_INTERVAL_REVOLUTIONS),
        tolerances=tolerances,
        ideal=bool(run.attrs.get("model_ideal", 0)),
        rigid=rigid,
    )
    out = model_lyapunov_dataset(result, (rtol, atol), shares)
    out.attrs.update({key: run.attrs[key] for key in MEMBER_ATTRS})
    out.attrs.update(
        {
            "study": sm.wildcards.study,
            "case": sm.wildcards.case,
            "source_run": str(sm.input.run),
            "model_lyapunov_revolutions": settings["revolutions"],
            "model_lyapunov_transient_revolutions": settings["transient"],
            "model_lyapunov_links": links,
        }
    )
    write_netcdf(out, sm.output[0])
    with open(sm.log[0], "w") as log:
        log.write(
            f"member {run.attrs['ensemble_member']}: {result.exponent:.4g} ± "
            f"{result.stderr:.2g} 1/s over {settings['revolutions']} revolutions "
            f"({settings['transient']} transient), rtol {rtol:g}\n"
        )


main(snakemake)  # noqa: F821 (injected by Snakemake)

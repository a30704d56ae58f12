"""The paper's section of the report's front page: each claim of docs/studies.md judged on our
results (sim.claims) in a table of short cells with the evidence folded beneath each row, the
headline figures drawn from the workflow's own tables (sim.plots.headline), and, folded, how
the claims are judged, the accelerometer data used, the six-bar's assumed values and the
software.

Only the paper's studies (config `report:`) feed it; every study, the paper's included, also has
its own section (sim.sections).
"""

import json
from collections.abc import Mapping, Sequence

import pandas as pd
import xarray as xr

from sim import front_page as page
from sim.analysis.verdicts import NOT_EVALUATED
from sim.claims import chaotic_points, exponent_comparison
from sim.plots import headline, responses, style
from sim.results import scene_of
from sim.studies.sweep import model_text

#: why the modal links' exponents read low, and where the exponent is not invariant
EXPONENT_NOTE = (
    "Modal links of one bending mode stand for the flexible rod2–rod4: on the flagship they "
    "read 269–274 1/s, about 10 % below four bending modes (307 1/s) and 18 % below the ANCF "
    "beams, the paper's model (321–344 1/s), all at converged tolerances, so the flexible "
    "exponents are low by about that much (docs/exponent.md, “Model convergence”). At 0.5 mm "
    "and 150 rpm the exponent on rigid and on modal links is invariant to the integrator's "
    "tolerance, the renormalisation interval (1/16 to 1/512 revolution) and the initial "
    "separation. It is not at the harder points: at 0.1 mm the default interval of 1/32 "
    "revolution reads 10–20 % low, and at 30 rpm the exponent rises with shorter intervals "
    "without settling (rigid links: 28 1/s at 1/32 revolution, 48 at 1/128, 66 at 1/512, 80 at "
    "1/2048), a finite-size value and a lower bound (docs/exponent.md, “The harder points”)."
)

#: how the claims on distributions are judged
JUDGING = (
    "The claims on peaks and impacts are tests on distributions, not on one maximum of one "
    "chaotic run (which moves by 15 % between runs a hair apart): each case runs as an "
    "ensemble (member 0 the nominal run, member k the initial crank angle shifted by a normal "
    "draw of standard deviation {size} deg seeded with {seed} + k{length}), and the peak of "
    "every revolution after the transient, over every accepted integrator step, is one "
    "observation; every member gives the same number of revolutions. Each component of such a "
    "claim compares the median or the 95th percentile between neighbouring settings: the "
    "{level} % percentile interval of the difference, from a seeded two-stage bootstrap "
    "({resamples} resamples of the members, then of moving blocks of their consecutive "
    "revolutions), wholly on the claimed side of 0 is supported, wholly on the other side not "
    "supported, containing 0 undecided. The claim is supported when every component is, mixed "
    "when its components are decided both ways, not supported when some are decided against "
    "it and none for it. The other claims are judged on one run, as their evidence says."
)


def _open(path) -> xr.Dataset:
    with xr.open_dataset(path) as ds:
        return ds.load()


def claims_table(claims: Sequence[Mapping]) -> str:
    """HTML: the verdict table: the claim in a few words, the verdict, and the key number with
    its interval, which unfolds into the claim in full, the intervals and the evidence."""
    rows = []
    for c in claims:
        evidence = page.paragraph(f"Claim: {c['claim']}") + page.paragraph(c["evidence"])
        if c["intervals"]:
            evidence += page.paragraph(c["intervals"])
        elif c["verdict"] != NOT_EVALUATED:
            evidence += page.paragraph("(single run)")
        rows.append(
            [
                page.escaped(c["short"]),
                f"<b>{page.escaped(c['verdict'])}</b>",
                page.details(c["key"], evidence),
            ]
        )
    header = ["claim", "verdict", "key number (click for the evidence)"]
    return page.table(header, rows, cells_are_html=True)


def headline_figures(inputs: Mapping[str, str]) -> list[tuple[str, str]]:
    """(title, embedded image) of each headline figure the inputs allow: the model exponent of
    every ensemble case on each link model, the dense sweeps with the exponent beneath and
    where chaos starts, the flagship against the ideal mechanism."""
    out = []
    tables = [
        (key.removesuffix("_model_exponents").replace("_", "-"), pd.read_csv(path))
        for key, path in inputs.items()
        if key.endswith("_model_exponents")
    ]
    if tables:
        fig = headline.plot_exponents(tables)
        image = page.image(style.png_bytes(fig), "model exponent of each case on each link model")
        out.append(("Chaos of the flexible and the rigid mechanism", image))
    sweeps = []
    for role in ("bifurcation_clearance", "bifurcation_speed"):
        if f"{role}_dataset" in inputs and f"{role}_table" in inputs:
            combined = _open(inputs[f"{role}_dataset"])
            chaotic = chaotic_points(
                pd.read_csv(inputs[f"{role}_table"]), combined.parameter.values
            )
            sweeps.append((role.removeprefix("bifurcation_"), combined, chaotic))
    if sweeps:
        image = page.image(style.png_bytes(headline.plot_sweeps(sweeps)), "the dense sweeps")
        out.append(("Chaos against clearance and speed", image))
    if "flagship_run" in inputs:
        fig = responses.plot_responses(
            _open(inputs["flagship_run"]), _open(inputs["flagship_ideal"])
        )
        image = page.image(style.png_bytes(fig), "the flagship against the ideal mechanism", "70%")
        out.append(("The flagship against the ideal mechanism", image))
    return out


def _exponent_numbers(inputs: Mapping[str, str]) -> str:
    """HTML, folded: the numbers the exponent figure draws, with why they read as they do."""
    rows = [
        [f"{row['role']}: {row['case']}", f"{links}{' (primary)' * primary}", text]
        for row in exponent_comparison(inputs)
        for links, primary, text in row["exponents"]
    ]
    if not rows:
        return ""
    table = page.table(["study: case", "link model", "exponent over the members"], rows)
    return page.details("The exponents in numbers", page.paragraph(EXPONENT_NOTE) + table)


def _recording(meta: Mapping, recording: Mapping) -> str:
    """Which accelerometer data the experiment study compared with."""
    if not meta:
        return "The experiment study was not run."
    if meta.get("synthetic"):
        return (
            f"Synthetic recording {recording['csv']}, written by the workflow with sim "
            f"experiment synthesize (seed {meta['synthesis']['seed']}): a higher-fidelity "
            "variant of the model passed through a sensor model. The paper's recording is not "
            "available; a synthetic comparison is a consistency check of the pipeline, never "
            "evidence that the model matches a real rig."
        )
    return f"Measured recording {recording['csv']}: {meta['description']}"


def paper_section(
    inputs: Mapping[str, str],
    claims: Sequence[Mapping],
    meta: Mapping,
    recording: Mapping,
    statistics: Mapping,
    ensemble: Mapping,
) -> str:
    """The paper's section (rst) from the landing rule's inputs (sim.claims), the judged
    ``claims``, the recording's metadata ``meta`` and file (``recording``), and the config's
    ``statistics`` and default ``ensemble``."""
    scene, assumptions, versions = {}, [], {}
    if "flagship_run" in inputs:
        with xr.open_dataset(inputs["flagship_run"]) as ds:
            scene = scene_of(ds)
            assumptions = json.loads(ds.attrs["assumptions"])
            versions = {"sim": ds.attrs["sim_version"]} | json.loads(
                ds.attrs.get("library_versions", "{}")
            )
    links = model_text(scene) if scene else "links not recorded (the flagship did not run)"
    introduction = page.paragraph(
        "Each claim of the paper (docs/studies.md) judged on our runs of the six-bar: the "
        "verdict and its key number in one line; click a line for the evidence behind it. Our "
        "geometry is assumed (below), so our numbers differ from the paper's. The flagship ran "
        f"on {links}, as every study on the six-bar does unless it names its own link model "
        "(the fidelity, extremes and cross-check cases, the dense sweeps). The same table, at "
        "full precision, is claims.csv."
    )
    length = ensemble.get("revolutions")
    judging = JUDGING.format(
        size=ensemble.get("size_deg"),
        seed=ensemble.get("seed"),
        length=f", running {length} revolutions with the transient" if length else "",
        level=round(statistics["level"] * 100),
        resamples=statistics["resamples"],
    )
    geometry = []
    if scene:
        geometry = [
            "Ground points: "
            + ", ".join(f"{n} = ({p[0]:g}, {p[1]:g}) m" for n, p in scene["ground"].items()),
            "Contact: " + ", ".join(f"{k} = {v}" for k, v in scene["contact"].items()),
            "Solver: " + ", ".join(f"{k} = {v}" for k, v in scene["solver"].items()),
        ]
    listed = "".join(f"<li>{page.escaped(a)}</li>" for a in [*assumptions, *geometry])
    folded = [
        _exponent_numbers(inputs),
        page.details("How the claims on distributions are judged", page.paragraph(judging)),
        page.details("Accelerometer data used", page.paragraph(_recording(meta, recording))),
        page.details(
            f"Assumed geometry and values of the six-bar ({len(assumptions)} assumptions, from "
            "the flagship run's assumptions attribute)",
            f"<ul>{listed}</ul>",
        ),
    ]
    if versions:
        folded.append(
            page.details(
                "Software",
                page.paragraph(
                    "The flagship run was computed with "
                    + ", ".join(f"{name} {v}" for name, v in versions.items())
                    + " (its library_versions attribute; every output file records its own); "
                    "requirements.txt pins them."
                ),
            )
        )
    figures = "".join(
        f"<h3>{page.escaped(title)}</h3>{image}" for title, image in headline_figures(inputs)
    )
    body = introduction + claims_table(claims) + figures + "".join(folded)
    return page.heading("The paper's claims: the six-bar press of Xiao et al.", "-") + page.raw(
        f'<div class="sim-paper">{body}</div>'
    )

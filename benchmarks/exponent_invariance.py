"""The model exponent against its settings and against the link model: the tables of
docs/exponent.md.

For one operating point of the six-bar and one link model, the largest Lyapunov exponent
(`sim.studies.model_lyapunov.linkage_lyapunov`) at each setting given as RTOL:INTERVAL:D0
(atol = rtol / 100; the interval in crank revolutions, as a fraction; d0 in m), one JSON line
each with its standard error, the CPU seconds it took, and how the separation grew interval by
interval (`stretch`: quantiles of ln(d / d0) per renormalisation interval and the share of
their total that the top 5 % of intervals carry). The exponent belongs to the dynamics when no
setting moves it beyond its standard error.

Points: `flagship` (A and B 0.5 mm, 150 rpm), `slow` (0.2 mm, 30 rpm), `small` (0.1 mm,
150 rpm), `lubricated` (the flagship with joint A's oil film, scene sixbar-lubricated).
Links: `rigid`, `modal-B-A` (B bending and A axial modes per rod; generalized-alpha
when A > 0, as the axial modes need it), `beam-E` (E ANCF elements per rod, generalized-alpha);
`:ga` after any of them forces generalized-alpha (e.g. `modal-1-0:ga`, to tell the method's
share of a difference from the link model's).

Usage: python benchmarks/exponent_invariance.py POINT LINKS REVOLUTIONS TRANSIENT SETTING...
e.g.   python benchmarks/exponent_invariance.py flagship modal-1-0 24 4 1e-6:1/32:1e-6
"""

import json
import sys
import time
from fractions import Fraction

import numpy as np

from sim.analysis.lyapunov import BenettinResult, interval_stretch
from sim.scene import load_scene
from sim.studies.model_lyapunov import linkage_lyapunov

POINTS = {
    "flagship": ("sixbar", ["joints.A.clearance=0.5e-3", "joints.B.clearance=0.5e-3"]),
    "slow": (
        "sixbar",
        ["joints.A.clearance=0.2e-3", "joints.B.clearance=0.2e-3", "drive.speed_rpm=30"],
    ),
    "small": ("sixbar", ["joints.A.clearance=0.1e-3", "joints.B.clearance=0.1e-3"]),
    "lubricated": (
        "sixbar-lubricated",
        ["joints.A.clearance=0.5e-3", "joints.B.clearance=0.5e-3"],
    ),
}
RODS = ("rod2", "rod3", "rod4")


def link_overrides(links: str) -> list[str]:
    """The scene overrides of a link model named as in the module docstring."""
    if links.endswith(":ga"):
        return [*link_overrides(links.removesuffix(":ga")), "solver.method=generalized_alpha"]
    if links == "rigid":
        return []
    kind, *sizes = links.split("-")
    if kind == "modal":
        bending, axial = sizes
        out = [
            f"bodies.{rod}.{key}={value}"
            for rod in RODS
            for key, value in (("kind", "modal"), ("modes", bending), ("axial_modes", axial))
        ]
        return out + (["solver.method=generalized_alpha"] if axial != "0" else [])
    if kind == "beam":
        (elements,) = sizes
        keys = ("kind=beam", f"elements={elements}")
        return [f"bodies.{rod}.{key}" for rod in RODS for key in keys] + [
            "solver.method=generalized_alpha"
        ]
    raise SystemExit(f"unknown link model '{links}': rigid, modal-B-A or beam-E")


def stretch(result: BenettinResult) -> dict:
    """Quantiles of the recorded intervals' stretch (`interval_stretch`) and the top 5 %'s
    share of their sum."""
    per_interval = interval_stretch(result)
    top = np.sort(per_interval)[::-1][: max(1, per_interval.size // 20)]
    names = ("median", "q90", "q99", "max")
    quantiles = np.quantile(per_interval, [0.5, 0.9, 0.99, 1.0])
    out = {name: round(float(q), 2) for name, q in zip(names, quantiles, strict=True)}
    return out | {"top5pct_share": round(float(top.sum() / per_interval.sum()), 3)}


def exponent_row(
    scene: dict, point: str, links: str, revolutions: str, transient: str, setting: str
) -> dict:
    """The exponent of `scene` at one RTOL:INTERVAL:D0 setting, as one JSON-ready row."""
    rtol, interval, d0 = setting.split(":")
    cpu = time.process_time()
    result = linkage_lyapunov(
        scene,
        revolutions=float(revolutions),
        transient_revolutions=float(transient),
        d0=float(d0),
        interval_revolutions=float(Fraction(interval)),
        tolerances=(float(rtol), float(rtol) / 100),
        rigid=links.startswith("rigid"),
    )
    return {
        "point": point,
        "links": links,
        "rtol": float(rtol),
        "interval_revolutions": interval,
        "d0_m": float(d0),
        "revolutions": float(revolutions),
        "transient": float(transient),
        "exponent_per_s": round(result.exponent, 1),
        "stderr_per_s": round(result.stderr, 1),
        "cpu_s": round(time.process_time() - cpu, 1),
        "stretch": stretch(result),
    }


def main() -> None:
    point, links, revolutions, transient, *settings = sys.argv[1:]
    name, overrides = POINTS[point]
    scene = load_scene(name, overrides + link_overrides(links))
    for setting in settings:
        row = exponent_row(scene, point, links, revolutions, transient, setting)
        print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()

"""Loading returns a fully defaulted scene (sim/scene_keys.py): every optional key with a default is
filled in, the result loads again unchanged, and the defaults mean what docs say."""

import json
from pathlib import Path

import pytest
import xarray as xr

from sim.model.assembly import body_mass_properties
from sim.results import scene_of
from sim.scene import SceneError, dump_scene, load_scene
from sim.scene_keys import BODY_COMMON, NO_DEFAULT, TABLES, TOP
from sim.scene_reference import reference

BEAMS = ["bodies.rod2.kind=beam", "bodies.rod3.kind=beam"]


def test_every_default_is_filled_in():
    scene = load_scene("sixbar")
    for key, field in TOP.items():
        if field.default is not NO_DEFAULT:
            assert key in scene, key
    for name, body in scene["bodies"].items():
        for key, field in BODY_COMMON.items():
            if field.default is not NO_DEFAULT:
                assert key in body, f"bodies.{name}.{key}"
    crank = scene["bodies"]["crank"]
    assert crank["mass"] is None and crank["inertia"] is None
    assert crank["elements"] == 2 and crank["points"] == {}
    assert crank["damping"] == {"kind": "none"}


def test_a_resolved_scene_loads_again_unchanged(tmp_path):
    # `sim scene` prints the resolved scene; saved as a file it must load to the same scene
    # (beams with the default empty `points`, null masses).
    scene = load_scene("sixbar", BEAMS)
    path = tmp_path / "resolved.yaml"
    path.write_text(dump_scene(scene))
    assert load_scene(str(path)) == scene


def test_null_mass_is_the_uniform_body_and_a_given_mass_wins():
    # docs/assumptions.md: a bar's mass is ρ A L and its inertia m L²/12 about the centre.
    scene = load_scene("sixbar")
    steel = scene["materials"]["steel"]
    mass, inertia = body_mass_properties(scene["bodies"]["rod2"], steel)
    expected = 7801.0 * 0.06 * 0.02 * 0.35
    assert mass == pytest.approx(expected, rel=1e-12)
    assert inertia == pytest.approx(expected * 0.35**2 / 12, rel=1e-12)
    given = load_scene("sixbar", ["bodies.rod2.mass=2.5", "bodies.rod2.inertia=0.03"])
    assert body_mass_properties(given["bodies"]["rod2"], steel) == (2.5, 0.03)


def test_overrides_reach_inside_a_default():
    # The default damping mapping exists before the overrides apply: its keys can be set.
    scene = load_scene(
        "sixbar",
        ["bodies.rod2.damping.kind=stiffness", "bodies.rod2.damping.coefficient=1e-5"],
    )
    assert scene["bodies"]["rod2"]["damping"] == {"kind": "stiffness", "coefficient": 1e-5}


def test_null_is_refused_where_nothing_computes_it():
    with pytest.raises(SceneError, match=r"'contact.friction' = None is not accepted"):
        load_scene("sixbar", ["contact.friction=null"])
    with pytest.raises(SceneError, match=r"expected a number 0 < x ≤ 1e\+06 \(kg\), or null"):
        load_scene("sixbar", ["bodies.rod2.mass=-1"])


def test_a_run_file_written_before_the_defaults_gets_them():
    scene = load_scene("sixbar")
    old = json.loads(json.dumps(scene))
    for body in old["bodies"].values():
        for key in ("mass", "inertia", "points", "elements", "damping"):
            del body[key]
    ds = xr.Dataset(attrs={"scene": json.dumps(old)})
    assert scene_of(ds) == scene


def test_the_scene_key_reference_page_is_the_generated_one():
    # docs/scenes.md is generated from the tables of keys: regenerate it with
    # `python -m sim.scene_reference docs/scenes.md` after changing a table.
    page = Path(__file__).parents[2] / "docs" / "scenes.md"
    assert page.read_text(encoding="utf-8") == reference()
    for table in TABLES.values():
        for key, field in table.items():
            assert field.doc, f"key '{key}' has no doc for the reference page"


def test_a_scene_without_contact_simulation_or_solver_gets_the_six_bars_values(tmp_path):
    # Declared once: the six-bar leans on the defaults, so a short scene gets its values. The
    # built-in four-bar without its one solver key (its own rtol) is such a scene.
    sixbar = load_scene("sixbar")
    text = (Path(__file__).parents[2] / "sim/scenes/fourbar.yaml").read_text()
    lines = [line for line in text.splitlines() if not line.startswith("solver:")]
    assert len(lines) == len(text.splitlines()) - 1
    (tmp_path / "short.yaml").write_text("\n".join(lines))
    short = load_scene(str(tmp_path / "short.yaml"))
    for section in ("contact", "simulation", "solver"):
        assert short[section] == sixbar[section], section

"""The workflow's study resolver (sim.studies.config): precedence of the settings and of a
case's scene overrides, the quick merge, the fidelity study's case grid against the cases
once typed by hand, ensemble members, the link model per scene, and the plan's scene check."""

import copy
from pathlib import Path

import pytest
import yaml
from snakemake.utils import validate

from sim.studies import config as resolver

ROOT = Path(__file__).resolve().parents[2]
SCHEMA = str(ROOT / "workflow/schemas/config.schema.yaml")
HERE = Path(__file__).parent


def _validated(config: dict) -> dict:
    """The config with the schema's defaults filled in, as the workflow validates it."""
    config = copy.deepcopy(config)
    validate(config, SCHEMA, set_default=True)
    return config


def _config(**study) -> dict:
    """A minimal config: one study `s` on the six-bar, the default scene; a key of `study`
    set to None is left out."""
    entry = {"title": "t", "analyses": ["responses"], "cases": {"c": {"drive.speed_rpm": 60.0}}}
    entry.update(study)
    entry = {key: value for key, value in entry.items() if value is not None}
    duration = {"scene": "sixbar", "revolutions": 10, "output_per_revolution": 20}
    return _validated(
        {
            "model": {
                "links": "beam",
                "elements": 2,
                "flexible_bodies": ["rod2"],
                "solver": {"method": "generalized_alpha"},
            },
            "defaults": {
                **duration,
                "transient": 2,
                "overrides": {"drive.speed_rpm": 150.0, "contact.friction": 0.15},
                "ensemble": {"members": 2, "seed": 5, "revolutions": 8},
                "model_lyapunov": {"revolutions": 30, "transient": 10, "links": "rigid"},
            },
            "quick_defaults": {
                **duration,
                "revolutions": 3,
                "transient": 1,
                "model_lyapunov": {"revolutions": 6, "transient": 2},
            },
            "studies": {"s": entry},
        }
    )


def test_case_overrides_later_wins_in_the_documented_order():
    # link model < duration < default overrides < study < case: each level sets a key the
    # next one overrides, and the order of the keys is the order of first setting
    config = _config(
        overrides={"contact.friction": 0.3, "solver.method": "dopri5", "joints.A.clearance": 1e-4},
        cases={"c": {"joints.A.clearance": 2e-4, "simulation.revolutions": 4}},
    )
    settings = resolver.study_settings(config, "s")
    out = resolver.case_overrides(settings, "c")
    assert list(out.items()) == [
        ("solver.method", "dopri5"),  # link model, overridden by the study
        ("bodies.rod2.kind", "beam"),
        ("bodies.rod2.elements", 2),
        ("simulation.revolutions", 4),  # duration, overridden by the case
        ("simulation.output_per_revolution", 20),
        ("drive.speed_rpm", 150.0),  # default overrides
        ("contact.friction", 0.3),  # ... overridden by the study
        ("joints.A.clearance", 2e-4),  # study, overridden by the case
    ]


def test_study_keys_win_over_the_defaults_and_the_schema_fills_the_rest():
    settings = resolver.study_settings(_config(revolutions=7, ensemble={"seed": 9}), "s")
    assert settings["revolutions"] == 7
    assert settings["transient"] == 2  # the defaults'
    assert settings["ensemble"] == {"members": 2, "seed": 9, "revolutions": 8}
    assert settings["timeout_s"] == 1800  # schema default of `defaults`
    assert settings["model_lyapunov"]["links"] == "rigid"


def test_quick_merge():
    # `quick: true` takes quick_defaults, the study's quick block replaces whole keys and
    # merges ensemble and model_lyapunov key by key
    config = _config(
        revolutions=50,
        ensemble={"members": 4, "seed": 3},
        model_lyapunov={"revolutions": 40},
        quick={"cases": {"q": {}}, "ensemble": {"members": 3}, "model_lyapunov": {"transient": 1}},
    )
    full = resolver.study_settings(config, "s")
    assert (full["revolutions"], resolver.case_names(full)) == (50, ["c"])
    config["quick"] = "True"  # `--config quick=True` passes text
    quick = resolver.study_settings(config, "s")
    assert resolver.case_names(quick) == ["q"]
    assert quick["revolutions"] == 50  # the study's own, not quick_defaults'
    assert quick["transient"] == 1  # quick_defaults'
    assert quick["timeout_s"] == 120  # schema default of `quick_defaults`
    assert quick["ensemble"] == {"members": 3, "seed": 3}  # quick_defaults: members 1, seed 0
    assert quick["model_lyapunov"] == {
        "revolutions": 40,
        "transient": 1,
        "links": "run",
        "compare": [],
    }


def test_exponent_links_lead_with_the_primary_model_and_keep_the_comparison_order():
    # the verdicts read `links`; `compare` adds the others once each, in their order
    settings = resolver.study_settings(_config(), "s")
    assert resolver.exponent_links(settings) == ["rigid"]
    lyapunov = {"links": "modal", "compare": ["rigid", "modal", "run"]}
    settings = resolver.study_settings(_config(model_lyapunov=lyapunov), "s")
    assert resolver.exponent_links(settings) == ["modal", "rigid", "run"]


def test_each_run_compiles_the_integrator_it_runs():
    # the config's link model sets generalized-α; a case may set its own; the built-in
    # six-bar scene names DOPRI5; the exponent on reduced links takes the explicit method
    cases = {"c": {}, "d": {"solver.method": "dopri5"}}
    settings = resolver.study_settings(_config(cases=cases), "s")
    assert resolver.scene_method("sixbar") == "dopri5"
    for case, method in (("c", "generalized_alpha"), ("d", "dopri5")):
        overrides = resolver.case_overrides(settings, case)
        assert resolver.run_method(settings, overrides) == method
        assert resolver.case_method(settings, case) == method
        assert resolver.exponent_method(settings, case, "run") == method
        for links in ("rigid", "modal"):
            assert resolver.exponent_method(settings, case, links) == "dopri5"
    assert resolver.run_method(settings, {}) == "dopri5"  # the scene's own
    sweep = {"keys": ["drive.speed_rpm"], "label": "v", "unit": "rpm", "values": [30.0]}
    sweep.update(batch=1, lyapunov_alignment=1)
    for study, method in (({}, "generalized_alpha"), ({"solver.method": "dopri5"}, "dopri5")):
        settings = resolver.study_settings(_config(cases=None, sweep=sweep, overrides=study), "s")
        assert resolver.sweep_method(settings) == method


def test_fidelity_grid_reproduces_the_cases_once_typed_by_hand():
    config = _validated(yaml.safe_load((ROOT / "config/config.yaml").read_text()))
    typed = yaml.safe_load((HERE / "fidelity_cases.yaml").read_text())
    for quick, expected in ((False, typed["cases"]), (True, typed["quick"])):
        config["quick"] = quick
        cases = resolver.study_settings(config, "fidelity")["cases"]
        assert list(cases) == list(expected)  # same names in the same order
        for name, case in expected.items():
            assert cases[name] == case, name
            # the same types (an int 1 is not the float 1.0 in a --set text)
            assert {k: type(v) for k, v in cases[name].items()} == {
                k: type(v) for k, v in case.items()
            }


@pytest.mark.parametrize(
    ("rtol", "name", "atol"),
    [(1e-3, "1e-3", 1e-5), (5e-12, "5e-12", 5e-14), (1e-10, "1e-10", 1e-12)],
)
def test_grid_names_and_absolute_tolerance(rtol, name, atol):
    grid = {
        "bodies": ["b"],
        "links": {"r": {"kind": "rigid"}},
        "series": [{"links": ["r"], "rtol": [rtol]}],
    }
    case = resolver.grid_cases(grid)[f"r-{name}"]
    assert case == {"bodies.b.kind": "rigid", "solver.rtol": rtol, "solver.atol": atol}
    assert case["solver.atol"] == float(
        f"{name[: -len(name.split('e')[1])]}{int(name.split('e')[1]) - 2}"
    )


def test_member_overrides_and_draw():
    config = _config(analyses=["peaks"], cases={"c": {"simulation.revolutions": 12}})
    settings = resolver.study_settings(config, "s")
    assert resolver.ensemble_size(settings) == 2
    # members run the ensemble's 8 revolutions, shorter than the case's 12
    assert resolver.member_overrides(settings, "c")["simulation.revolutions"] == 8
    assert resolver.case_overrides(settings, "c")["simulation.revolutions"] == 12
    assert resolver.member_draw(settings, "3") == {"index": 3, "base_seed": 5}
    # a study without statistics on peaks runs its nominal member only
    assert resolver.ensemble_size(resolver.study_settings(_config(), "s")) == 1


def test_the_files_of_members_exponents_and_batches():
    # member 0 of a case is its nominal run; exponents go case, link model, member
    lyapunov = {"links": "modal", "compare": ["rigid"]}
    config = _config(analyses=["peaks"], cases={"c": {}, "d": {}}, model_lyapunov=lyapunov)
    settings = resolver.study_settings(config, "s")
    assert resolver.member_files(settings) == [
        ("run", {"case": "c"}),
        ("member", {"case": "c", "member": 1}),
        ("run", {"case": "d"}),
        ("member", {"case": "d", "member": 1}),
    ]
    assert resolver.member_file("d", "0") == ("run", {"case": "d"})
    exponents = [tuple(w.values()) for _, w in resolver.exponent_files(settings)]
    assert exponents == [
        (case, links, k) for case in "cd" for links in ("modal", "rigid") for k in (0, 1)
    ]
    # five sweep points in batches of two: three batches, the last one short
    sweep = {"keys": ["drive.speed_rpm"], "label": "v", "unit": "rpm", "batch": 2}
    sweep.update(values=[30.0, 60.0, 90.0, 120.0, 150.0], lyapunov_alignment=1)
    settings = resolver.study_settings(_config(cases=None, sweep=sweep), "s")
    assert resolver.batch_files(settings) == [("sweep_batch", {"batch": k}) for k in range(3)]
    assert resolver.sweep_batch(settings, "2") == [("v-150rpm", 150.0)]
    assert resolver.crank_rpm(settings, "v-90rpm") == 90.0
    assert resolver.sweep_parameter(settings) == "drive.speed_rpm"


def test_members_no_longer_than_the_transient_are_refused():
    with pytest.raises(resolver.ConfigError, match=r"studies\.s\.ensemble\.revolutions"):
        resolver.study_settings(_config(analyses=["peaks"], transient=8), "s")


def test_a_study_on_its_own_scene_gets_no_default_scene_keys():
    # the config's model and default overrides describe the default scene only
    config = _config(scene="slider-crank", cases={"c": {}})
    settings = resolver.study_settings(config, "s")
    assert resolver.case_overrides(settings, "c") == {
        "simulation.revolutions": 10,
        "simulation.output_per_revolution": 20,
    }
    # its own link model names its own bodies and takes the config's other link keys
    config = _config(scene="slider-crank", model={"flexible_bodies": ["rod"], "elements": 3})
    out = resolver.case_overrides(resolver.study_settings(config, "s"), "c")
    assert out["bodies.rod.kind"] == "beam" and out["bodies.rod.elements"] == 3
    assert out["solver.method"] == "generalized_alpha"
    assert not any("rod2" in key for key in out)


def test_a_study_chooses_its_link_model_and_force_model_puts_the_config_s_back():
    config = _config(model={"links": "modal", "modes": 2, "solver": {"method": "dopri5"}})
    out = resolver.case_overrides(resolver.study_settings(config, "s"), "c")
    assert (out["bodies.rod2.kind"], out["bodies.rod2.modes"]) == ("modal", 2)
    assert out["solver.method"] == "dopri5"
    config["model"] = {"links": "rigid", "elements": 2, "flexible_bodies": ["rod2"]}
    config["force_model"] = True
    out = resolver.case_overrides(resolver.study_settings(config, "s"), "c")
    assert out["bodies.rod2.kind"] == "rigid"


def test_the_plan_refuses_a_scene_that_cannot_run():
    config = _config(cases={"good": {}, "bad": {"joints.A.clearence": 1e-4}})
    studies = resolver.resolve(config)
    with pytest.raises(resolver.ConfigError) as error:
        resolver.check_scenes(studies)
    message = str(error.value)
    assert "studies.s, case bad" in message and "clearence" in message
    # a body of the six-bar on another scene is refused the same way
    config = _config(scene="slider-crank", model={"flexible_bodies": ["rod2"]}, cases={"c": {}})
    with pytest.raises(resolver.ConfigError, match=r"(?s)studies\.s, case c.*rod2"):
        resolver.check_scenes(resolver.resolve(config))


def test_flexible_links_without_their_bodies_are_refused_on_another_scene():
    # the config's `model` names the default scene's bodies: a study on its own scene that
    # asks for beams or modal links must name its own, or it would run rigid unawares
    for links in ("beam", "modal"):
        config = _config(scene="slider-crank", model={"links": links}, cases={"c": {}})
        with pytest.raises(resolver.ConfigError) as error:
            resolver.study_settings(config, "s")
        message = str(error.value)
        assert message.startswith("config: studies.s.model.flexible_bodies: links: " + links)
        assert "(its bodies: crank, rod, slider)" in message


def test_exponent_link_models_a_scene_does_not_have_are_not_computed():
    """On a mechanism without flexible links a modal exponent would be the rigid one again,
    and `run` is `rigid`: one exponent, on the first of them named."""
    lyapunov = {"links": "modal", "compare": ["rigid"]}
    rigid = _config(scene="slider-crank", model_lyapunov=lyapunov, cases={"c": {}})
    settings = resolver.study_settings(rigid, "s")
    assert resolver.exponent_links(settings) == ["rigid"]
    assert [w["links"] for _, w in resolver.exponent_files(settings)] == ["rigid"]
    both = {"links": "run", "compare": ["modal", "rigid"]}
    settings = resolver.study_settings(_config(scene="slider-crank", model_lyapunov=both), "s")
    assert resolver.exponent_links(settings) == ["run"]
    # a flexible body, from the study's link model or from one case, brings the modal one back
    model = {"links": "beam", "flexible_bodies": ["rod"]}
    flexible = _config(scene="slider-crank", model=model, model_lyapunov=lyapunov)
    assert resolver.exponent_links(resolver.study_settings(flexible, "s")) == ["modal", "rigid"]
    cases = {"c": {}, "beam": {"bodies.rod.kind": "beam"}}
    one_case = _config(scene="slider-crank", model_lyapunov=lyapunov, cases=cases)
    assert resolver.exponent_links(resolver.study_settings(one_case, "s")) == ["modal", "rigid"]


def test_the_plan_refuses_a_linkage_that_locks_naming_the_case_and_the_crank_angle():
    # tests/model/test_mobility.py: the four-bar with a 0.28 m crank is not Grashof and locks
    # at 145.27° (closed form); the dry run drives every planned scene through a turn
    cases = {"short": {}, "long-crank": {"bodies.crank.length": 0.28}}
    overrides = {"bodies.coupler.hint": "null", "bodies.rocker.hint": "null"}
    config = _config(scene="fourbar", cases=cases, overrides=overrides)
    with pytest.raises(resolver.ConfigError) as error:
        resolver.check_scenes(resolver.resolve(config))
    message = str(error.value)
    assert message.startswith("config: studies.s, case long-crank: its scene 'fourbar'")
    assert "locks at crank angle 145.27°" in message


def test_the_full_config_plans_scenes_that_load():
    config = _validated(yaml.safe_load((ROOT / "config/config.yaml").read_text()))
    resolver.check_scenes(resolver.resolve(config))


def test_the_claims_take_the_landing_inputs_and_nothing_else():
    from sim.analysis.revolutions import Bootstrap
    from sim.claims import INPUT_NAMES, judge_all

    assert {f"{i.role}_{i.name}" for i in resolver.LANDING_INPUTS} < INPUT_NAMES
    with pytest.raises(ValueError, match="flagship_runs"):
        judge_all({"flagship_runs": "x.nc"}, Bootstrap())

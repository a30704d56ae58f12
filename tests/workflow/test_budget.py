"""benchmarks/workflow_budget.py: the extrapolation of a shortened job to its full length, and
the shortened configuration it derives from config/config.yaml."""

import importlib.util
from pathlib import Path

import pytest
import yaml

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def budget():
    spec = importlib.util.spec_from_file_location("budget", ROOT / "benchmarks/workflow_budget.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def config():
    return yaml.safe_load((ROOT / "config/config.yaml").read_text())


def test_a_job_linear_in_its_length_extrapolates_exactly(budget):
    """cost = a + b r through two shortened lengths gives a + b R at the full length R."""
    a, b, full = 3.0, 0.7, 200.0
    r1, r2 = budget.shortened(full, 1 / 50, 0.25), budget.shortened(full, 1 / 20, 0.5)
    assert (r1, r2) == (4.0, 10.0)
    estimate = budget.extrapolate(a + b * r1, r1, a + b * r2, r2, full)
    assert estimate == pytest.approx(a + b * full, rel=1e-12)
    # noise that makes the longer pass cheaper: the length's cost counts as zero
    assert budget.extrapolate(5.0, r1, 4.0, r2, full) == 4.0
    # a job short enough to run in full is its measured cost
    assert budget.shortened(0.25, 1 / 20, 0.5) == 0.25
    assert budget.extrapolate(None, 0.25, 9.0, 0.25, 0.25) == 9.0


def test_the_shortened_config_keeps_every_job_and_scales_its_length(budget, config):
    first, durations = budget.shorten(config, 0, every=20, last=False)
    last, _ = budget.shorten(config, 1, every=20, last=True)
    for name, plan in durations.items():
        if "sweep" in plan:
            sweep = config["studies"][name]["sweep"]
            points = sweep["range"][2] if "range" in sweep else len(sweep["values"])
            kept = last["studies"][name]["sweep"]["values"]
            assert plan["sweep"] == pytest.approx(points / len(kept))
            assert first["studies"][name]["enabled"] is False
            continue
        for case, (full, run) in plan["cases"].items():
            assert run <= full
            assert first["studies"][name]["cases"][case]["simulation.revolutions"] == run
        exponent = first["studies"][name]["model_lyapunov"]
        assert 0 < exponent["transient"] < exponent["revolutions"] <= plan["model_exponent"][0]
    # the long fidelity cases are shortened, the short ones run in full in the last pass only
    fidelity = durations["fidelity"]["cases"]
    assert fidelity["long-rigid-1e-11"] == (200.0, 4.0)
    assert "rigid-1e-5" not in fidelity
    assert last["studies"]["fidelity"]["cases"]["rigid-1e-5"]["simulation.revolutions"] == 0.25

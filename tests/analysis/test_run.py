"""analyze_run, combine_sweep and the `sim analyze` subcommand on synthetic runs."""

import argparse
import json

import numpy as np
import pytest
import xarray as xr
from conftest import SAMPLES_PER_REVOLUTION, run_dataset

from sim.analysis.bifurcation import combine_sweep
from sim.analysis.run import analyze_run
from sim.cli import main
from sim.cli.analyze import register
from sim.studies.model_lyapunov import DEFAULT_TOLERANCES

TRANSIENT = 20


@pytest.fixture(scope="module")
def ideal_analysis(ideal_run):
    return analyze_run(ideal_run, transient_revolutions=TRANSIENT)


@pytest.fixture(scope="module")
def duffing_analysis(duffing_run):
    return analyze_run(duffing_run, transient_revolutions=TRANSIENT)


def test_ideal_run_is_periodic(ideal_analysis):
    assert list(ideal_analysis["channel"].values) == ["crank.x", "crank.y", "slider.x", "slider.y"]
    assert set(ideal_analysis["verdict"].values) == {"periodic"}
    assert (ideal_analysis["section_period"] == 1).all()


def test_duffing_joint_is_chaotic_across_and_periodic_along(duffing_analysis):
    verdict = duffing_analysis["verdict"].to_series()
    assert verdict["A.x"] == "chaotic"
    assert verdict["A.y"] == "periodic"
    assert duffing_analysis["lyapunov_exponent"].sel(channel="A.x") > 0
    # K of a chaotic orbit tends to 1 as the section series grows: over 30 orbits of this
    # oscillator, 140 section points gave K = 0.81-0.99 (a bound of 0.8 failed on another
    # CPU's orbit), 380 points 0.91-0.99
    assert duffing_analysis["zero_one_K"].sel(channel="A.x") > 0.8
    assert list(duffing_analysis["channel_joint"].values) == ["A", "A"]
    assert list(duffing_analysis["channel_axis"].values) == ["x", "y"]


def test_output_is_cf_annotated(duffing_analysis, duffing_run):
    for name, variable in duffing_analysis.variables.items():
        if name != "channel":
            assert {"units", "long_name"} <= set(variable.attrs), name
    for value in duffing_analysis.attrs.values():
        assert isinstance(value, str | int | float)
    steady = duffing_analysis.sizes["revolution"]
    assert steady == duffing_run.sizes["revolution"] - TRANSIENT
    assert duffing_analysis["phase_eccentricity"].dims == ("sample", "channel")


def test_sweep_pads_revolutions(duffing_run):
    shorter = duffing_run.isel(revolution=slice(0, 100))
    sweep = combine_sweep([duffing_run, shorter], "joints.A.clearance", [1e-4, 2e-4])
    assert sweep["parameter"].attrs["name"] == "joints.A.clearance"
    assert sweep.sizes["revolution"] == duffing_run.sizes["revolution"]
    assert np.isnan(sweep["section_eccentricity"].isel(parameter=1, revolution=-1)).all()
    assert not np.isnan(sweep["section_eccentricity"].isel(parameter=0)).any()


def parse(argv: list[str]) -> argparse.Namespace:
    parser = argparse.ArgumentParser(prog="sim")
    register(parser.add_subparsers(required=True))
    return parser.parse_args(argv)


def test_cli_writes_the_analysis(ideal_run, tmp_path, capsys):
    run_file, out_file = tmp_path / "run.nc", tmp_path / "run-analysis.nc"
    ideal_run.to_netcdf(run_file)
    args = parse(["analyze", str(run_file), "-o", str(out_file), "--transient", "10"])
    assert args.func(args) == 0
    with xr.open_dataset(out_file) as written:
        assert set(written["verdict"].values) == {"periodic"}
        assert written.attrs["transient_revolutions"] == 10
        channels = [str(c) for c in written["channel"].values]
    # the verdict table on stdout: a header and one line per channel, naming its verdict
    table = capsys.readouterr().out.splitlines()[1:]
    assert table[0].split()[:2] == ["channel", "verdict"]
    assert [line.split()[:2] for line in table[1:]] == [[c, "periodic"] for c in channels]
    assert sorted(path.name for path in tmp_path.iterdir()) == ["run-analysis.nc", "run.nc"]


def test_cli_rejects_a_missing_variable(ideal_run, tmp_path, capsys):
    run_file, out_file = tmp_path / "run.nc", tmp_path / "out.nc"
    ideal_run.drop_vars("section_velocity").to_netcdf(run_file)
    args = parse(["analyze", str(run_file), "-o", str(out_file)])
    assert args.func(args) == 1
    message = capsys.readouterr().err
    assert str(run_file) in message and "'section_velocity'" in message
    assert not out_file.exists()


def test_cli_rejects_too_few_revolutions(ideal_run, tmp_path, capsys):
    run_file = tmp_path / "run.nc"
    ideal_run.isel(revolution=slice(0, 30)).to_netcdf(run_file)
    args = parse(["analyze", str(run_file), "-o", str(tmp_path / "out.nc"), "--transient", "10"])
    assert args.func(args) == 1
    assert "revolution" in capsys.readouterr().err


def test_cli_states_the_run_length_it_needs_as_a_fixed_number(ideal_run, tmp_path, capsys):
    # With the default transient (min(20, a quarter of the sections)) a run needs 32
    # revolutions: 33 sections less 8 dropped leave the 25 the period search needs; 31 leave 24.
    # The number does not move as the run grows.
    for kept in (20, 31):
        run_file = tmp_path / f"run{kept}.nc"
        ideal_run.isel(revolution=slice(0, kept + 1)).to_netcdf(run_file)
        args = parse(["analyze", str(run_file), "-o", str(tmp_path / "out.nc")])
        assert args.func(args) == 1
        err = capsys.readouterr().err
        assert f"the run has {kept} crank revolutions" in err
        assert "the analysis needs runs of at least 32 (simulation.revolutions ≥ 32)" in err


@pytest.fixture(scope="module")
def sixbar_ideal_file(tmp_path_factory):
    """The built-in six-bar with every joint ideal, simulated (30 revolutions, 64 samples each)."""
    from sim.results import write_netcdf
    from sim.run import simulate
    from sim.scene import load_scene

    scene = load_scene(
        "sixbar", ["simulation.revolutions=30", "simulation.output_per_revolution=64"]
    )
    return write_netcdf(simulate(scene), tmp_path_factory.mktemp("sixbar") / "ideal.nc")


def test_simulated_ideal_sixbar_is_periodic(sixbar_ideal_file, tmp_path, capsys):
    # Issue 3, check 5: a driven mechanism without clearance repeats every revolution; every
    # body channel must be periodic with period 1. The model's own exponent (Benettin on the
    # run's scene): perturbations only violate the constraints, which Baumgarte stabilisation
    # with α = β = 10 1/s pulls back critically damped, δ ∝ (a + b t) e^(−α t). Recorded from
    # t0 = 2 s (5 revolutions) to t1 = 12 s, the estimate is −α + ln((a + b t1)/(a + b t0)) /
    # (t1 − t0) = −10 + ln(6)/10 for a/b ≪ t0; a/b ~ 1/α moves it by under 0.005 1/s.
    out_file = tmp_path / "analysis.nc"
    argv = ["analyze", str(sixbar_ideal_file), "-o", str(out_file), "--transient", "5"]
    args = parse([*argv, "--model-lyapunov"])
    assert args.func(args) == 0
    with xr.open_dataset(out_file) as analysis:
        assert analysis.sizes["channel"] == 10  # five bodies, x and y
        assert set(analysis["verdict"].values) == {"periodic"}
        assert (analysis["section_period"] == 1).all()
        exponent = float(analysis["model_lyapunov_exponent"])
        stderr = float(analysis["model_lyapunov_stderr"])
        assert exponent + 3 * stderr < 0
        assert abs(exponent - (-10.0 + np.log(6.0) / 10.0)) < 0.01
        # the built-in six-bar's integrator is DOPRI5
        assert analysis.attrs["model_lyapunov_rtol"] == DEFAULT_TOLERANCES["dopri5"][0]
    # printed with its standard error, and read by every verdict's reason
    printed = capsys.readouterr().out
    assert f"model exponent {exponent:.3g} ± {stderr:.2g} 1/s" in printed
    assert printed.count(f"model exponent {exponent:.3g} ± {stderr:.2g} 1/s votes regular") == 10
    # the same exponent read back from that file: the same verdicts, not computed again
    again = tmp_path / "again.nc"
    assert main([*argv[:3], str(again), "--transient", "5", "--model-exponent", str(out_file)]) == 0
    with xr.open_dataset(out_file) as first, xr.open_dataset(again) as second:
        assert float(second.model_lyapunov_exponent) == float(first.model_lyapunov_exponent)
        assert (second.verdict_reason == first.verdict_reason).all()
    # a file without an exponent is refused before anything is computed, naming the variable
    assert (
        main([*argv[:3], str(tmp_path / "x.nc"), "--model-exponent", str(sixbar_ideal_file)]) == 2
    )
    assert "'model_lyapunov_exponent'" in capsys.readouterr().err
    assert not (tmp_path / "x.nc").exists()


#: the slider's clearance across its guide in ``wall_run`` (m)
WALL_CLEARANCE = 2e-4


def _wall_run(duffing_run: xr.Dataset, joint_a_chaotic: bool) -> xr.Dataset:
    """A run with a revolute clearance joint A and a slider B whose across-guide channel B.x
    rests on its wall (−c) at every section instant and leaves it in between by an amount that
    follows A's x (so it is as irregular as A); B.y moves along the guide periodically. With
    ``joint_a_chaotic`` False, A moves periodically (the whole state returns)."""
    time = duffing_run.time.values
    period = float(duffing_run.attrs["crank_period"])
    a = duffing_run.eccentricity.sel(joint="A")
    a_rate = duffing_run.eccentricity_rate.sel(joint="A")
    if not joint_a_chaotic:
        a = a.copy(data=np.stack([a.sel(axis="y").values] * 2, axis=-1))
        a_rate = a_rate.copy(data=np.stack([a_rate.sel(axis="y").values] * 2, axis=-1))
    lift = np.sin(np.pi * time / period) ** 2  # 0 at every section instant
    lift_rate = np.pi / period * np.sin(2 * np.pi * time / period)
    size = np.abs(a.sel(axis="x").values) / 1e-4  # A's x, of order 1, irregular when A is
    size_rate = np.sign(a.sel(axis="x").values) * a_rate.sel(axis="x").values / 1e-4
    across = -WALL_CLEARANCE + 0.5 * WALL_CLEARANCE * lift * size
    across_rate = 0.5 * WALL_CLEARANCE * (lift_rate * size + lift * size_rate)
    along = 0.05 * np.cos(2 * np.pi * time / period)
    along_rate = -0.1 * np.pi / period * np.sin(2 * np.pi * time / period)
    slider = np.stack([np.stack([across, across_rate], -1), np.stack([along, along_rate], -1)], 1)
    joint_a = np.stack([a.values, a_rate.values], axis=-1)
    bodies = {
        name: np.stack(
            [duffing_run.position.sel(body=name), duffing_run.velocity.sel(body=name)], -1
        )
        for name in duffing_run.body.values
    }
    run = run_dataset(period, SAMPLES_PER_REVOLUTION, {"A": joint_a, "B": slider}, bodies)
    scene = {
        "joints": {
            "A": {"type": "revolute", "clearance": 1e-4},
            "B": {"type": "translational", "clearance": WALL_CLEARANCE},
        }
    }
    return run.assign_attrs(scene=json.dumps(scene))


def test_a_slider_resting_on_its_wall_at_the_section_is_not_called_periodic(duffing_run):
    """B.x sits at −c at every section instant, so its own Poincaré points repeat exactly, but
    the mechanism (A) does not return: B.x is not periodic, and the 0–1 test on its pinned
    section values does not vote; B.y, which no wall bounds, keeps its periodic verdict. With
    A periodic the whole state returns, and B.x is periodic."""
    analysis = analyze_run(_wall_run(duffing_run, True), transient_revolutions=TRANSIENT)
    across = analysis.sel(channel="B.x")
    assert int(across.section_period) == 1  # its own points repeat: the wall holds them
    assert int(across.section_held) == 1 and int(across.state_period) == 0
    assert str(across.verdict.item()) != "periodic"
    assert "not read as periodic" in str(across.verdict_reason.item())
    assert str(analysis.verdict.sel(channel="A.x").item()) == "chaotic"
    assert str(analysis.verdict.sel(channel="B.y").item()) == "periodic"
    assert int(analysis.section_held.sel(channel="B.y")) == 0
    # the model's own exponent, decided positive, then gives B.x its verdict
    with_model = analyze_run(
        _wall_run(duffing_run, True),
        transient_revolutions=TRANSIENT,
        model_exponent=212.0,
        model_stderr=5.0,
    )
    assert str(with_model.verdict.sel(channel="B.x").item()) == "chaotic"
    regular = analyze_run(_wall_run(duffing_run, False), transient_revolutions=TRANSIENT)
    assert int(regular.state_period.sel(channel="B.x")) > 0
    assert str(regular.verdict.sel(channel="B.x").item()) == "periodic"

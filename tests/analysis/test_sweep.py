"""`sim sweep`: one scene over a parameter, every run written, the Poincaré samples stacked."""

import re

import numpy as np
import pytest
import xarray as xr

from sim.cli import main

SHORT = ["--set", "simulation.revolutions=2", "--set", "simulation.output_per_revolution=16"]


def slider_at_crank_angle_zero() -> np.ndarray:
    """Slider centre E (m) of docs/model.md's six-bar at crank angle 0, from its geometry alone:
    D is the upper intersection of the circles |D − A| = L2 and |D − C| = L3, and E lies on
    the guide x = 0.15 m below D with |E − D| = L4."""
    a, c = np.array([0.10, 0.0]), np.array([0.35, 0.10])
    l2, l3, l4 = 0.35, 0.30, 0.45
    dist = np.linalg.norm(c - a)
    u = (c - a) / dist
    along = (l2**2 - l3**2 + dist**2) / (2 * dist)
    d = a + along * u + np.sqrt(l2**2 - along**2) * np.array([-u[1], u[0]])
    return np.array([0.15, d[1] - np.sqrt(l4**2 - (0.15 - d[0]) ** 2)])


@pytest.mark.parametrize("continuation", [False, True])
def test_speed_sweep_of_the_ideal_sixbar(tmp_path, continuation):
    """Cold or continued (the 120 rpm run starts from the 60 rpm run's end, angles brought
    back by whole turns, velocities doubled), the sections obey the closed-form kinematics."""
    out_dir, combined_file = tmp_path / "runs", tmp_path / "bifurcation.nc"
    argv = ["sweep", "sixbar", "-q", *SHORT, "--key", "drive.speed_rpm", "--values", "60", "120"]
    argv += ["--transient", "1", "--out-dir", str(out_dir), "-o", str(combined_file)]
    assert main(argv + ["--continuation"] * continuation) == 0
    assert sorted(p.name for p in out_dir.iterdir()) == ["speed_rpm-120.nc", "speed_rpm-60.nc"]
    with xr.open_dataset(out_dir / "speed_rpm-120.nc") as run:
        assert '"speed_rpm": 120' in run.attrs["scene"]
        origin = "continued from speed_rpm = 60" if continuation else "assembled"
        assert run.attrs["initial_state"] == origin
    with xr.open_dataset(combined_file) as sweep:
        assert sweep["parameter"].attrs["name"] == "drive.speed_rpm"
        np.testing.assert_array_equal(sweep["parameter"].values, [60.0, 120.0])
        assert sweep.sizes["revolution"] == 3
        assert sweep.attrs["transient_revolutions"] == 1
        # rigid ideal kinematics: the section (crank angle 0) puts the slider at the same
        # place at every speed, and its velocity scales with the speed
        slider = sweep["section_position"].sel(body="slider").values
        np.testing.assert_allclose(
            slider, np.broadcast_to(slider_at_crank_angle_zero(), slider.shape), atol=1e-8
        )
        velocity = sweep["section_velocity"].sel(body="slider", axis="y").values
        np.testing.assert_allclose(velocity[1], 2.0 * velocity[0], rtol=1e-6)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["bifurcation.nc", "runs"]


def test_the_progress_counts_the_points_and_reports_the_assembly_once(tmp_path, capsys):
    """Each point is announced as "point k of N" with where it goes and, from the second on,
    the time the sweep has left; a scene without hints says which assembly branch it took
    once, not at every point."""
    out_dir = tmp_path / "runs"
    argv = ["sweep", "slider-crank", "--set", "simulation.revolutions=1", "--transient", "0"]
    argv += ["--set", "bodies.rod.hint=null", "--set", "bodies.slider.hint=null"]
    argv += ["--key", "drive.speed_rpm", "--values", "60", "120", "180"]
    assert main([*argv, "--out-dir", str(out_dir), "-o", str(tmp_path / "b.nc")]) == 0
    lines = capsys.readouterr().err.splitlines()
    announced = [line for line in lines if line.startswith("point ")]
    assert [line.split(";")[0] for line in announced] == [
        f"point {k} of 3: speed_rpm = {value}, to {out_dir / f'speed_rpm-{value}.nc'}"
        for k, value in ((1, 60), (2, 120), (3, 180))
    ]
    for k, line in enumerate(announced[1:], start=1):
        assert re.search(rf"; {k} done in \d+ s, ~\d+ s left$", line), line
    assert sum(line.startswith("assembly: ") for line in lines) == 1


def test_clearance_sweep_through_the_ideal_joint(tmp_path):
    combined_file = tmp_path / "bifurcation.nc"
    argv = ["sweep", "sixbar", "-q", *SHORT, "--key", "joints.A.clearance"]
    argv += ["--key", "joints.B.clearance", "--values", "0", "5e-4", "--transient", "1"]
    argv += ["--label", "clearance", "--out-dir", str(tmp_path / "runs"), "-o", str(combined_file)]
    assert main(argv) == 0
    with xr.open_dataset(combined_file) as sweep:
        assert sweep["parameter"].attrs["name"] == "joints.A.clearance,joints.B.clearance"
        assert list(sweep["joint"].values) == ["A", "B"]
        eccentricity = sweep["section_eccentricity"]
        # the ideal point has no eccentricity; the clearance point stays within its clearance
        # (plus a Hertz penetration far below 10 % of it)
        assert np.isnan(eccentricity.sel(parameter=0.0)).all()
        journal = np.hypot(*eccentricity.sel(parameter=5e-4, joint="A").values.T)
        assert np.isfinite(journal).all() and journal.max() < 1.1 * 5e-4


def test_continued_clearance_sweep_restarts_where_the_model_changes(tmp_path):
    """0.5 → 0.4 mm continues (the journal's eccentricity scaled into the smaller bearing);
    0.4 mm → 0 makes the joints ideal, another model: that value starts assembled."""
    out_dir = tmp_path / "runs"
    argv = ["sweep", "sixbar", "-q", *SHORT, "--key", "joints.A.clearance"]
    argv += ["--key", "joints.B.clearance", "--values", "5e-4", "4e-4", "0", "--continuation"]
    argv += ["--transient", "1", "--label", "clearance", "--out-dir", str(out_dir)]
    assert main([*argv, "-o", str(tmp_path / "b.nc")]) == 0
    origins = {}
    for value in ("0.0005", "0.0004", "0"):
        with xr.open_dataset(out_dir / f"clearance-{value}.nc") as run:
            origins[value] = run.attrs["initial_state"]
            if value == "0.0004":
                journal = np.hypot(*run.eccentricity.sel(joint="A").values.T)
                assert journal[0] > 0.5 * 4e-4  # not centred: it kept its place in the bearing
                assert journal.max() < 1.1 * 4e-4
    assert origins["0.0005"] == "assembled"
    assert origins["0.0004"] == "continued from clearance = 0.0005"
    assert origins["0"].startswith("assembled: no continuation from clearance = 0.0004")
    assert "a clearance of 0 makes a joint ideal" in origins["0"]


def test_bad_key_is_refused_before_any_run(tmp_path, capsys):
    out_dir = tmp_path / "runs"
    argv = ["sweep", "sixbar", "-q", *SHORT, "--key", "joints.Q.clearance", "--values", "1e-4"]
    argv += ["--out-dir", str(out_dir), "-o", str(tmp_path / "b.nc")]
    assert main(argv) == 2
    assert "no section 'joints.Q'" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []


def test_range_needs_a_whole_count(tmp_path, capsys):
    argv = ["sweep", "sixbar", "--key", "drive.speed_rpm", "--range", "30", "240", "2.5"]
    argv += ["--out-dir", str(tmp_path / "runs"), "-o", str(tmp_path / "b.nc")]
    assert main(argv) == 2
    assert "--range COUNT = 2.5" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []

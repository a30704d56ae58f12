"""Reproducibility and the output file's contract."""

import json

import numpy as np
import xarray as xr

from sim.cli import main
from sim.run import simulate
from sim.scene import load_scene

CASE = ["simulation.revolutions=1", "joints.A.clearance=0.5e-3", "joints.B.clearance=0.5e-3"]


def test_same_scene_gives_identical_data():
    scene = load_scene("sixbar", CASE)
    first, second = simulate(scene), simulate(scene)
    for name in first.data_vars:
        np.testing.assert_array_equal(first[name].values, second[name].values, err_msg=name)


def test_netcdf_is_cf_annotated_and_records_its_making(tmp_path):
    out = tmp_path / "run.nc"
    overrides = [arg for item in CASE for arg in ("--set", item)]
    assert main(["run", "sixbar", "-q", "-o", str(out), *overrides]) == 0
    with xr.open_dataset(out) as ds:
        for name, var in ds.variables.items():
            assert var.attrs.get("units") or name in ("body", "axis", "joint"), name
            assert var.attrs.get("long_name"), name
        assert ds.attrs["Conventions"] == "CF-1.8"
        scene = json.loads(ds.attrs["scene"])
        assert scene["joints"]["A"]["clearance"] == 0.5e-3
        assert ds.attrs["solver_accepted_steps"] > 0
        assert ds.attrs["sim_version"]
        assert list(ds.joint.values) == ["A", "B"]
        assert ds.sizes["revolution"] == 2
    assert [p.name for p in tmp_path.iterdir()] == ["run.nc"]  # no temporary left


def test_failed_run_writes_nothing(tmp_path, capsys):
    out = tmp_path / "run.nc"
    code = main(["run", "sixbar", "-q", "-o", str(out), "--set", "solver.max_steps=10"])
    assert code == 1
    assert "max_steps" in capsys.readouterr().err
    assert list(tmp_path.iterdir()) == []

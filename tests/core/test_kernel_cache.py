"""The compiled integrator before a run's clock starts (sim/kernel_cache.py, sim/run.py): the
cache is asked without compiling, a cold cache is announced once with an estimate, the compile
is kept out of the recorded wall time, and a run above the energy-audit bound says so."""

import types

import xarray as xr

from sim import kernel_cache
from sim.cli import main
from sim.run import prepare, simulate
from sim.scene import load_scene
from sim.solve import stepping

SHORT = ["simulation.revolutions=0.05"]


def test_the_cache_is_asked_for_the_signature_of_the_run():
    integ = prepare(load_scene("fourbar", SHORT), ideal=True, rigid=True)
    simulate(load_scene("fourbar", SHORT), ideal=True, rigid=True)
    assert kernel_cache.is_cached(stepping.integrate, integ.arguments(0.0))
    # an integer end time is another signature, which nothing compiled
    arguments = list(integ.arguments(0.0))
    arguments[4] = 0
    assert not kernel_cache.is_cached(stepping.integrate, tuple(arguments))


def test_a_cold_compile_is_announced_and_kept_out_of_the_wall_time(monkeypatch, capsys):
    pause = 1.0  # s, the stand-in compile

    def compile_(signature):
        import time

        time.sleep(pause)

    fake = types.SimpleNamespace(integrate=types.SimpleNamespace(overloads={}, compile=compile_))
    monkeypatch.setattr(kernel_cache, "stepping", fake)
    monkeypatch.setattr(kernel_cache, "is_cached", lambda dispatcher, args: False)
    run = simulate(load_scene("fourbar", SHORT), ideal=True, rigid=True)
    err = capsys.readouterr().err
    assert err.count("compiling the integrator's kernels for dopri5") == 1
    seconds = kernel_cache.COMPILE_SECONDS["dopri5"]
    assert f"about {seconds:.0f} s on an idle core" in err
    assert run.attrs["solver_compile_time_s"] >= pause
    # 0.05 revolution of an ideal four-bar integrates in milliseconds, not the compile's second
    assert run.attrs["solver_wall_time_s"] < pause
    assert (
        run.attrs["real_time_factor"]
        == run.attrs["simulated_time_s"] / run.attrs["solver_wall_time_s"]
    )


def test_a_run_above_the_energy_audit_bound_says_so(tmp_path, capsys, monkeypatch):
    out = tmp_path / "run.nc"
    argv = ["run", "fourbar", "-q", "--ideal", "--rigid", "-o", str(out), "--set", SHORT[0]]
    assert main(argv) == 0
    assert "exceeds the bound" not in capsys.readouterr().out
    with xr.open_dataset(out) as run:
        assert run.attrs["energy_audit_exceeded"] == 0 and run.attrs["energy_audit_bound"] == 1e-3
        audit = run.attrs["energy_error_relative"]
    # The same run judged against a bound below its audit (the documented 1e-3 stands for a
    # run of a loose tolerance, which would take minutes to reach it)
    import sim.run

    monkeypatch.setattr(sim.run, "ENERGY_AUDIT_BOUND", audit / 2)
    assert main(argv) == 0
    assert f"the energy audit {audit:.2e} exceeds the bound" in capsys.readouterr().out
    with xr.open_dataset(out) as run:
        assert run.attrs["energy_audit_exceeded"] == 1

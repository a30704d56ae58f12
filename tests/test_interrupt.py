"""Ctrl-C on `sim run`, `sim sweep` and `sim analyze`: one line saying what was interrupted,
where and what was kept, exit code 130, no traceback and nothing half-written."""

import signal
import subprocess
import sys
from pathlib import Path

import pytest

from sim.cli import INTERRUPTED, main
from sim.run import Integration

ROOT = Path(__file__).resolve().parents[1]
SIM = str(Path(sys.executable).with_name("sim"))


def _interrupt_after(monkeypatch, calls: int) -> None:
    """Ctrl-C arriving while the integrator runs its `calls`-th piece (a quarter revolution):
    Python raises KeyboardInterrupt as the compiled loop returns."""
    advance = Integration.advance
    count = iter(range(calls - 1))

    def interrupted(self, t_end):
        piece = t_end > self.t  # not the first call, which records the samples at t = 0
        status = advance(self, t_end)
        if piece and next(count, None) is None:
            raise KeyboardInterrupt
        return status

    monkeypatch.setattr(Integration, "advance", interrupted)


def test_run_says_when_it_was_interrupted_and_writes_nothing(tmp_path, monkeypatch, capsys):
    _interrupt_after(monkeypatch, 3)  # in the third quarter revolution: t = 0.75 T, of 2 T
    argv = ["run", "slider-crank", "-o", str(tmp_path / "run.nc"), "-q"]
    assert main(argv) == INTERRUPTED
    lines = capsys.readouterr().err.splitlines()
    assert len(lines) == 1
    period = 0.2  # s, the slider-crank's 300 rpm
    assert lines[0] == (
        f"sim run: interrupted at t = {0.75 * period:.4g} s of {2 * period:.4g} s, crank "
        "revolution 0.8 of 2; nothing written"
    )
    assert list(tmp_path.iterdir()) == []


def test_analyze_says_what_it_was_computing(tmp_path, monkeypatch, capsys):
    run = tmp_path / "run.nc"
    assert (
        main(["run", "slider-crank", "-q", "-o", str(run), "--set", "simulation.revolutions=32"])
        == 0
    )
    capsys.readouterr()
    _interrupt_after(monkeypatch, 5)
    argv = ["analyze", str(run), "-o", str(tmp_path / "analysis.nc"), "--model-lyapunov"]
    assert main(argv) == INTERRUPTED
    assert capsys.readouterr().err.splitlines() == [
        "sim analyze: interrupted while computing the model exponent; nothing written"
    ]
    assert [p.name for p in tmp_path.iterdir()] == ["run.nc"]


@pytest.mark.skipif(sys.platform == "win32", reason="SIGINT to a child process")
def test_sweep_keeps_the_points_it_finished(tmp_path):
    """A real SIGINT, sent while the second of two points runs (the sweep's own key is the
    run length: 2 revolutions, then 20000, minutes of integration): the first point's run file
    stays, nothing else is written, and the one line says so."""
    out_dir = tmp_path / "runs"
    argv = [SIM, "sweep", "slider-crank", "--key", "simulation.revolutions"]
    argv += ["--values", "2", "20000", "--transient", "0", "--label", "length"]
    argv += ["--out-dir", str(out_dir), "-o", str(tmp_path / "sweep.nc")]
    # a shell's background job (`pytest &`, nohup) hands its children SIGINT ignored, and
    # Python keeps it so: the sweep gets the default action back, as a terminal's Ctrl-C finds it
    sweep = subprocess.Popen(
        argv,
        stderr=subprocess.PIPE,
        text=True,
        cwd=tmp_path,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL),
    )
    lines = []
    for line in sweep.stderr:
        lines.append(line.rstrip("\n"))
        if line.startswith("point 2 of 2"):
            break
    sweep.send_signal(signal.SIGINT)
    lines += sweep.stderr.read().splitlines()
    assert sweep.wait(timeout=60) == INTERRUPTED
    assert lines[0].startswith("point 1 of 2: length = 2, to ")
    assert "Traceback" not in "\n".join(lines)
    last = lines[-1]
    assert last.startswith("sim sweep: interrupted at point 2 of 2 (length = 20000)")
    assert last.endswith(
        f"kept the run files of point 1 in {out_dir}; no bifurcation dataset written"
    )
    assert [p.name for p in out_dir.iterdir()] == ["length-2.nc"]
    assert sorted(p.name for p in tmp_path.iterdir()) == ["runs"]

"""Run files and options that `sim analyze` and `sim sweep` cannot use are refused before any
computation, through `sim`'s one error path: exit code 2 and one line naming the file or the
option and what is accepted."""

import pytest

from sim.cli import main


@pytest.mark.parametrize(
    ("kind", "message"),
    [
        ("text", "is not a netCDF file: give a file written by `sim run`"),
        ("truncated", "is not a netCDF file"),
        ("directory", "is a directory, not a netCDF file"),
        ("missing", "does not exist"),
    ],
)
def test_analyze_names_a_run_file_it_cannot_read(tmp_path, capsys, kind, message):
    run = tmp_path / "run.nc"
    if kind == "text":
        run.write_text("time,acceleration\n0,1\n")
    elif kind == "truncated":
        run.write_bytes(b"\x89HDF\r\n\x1a\n" + bytes(64))  # an HDF5 (netCDF-4) signature, no file
    elif kind == "directory":
        run.mkdir()
    assert main(["analyze", str(run), "-o", str(tmp_path / "a.nc")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"sim analyze: error: run file '{run}' {message}"), err
    assert not (tmp_path / "a.nc").exists()


def test_analyze_refuses_a_negative_transient(tmp_path, capsys):
    argv = ["analyze", str(tmp_path / "run.nc"), "-o", str(tmp_path / "a.nc")]
    assert main([*argv, "--transient", "-1"]) == 2
    expected = "--transient = -1 is not accepted; expected a whole number 0 ≤ x (revolutions)"
    assert expected in capsys.readouterr().err


@pytest.mark.parametrize(
    ("options", "message"),
    [
        (["--transient", "-3"], "--transient = -3 is not accepted"),
        (["--out-dir", "{file}"], "--out-dir '{file}' is a file; give a directory"),
        (["-o", "{tmp}"], "--output '{tmp}' is a directory; give a file name"),
    ],
)
def test_sweep_refuses_bad_options_before_any_run(tmp_path, capsys, options, message):
    file = tmp_path / "taken"
    file.write_text("")
    fill = {"file": file, "tmp": tmp_path}
    argv = ["sweep", "sixbar", "-q", "--key", "drive.speed_rpm", "--values", "60"]
    argv += ["--out-dir", str(tmp_path / "runs"), "-o", str(tmp_path / "b.nc")]
    assert main([*argv, *(o.format(**fill) for o in options)]) == 2
    assert message.format(**fill) in capsys.readouterr().err
    assert sorted(p.name for p in tmp_path.iterdir()) == ["taken"]

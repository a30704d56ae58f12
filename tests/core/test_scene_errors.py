"""Bad scenes are refused before any computation, with a message naming the
key and what is accepted, and nothing is written."""

import pytest

from sim.cli import main

CASES = [
    (
        ["--set", "joints.A.clearance=-1"],
        "'joints.A.clearance' = -1 is not accepted; expected a number 0 ≤ x ≤ 0.01 (m)",
    ),
    (
        ["--set", "joints.A.clearnce=1e-4"],
        "unknown key 'joints.A.clearnce'; accepted keys in 'joints.A': type, bodies",
    ),
    (
        ["--set", "drive.speed_rpm=fast"],
        "'drive.speed_rpm' = 'fast' is not accepted; expected a number",
    ),
    (
        ["--set", "joints.Q.clearance=1e-4"],
        "no section 'joints.Q' in the scene; accepted here: A, B, C, D1, D2, E, O",
    ),
    (
        ["--set", "joints.A.bodies=[rod2, rod9]"],
        "names unknown body 'rod9'; accepted: ground, crank",
    ),
    (["--set", "joints.A.points=[start, tip]"], "names unknown point of 'crank' 'tip'"),
    (
        ["--set", "joints.A.clearance=0.009", "--set", "joints.A.bearing_radius=0.005"],
        "must be smaller than 'joints.A.bearing_radius'",
    ),
    (["--set", "contact.v1=1e-5"], "'contact.v1' = 1e-05 must exceed 'contact.v0'"),
    (
        ["--set", "bodies.rod2.kind=plastic"],
        "'bodies.rod2.kind' = 'plastic' is not accepted; expected one of 'rigid', 'beam'",
    ),
    (["--set", "solver.method=euler"], "expected one of 'dopri5'"),
    (["--set", "contact.slider_law=magic"], "expected one of 'winkler', 'paper'"),
    (
        ["--set", "simulation.revolutions=0"],
        "'simulation.revolutions' = 0 is not accepted; expected a number 0 < x",
    ),
    (["--set", "joints.A.clearance"], "expected dotted.key=value"),
    (["--set", "bodies.slider.kind=beam"], "'bodies.slider.kind' = 'beam' needs shape 'bar'"),
    (
        ["--set", "bodies.rod2.damping={kind: modal}"],
        "'bodies.rod2.damping.kind' = 'modal' needs 'bodies.rod2.damping.ratio'",
    ),
    (["--set", "simulation.beam_start=bent"], "expected one of 'quasi-static', 'straight'"),
    # A loop that cannot close: rod3 far too short to reach D from C.
    (["--set", "bodies.rod3.length=0.05"], "the linkage cannot close: joint 'C' misses by 0.146 m"),
]


@pytest.mark.parametrize(("args", "message"), CASES)
def test_bad_override_is_refused(tmp_path, capsys, args, message):
    out = tmp_path / "x.nc"
    assert main(["run", "sixbar", "-q", "-o", str(out), *args]) == 2
    assert message in capsys.readouterr().err
    assert not out.exists()


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("name: [unclosed\n", "not valid YAML"),
        ("- a list\n", "must hold a mapping"),
        (
            "base: sixbar\njoints:\n  A: {type: hinge}\n",
            "'joints.A.type' = 'hinge' is not accepted",
        ),
        ("base: nosuch\n", "unknown scene 'nosuch'"),
    ],
)
def test_bad_scene_file_is_refused(tmp_path, capsys, text, message):
    scene = tmp_path / "bad.yaml"
    scene.write_text(text)
    assert main(["run", str(scene), "-q", "-o", str(tmp_path / "x.nc")]) == 2
    assert message in capsys.readouterr().err
    assert not (tmp_path / "x.nc").exists()


def test_missing_scene_file(tmp_path, capsys):
    assert main(["run", str(tmp_path / "none.yaml"), "-o", str(tmp_path / "x.nc")]) == 2
    assert "does not exist" in capsys.readouterr().err

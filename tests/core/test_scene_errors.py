"""Bad scenes are refused before any computation, with a message naming the
key and what is accepted, and nothing is written."""

import math
import re

import pytest

from sim.cli import main
from sim.scene import load_scene

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


@pytest.mark.parametrize(
    ("text", "key", "lines"),
    [
        # a body defined twice: YAML alone would keep the second and drop the first
        (
            "base: sixbar\nbodies:\n  crank: {length: 0.1}\n  crank: {length: 0.2}\n",
            "bodies.crank",
            (3, 4),
        ),
        (
            "base: sixbar\njoints:\n  A:\n    clearance: 0.0\n    clearance: 1.0e-4\n",
            "joints.A.clearance",
            (4, 5),
        ),
        ("name: a\nbase: sixbar\nname: b\n", "name", (1, 3)),
    ],
)
def test_duplicate_key_is_refused(tmp_path, capsys, text, key, lines):
    scene = tmp_path / "twice.yaml"
    scene.write_text(text)
    assert main(["run", str(scene), "-q", "-o", str(tmp_path / "x.nc")]) == 2
    err = capsys.readouterr().err
    assert f"scene '{scene}': key '{key}' is defined twice (lines {lines[0]} and {lines[1]})" in err
    assert not (tmp_path / "x.nc").exists()


def test_scene_file_that_is_not_utf8(tmp_path, capsys):
    scene = tmp_path / "latin1.yaml"
    scene.write_bytes("base: sixbar\ndescription: presse à six barres\n".encode("latin-1"))
    assert main(["scene", str(scene)]) == 2
    err = capsys.readouterr().err
    assert f"scene file '{scene}' is not UTF-8 text (byte 0xe0" in err
    assert "must be a YAML file saved as UTF-8" in err and "Traceback" not in err


def test_directory_given_as_scene(tmp_path, capsys):
    assert main(["scene", str(tmp_path)]) == 2
    assert f"scene file '{tmp_path}' is a directory" in capsys.readouterr().err


def test_output_that_is_a_directory_is_refused_before_the_run(tmp_path, capsys):
    assert main(["run", "sixbar", "-q", "-o", str(tmp_path)]) == 2
    assert f"--output '{tmp_path}' is a directory; give a file name" in capsys.readouterr().err


# The loops of the six-bar that hold rod3 (joints C and D2): the crank loop O-A-D1-D2-C and
# the slider loop C-D2-E-B. With rod3 5 cm long the crank loop cannot close; the slider loop
# can (the slider's guide takes any height).
CRANK_LOOP = {"O", "A", "C", "D1", "D2"}


def test_loop_that_cannot_close_is_named(tmp_path, capsys):
    override = "bodies.rod3.length=0.05"
    assert main(["run", "sixbar", "-q", "-o", str(tmp_path / "x.nc"), "--set", override]) == 2
    err = capsys.readouterr().err
    loop = re.search(r"the loop through joints ([\w, ]+) cannot close", err)
    miss = re.search(r"joint '(\w+)' misses by ([0-9.e+-]+) m", err)
    assert loop and miss, err
    assert set(loop.group(1).split(", ")) <= CRANK_LOOP
    joint, distance = miss.group(1), float(miss.group(2))
    assert joint in CRANK_LOOP
    # How far the loop is from closing: D must lie rod2's length from A (crank at its drive
    # angle, 0) and rod3's length from C, and the circle about C lies inside the one about A.
    scene = load_scene("sixbar", [override])
    crank, rod2, rod3 = (scene["bodies"][b]["length"] for b in ("crank", "rod2", "rod3"))
    c = scene["ground"]["C"]
    gap = rod2 - rod3 - math.dist((crank, 0.0), c)  # 0.0307 m
    # At any pose the gaps of the loop's five joints add up to at least `gap` (triangle
    # inequality), so the largest is at least gap / 5; the least-squares closest approach
    # costs no more than the whole gap at one joint, so none exceeds it. 10 % slack for the
    # small turn of the crank away from its drive angle that the least squares also uses.
    assert 0.9 * gap / len(CRANK_LOOP) <= distance <= 1.1 * gap


def test_redundant_joint_is_named(tmp_path, capsys):
    twin = "joints.X={type: revolute, bodies: [ground, crank], points: [O, start], "
    twin += "clearance: 0.0, bearing_radius: 0.015}"
    assert main(["run", "sixbar", "-q", "-o", str(tmp_path / "x.nc"), "--set", twin]) == 2
    err = capsys.readouterr().err
    assert "the constraints are redundant at t = 0: the rows of joints 'O', 'X' depend" in err
    assert "Remove one of those joints (e.g. 'X', defined last)" in err
    assert not (tmp_path / "x.nc").exists()


def test_every_problem_is_reported_at_once(tmp_path, capsys):
    # Three problems of the file and one of an override, in one message, each named by its
    # origin: the file for the keys it wrote, the --set for the key the --set wrote.
    scene = tmp_path / "many.yaml"
    scene.write_text(
        "base: sixbar\ncontact: {friction: -1}\nbodies: {rod2: {lenght: 0.3}}\nsolver: {rtol: 1}\n"
    )
    out = tmp_path / "x.nc"
    assert main(["run", str(scene), "-q", "-o", str(out), "--set", "joints.A.clearnce=1e-4"]) == 2
    err = capsys.readouterr().err
    assert "4 problems, all reported here:" in err
    assert f"scene '{scene}': 'contact.friction' = -1 is not accepted; expected a number" in err
    assert f"scene '{scene}': unknown key 'bodies.rod2.lenght'" in err
    assert f"scene '{scene}': 'solver.rtol' = 1 is not accepted; expected a number" in err
    assert "--set 'joints.A.clearnce=1e-4': unknown key 'joints.A.clearnce'" in err
    assert not out.exists()


def test_a_typo_in_an_override_is_blamed_on_the_override(capsys):
    assert main(["scene", "sixbar", "--set", "drive.sped_rpm=60"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("sim scene: error: --set 'drive.sped_rpm=60': unknown key")
    assert "(built-in)" not in err


def test_base_removes_an_inherited_body_and_its_joints(tmp_path):
    # The six-bar minus rod4 and the slider is a four-bar once rod2 and rod3 are joined at D.
    scene = tmp_path / "fourbar-from-sixbar.yaml"
    scene.write_text(
        "base: sixbar\n"
        "name: fourbar-from-sixbar\n"
        "bodies: {rod4: null, slider: null}\n"
        "joints:\n"
        "  D1: null\n"
        "  D2: null\n"
        "  E: null\n"
        "  B: null\n"
        "  D: {type: revolute, bodies: [rod2, rod3], points: [end, end]}\n"
    )
    resolved = load_scene(str(scene))
    assert list(resolved["bodies"]) == ["crank", "rod2", "rod3"]
    assert list(resolved["joints"]) == ["O", "A", "C", "D"]
    assert resolved["joints"]["D"]["clearance"] == 0.0


def test_a_joint_left_without_its_body_is_named(tmp_path, capsys):
    scene = tmp_path / "dangling.yaml"
    scene.write_text("base: sixbar\nbodies: {rod4: null, rod9: null}\n")
    assert main(["scene", str(scene)]) == 2
    err = capsys.readouterr().err
    assert "4 problems" in err  # rod9, and the joints D1, D2, E of rod4
    assert "'bodies.rod9: null' removes an inherited entry, but the base has none" in err
    assert "'joints.D1.bodies[1]' names unknown body 'rod4'" in err


def test_a_joint_of_another_type_replaces_the_inherited_one_whole(tmp_path, capsys):
    # The six-bar's B is translational; a revolute B replaces it, keeping none of the guide's
    # keys (no merged hybrid), and its own missing keys are named.
    scene = tmp_path / "retyped.yaml"
    scene.write_text(
        "base: sixbar\njoints:\n"
        "  B: {type: revolute, bodies: [ground, slider], points: [O, centre]}\n"
    )
    joint = load_scene(str(scene))["joints"]["B"]
    assert joint == {
        "type": "revolute",
        "bodies": ["ground", "slider"],
        "points": ["O", "centre"],
        "clearance": 0.0,
        "bearing_radius": 0.015,
        "lubricant": None,
        "law": None,
        "stiffness_law": None,
        "bearing_length": None,
    }
    scene.write_text("base: sixbar\njoints:\n  B: {type: revolute}\n")
    assert main(["scene", str(scene)]) == 2
    err = capsys.readouterr().err
    assert "missing key 'joints.B.bodies'" in err and "missing key 'joints.B.points'" in err
    assert "guide" not in err

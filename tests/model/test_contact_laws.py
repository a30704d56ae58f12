"""The damping laws (sim.model.contact_laws) and `sim restitution`, against an independent
integration written here, the exact restitution of the Hunt–Crossley form, and the law without
memory's independence of the impact speed; the choice of a law in a scene; Johnson's law."""

import json
import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from sim.cli import build_parser, main
from sim.model.assembly import build_system
from sim.model.contact import johnson_elastic
from sim.model.contact_laws import LAW_CODES, LAW_NAMES, LAWS
from sim.scene import SceneError, load_scene

#: χ(e) of each law with memory, written anew from the papers (docs/model.md, "Contact laws")
CHI = {
    "lankarani-nikravesh": lambda e: 3.0 * (1.0 - e**2) / 4.0,
    "hunt-crossley": lambda e: 3.0 * (1.0 - e) / 2.0,
    "flores": lambda e: 8.0 * (1.0 - e) / (5.0 * e),
    "gonthier-carvalho": lambda e: (
        3.0 * (1.0 - e) * (11.0 - e) / (2.0 * (1.0 + 9.0 * e)) if e > 1 / 3 else (1 - e**2) / e
    ),
}
V_MIN = 1e-4  # m/s, the damping guard the command uses (the scenes' default)


def command(law: str, nominal: float, speed: float, capsys) -> dict:
    """`sim restitution ... --json`, parsed."""
    args = ["restitution", "--law", law, "--nominal", str(nominal), "--speed", str(speed)]
    assert main([*args, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def independent_restitution(chi: float, speed: float) -> float:
    """e_eff of m δ̈ = −max(0, K δ^1.5 (1 + χ δ̇ / max(v, v_min))) from δ = 0, δ̇ = v, in the
    units of the impact (length (m v²/K)^(2/5), time that over v): x'' = −max(0, x^1.5
    (1 + χ x' v / max(v, v_min)))."""
    ratio = speed / max(speed, V_MIN)

    def rhs(_t, y):
        x = max(y[0], 0.0)
        return [y[1], -max(0.0, x**1.5 * (1.0 + chi * ratio * y[1]))]

    def out(_t, y):
        return y[0]

    out.terminal, out.direction = True, -1
    sol = solve_ivp(rhs, (0, 1e3), [0.0, 1.0], "LSODA", events=out, rtol=1e-11, atol=1e-14)
    return -sol.y_events[0][0][1]


def exact_hunt_crossley_restitution(chi: float) -> float:
    """The exact restitution of F = K δⁿ (1 + χ δ̇/δ̇⁻) while the force stays positive
    (χ e_eff < 1): m v dv/(1 + χ v/v⁻) = −K δⁿ dδ integrates over the impact to
    a − ln(1 + a) = −ε a − ln(1 − ε a), a = χ, ε = e_eff (Carvalho & Martins, Mech. Mach.
    Theory 134, 2019, eq. 20; for any n)."""
    top = min(1.0, (1.0 - 1e-12) / chi)
    return brentq(lambda eps: chi + eps * chi - math.log((1 + chi) / (1 - eps * chi)), 1e-9, top)


@pytest.mark.parametrize("law", list(CHI))
def test_restitution_of_each_law_with_memory_matches_an_independent_integration(law, capsys):
    for nominal, speed in ((0.5, 0.1), (0.9, 1e-3), (0.3, 1e-5)):
        got = command(law, nominal, speed, capsys)
        assert got == {**got, "law": law, "nominal": nominal, "speed": speed}
        # both integrate at rtol ≤ 1e-10: 1e-7 is a margin of orders of magnitude
        assert got["effective"] == pytest.approx(
            independent_restitution(CHI[law](nominal), speed), abs=1e-7
        )


@pytest.mark.parametrize("law", ["lankarani-nikravesh", "hunt-crossley", "gonthier-carvalho"])
def test_restitution_of_the_memory_form_matches_its_exact_closed_form(law, capsys):
    """Above the guard the laws with memory restitute the exact value of their χ; only
    Gonthier–Carvalho's χ is built to give back e itself (within 1e-3, the fit's accuracy)."""
    for nominal in (0.5, 0.7, 0.9):
        chi = CHI[law](nominal)
        assert chi * nominal < 1.0  # the force never reaches zero: the closed form holds
        effective = command(law, nominal, 0.1, capsys)["effective"]
        assert effective == pytest.approx(exact_hunt_crossley_restitution(chi), abs=1e-7)
        if law == "gonthier-carvalho":
            assert abs(effective - nominal) < 1e-3
        else:  # derived for e near 1: too high further down
            assert effective > nominal


def test_the_law_without_memory_restitutes_its_nominal_value_at_every_speed(capsys):
    for nominal in (0.1, 0.5, 0.9):
        values = [command("tsuji", nominal, v, capsys)["effective"] for v in (1e-3, 0.03, 1.0)]
        # ζ(e) is the dimensionless impact's exact inverse (brentq to 1e-10 relative)
        np.testing.assert_allclose(values, nominal, atol=1e-7)


@pytest.mark.parametrize(
    "option, value", [("--nominal", "0"), ("--nominal", "1.5"), ("--speed", "0"), ("--speed", "-1")]
)
def test_restitution_refuses_input_out_of_range(option, value, capsys):
    args = {"--nominal": "0.5", "--speed": "0.1", option: value}
    assert main(["restitution", *(x for kv in args.items() for x in kv)]) == 2
    err = capsys.readouterr().err
    assert option in err and "not accepted" in err


def test_restitution_lists_the_laws_of_the_table():
    sub = next(a for a in build_parser()._actions if a.dest == "command")
    law = next(a for a in sub.choices["restitution"]._actions if a.dest == "law")
    assert tuple(law.choices) == LAW_NAMES == tuple(entry.name for entry in LAWS)


def test_a_joint_overrides_the_scenes_law():
    scene = load_scene(
        "sixbar",
        [
            "joints.A.clearance=5e-4",
            "joints.B.clearance=5e-4",
            "contact.law=flores",
            "joints.B.law=tsuji",
            "contact.restitution=0.5",
        ],
    )
    system, _ = build_system(scene)
    # A is a revolute clearance, B the slider's translational one
    assert (system.rj["law"][0], system.tj["law"][0]) == (LAW_CODES["flores"], LAW_CODES["tsuji"])
    assert system.rj["damping"][0] == CHI["flores"](0.5)
    # without memory: c = ζ(e, n) √(m* K) at a corner (n = 1.5) and at a face (n = 1)
    assert system.tj["damping"][0] > 0.0 and system.tj["face_damping"][0] > 0.0


def test_an_unknown_law_is_refused_naming_the_key():
    with pytest.raises(SceneError, match=r"joints\.A\.law"):
        load_scene("sixbar", ["joints.A.clearance=5e-4", "joints.A.law=newton"])


def test_johnson_law_satisfies_its_implicit_relation_and_derives_from_its_energy():
    """δ = s [ln(4ΔR/s) − 1], s = F/(πLE*), and dU/dδ = F, across the Newton-solved range and
    the linear continuation beyond δ = 8ΔR/e³."""
    line, clearance = 7.2e9, 5e-4
    limit = 8.0 * clearance * math.exp(-3.0)
    for delta in (1e-9, 1e-7, 1e-5, 0.99 * limit):
        force, _ = johnson_elastic(line, clearance, delta)
        s = force / line
        assert s * (math.log(4 * clearance / s) - 1) == pytest.approx(delta, rel=1e-12)
    for delta in (1e-8, 1e-6, 0.5 * limit, 1.5 * limit):
        h = 1e-6 * delta
        du = (
            johnson_elastic(line, clearance, delta + h)[1]
            - johnson_elastic(line, clearance, delta - h)[1]
        )
        assert du / (2 * h) == pytest.approx(johnson_elastic(line, clearance, delta)[0], rel=1e-6)
    below, above = (johnson_elastic(line, clearance, limit * (1 + s))[0] for s in (-1e-9, 1e-9))
    assert above == pytest.approx(below, rel=1e-6)


def test_johnson_law_needs_the_bearing_length_and_a_law_with_memory():
    common = ["joints.A.clearance=5e-4", "joints.A.stiffness_law=johnson"]
    with pytest.raises(Exception, match="bearing_length"):
        build_system(load_scene("sixbar", common))
    with pytest.raises(Exception, match="power-law"):
        build_system(
            load_scene("sixbar", [*common, "joints.A.bearing_length=0.02", "joints.A.law=tsuji"])
        )
    johnson, _ = build_system(load_scene("sixbar", [*common, "joints.A.bearing_length=0.02"]))
    hertz, _ = build_system(load_scene("sixbar", ["joints.A.clearance=5e-4"]))
    # π L E* against (4/3) E* √(R_B R_J / ΔR): the same E*
    r_b, r_j = hertz.rj["bearing_radius"][0], hertz.rj["journal_radius"][0]
    ratio = math.pi * 0.02 / (4.0 / 3.0 * math.sqrt(r_b * r_j / (r_b - r_j)))
    assert johnson.rj["stiffness"][0] / hertz.rj["stiffness"][0] == pytest.approx(ratio)

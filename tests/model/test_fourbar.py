"""A user's own linkage in a short scene: the built-in crank-rocker four-bar (no contact,
simulation or solver block) loads with the defaults and its ideal, rigid motion follows the
closed-form position analysis of a four-bar (Freudenstein's equation)."""

import re

import numpy as np
import pytest

from sim.analysis.revolutions import SLIDER_ACCELERATION, revolution_table
from sim.model.assembly import build_system
from sim.run import simulate
from sim.scene import SceneError, load_scene, output_channel, parse_yaml
from sim.scene_keys import CONTACT, SIMULATION, SOLVER

# Crank a, coupler b, rocker c, ground pivots d apart: sim/scenes/fourbar.yaml.
A, B, C, D = 0.10, 0.35, 0.30, 0.40


def freudenstein(theta2: np.ndarray, sign: float) -> np.ndarray:
    """Rocker angle θ4 (rad) of the four-bar with ground pivots (0, 0) and (d, 0) at crank
    angle θ2, from Freudenstein's equation K1 cos θ4 − K2 cos θ2 + K3 = cos(θ2 − θ4) solved by
    the half-angle tangent (Norton, Design of Machinery, 5th ed., §4.5): sign +1 or −1 picks
    the branch (open or crossed)."""
    k1, k2, k3 = D / A, D / C, (A * A - B * B + C * C + D * D) / (2.0 * A * C)
    a = np.cos(theta2) - k1 - k2 * np.cos(theta2) + k3
    b = -2.0 * np.sin(theta2)
    c = k1 - (k2 + 1.0) * np.cos(theta2) + k3
    return 2.0 * np.arctan2(-b + sign * np.sqrt(b * b - 4.0 * a * c), 2.0 * a)


def wrapped(angle: np.ndarray) -> np.ndarray:
    return (angle + np.pi) % (2.0 * np.pi) - np.pi


def test_the_builtin_four_bar_takes_every_numerical_setting_but_rtol_from_the_defaults():
    # rtol is the scene's own: in sustained contact the default leaves its energy audit above
    # the bound (docs/fidelity.md, "The energy audit")
    scene = load_scene("fourbar")
    for section, table in (("contact", CONTACT), ("simulation", SIMULATION)):
        assert scene[section] == {k: f.default for k, f in table.items()}, section
    assert scene["solver"] == {k: f.default for k, f in SOLVER.items()} | {"rtol": 1e-6}
    assert scene["joints"]["B"]["clearance"] == 0.3e-3
    assert scene["bodies"]["rocker"]["kind"] == "rigid"


# A minimal four-bar as a user writes it: no contact, simulation or solver block.
MINIMAL = """
name: my-fourbar
materials: {steel: {youngs_modulus: 207.0e9, poisson: 0.3, density: 7801.0}}
ground: {O: [0.0, 0.0], C: [0.40, 0.0]}
bodies:
  crank: {length: 0.10, section: [0.06, 0.02], material: steel,
          hint: {position: [0.05, 0.0], angle_deg: 0.0}}
  coupler: {length: 0.35, section: [0.06, 0.02], material: steel,
            hint: {position: [0.2, 0.14], angle_deg: 54.0}}
  rocker: {length: 0.30, section: [0.06, 0.02], material: steel,
           hint: {position: [0.35, 0.14], angle_deg: 109.0}}
joints:
  O: {type: revolute, bodies: [ground, crank], points: [O, start]}
  A: {type: revolute, bodies: [coupler, crank], points: [start, end]}
  B: {type: revolute, bodies: [coupler, rocker], points: [end, end], clearance: 0.3e-3}
  C: {type: revolute, bodies: [ground, rocker], points: [C, start]}
drive: {body: crank, speed_rpm: 120.0}
"""


def test_a_minimal_four_bar_runs_and_follows_the_closed_form(tmp_path):
    path = tmp_path / "my-fourbar.yaml"
    path.write_text(MINIMAL)
    assert "contact" not in parse_yaml(MINIMAL)
    scene = load_scene(str(path), ["simulation.output_per_revolution=90"])
    ds = simulate(scene, ideal=True, rigid=True, revolutions=1.0)
    theta2 = ds.crank_angle.values.astype(float)
    theta4 = ds.angle.sel(body="rocker").values.astype(float)
    # the hints' branch: B above the ground line (the rocker's angle in (0, π) at crank
    # angle 0), the half-angle solution with the minus sign
    assert 0.0 < theta4[0] < np.pi
    error = np.abs(wrapped(theta4 - freudenstein(theta2, -1.0)))
    assert theta2.size == 91  # a full crank turn, 90 samples a revolution and t = 0
    # Margin 1e-6 rad: the crank angle is prescribed exactly; the rocker's follows from the
    # loop closure, which the integrator holds to its absolute tolerance (atol 1e-7 m, the
    # default) under Baumgarte stabilization: 3.3e-7 rad on the 0.3 m rocker, here with a
    # factor 3 of room. Measured: 2e-11 rad.
    assert error.max() < 1e-6, error.max()


def loop_rates(theta2, theta3, theta4, omega2):
    """Angular velocities (ω3, ω4, rad/s) and accelerations (α3, α4, rad/s²) of the coupler and
    the rocker of the four-bar a e^{iθ2} + b e^{iθ3} = d + c e^{iθ4} driven at constant ω2: the
    loop's first and second time derivatives, two linear equations each with the same matrix
    (Norton, Design of Machinery, 5th ed., §6.7 and §7.3)."""
    s2, c2, s3, c3, s4, c4 = (f(x) for x in (theta2, theta3, theta4) for f in (np.sin, np.cos))
    matrix = np.moveaxis(np.array([[-B * s3, C * s4], [B * c3, -C * c4]]), -1, 0)
    velocity = np.linalg.solve(matrix, np.stack([A * omega2 * s2, -A * omega2 * c2], -1)[..., None])
    w3, w4 = velocity[..., 0].T
    rhs = np.stack(
        [
            A * omega2**2 * c2 + B * w3**2 * c3 - C * w4**2 * c4,
            A * omega2**2 * s2 + B * w3**2 * s3 - C * w4**2 * s4,
        ],
        -1,
    )
    a3, a4 = np.linalg.solve(matrix, rhs[..., None])[..., 0].T
    return w3, w4, a3, a4


def test_the_rocker_angular_velocity_and_acceleration_follow_the_closed_form(tmp_path):
    # The minimal four-bar, ideal and rigid, recorded at instants (point samples): the
    # recorded angular velocity and acceleration of the coupler and the rocker against the
    # loop's closed-form rates at the recorded angles. Margin 1e-4 of each peak: the angles
    # are stored in float32 (6e-8 relative) and held on the loop to the integrator's atol
    # (1e-7 m: 3e-7 rad on the 0.3 m rocker), which the rate equations pass on amplified by at
    # most 1/sin of the transmission angle (its smallest here, ~25°: 2.4 x).
    path = tmp_path / "my-fourbar.yaml"
    path.write_text(MINIMAL)
    scene = load_scene(str(path), ["simulation.sampling=point"])
    ds = simulate(scene, ideal=True, rigid=True, revolutions=1.0)
    theta2 = ds.crank_angle.values.astype(float)
    theta3, theta4 = (ds.angle.sel(body=b).values.astype(float) for b in ("coupler", "rocker"))
    omega2 = 2.0 * np.pi * 120.0 / 60.0
    w3, w4, a3, a4 = loop_rates(theta2, theta3, theta4, omega2)
    for body, w, a in (("coupler", w3, a3), ("rocker", w4, a4)):
        recorded_w = ds.angular_velocity.sel(body=body).values
        recorded_a = ds.angular_acceleration.sel(body=body).values
        assert np.abs(recorded_w - w).max() < 1e-4 * np.abs(w).max(), body
        assert np.abs(recorded_a - a).max() < 1e-4 * np.abs(a).max(), body


@pytest.mark.parametrize("point", ["end", [0.1, 0.02]], ids=["named", "body-frame"])
def test_the_output_point_follows_the_closed_form(tmp_path, point):
    # The rocker's end, or a point given in its frame, as the output point: its recorded
    # position, velocity and acceleration (point samples) against the rocker's rigid motion
    # about its ground pivot C at the closed-form rates (`loop_rates`) of the recorded angles:
    # r = C + A(θ4) (u + (c/2, 0)), v = ω4 k × (r − C), a = α4 k × (r − C) − ω4² (r − C).
    # Margin 1e-4 of each peak, as for the rates above.
    path = tmp_path / "my-fourbar.yaml"
    path.write_text(MINIMAL + f"output: {{body: rocker, point: {point}, axis: y}}\n")
    scene = load_scene(str(path), ["simulation.sampling=point"])
    ds = simulate(scene, ideal=True, rigid=True, revolutions=1.0)
    theta2 = ds.crank_angle.values.astype(float)
    theta3, theta4 = (ds.angle.sel(body=b).values.astype(float) for b in ("coupler", "rocker"))
    _, w4, _, a4 = loop_rates(theta2, theta3, theta4, 2.0 * np.pi * 120.0 / 60.0)
    u = (C / 2.0, 0.0) if point == "end" else point
    ux, uy = u[0] + C / 2.0, u[1]  # from the pivot C, the rocker's start
    rx = np.cos(theta4) * ux - np.sin(theta4) * uy
    ry = np.sin(theta4) * ux + np.cos(theta4) * uy
    expected = {
        "output_position": (D + rx, ry),
        "output_velocity": (-w4 * ry, w4 * rx),
        "output_acceleration": (-a4 * ry - w4**2 * rx, a4 * rx - w4**2 * ry),
    }
    for name, (x, y) in expected.items():
        for axis, value in (("x", x), ("y", y)):
            recorded = ds[name].sel(axis=axis).values
            scale = max(np.abs(x).max(), np.abs(y).max())
            assert np.abs(recorded - value).max() < 1e-4 * scale, (name, axis)


def test_an_output_point_the_body_lacks_is_refused_with_the_points_it_has():

    with pytest.raises(
        SceneError, match=re.escape("output.point: body 'rocker' has no point 'tip'")
    ):
        build_system(load_scene("fourbar", ["output.point=tip"]))
    beam = load_scene("fourbar", ["bodies.rocker.kind=beam", "output.point=[0.1, 0.0]"])
    with pytest.raises(SceneError, match="offers 'start', 'centre' and 'end' only"):
        build_system(beam)


def test_the_analyses_read_the_scenes_output_channel():
    # The six-bar's channel is its slider along the guide (no `output` key); the four-bar
    # names its rocker; a scene with neither is told to name one.
    assert output_channel(load_scene("sixbar")) == ("slider", "centre", "y")
    assert output_channel(load_scene("fourbar")) == ("rocker", "centre", "y")
    with pytest.raises(ValueError, match=re.escape("give output: {body: <name>, axis: x or y}")):
        output_channel(load_scene("fourbar", ["output=null"]))
    with pytest.raises(SceneError, match=re.escape("'output.body' names unknown body 'rod9'")):
        load_scene("fourbar", ["output.body=rod9"])
    run = simulate(load_scene("fourbar"), ideal=True, rigid=True, revolutions=2.0)
    table = revolution_table(run, "nominal", transient=0)
    expected = run.revolution_peak_acceleration.sel(body="rocker", axis="y").values[1:]
    np.testing.assert_array_equal(table[SLIDER_ACCELERATION].values, expected)


def test_the_built_in_four_bar_runs_with_its_clearance():
    # One revolution with the 0.3 mm clearance at B and every default setting: the journal
    # stays in its bearing (the Hertz penetration at the default contact law is far below 10 %
    # of the clearance) and the energy audit within the bound of a sound run (1e-3).
    run = simulate(load_scene("fourbar"), revolutions=1.0)
    journal = np.hypot(*run.eccentricity.sel(joint="B").values.T)
    assert np.isfinite(journal).all() and journal.max() < 1.1 * 0.3e-3
    assert run.attrs["energy_error_relative"] < 1e-3
    assert run.attrs["energy_audit_exceeded"] == 0

"""Rigid ideal linkages against closed-form kinematics and the power balance.

The references are computed here from docs/model.md's geometry alone: circle
intersections for positions, the differentiated loop equations (2×2 linear
systems) for velocities and accelerations, and τω = dT/dt + dV/dt for the
driving torque of rigid links with ideal joints.
"""

import numpy as np
import pytest

O = np.array([0.0, 0.0])
C = np.array([0.35, 0.10])
L1, L2, L3, L4 = 0.10, 0.35, 0.30, 0.45
GUIDE_X = 0.15
OMEGA = 2 * np.pi * 150 / 60
RHO, AREA = 7801.0, 0.06 * 0.02
SLIDER_MASS = 5.85075
G = 9.81
# point samples: the closed forms hold at instants (tests/core/test_sample_row.py checks the
# interval means, the default, against the closed forms' means over each window)
TIGHT = [
    "simulation.revolutions=1",
    "simulation.sampling=point",
    "solver.rtol=1e-10",
    "solver.atol=1e-12",
]


def cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def solve2(m, rhs):
    """Solve the 2×2 systems m x = rhs, vectorised over the first axis."""
    return np.linalg.solve(m, rhs[..., None])[..., 0]


def sixbar_kinematics(theta):
    """Positions, velocities, accelerations of A, D, E for crank angles θ (vectorised)."""
    c, s = np.cos(theta), np.sin(theta)
    a = L1 * np.stack([c, s], -1)
    va = L1 * OMEGA * np.stack([-s, c], -1)
    aa = -(OMEGA**2) * a
    d_vec = C - a
    dist = np.linalg.norm(d_vec, axis=-1)
    along = (L2**2 - L3**2 + dist**2) / (2 * dist)
    height = np.sqrt(L2**2 - along**2)
    u = d_vec / dist[:, None]
    perp = np.stack([-u[:, 1], u[:, 0]], -1)
    cand = [a + along[:, None] * u + sgn * height[:, None] * perp for sgn in (1, -1)]
    d = np.where((cand[0][:, 1] > cand[1][:, 1])[:, None], cand[0], cand[1])
    # |D − A|² = L2², |D − C|² = L3², differentiated once and twice.
    m = np.stack([d - a, d - C], 1)
    vd = solve2(m, np.stack([np.sum((d - a) * va, -1), np.zeros(len(theta))], -1))
    rhs = np.stack([np.sum((d - a) * aa, -1) - np.sum((vd - va) ** 2, -1), -np.sum(vd**2, -1)], -1)
    ad = solve2(m, rhs)
    # E on x = GUIDE_X below D, |E − D| = L4.
    ey = d[:, 1] - np.sqrt(L4**2 - (GUIDE_X - d[:, 0]) ** 2)
    e = np.stack([np.full_like(ey, GUIDE_X), ey], -1)
    r = e - d
    ve_y = vd[:, 1] + r[:, 0] * vd[:, 0] / r[:, 1]
    ve = np.stack([np.zeros_like(ve_y), ve_y], -1)
    ae_y = ad[:, 1] + (r[:, 0] * ad[:, 0] - np.sum((ve - vd) ** 2, -1)) / r[:, 1]
    ae = np.stack([np.zeros_like(ae_y), ae_y], -1)
    return {"A": (a, va, aa), "D": (d, vd, ad), "E": (e, ve, ae)}


def link_power(p0, v0, a0, p1, v1, a1, length):
    """d/dt of the kinetic plus gravitational energy of a uniform bar between two points."""
    m = RHO * AREA * length
    j = m * length**2 / 12
    vg = 0.5 * (v0 + v1)
    ag = 0.5 * (a0 + a1)
    dvec, dvel, dacc = p1 - p0, v1 - v0, a1 - a0
    w = cross(dvec, dvel) / length**2
    alpha = cross(dvec, dacc) / length**2
    return m * np.sum(vg * ag, -1) + j * w * alpha + m * G * vg[:, 1]


def test_sixbar_slider_matches_closed_form(run):
    ds = run("sixbar", *TIGHT)
    ref = sixbar_kinematics(OMEGA * ds.time.values)
    e, ve, ae = ref["E"]
    pos = ds.position.sel(body="slider").values
    vel = ds.velocity.sel(body="slider").values
    acc = ds.acceleration.sel(body="slider").values
    # The specification: 1e-8 m in position, 1e-6 of the peak in rate terms.
    assert np.abs(pos - e).max() < 1e-8
    assert np.abs(vel - ve).max() < 1e-6 * np.abs(ve).max()
    assert np.abs(acc - ae).max() < 1e-6 * np.abs(ae).max()


def test_sixbar_drive_torque_matches_power_balance(run):
    ds = run("sixbar", *TIGHT)
    ref = sixbar_kinematics(OMEGA * ds.time.values)
    zero = np.zeros_like(ref["A"][0])
    origin = (zero, zero, zero)
    c_pt = (np.broadcast_to(C, zero.shape), zero, zero)
    power = (
        link_power(*origin, *ref["A"], L1)
        + link_power(*ref["A"], *ref["D"], L2)
        + link_power(*c_pt, *ref["D"], L3)
        + link_power(*ref["D"], *ref["E"], L4)
        + SLIDER_MASS * (ref["E"][1][:, 1] * ref["E"][2][:, 1] + G * ref["E"][1][:, 1])
    )
    torque = power / OMEGA
    err = np.abs(ds.drive_torque.values - torque).max()
    assert err < 1e-6 * np.abs(torque).max()


def test_slider_crank_matches_textbook(run):
    # Slider-crank (crank r, rod l, guide through O): x = r cos θ + sqrt(l² − r² sin² θ).
    ds = run("slider-crank", "solver.rtol=1e-10", "solver.atol=1e-12")
    r, length, omega = 0.05, 0.20, 2 * np.pi * 300 / 60
    theta = omega * ds.time.values
    root = np.sqrt(length**2 - (r * np.sin(theta)) ** 2)
    x = r * np.cos(theta) + root
    v = -r * omega * np.sin(theta) - (r**2 * omega * np.sin(theta) * np.cos(theta)) / root
    pos = ds.position.sel(body="slider", axis="x").values
    vel = ds.velocity.sel(body="slider", axis="x").values
    assert np.abs(pos - x).max() < 1e-8
    assert np.abs(vel - v).max() < 1e-6 * np.abs(v).max()
    # The slider stays on its guide line exactly (ideal prismatic joint).
    assert np.abs(ds.position.sel(body="slider", axis="y").values).max() < 1e-9


@pytest.mark.parametrize("body", ["crank", "rod2", "rod3", "rod4"])
def test_sections_are_taken_at_whole_revolutions(run, body):
    # A driven ideal mechanism repeats exactly every revolution.
    ds = run("sixbar", *TIGHT)
    sec = ds.section_position.sel(body=body).values
    assert np.abs(sec[1] - sec[0]).max() < 1e-8

"""The cross-check's measures (sim.crosscheck.compare) on signals and beams with known answers;
none needs Exudyn."""

import json

import numpy as np
import pytest
import xarray as xr

from sim.crosscheck.compare import (
    dominant_frequencies,
    elastic_law_difference,
    exudyn_strain_energy,
    first_impact,
    lowpass,
)
from sim.model.ancf import straight_beam_coordinates
from sim.scene import load_scene

FS = 50_000.0
T = np.arange(int(0.4 * FS)) / FS


def test_dominant_frequencies_of_two_tones():
    """380 Hz and 972 Hz (amplitudes 2 : 1) over 0.4 s: found within one bin (2.5 Hz),
    strongest first."""
    x = 2.0 * np.sin(2 * np.pi * 380.0 * T) + np.sin(2 * np.pi * 972.0 * T + 0.3)
    found = dominant_frequencies(x, FS, count=2)
    np.testing.assert_allclose(found, [380.0, 972.0], atol=FS / T.size)


def test_lowpass_is_zero_phase_and_cuts_high_frequencies():
    """A 5 Hz wave passes unshifted (|H|² of a 4th-order Butterworth at 100 Hz: 1 − 8e-11);
    a 1 kHz wave is cut to (100/1000)^8 = 1e-8 of its amplitude. The filter's start-up
    transients decay at ~2π · 100 Hz · sin(π/8) = 240 1/s: 0.04 s from the record's ends they
    are still ~8e-6, 0.08 s from them below 1e-9 (measured 1.3e-10 and 1.1e-8). There both
    hold to 1e-7, ten times what the filter leaves of a 1 kHz wave (1e-8)."""
    slow = np.sin(2 * np.pi * 5.0 * T)
    fast = np.sin(2 * np.pi * 1000.0 * T)
    inner = slice(T.size // 5, -T.size // 5)
    assert np.max(np.abs(lowpass(slow, FS, 100.0) - slow)[inner]) < 1e-7
    assert np.max(np.abs(lowpass(fast, FS, 100.0))[inner]) < 1e-7


def test_elastic_laws_of_a_stretched_beam():
    """A straight link stretched uniformly by λ: Exudyn's axial force EA(λ − 1), ours from the
    Green strain EA λ(λ² − 1)/2; the end forces differ by that ratio, the energies
    ½EA(λ−1)²L and ½EA((λ²−1)/2)²L likewise."""
    ea, ei, length, lam = 2.484e8, 8280.0, 0.35, 1.001
    q = straight_beam_coordinates(np.zeros(2), np.array([length * lam, 0.0]), 2)
    q[2::4] = lam  # slope r' = λ e_x at every node
    ours = lam * (lam**2 - 1) / 2
    theirs = lam - 1
    diff = elastic_law_difference(q, length / 2, ea, ei)
    assert diff["force"] == pytest.approx(abs(theirs - ours) / ours, rel=1e-6)
    u_theirs = 0.5 * ea * theirs**2 * length
    assert exudyn_strain_energy(q, length / 2, ea, ei) == pytest.approx(u_theirs, rel=1e-9)


def test_exudyn_bending_energy_of_an_arc():
    """Nodes on a circular arc of radius R with unit tangent slopes: material curvature 1/R,
    energy ½ EI L / R² up to the cubic interpolation of the arc (angle 0.035 rad)."""
    ei, radius, length, n = 8280.0, 10.0, 0.35, 2
    s = np.linspace(0.0, length, n + 1)
    phi = s / radius
    q = np.column_stack(
        [radius * np.sin(phi), radius * (1 - np.cos(phi)), np.cos(phi), np.sin(phi)]
    ).ravel()
    energy = exudyn_strain_energy(q, length / n, 0.0, ei)
    assert energy == pytest.approx(0.5 * ei * length / radius**2, rel=1e-4)


def _impact_run(t: np.ndarray, delta: np.ndarray, rate: np.ndarray, stiffness: float):
    """A run of joint A (clearance 0.5 mm) whose journal moves along the direction 30° with
    penetration δ(t) and rate δ̇(t), and whose normal force is K δ^1.5 in contact."""
    scene = load_scene("sixbar", ["joints.A.clearance=5e-4"])
    direction = np.array([np.cos(np.pi / 6), np.sin(np.pi / 6)])
    ecc = (5e-4 + delta)[:, None, None] * direction
    force = stiffness * np.maximum(delta, 0.0) ** 1.5
    return xr.Dataset(
        {
            "eccentricity": (("time", "joint", "axis"), ecc),
            "eccentricity_rate": (("time", "joint", "axis"), rate[:, None, None] * direction),
            "normal_force": (("time", "joint"), force[:, None]),
        },
        coords={"time": t, "joint": ["A"], "axis": ["x", "y"]},
        attrs={"scene": json.dumps(scene)},
    )


def test_first_impact_of_a_known_contact():
    """Approach at v = 0.2 m/s until t0 = 1 ms, a contact of T = 0.2 ms with
    δ = v T s (1 − s)(1 + k s), s = (t − t0)/T, k = −0.2, which leaves at δ̇ = −v (1 + k):
    rebound 0.8; then apart at that speed. Sampled every T/400, off the
    crossings: the onset and separation times within 1e-3 T (linear interpolation across a
    curvature jump: at most |δ̈| dt² / (2 v) ≈ 1.2 dt² / T); onset rate and rebound within 0.3 %
    (the rate interpolated across the jump of δ̈: at most |δ̈| dt / 4 = 0.15 %); peak force and
    deepest penetration within 1e-6 (the parabola's vertex, against a 1e5-point search)."""
    v, t0, duration, k, stiffness = 0.2, 1e-3, 2e-4, -0.2, 1e11
    dt = duration / 400
    t = 0.3 * dt + np.arange(int(2e-3 / dt)) * dt
    s = (t - t0) / duration
    inside = (s > 0) & (s < 1)
    delta = np.where(s <= 0, v * (t - t0), -(1 + k) * v * (t - t0 - duration))
    rate = np.where(s <= 0, v, -(1 + k) * v)
    shape = s * (1 - s) * (1 + k * s)
    slope = (1 - 2 * s) * (1 + k * s) + k * s * (1 - s)
    delta[inside] = v * duration * shape[inside]
    rate[inside] = v * slope[inside]
    found = first_impact(_impact_run(t, delta, rate, stiffness), "A")
    fine = np.linspace(0, 1, 100_001)
    deepest = v * duration * np.max(fine * (1 - fine) * (1 + k * fine))
    assert found["onset_s"] == pytest.approx(t0, abs=1e-3 * duration)
    assert found["separation_s"] == pytest.approx(t0 + duration, abs=1e-3 * duration)
    assert found["onset_rate"] == pytest.approx(v, rel=3e-3)
    assert found["rebound"] == pytest.approx(1 + k, rel=3e-3)
    assert found["max_penetration"] == pytest.approx(deepest, rel=1e-6)
    assert found["peak_force"] == pytest.approx(stiffness * deepest**1.5, rel=1e-6)

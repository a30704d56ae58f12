"""The cross-check's measures (sim.crosscheck.compare) on signals and beams with known answers;
none needs Exudyn."""

import numpy as np
import pytest

from sim.crosscheck.compare import (
    dominant_frequencies,
    elastic_law_difference,
    exudyn_strain_energy,
    lowpass,
)
from sim.model.ancf import straight_beam_coordinates

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

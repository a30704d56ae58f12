"""Agreement of two runs of the same scene (ours and Exudyn's), measured, not eyeballed.

The compared signals are the slider's displacement, velocity and acceleration along its guide
and the driving torque (the paper's comparison with ADAMS). Three kinds of measure:

- `deterministic`: sample-by-sample error norms of each signal over the same output times,
  max |Δ| and RMS(Δ), both over the peak |x| of our signal. With `cutoff` the signals are first
  split by a zero-phase low-pass (`lowpass`): the low band is compared sample by sample; the high
  band (raw minus low), where undamped beam vibration lives and never converges sample by
  sample, by its RMS and its dominant frequencies (`dominant_frequencies`).
- `statistical`: for chaotic runs (clearance joints), where trajectories separate after a few
  impacts, the statistics that survive: the distribution of per-revolution peaks of
  |acceleration| and |torque| and the distribution of the Poincaré points of each clearance
  joint (eccentricity at each crank revolution), by mean, standard deviation, the two-sample
  Kolmogorov–Smirnov statistic and the Wasserstein distance over the pooled spread.
- `first_impact` / `impact`: one contact of a revolute clearance joint (onset time, onset rate,
  peak normal force, deepest penetration, rebound) in each run and their differences, for the
  contact law compared with Exudyn's own contact object (sim.crosscheck.model).
- `elastic_law_difference`: what our beam law (Green strain, constant bending stiffness) and
  Exudyn's (|r'| − 1 strain, material curvature) change in the elastic forces at given states.
"""

import numpy as np
import xarray as xr
from numpy.polynomial import Polynomial
from scipy import signal, stats

from sim.model import ancf
from sim.model.beams import hermite_shape
from sim.results import scene_of

SIGNALS = ("displacement", "velocity", "acceleration", "drive_torque")


def slider_signals(ds: xr.Dataset) -> dict[str, np.ndarray]:
    """Slider displacement (m), velocity (m/s), acceleration (m/s²) along the guide of the
    scene's first translational joint, and the driving torque (N m)."""
    scene = scene_of(ds)
    joint = next(j for j in scene["joints"].values() if j["type"] == "translational")
    angle = np.radians(joint["guide_angle_deg"])
    tangent = np.array([np.cos(angle), np.sin(angle)])
    body = joint["bodies"][1]
    out = {
        name: ds[variable].sel(body=body).values @ tangent
        for name, variable in zip(
            SIGNALS[:3], ("position", "velocity", "acceleration"), strict=True
        )
    }
    out["drive_torque"] = ds["drive_torque"].values
    return out


def lowpass(x: np.ndarray, fs: float, cutoff: float, order: int = 4) -> np.ndarray:
    """Zero-phase Butterworth low-pass of x sampled at fs (Hz) with corner `cutoff` (Hz).

    Forward and backward (scipy.signal.sosfiltfilt, odd extension at the ends): no phase shift,
    magnitude |H|² of an order-`order` Butterworth filter, −6 dB at the cutoff."""
    return signal.sosfiltfilt(signal.butter(order, cutoff, fs=fs, output="sos"), x)


def error_norms(test: np.ndarray, ref: np.ndarray) -> dict[str, float]:
    """max |test − ref| and RMS(test − ref), both over max |ref|."""
    scale = float(np.max(np.abs(ref)))
    diff = test - ref
    return {
        "max": float(np.max(np.abs(diff))) / scale,
        "rms": float(np.sqrt(np.mean(diff**2))) / scale,
        "peak": scale,
    }


def dominant_frequencies(x: np.ndarray, fs: float, count: int = 3) -> np.ndarray:
    """The `count` strongest spectral peaks of x (Hz), strongest first.

    Amplitude spectrum of the Hann-windowed signal; peaks are local maxima at least 3 bins
    (3 fs / N) apart, so that one line's leakage is not counted twice. The resolution is fs / N.
    """
    amplitude = np.abs(np.fft.rfft((x - x.mean()) * np.hanning(x.size)))
    freq = np.fft.rfftfreq(x.size, 1.0 / fs)
    peaks, _ = signal.find_peaks(amplitude, distance=3)
    strongest = peaks[np.argsort(amplitude[peaks])[::-1][:count]]
    return freq[strongest]


def deterministic(
    ours: xr.Dataset, theirs: xr.Dataset, cutoff: float | None = None, count: int = 3
) -> dict:
    """Per signal: error norms (raw, or of the low band when `cutoff` (Hz) is given) and, with
    a cutoff, RMS and dominant frequencies of the high band in both runs. Both runs must share
    their output times."""
    if not np.allclose(ours.time.values, theirs.time.values, rtol=0.0, atol=1e-12):
        raise ValueError("the two runs do not share their output times")
    fs = 1.0 / float(ours.time[1] - ours.time[0])
    a, b = slider_signals(ours), slider_signals(theirs)
    out = {}
    for name in SIGNALS:
        entry = {"raw": error_norms(b[name], a[name])}
        if cutoff is not None:
            low_a, low_b = lowpass(a[name], fs, cutoff), lowpass(b[name], fs, cutoff)
            high_a, high_b = a[name] - low_a, b[name] - low_b
            entry["low"] = error_norms(low_b, low_a)
            entry["high"] = {
                "rms_ours": float(np.sqrt(np.mean(high_a**2))),
                "rms_exudyn": float(np.sqrt(np.mean(high_b**2))),
                "frequencies_ours": dominant_frequencies(high_a, fs, count).tolist(),
                "frequencies_exudyn": dominant_frequencies(high_b, fs, count).tolist(),
                "resolution": fs / a[name].size,
            }
        out[name] = entry
    return out


def _distribution(x: np.ndarray, y: np.ndarray) -> dict[str, float]:
    """Two samples: means, standard deviations, KS statistic and p-value, and the Wasserstein
    distance over the pooled standard deviation (0: identical distributions)."""
    spread = float(np.std(np.concatenate([x, y])))
    ks = stats.ks_2samp(x, y)
    return {
        "mean_ours": float(np.mean(x)),
        "mean_exudyn": float(np.mean(y)),
        "std_ours": float(np.std(x)),
        "std_exudyn": float(np.std(y)),
        "ks_statistic": float(ks.statistic),
        "ks_pvalue": float(ks.pvalue),
        "wasserstein_over_spread": float(stats.wasserstein_distance(x, y)) / spread
        if spread > 0
        else 0.0,
    }


def revolution_peaks(ds: xr.Dataset, x: np.ndarray, transient: int) -> np.ndarray:
    """max |x| within each whole crank revolution after the first `transient` ones."""
    period = float(ds.attrs["crank_period"])
    rev = np.floor(ds.time.values / period + 1e-9).astype(int)
    last = int(rev[-1])  # the final sample opens a revolution that is not simulated
    return np.array([np.max(np.abs(x[rev == k])) for k in range(transient, last)])


def statistical(ours: xr.Dataset, theirs: xr.Dataset, transient: int = 0) -> dict:
    """Peak and Poincaré statistics that survive chaos (see the module docstring), over the
    revolutions after `transient`."""
    a, b = slider_signals(ours), slider_signals(theirs)
    out = {"peaks": {}, "poincare": {}}
    for name in ("acceleration", "drive_torque"):
        pa = revolution_peaks(ours, a[name], transient)
        pb = revolution_peaks(theirs, b[name], transient)
        entry = _distribution(pa, pb)
        entry["max_ours"] = float(pa.max())
        entry["max_exudyn"] = float(pb.max())
        out["peaks"][name] = entry
    for joint in ours.joint.values:
        for axis in ours.axis.values:
            x = ours.section_eccentricity.sel(joint=joint, axis=axis).values[transient + 1 :]
            y = theirs.section_eccentricity.sel(joint=joint, axis=axis).values[transient + 1 :]
            out["poincare"][f"{joint} {axis}"] = _distribution(x, y)
    return out


def _crossing(t: np.ndarray, x: np.ndarray, i: int) -> float:
    """Time (s) where x crosses 0 between samples i − 1 and i, linearly interpolated."""
    return float(t[i - 1] - x[i - 1] * (t[i] - t[i - 1]) / (x[i] - x[i - 1]))


def _at(t: np.ndarray, x: np.ndarray, time: float) -> float:
    return float(np.interp(time, t, x))


def _vertex(t: np.ndarray, x: np.ndarray, i: int) -> tuple[float, float]:
    """(time, value) of the parabola through samples i − 1, i, i + 1 at its vertex (the peak
    between samples; the sample itself at the ends)."""
    if i == 0 or i == x.size - 1:
        return float(t[i]), float(x[i])
    a, b, c = x[i - 1], x[i], x[i + 1]
    curvature = a - 2.0 * b + c
    shift = 0.5 * (a - c) / curvature if curvature != 0.0 else 0.0
    h = t[i + 1] - t[i]
    return float(t[i] + shift * h), float(b - 0.25 * (a - c) * shift)


def first_impact(ds: xr.Dataset, joint: str) -> dict[str, float]:
    """The first contact of revolute clearance `joint` (clearance c from the run's scene):
    penetration δ = |e| − c and its rate δ̇ = ė·e/|e| from the sampled eccentricity e;
    onset t⁻ and separation t⁺ where δ crosses 0 (linear between samples), the onset rate
    δ̇⁻ and separation rate δ̇⁺ there, the rebound −δ̇⁺/δ̇⁻ (the effective restitution in the
    mechanism), the peak normal force F_max (N) and deepest penetration δ_max (m) (vertices of
    the parabolas through the largest sample and its neighbours) and the time of F_max (s).
    Samples must resolve the contact (tens per contact)."""
    clearance = float(scene_of(ds)["joints"][joint]["clearance"])
    t = ds.time.values
    e = ds.eccentricity.sel(joint=joint).values
    de = ds.eccentricity_rate.sel(joint=joint).values
    length = np.hypot(e[:, 0], e[:, 1])
    delta = length - clearance
    rate = np.divide(np.sum(e * de, axis=1), length, out=np.zeros_like(length), where=length > 0)
    inside = np.flatnonzero(delta > 0.0)
    if inside.size == 0 or inside[0] == 0:
        raise ValueError(f"joint {joint}: no contact onset within the run's samples")
    first = inside[0]
    after = np.flatnonzero(delta[first:] <= 0.0)
    if after.size == 0:
        raise ValueError(f"joint {joint}: the first contact does not end within the run")
    last = first + after[0]
    onset, separation = _crossing(t, delta, first), _crossing(t, delta, last)
    window = slice(first - 1, last + 1)
    force = ds.normal_force.sel(joint=joint).values[window]
    peak_time, peak_force = _vertex(t[window], force, int(np.argmax(force)))
    _, deepest = _vertex(t[window], delta[window], int(np.argmax(delta[window])))
    onset_rate, separation_rate = _at(t, rate, onset), _at(t, rate, separation)
    return {
        "onset_s": onset,
        "separation_s": separation,
        "onset_rate": onset_rate,
        "separation_rate": separation_rate,
        "rebound": -separation_rate / onset_rate,
        "peak_force": peak_force,
        "peak_force_s": peak_time,
        "max_penetration": deepest,
    }


def impact(ours: xr.Dataset, theirs: xr.Dataset, joint: str) -> dict:
    """`first_impact` of `joint` in both runs and their differences: onset, separation and
    peak times (s), relative differences of the onset rate, rebound, peak force and
    deepest penetration (Exudyn's over ours, minus 1)."""
    a, b = first_impact(ours, joint), first_impact(theirs, joint)
    relative = ("onset_rate", "rebound", "peak_force", "max_penetration")
    return {
        "joint": joint,
        "ours": a,
        "exudyn": b,
        "difference": {
            **{k: b[k] - a[k] for k in ("onset_s", "separation_s", "peak_force_s")},
            **{k: b[k] / a[k] - 1.0 for k in relative},
        },
    }


def _hermite_derivatives(xi: np.ndarray, length: float) -> tuple[np.ndarray, np.ndarray]:
    """S' and S'' (1/m, 1/m²) of the four Hermite shape functions at the points ξ, (len(ξ), 4):
    each function is the cubic in ξ through its values (`sim.model.beams.hermite_shape`) at
    four points, differentiated exactly."""
    nodes = np.linspace(0.0, 1.0, 4)
    values = np.array([hermite_shape(x, length) for x in nodes])
    cubics = [
        Polynomial.fit(nodes, values[:, k], 3, domain=[0, 1], window=[0, 1]) for k in range(4)
    ]
    return tuple(
        np.array([c.deriv(order)(xi) for c in cubics]).T / length**order for order in (1, 2)
    )


def exudyn_strain_energy(q: np.ndarray, length: float, ea: float, ei: float) -> float:
    """Strain energy (J) of one planar ANCF link under Exudyn's ANCFCable2D law (Exudyn
    documentation, ObjectANCFCable2D): U = ½ ∫ EA (|r'| − 1)² dx + ½ ∫ EI K² dx with the
    material curvature K = (r' × r'')/|r'|², integrated here with 8 Gauss points per element.
    q holds the link's nodes (r, r') as in sim.model.ancf; elements of length `length` (m)."""
    xi, w = np.polynomial.legendre.leggauss(8)
    xi, w = 0.5 * (xi + 1.0), 0.5 * w
    d1_shape, d2_shape = _hermite_derivatives(xi, length)
    energy = 0.0
    for e in range(q.size // 4 - 1):
        qe = q[4 * e : 4 * e + 8].reshape(4, 2)
        d1, d2 = d1_shape @ qe, d2_shape @ qe
        stretch = np.hypot(d1[:, 0], d1[:, 1])
        curvature = (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / stretch**2
        energy += 0.5 * length * np.sum(w * (ea * (stretch - 1.0) ** 2 + ei * curvature**2))
    return float(energy)


def elastic_law_difference(q: np.ndarray, length: float, ea: float, ei: float) -> dict:
    """Our elastic forces of one link at q against the gradient of `exudyn_strain_energy`
    (central differences): max |ΔF| over max |F| and the relative energy difference."""
    consts = ancf.beam_constants(length, ea, ei)
    ours = np.zeros(q.size)
    ancf.beam_elastic_forces(q, *consts, ours)
    theirs = np.zeros(q.size)
    for i in range(q.size):
        step = 1e-7 * max(1.0, abs(q[i]))
        up, down = q.copy(), q.copy()
        up[i] += step
        down[i] -= step
        theirs[i] = (
            exudyn_strain_energy(up, length, ea, ei) - exudyn_strain_energy(down, length, ea, ei)
        ) / (2 * step)
    u_ours = ancf.beam_strain_energy(q, *consts)
    u_theirs = exudyn_strain_energy(q, length, ea, ei)
    return {
        "force": float(np.max(np.abs(theirs - ours)) / np.max(np.abs(ours))),
        "energy": abs(u_theirs - u_ours) / u_ours if u_ours > 0 else 0.0,
    }

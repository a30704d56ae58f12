"""Agreement between an aligned recording and simulation: errors, ratios and spectra.

Every scalar metric is computed per whole crank revolution and reported as mean ± standard
deviation over the revolutions, the spread being the uncertainty of the comparison. Both
signals lose their mean over the analysed revolutions first: the sensor's offset error is
unknown, and the slider's true mean acceleration over whole revolutions of a periodic motion
is zero.

Spectra are Welch power spectral densities (Welch 1967, IEEE Trans. Audio Electroacoustics
15(2), 70-73) with a Hann window one revolution long and half overlap, so the crank harmonics
fall on frequency bins.
"""

import itertools
import json
from dataclasses import dataclass

import numpy as np
import xarray as xr
from scipy.signal import find_peaks, periodogram, welch

from sim import __version__
from sim.experiment.alignment import Alignment

METRIC_UNITS = {
    "rms_error": "m s-2",
    "correlation": "1",
    "peak_to_peak_ratio": "1",
    "peak_ratio": "1",
    "dominant_frequency_measured": "Hz",
    "dominant_frequency_simulated": "Hz",
}
_METRIC_NAMES = {
    "rms_error": "RMS of measured minus simulated acceleration",
    "correlation": "Pearson correlation of measured and simulated acceleration",
    "peak_to_peak_ratio": "peak-to-peak acceleration, measured over simulated",
    "peak_ratio": "largest absolute acceleration, measured over simulated",
    "dominant_frequency_measured": "strongest non-zero frequency of the measured acceleration",
    "dominant_frequency_simulated": "strongest non-zero frequency of the simulated acceleration",
}
SYNTHETIC_NOTE = (
    "synthetic recording: a consistency check of the pipeline, not evidence that the model "
    "matches a real rig"
)


@dataclass(frozen=True)
class Comparison:
    """Metrics of one aligned recording against the simulation.

    ``per_revolution`` maps each name of ``METRIC_UNITS`` to one value per whole revolution
    (the dominant frequencies come from one-revolution periodograms, so their resolution is
    the crank frequency);
    ``frequency_hz`` and the two PSDs ((m/s^2)^2/Hz) are Welch spectra of the analysed span;
    ``spectral_distance_db`` is the RMS over the sensor band (crank frequency up to the
    bandwidth) of the ratio of the two PSDs in dB; ``peaks_*_hz`` the strongest spectral peaks,
    strongest first (NaN where fewer were found).
    """

    alignment: Alignment
    crank_period_s: float
    synthetic: bool
    time: np.ndarray
    measured: np.ndarray
    simulated: np.ndarray
    per_revolution: dict[str, np.ndarray]
    frequency_hz: np.ndarray
    psd_measured: np.ndarray
    psd_simulated: np.ndarray
    spectral_distance_db: float
    peaks_measured_hz: np.ndarray
    peaks_simulated_hz: np.ndarray

    @property
    def data_kind(self) -> str:
        """'synthetic recording' or 'measured recording', for every label that shows it."""
        return "synthetic recording" if self.synthetic else "measured recording"

    def summary(self) -> dict:
        """JSON-ready summary: data kind, alignment, mean ± std of each metric, spectra."""
        return {
            "data_kind": self.data_kind,
            "note": SYNTHETIC_NOTE if self.synthetic else "measured on a test rig",
            "alignment": {
                "method": self.alignment.method,
                "shift_s": self.alignment.shift_s,
                "sampling_rate_hz": self.alignment.sampling_rate_hz,
                "bandwidth_hz": self.alignment.bandwidth_hz,
            },
            "crank_period_s": self.crank_period_s,
            "revolutions": int(self.per_revolution["rms_error"].size),
            "metrics": {
                name: {
                    "mean": float(np.mean(values)),
                    "std": float(np.std(values, ddof=1)),
                    "unit": METRIC_UNITS[name],
                }
                for name, values in self.per_revolution.items()
            },
            "spectral_distance_db": self.spectral_distance_db,
            "spectral_peaks_hz": {
                "measured": _finite_list(self.peaks_measured_hz),
                "simulated": _finite_list(self.peaks_simulated_hz),
            },
        }

    def to_dataset(self) -> xr.Dataset:
        """CF-annotated dataset of the aligned signals, per-revolution metrics and spectra."""
        revolutions = np.arange(self.per_revolution["rms_error"].size)
        data_vars = {
            "measured": ("time", self.measured, _attrs("measured acceleration, offset removed")),
            "simulated": ("time", self.simulated, _attrs("simulated acceleration, same filter")),
            "residual": (
                "time",
                self.measured - self.simulated,
                _attrs("measured minus simulated acceleration"),
            ),
            "psd_measured": (
                "frequency",
                self.psd_measured,
                _attrs("Welch PSD of measured acceleration", "m2 s-4 Hz-1"),
            ),
            "psd_simulated": (
                "frequency",
                self.psd_simulated,
                _attrs("Welch PSD of simulated acceleration", "m2 s-4 Hz-1"),
            ),
            "peaks_measured": (
                "rank",
                self.peaks_measured_hz,
                _attrs("strongest spectral peaks, measured", "Hz"),
            ),
            "peaks_simulated": (
                "rank",
                self.peaks_simulated_hz,
                _attrs("strongest spectral peaks, simulated", "Hz"),
            ),
        }
        for name, values in self.per_revolution.items():
            data_vars[name] = (
                "revolution",
                values,
                _attrs(_METRIC_NAMES[name] + ", per revolution", METRIC_UNITS[name]),
            )
        return xr.Dataset(
            data_vars,
            coords={
                "time": ("time", self.time, {"long_name": "recorder time", "units": "s"}),
                "revolution": ("revolution", revolutions, {"long_name": "revolution index"}),
                "frequency": (
                    "frequency",
                    self.frequency_hz,
                    {"long_name": "frequency", "units": "Hz"},
                ),
                "rank": ("rank", np.arange(self.peaks_measured_hz.size) + 1),
            },
            attrs={
                "Conventions": "CF-1.8",
                "title": f"slider acceleration: simulation against {self.data_kind}",
                "source": f"sim {__version__}, sim.experiment.metrics.compare",
                "data_kind": self.data_kind,
                "synthetic": int(self.synthetic),
                "crank_period_s": self.crank_period_s,
                "shift_s": self.alignment.shift_s,
                "alignment_method": self.alignment.method,
                "bandwidth_hz": self.alignment.bandwidth_hz,
                "spectral_distance_db": self.spectral_distance_db,
                "summary": json.dumps(self.summary()),
            },
        )


def compare(
    alignment: Alignment, *, crank_period_s: float, synthetic: bool, n_peaks: int = 3
) -> Comparison:
    """Per-revolution metrics and Welch spectra of an aligned recording and simulation.

    Uses the whole crank revolutions (period ``crank_period_s`` in s) from the first aligned
    sample; needs at least two of them for a standard deviation.
    """
    rate = alignment.sampling_rate_hz
    start = alignment.time[0]
    count = int(np.floor((alignment.time[-1] - start + 1.0 / rate) / crank_period_s))
    if count < 2:
        raise ValueError(
            f"the aligned span holds {count} whole revolution(s) of {crank_period_s:g} s; "
            "at least two are needed for an uncertainty"
        )
    bounds = np.searchsorted(alignment.time, start + crank_period_s * np.arange(count + 1))
    span = slice(0, bounds[-1])
    measured = alignment.measured[span] - np.mean(alignment.measured[span])
    simulated = alignment.simulated[span] - np.mean(alignment.simulated[span])
    revolutions = [slice(a, b) for a, b in itertools.pairwise(bounds)]
    per_revolution = {
        name: np.array([metric(measured[r], simulated[r], rate) for r in revolutions])
        for name, metric in _PER_REVOLUTION.items()
    }
    segment = round(crank_period_s * rate)
    frequency, psd_measured = welch(measured, fs=rate, nperseg=segment)
    _, psd_simulated = welch(simulated, fs=rate, nperseg=segment)
    band = (frequency >= 1.0 / crank_period_s) & (frequency <= alignment.bandwidth_hz)
    ratio_db = 10.0 * np.log10(psd_measured[band] / psd_simulated[band])
    return Comparison(
        alignment=alignment,
        crank_period_s=float(crank_period_s),
        synthetic=bool(synthetic),
        time=alignment.time[span],
        measured=measured,
        simulated=simulated,
        per_revolution=per_revolution,
        frequency_hz=frequency,
        psd_measured=psd_measured,
        psd_simulated=psd_simulated,
        spectral_distance_db=float(np.sqrt(np.mean(ratio_db**2))),
        peaks_measured_hz=_strongest_peaks(frequency, psd_measured, band, n_peaks),
        peaks_simulated_hz=_strongest_peaks(frequency, psd_simulated, band, n_peaks),
    )


def _rms_error(measured: np.ndarray, simulated: np.ndarray, rate: float) -> float:
    return float(np.sqrt(np.mean((measured - simulated) ** 2)))


def _correlation(measured: np.ndarray, simulated: np.ndarray, rate: float) -> float:
    return float(np.corrcoef(measured, simulated)[0, 1])


def _peak_to_peak_ratio(measured: np.ndarray, simulated: np.ndarray, rate: float) -> float:
    return float(np.ptp(measured) / np.ptp(simulated))


def _peak_ratio(measured: np.ndarray, simulated: np.ndarray, rate: float) -> float:
    return float(np.max(np.abs(measured)) / np.max(np.abs(simulated)))


def _dominant_frequency(signal: np.ndarray, rate: float) -> float:
    # One revolution long, so the resolution is the crank frequency.
    frequency, power = periodogram(signal, fs=rate, window="hann")
    return float(frequency[1:][np.argmax(power[1:])])


_PER_REVOLUTION = {
    "rms_error": _rms_error,
    "correlation": _correlation,
    "peak_to_peak_ratio": _peak_to_peak_ratio,
    "peak_ratio": _peak_ratio,
    "dominant_frequency_measured": lambda m, s, rate: _dominant_frequency(m, rate),
    "dominant_frequency_simulated": lambda m, s, rate: _dominant_frequency(s, rate),
}


def _strongest_peaks(
    frequency: np.ndarray, psd: np.ndarray, band: np.ndarray, count: int
) -> np.ndarray:
    """Frequencies (Hz) of the ``count`` highest local maxima of a PSD within ``band``."""
    indices, _ = find_peaks(np.where(band, psd, 0.0))
    strongest = indices[np.argsort(psd[indices])[::-1][:count]]
    peaks = np.full(count, np.nan)
    peaks[: strongest.size] = frequency[strongest]
    return peaks


def _finite_list(values: np.ndarray) -> list[float]:
    return [float(v) for v in values if np.isfinite(v)]


def _attrs(long_name: str, units: str = "m s-2") -> dict[str, str]:
    return {"long_name": long_name, "units": units}

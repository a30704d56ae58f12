"""Figures of the experiment comparison, drawn from the dataset of
:meth:`sim.experiment.metrics.Comparison.to_dataset`.

Figures are built on ``matplotlib.figure.Figure`` directly (no pyplot state), which renders
with the Agg backend whatever backend the session has. A synthetic recording is labelled as
such in every title.
"""

import numpy as np
import xarray as xr
from matplotlib.figure import Figure


def plot_overlay(comparison: xr.Dataset, *, revolutions: int = 3) -> Figure:
    """Measured and simulated slider acceleration over the first ``revolutions`` crank
    revolutions (top) and their residual (bottom), in m/s^2 against recorder time in s."""
    period = float(comparison.attrs["crank_period_s"])
    window = comparison.sel(time=slice(None, float(comparison.time[0]) + revolutions * period))
    figure = Figure(figsize=(8.0, 5.5), layout="constrained")
    top, bottom = figure.subplots(2, 1, sharex=True, height_ratios=(2, 1))
    top.plot(window.time, window.measured, lw=0.8, label=str(comparison.attrs["data_kind"]))
    top.plot(window.time, window.simulated, lw=0.8, label="simulated (sensor filter applied)")
    top.set_ylabel("slider acceleration [m/s²]")
    top.legend(loc="upper right", fontsize="small")
    bottom.plot(window.time, window.residual, lw=0.8, color="0.3")
    bottom.set_ylabel("residual [m/s²]")
    bottom.set_xlabel("recorder time [s]")
    summary = comparison.attrs
    figure.suptitle(
        f"Slider acceleration: simulation against {summary['data_kind']}\n"
        f"shift {float(summary['shift_s']) * 1e3:.2f} ms by {summary['alignment_method']}\n"
        f"RMS error {float(comparison.rms_error.mean()):.3g} ± "
        f"{float(comparison.rms_error.std(ddof=1)):.2g} m/s², correlation "
        f"{float(comparison.correlation.mean()):.3f} ± "
        f"{float(comparison.correlation.std(ddof=1)):.2g} "
        f"({comparison.sizes['revolution']} revolutions)",
        fontsize="medium",
    )
    return figure


def plot_spectra(comparison: xr.Dataset) -> Figure:
    """Welch power spectral densities ((m/s²)²/Hz, log scale) of measured and simulated
    acceleration against frequency in Hz, up to the sensor bandwidth."""
    band = comparison.sel(frequency=slice(0.0, float(comparison.attrs["bandwidth_hz"])))
    figure = Figure(figsize=(8.0, 4.0), layout="constrained")
    axes = figure.subplots()
    axes.semilogy(
        band.frequency, band.psd_measured, lw=0.8, label=str(comparison.attrs["data_kind"])
    )
    axes.semilogy(band.frequency, band.psd_simulated, lw=0.8, label="simulated")
    for peak in comparison.peaks_measured.values[np.isfinite(comparison.peaks_measured.values)]:
        axes.axvline(peak, color="0.7", lw=0.5, zorder=0)
    axes.set_xlabel("frequency [Hz]")
    axes.set_ylabel("PSD of slider acceleration [(m/s²)²/Hz]")
    axes.legend(loc="upper right", fontsize="small")
    axes.set_title(
        f"Spectra: simulation against {comparison.attrs['data_kind']}\n"
        f"Welch, one revolution per segment; spectral distance "
        f"{float(comparison.attrs['spectral_distance_db']):.2f} dB",
        fontsize="medium",
    )
    return figure

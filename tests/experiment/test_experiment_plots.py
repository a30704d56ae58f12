"""The comparison figures label their axes and say when the recording is synthetic."""

import numpy as np

from sim.experiment import align_signals, compare
from sim.plots.experiment import plot_overlay, plot_spectra


def _comparison(synthetic: bool):
    time = np.arange(0.0, 3.0, 1e-3)
    measured = np.sin(2.0 * np.pi * time) + 0.1 * np.sin(2.0 * np.pi * 40.0 * time)
    simulated = np.sin(2.0 * np.pi * time)
    alignment = align_signals(
        time, measured, time, simulated, shift_s=0.0, method="given", bandwidth_hz=100.0
    )
    return compare(alignment, crank_period_s=1.0, synthetic=synthetic).to_dataset()


def _texts(figure) -> str:
    return " ".join(t.get_text() for t in figure.findobj(lambda a: hasattr(a, "get_text")))


def test_synthetic_recording_is_named_in_every_figure() -> None:
    for plot in (plot_overlay, plot_spectra):
        assert "synthetic recording" in _texts(plot(_comparison(synthetic=True)))
        assert "synthetic" not in _texts(plot(_comparison(synthetic=False)))


def test_axes_carry_quantity_and_unit() -> None:
    overlay = plot_overlay(_comparison(synthetic=True))
    labels = [axes.get_ylabel() for axes in overlay.axes] + [overlay.axes[-1].get_xlabel()]
    assert labels == ["slider acceleration [m/s²]", "residual [m/s²]", "recorder time [s]"]
    spectra = plot_spectra(_comparison(synthetic=True)).axes[0]
    assert spectra.get_xlabel() == "frequency [Hz]"
    assert "[(m/s²)²/Hz]" in spectra.get_ylabel()

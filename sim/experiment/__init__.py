"""Accelerometer recordings of the slider, and their comparison with the simulation.

Modules, one job each:

- :mod:`~sim.experiment.recording`: the recording format (CSV + ``.meta.yaml``), its checks,
  the loader and the atomic writer;
- :mod:`~sim.experiment.sampling`: the sensor's anti-alias filter and resampling, shared by the
  sensor model and the alignment;
- :mod:`~sim.experiment.sensor`: the sensor model that turns a simulated acceleration into a
  recording (filter, sampling rate, gain, offset, noise, time shift);
- :mod:`~sim.experiment.synthesize`: a synthetic recording with its full metadata;
- :mod:`~sim.experiment.alignment`: time-shift estimation and resampling of the simulation onto
  the recording's times;
- :mod:`~sim.experiment.metrics`: error metrics and spectra, per crank revolution.

The ``sim experiment`` subcommand is :mod:`sim.cli.experiment`.

The names below are loaded from their modules on first use (PEP 562), so that importing one
module of the package (the command line reads `metadata`) does not import scipy.signal with
the alignment and the sensor: a third of a second of every `sim` start.
"""

import importlib

#: each exported name → the module of the package that defines it
_SOURCES = {
    "Alignment": "alignment",
    "align_signals": "alignment",
    "align_simulation": "alignment",
    "estimate_shift": "alignment",
    "estimate_shift_from_crank_angle": "alignment",
    "estimate_shift_from_trigger": "alignment",
    "Comparison": "metrics",
    "compare": "metrics",
    "Recording": "recording",
    "RecordingError": "recording",
    "load_recording": "recording",
    "metadata_path": "recording",
    "validate_recording": "recording",
    "write_recording": "recording",
    "SensorDraws": "sensor",
    "SensorOutput": "sensor",
    "SensorSettings": "sensor",
    "apply_sensor": "sensor",
    "synthesize_recording": "synthesize",
}

__all__ = sorted(_SOURCES)


def __getattr__(name: str) -> object:
    """An exported name, imported from its module at first use."""
    if name not in _SOURCES:
        raise AttributeError(f"module 'sim.experiment' has no attribute '{name}'")
    return getattr(importlib.import_module(f"sim.experiment.{_SOURCES[name]}"), name)

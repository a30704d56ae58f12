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
"""

from sim.experiment.alignment import (
    Alignment,
    align_signals,
    align_simulation,
    estimate_shift,
    estimate_shift_from_crank_angle,
    estimate_shift_from_trigger,
)
from sim.experiment.metrics import Comparison, compare
from sim.experiment.recording import (
    Recording,
    RecordingError,
    load_recording,
    metadata_path,
    validate_recording,
    write_recording,
)
from sim.experiment.sensor import SensorDraws, SensorOutput, SensorSettings, apply_sensor
from sim.experiment.synthesize import synthesize_recording

__all__ = [
    "Alignment",
    "Comparison",
    "Recording",
    "RecordingError",
    "SensorDraws",
    "SensorOutput",
    "SensorSettings",
    "align_signals",
    "align_simulation",
    "apply_sensor",
    "compare",
    "estimate_shift",
    "estimate_shift_from_crank_angle",
    "estimate_shift_from_trigger",
    "load_recording",
    "metadata_path",
    "synthesize_recording",
    "validate_recording",
    "write_recording",
]

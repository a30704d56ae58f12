"""The ``sim experiment`` subcommand: ``synthesize`` a recording, ``compare`` one with a run.

The simulator (``sim.scene``, ``sim.run``) is imported inside the handler, so this module
loads, and ``compare`` works, without it.
"""

import argparse
import json
import sys
from pathlib import Path

import numpy as np
import xarray as xr

from sim import __version__
from sim.cli import add_scene_arguments
from sim.experiment.alignment import align_simulation
from sim.experiment.errors import RecordingError
from sim.experiment.metrics import compare
from sim.experiment.recording import load_recording, write_atomically, write_recording
from sim.experiment.sensor import SensorSettings, load_sensor_settings
from sim.experiment.synthesize import synthesize_recording

DEFAULT_SEED = 20240607
# Outputs of `compare`, fixed names inside --out-dir so a workflow can declare them.
COMPARISON_NETCDF = "comparison.nc"
COMPARISON_JSON = "comparison.json"
OVERLAY_FIGURE = "overlay.png"
SPECTRA_FIGURE = "spectra.png"


def register(subparsers: argparse._SubParsersAction) -> None:
    """Add ``experiment`` with its actions ``synthesize`` and ``compare`` to a CLI."""
    parser = subparsers.add_parser(
        "experiment", help="accelerometer recordings: synthesize one, compare with a run"
    )
    actions = parser.add_subparsers(dest="experiment_action", required=True)

    synthesize = actions.add_parser(
        "synthesize",
        help="simulate a scene and record its slider acceleration with the sensor model",
    )
    add_scene_arguments(synthesize)
    synthesize.add_argument(
        "--sensor", type=Path, help="YAML file of sensor settings (default: built-in values)"
    )
    synthesize.add_argument("--seed", type=int, default=DEFAULT_SEED, help="random seed")
    synthesize.add_argument(
        "-o", "--output", type=Path, required=True, help="recording CSV to write"
    )
    synthesize.set_defaults(func=run_synthesize)

    compare_parser = actions.add_parser(
        "compare", help="align a recording with a simulation and report metrics and figures"
    )
    compare_parser.add_argument("recording", type=Path, help="recording CSV (with .meta.yaml)")
    compare_parser.add_argument("simulation", type=Path, help="simulation output (.nc)")
    compare_parser.add_argument(
        "--crank-rpm", type=float, required=True, help="crank speed of the run in rpm"
    )
    compare_parser.add_argument(
        "--crank-angle-at-zero",
        type=float,
        default=0.0,
        help="simulated crank angle at t = 0 in rad (for trigger or crank-angle channels)",
    )
    compare_parser.add_argument(
        "--max-shift",
        type=float,
        help="largest time shift searched by cross-correlation in s (default half a period)",
    )
    compare_parser.add_argument(
        "--out-dir", type=Path, required=True, help="directory for metrics and figures"
    )
    compare_parser.set_defaults(func=run_compare)


def run_synthesize(args: argparse.Namespace) -> int:
    """Handler of ``sim experiment synthesize``; returns the exit code."""
    from sim.run import simulate
    from sim.scene import load_scene

    scene = load_scene(args.scene, args.overrides)
    dataset = simulate(scene)
    sensor = SensorSettings() if args.sensor is None else load_sensor_settings(args.sensor)
    provenance = {
        "scene": args.scene,
        "overrides": list(args.overrides),
        "sim_version": __version__,
        # Through JSON so the metadata holds plain YAML values whatever types the scene uses.
        "resolved_scene": json.loads(json.dumps(scene, default=str)),
        "signal": 'acceleration.sel(body="slider", axis="y")',
    }
    frame, metadata = synthesize_recording(
        dataset.time.values,
        dataset.acceleration.sel(body="slider", axis="y").values,
        sensor=sensor,
        seed=args.seed,
        provenance=provenance,
    )
    try:
        write_recording(args.output, frame, metadata)
    except RecordingError as exc:
        print(f"sim experiment synthesize: {exc}", file=sys.stderr)
        return 1
    print(f"wrote synthetic recording {args.output} ({len(frame)} samples, seed {args.seed})")
    return 0


def run_compare(args: argparse.Namespace) -> int:
    """Handler of ``sim experiment compare``; returns the exit code."""
    from sim.plots.experiment import plot_overlay, plot_spectra

    try:
        recording = load_recording(args.recording)
    except RecordingError as exc:
        print(f"sim experiment compare: {exc}", file=sys.stderr)
        return 1
    period = 60.0 / args.crank_rpm
    with xr.open_dataset(args.simulation) as simulation:
        time = np.asarray(simulation.time.values, dtype=float)
        acceleration = simulation.acceleration.sel(body="slider", axis="y").values
    alignment = align_simulation(
        recording,
        time,
        acceleration,
        crank_period_s=period,
        crank_angle_at_zero_rad=args.crank_angle_at_zero,
        max_shift_s=args.max_shift,
    )
    comparison = compare(alignment, crank_period_s=period, synthetic=recording.synthetic)
    dataset = comparison.to_dataset()
    dataset.attrs["recording"] = str(args.recording)
    dataset.attrs["simulation"] = str(args.simulation)
    summary = comparison.summary() | {
        "recording": str(args.recording),
        "simulation": str(args.simulation),
    }
    if recording.synthetic:
        # the truth the alignment should recover, drawn by the sensor model
        injected = float(recording.metadata["synthesis"]["sensor_draws"]["time_shift_s"])
        summary["alignment"]["injected_shift_s"] = injected
    args.out_dir.mkdir(parents=True, exist_ok=True)
    outputs = {
        COMPARISON_NETCDF: dataset.to_netcdf,
        COMPARISON_JSON: lambda path: path.write_text(json.dumps(summary, indent=2) + "\n"),
        OVERLAY_FIGURE: lambda path: plot_overlay(dataset).savefig(path, dpi=150, format="png"),
        SPECTRA_FIGURE: lambda path: plot_spectra(dataset).savefig(path, dpi=150, format="png"),
    }
    for name, write in outputs.items():
        write_atomically(args.out_dir / name, write)
    print(format_summary(summary))
    print(f"metrics and figures in {args.out_dir}")
    return 0


def format_summary(summary: dict) -> str:
    """The comparison summary (of ``Comparison.summary``) as a few lines of text."""
    alignment = summary["alignment"]
    rate = alignment["sampling_rate_hz"]
    shift = f"shift {alignment['shift_s'] * 1e3:.4g} ms by {alignment['method']}"
    if "injected_shift_s" in alignment:
        error = (alignment["shift_s"] - alignment["injected_shift_s"]) * rate
        shift += f" (injected {alignment['injected_shift_s'] * 1e3:.4g} ms: {error:+.2f} samples)"
    lines = [
        f"{summary['data_kind']} ({summary['note']})",
        f"  {shift}; {summary['revolutions']} revolutions at {rate:g} Hz, "
        f"band {alignment['bandwidth_hz']:g} Hz",
    ]
    for name, metric in summary["metrics"].items():
        lines.append(f"  {name:30s} {metric['mean']:10.4g} ± {metric['std']:.2g} {metric['unit']}")
    peaks = summary["spectral_peaks_hz"]
    lines.append(f"  spectral distance {summary['spectral_distance_db']:.3g} dB")
    for kind in ("measured", "simulated"):
        shown = ", ".join(f"{f:.4g}" for f in peaks[kind][:5])
        lines.append(f"  spectral peaks, {kind:9s} [Hz]: {shown}")
    return "\n".join(lines)

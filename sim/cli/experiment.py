"""The ``sim experiment`` subcommand: ``synthesize`` a recording, ``compare`` one with a run.

The simulator (``sim.run``) is imported inside the handler, so this module loads, and
``compare`` works, without it. Bad input (options, files) raises ValueError before any
computation; ``sim.cli.main`` reports it with exit code 2.
"""

import argparse
import json
import math
from pathlib import Path

import numpy as np
import xarray as xr

from sim import __version__
from sim.atomic import write_atomically
from sim.cli.arguments import add_scene_arguments, check_output
from sim.experiment.metadata import CHANNEL_AXES, DEFAULT_CHANNEL
from sim.experiment.recording import (
    Recording,
    load_recording,
    metadata_path,
    write_recording,
)
from sim.provenance import library_versions_json
from sim.quantities import POINT
from sim.scene_keys import DRIVE, Field, check_option

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
        help="simulate a scene and record one body's acceleration with the sensor model",
    )
    add_scene_arguments(synthesize)
    synthesize.add_argument(
        "--body",
        default=DEFAULT_CHANNEL["body"],
        help="body whose reference-point acceleration is recorded (default: %(default)s)",
    )
    synthesize.add_argument(
        "--axis",
        choices=CHANNEL_AXES,
        default=DEFAULT_CHANNEL["axis"],
        help="global axis of the recorded acceleration (default: %(default)s)",
    )
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
    from sim.experiment.sensor import SensorSettings, load_sensor_settings
    from sim.experiment.synthesize import synthesize_recording
    from sim.run import simulate
    from sim.scene import load_scene

    check_option("--seed", args.seed, Field("int", 0))
    check_output("--output", args.output)
    scene = load_scene(args.scene, args.overrides)
    if args.body not in scene["bodies"]:
        raise ValueError(
            f"--body '{args.body}' is not a body of scene '{scene['name']}'; accepted: "
            + ", ".join(scene["bodies"])
        )
    sensor = SensorSettings() if args.sensor is None else load_sensor_settings(args.sensor)
    # the sensor's anti-alias filter needs its cut-off below the simulated output's Nyquist
    per_revolution = scene["simulation"]["output_per_revolution"]
    output_rate_hz = per_revolution * scene["drive"]["speed_rpm"] / 60.0
    if not sensor.bandwidth_hz < output_rate_hz / 2.0:
        needed = math.floor(per_revolution * 2.0 * sensor.bandwidth_hz / output_rate_hz) + 1
        raise ValueError(
            f"the scene's output rate, simulation.output_per_revolution = {per_revolution} per "
            f"revolution at {scene['drive']['speed_rpm']:g} rpm, is {output_rate_hz:g} Hz: too "
            f"coarse for the sensor's bandwidth_hz {sensor.bandwidth_hz:g} Hz (it must exceed "
            f"twice that); set simulation.output_per_revolution to at least {needed}"
        )
    if scene["simulation"]["sampling"] != "mean":
        raise ValueError(
            f"simulation.sampling = '{scene['simulation']['sampling']}': the sensor model filters "
            "samples, which must be free of aliasing (interval means); point samples fold the "
            "ringing above the output rate into the sensor's band. Leave simulation.sampling "
            "at its default, mean"
        )
    dataset = simulate(scene)
    channel = DEFAULT_CHANNEL | {"body": args.body, "axis": args.axis}
    provenance = {
        "scene": args.scene,
        "overrides": list(args.overrides),
        "sim_version": __version__,
        # Through JSON so the metadata holds plain YAML values whatever types the scene uses.
        "resolved_scene": json.loads(json.dumps(scene, default=str)),
        "signal": f'acceleration.sel(body="{args.body}", axis="{args.axis}")',
    }
    frame, metadata = synthesize_recording(
        dataset.time.values,
        dataset.acceleration.sel(body=args.body, axis=args.axis).values,
        sensor=sensor,
        seed=args.seed,
        provenance=provenance,
        channel=channel,
    )
    write_recording(args.output, frame, metadata)
    print(f"wrote synthetic recording {args.output} ({len(frame)} samples, seed {args.seed})")
    return 0


def simulated_channel(
    run: xr.Dataset, recording: Recording, run_path: Path
) -> tuple[np.ndarray, np.ndarray]:
    """Time (s) and acceleration (m/s^2) of the channel the recording measures, from a run;
    ValueError naming the channel and the bodies the run has when it has no such body."""
    channel = recording.channel
    if "acceleration" not in run or run.acceleration.dims != ("time", "body", "axis"):
        raise ValueError(
            f"run file '{run_path}' holds no 'acceleration' (time, body, axis): give a file "
            "written by `sim run`"
        )
    bodies = [str(body) for body in run.body.values]
    if channel["body"] not in bodies:
        named = "" if "channel" in recording.metadata else " (the default: no 'channel' key)"
        raise ValueError(
            f"{metadata_path(recording.source)}: the recording measures the acceleration of "
            f"body '{channel['body']}', point '{channel['point']}', axis '{channel['axis']}'"
            f"{named}, but run file '{run_path}' has no body '{channel['body']}'; its bodies: "
            f"{', '.join(bodies)}. Set channel.body in the metadata to the body the sensor is on"
        )
    if run.acceleration.attrs.get("sampling") == POINT:
        raise ValueError(
            f"run file '{run_path}' records the acceleration as point samples "
            "(simulation.sampling: point), which fold the ringing above the output rate into "
            "the sensor's band; compare a run with simulation.sampling mean (the default)"
        )
    acceleration = run.acceleration.sel(body=channel["body"], axis=channel["axis"])
    return np.asarray(run.time.values, dtype=float), acceleration.values


def run_compare(args: argparse.Namespace) -> int:
    """Handler of ``sim experiment compare``; returns the exit code."""
    from sim.experiment.alignment import align_simulation
    from sim.experiment.metrics import compare
    from sim.plots.experiment import plot_overlay, plot_spectra
    from sim.results import open_run

    check_option("--crank-rpm", args.crank_rpm, DRIVE["speed_rpm"])
    check_option("--crank-angle-at-zero", args.crank_angle_at_zero, Field("number", unit="rad"))
    period = 60.0 / args.crank_rpm
    if args.max_shift is not None:
        # cross-correlation repeats every period: a shift is unambiguous within half of one
        check_option(
            "--max-shift", args.max_shift, Field("number", 0.0, period / 2, open_min=True, unit="s")
        )
    check_output("--out-dir", args.out_dir, directory=True)
    recording = load_recording(args.recording)
    time, acceleration = simulated_channel(open_run(args.simulation), recording, args.simulation)
    try:
        alignment = align_simulation(
            recording,
            time,
            acceleration,
            crank_period_s=period,
            crank_angle_at_zero_rad=args.crank_angle_at_zero,
            max_shift_s=args.max_shift,
        )
        comparison = compare(alignment, crank_period_s=period, synthetic=recording.synthetic)
    except ValueError as exc:  # the two files do not fit together: say which they are
        raise ValueError(f"{args.recording} against run file '{args.simulation}': {exc}") from None
    dataset = comparison.to_dataset()
    dataset.attrs["recording"] = str(args.recording)
    dataset.attrs["simulation"] = str(args.simulation)
    dataset.attrs["channel"] = json.dumps(recording.channel)
    summary = comparison.summary() | {
        "recording": str(args.recording),
        "simulation": str(args.simulation),
        "channel": recording.channel,
    }
    if recording.synthetic:
        # the truth the alignment should recover, drawn by the sensor model
        injected = float(recording.metadata["synthesis"]["sensor_draws"]["time_shift_s"])
        summary["alignment"]["injected_shift_s"] = injected
    args.out_dir.mkdir(parents=True, exist_ok=True)
    outputs = {
        COMPARISON_NETCDF: dataset.assign_attrs(library_versions=library_versions_json()).to_netcdf,
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

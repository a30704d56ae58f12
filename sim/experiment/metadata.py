"""The metadata file beside a recording (``<stem>.meta.yaml``): parsing and schema checks.

Every key is known (a misspelt key is an error, not silently ignored), every key appears once,
every value has a type, and errors point at the line of the offending key in the YAML file.

The optional ``channel`` says which simulated signal the recording measures: the acceleration
of a body's reference point (``point: centre``: a rigid body's centre, a beam's mid-span; the
only point a run records) along a global axis (``x`` or ``y``). Without it the recording
measures ``DEFAULT_CHANNEL``, the vertical acceleration of the body ``slider``, as every
recording before the key existed does.
"""

from collections.abc import Mapping
from numbers import Real
from typing import Any

import yaml

from sim.experiment.errors import RecordingError
from sim.yaml_keys import DuplicateKeyError, KeyPath, dotted, key_lines

FORMAT_VERSION = 1
DEFAULT_FILTER_ORDER = 4
DEFAULT_CHANNEL = {"body": "slider", "point": "centre", "axis": "y"}
CHANNEL_POINTS = ("centre",)
CHANNEL_AXES = ("x", "y")

# key -> (type, required). ``bool`` is a subclass of ``int`` in Python, so booleans are
# rejected explicitly where a number is expected (see _has_type).
_TOP_LEVEL = {
    "format_version": (int, True),
    "description": (str, True),
    "synthetic": (bool, True),
    "sampling_rate_hz": (Real, True),
    "units": (Mapping, True),
    "sensor": (Mapping, True),
    "trigger_angle_rad": (Real, False),
    "channel": (Mapping, False),
    "synthesis": (Mapping, False),
}
_CHANNEL = {
    "body": (str, True),
    "point": (str, False),
    "axis": (str, True),
}
_SENSOR = {
    "axis": (str, True),
    "bandwidth_hz": (Real, True),
    "range": (Real, True),
    "filter_order": (int, False),
}
_SYNTHESIS = {
    "seed": (int, True),
    "sensor_settings": (Mapping, True),
    "sensor_draws": (Mapping, True),
    "provenance": (Mapping, True),
}

KeyLines = dict[KeyPath, int]


def parse_metadata(text: str, source: str) -> tuple[dict[str, Any], KeyLines]:
    """Parse and check metadata YAML text.

    Returns the metadata mapping and the 1-based line of every key (by key path), used to
    point later consistency errors at the right line.
    """
    metadata, lines = load_yaml(text, source)
    if not isinstance(metadata, dict):
        raise RecordingError(source, "metadata must be a YAML mapping of keys to values")
    check_metadata(metadata, source, lines)
    return metadata, lines


def load_yaml(text: str, source: str) -> tuple[Any, KeyLines]:
    """YAML text to Python data and the 1-based line of every mapping key (by key path);
    RecordingError naming ``source`` and the line for invalid YAML or a key given twice."""
    loader = yaml.SafeLoader(text)
    try:
        node = loader.get_single_node()
        lines = key_lines(node)
        return (None if node is None else loader.construct_document(node)), lines
    except DuplicateKeyError as exc:
        raise RecordingError(
            source,
            f"key '{dotted(exc.path)}' is given twice (lines {exc.first_line} and "
            f"{exc.second_line}); YAML would keep only the last: remove or rename one",
            exc.second_line,
        ) from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        line = None if mark is None else mark.line + 1
        raise RecordingError(source, f"not valid YAML ({exc})", line) from exc
    finally:
        loader.dispose()


def measured_channel(metadata: Mapping[str, Any]) -> dict[str, str]:
    """The simulated signal a recording measures: ``body``, ``point`` and ``axis`` of its
    ``channel``, ``DEFAULT_CHANNEL`` for what the metadata leaves out."""
    return DEFAULT_CHANNEL | dict(metadata.get("channel", {}))


def check_metadata(metadata: Mapping[str, Any], source: str, lines: KeyLines) -> None:
    """Check keys, types and the values that do not depend on the data (raises RecordingError)."""
    _check_mapping(metadata, _TOP_LEVEL, (), source, lines)
    _check_mapping(metadata["sensor"], _SENSOR, ("sensor",), source, lines)
    if "channel" in metadata:
        _check_channel(metadata["channel"], source, lines)
    if metadata["format_version"] != FORMAT_VERSION:
        raise RecordingError(
            source,
            f"format_version {metadata['format_version']} is not supported "
            f"(this reader knows version {FORMAT_VERSION})",
            lines.get(("format_version",)),
        )
    rate = metadata["sampling_rate_hz"]
    _require_positive(rate, ("sampling_rate_hz",), source, lines)
    sensor = metadata["sensor"]
    _require_positive(sensor["bandwidth_hz"], ("sensor", "bandwidth_hz"), source, lines)
    _require_positive(sensor["range"], ("sensor", "range"), source, lines)
    if sensor["bandwidth_hz"] >= rate / 2:
        raise RecordingError(
            source,
            f"sensor bandwidth_hz {sensor['bandwidth_hz']} Hz is not below the Nyquist "
            f"frequency {rate / 2} Hz of sampling_rate_hz {rate} Hz: the recording would be "
            "aliased, or one of the two values is wrong",
            lines.get(("sensor", "bandwidth_hz")),
        )
    if sensor.get("filter_order", DEFAULT_FILTER_ORDER) < 1:
        raise RecordingError(
            source, "sensor filter_order must be at least 1", lines.get(("sensor", "filter_order"))
        )
    for column, unit in metadata["units"].items():
        if not isinstance(unit, str):
            raise RecordingError(
                source,
                f"unit of column '{column}' must be text, got {unit!r}",
                lines.get(("units", str(column))),
            )
    _check_synthesis(metadata, source, lines)


def _check_channel(channel: Mapping[str, Any], source: str, lines: KeyLines) -> None:
    """Keys and types of ``channel``, its point and axis among those a run records."""
    _check_mapping(channel, _CHANNEL, ("channel",), source, lines)
    for key, accepted in (("point", CHANNEL_POINTS), ("axis", CHANNEL_AXES)):
        if key in channel and channel[key] not in accepted:
            raise RecordingError(
                source,
                f"metadata key 'channel.{key}' = {channel[key]!r} is not accepted; a run "
                f"records {', '.join(map(repr, accepted))} (channel: body, point, axis)",
                lines.get(("channel", key)),
            )


def _check_synthesis(metadata: Mapping[str, Any], source: str, lines: KeyLines) -> None:
    """A synthetic recording must say how it was made; a measured one must not claim to."""
    synthesis = metadata.get("synthesis")
    if metadata["synthetic"] and synthesis is None:
        raise RecordingError(
            source,
            "synthetic: true needs a 'synthesis' block (seed, sensor_settings, sensor_draws, "
            "provenance) recording every setting used",
            lines.get(("synthetic",)),
        )
    if not metadata["synthetic"] and synthesis is not None:
        raise RecordingError(
            source,
            "a 'synthesis' block is present but synthetic is false: say which it is",
            lines.get(("synthesis",)),
        )
    if synthesis is not None:
        _check_mapping(synthesis, _SYNTHESIS, ("synthesis",), source, lines)


def _check_mapping(
    mapping: Mapping[str, Any],
    schema: Mapping[str, tuple[type, bool]],
    where: tuple[str, ...],
    source: str,
    lines: KeyLines,
) -> None:
    """Unknown keys, missing required keys and wrong types, each reported at its line."""
    prefix = ".".join(where) + "." if where else ""
    for key in mapping:
        if key not in schema:
            raise RecordingError(
                source,
                f"unknown metadata key '{prefix}{key}' (known keys: {', '.join(schema)})",
                lines.get((*where, str(key))),
            )
    for key, (kind, required) in schema.items():
        if key not in mapping:
            if required:
                raise RecordingError(
                    source, f"missing metadata key '{prefix}{key}'", lines.get(where)
                )
            continue
        if not _has_type(mapping[key], kind):
            raise RecordingError(
                source,
                f"metadata key '{prefix}{key}' must be {_type_name(kind)}, got {mapping[key]!r}",
                lines.get((*where, key)),
            )


def _has_type(value: Any, kind: type) -> bool:
    if kind is not bool and isinstance(value, bool):
        return False
    return isinstance(value, kind)


def _type_name(kind: type) -> str:
    return {
        int: "an integer",
        str: "text",
        bool: "true or false",
        Real: "a number",
        Mapping: "a mapping",
    }[kind]


def _require_positive(value: float, key: tuple[str, ...], source: str, lines: KeyLines) -> None:
    if not value > 0:
        raise RecordingError(
            source, f"metadata key '{'.'.join(key)}' must be positive, got {value}", lines.get(key)
        )

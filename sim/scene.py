"""Scenes: load, override, validate.

A scene is a YAML mapping that describes one planar linkage and how to
simulate it (see `sim/scenes/sixbar.yaml`). It is loaded by built-in name
(`sixbar`, `fourbar`, `slider-crank`) or by path. A file may start from a built-in scene
with `base: <name>` and list only what it changes. `--set dotted.key=value`
overrides any key; values are parsed as YAML scalars.

What each key accepts, and its default, is declared in `sim.scene_keys`; loading fills the
defaults in, so the resolved scene has every key. Validation runs before any computation and
raises one `SceneError` listing every problem, each naming its origin (the file or the
`--set`), the key, the offending value and what is accepted.
"""

import copy
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Any, NamedTuple

import yaml

from sim.model.lubrication import BEARING_FINITE, FINITE_ECCENTRICITY_MAX, bearing_model
from sim.scene_keys import (
    BAR,
    BLOCK,
    BODY_COMMON,
    CONTACT,
    DAMPING,
    DRIVE,
    HINT,
    LUBRICANT,
    MATERIAL,
    NO_DEFAULT,
    OUTPUT,
    REVOLUTE,
    SIMULATION,
    SLIDER_OUTPUT,
    SOLVER,
    TOP,
    TRANSLATIONAL,
    WELD,
    Field,
    check_value,
    describe,
)
from sim.yaml_keys import DuplicateKeyError, dotted, key_lines

GROUND = "ground"


class SceneError(ValueError):
    """A scene that cannot be used, with a message naming the source and key."""


# ---------------------------------------------------------------- loading


class _Loader(yaml.SafeLoader):
    """SafeLoader that reads floats as YAML 1.2 does: PyYAML's YAML 1.1 rule
    takes '207.0e9' or '1e-3' without a dot for text."""


_Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(
        r"^[-+]?(?:[0-9][0-9_]*\.[0-9_]*(?:[eE][-+]?[0-9]+)?|\.[0-9_]+(?:[eE][-+]?[0-9]+)?"
        r"|[0-9][0-9_]*[eE][-+]?[0-9]+|\.(?:inf|Inf|INF)|[-+]\.(?:inf|Inf|INF)|\.(?:nan|NaN|NAN))$"
    ),
    list("-+0123456789."),
)


def parse_yaml(text: str):
    """YAML text to Python data with the 1.2 float rule."""
    return yaml.load(text, Loader=_Loader)


def builtin_names() -> list[str]:
    """Names of the scenes shipped inside the package."""
    files = resources.files("sim.scenes")
    return sorted(p.name[:-5] for p in files.iterdir() if p.name.endswith(".yaml"))


def _read_yaml(text: str, source: str) -> dict:
    loader = _Loader(text)
    try:
        node = loader.get_single_node()
        key_lines(node)
        data = None if node is None else loader.construct_document(node)
    except DuplicateKeyError as exc:
        raise SceneError(
            f"scene {source}: key '{dotted(exc.path)}' is defined twice (lines "
            f"{exc.first_line} and {exc.second_line}); YAML would keep only the last: remove "
            "or rename one"
        ) from None
    except yaml.YAMLError as exc:
        raise SceneError(f"scene {source}: not valid YAML: {exc}") from None
    finally:
        loader.dispose()
    if not isinstance(data, dict):
        raise SceneError(f"scene {source}: the file must hold a mapping of keys, not {data!r}")
    return data


def _read_source(name_or_path: str) -> tuple[dict, str]:
    """The raw mapping of a built-in scene or a file, and a label for messages."""
    path = Path(name_or_path)
    if path.suffix in (".yaml", ".yml") or path.exists():
        if not path.is_file():
            what = "is a directory, not a YAML file" if path.is_dir() else "does not exist"
            raise SceneError(f"scene file '{path}' {what}")
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError as exc:
            raise SceneError(
                f"scene file '{path}' is not UTF-8 text (byte {exc.object[exc.start]:#04x} at "
                f"offset {exc.start}): a scene must be a YAML file saved as UTF-8"
            ) from None
        except OSError as exc:
            raise SceneError(f"scene file '{path}' cannot be read: {exc.strerror}") from None
        return _read_yaml(text, f"'{path}'"), f"'{path}'"
    if name_or_path not in builtin_names():
        raise SceneError(
            f"unknown scene '{name_or_path}': give a path to a YAML file or one of the "
            f"built-in scenes {', '.join(builtin_names())}"
        )
    text = resources.files("sim.scenes").joinpath(f"{name_or_path}.yaml").read_text()
    return _read_yaml(text, f"'{name_or_path}' (built-in)"), f"'{name_or_path}' (built-in)"


# Named collections of a scene: in a file with `base:`, `<collection>.<name>: null` removes
# the inherited entry.
COLLECTIONS = ("materials", "ground", "bodies", "joints")
# The key whose change makes an entry of another kind: an inherited entry whose value differs
# is replaced whole, never merged into a hybrid (a revolute joint with a guide's keys).
_KIND_KEY = {"bodies": "shape", "joints": "type"}


@dataclass(frozen=True)
class Problem:
    """One thing wrong with a scene: the dotted key it is about and the message, which names
    the key and what is accepted."""

    key: str
    text: str


def deep_merge(base: dict, changes: dict) -> dict:
    """A copy of `base` with `changes` merged in, mappings key by key."""
    out = copy.deepcopy(base)
    for key, value in changes.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = deep_merge(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def _inherit(base: dict, changes: dict, problems: list[Problem]) -> dict:
    """`base` with a file's `changes` merged in: in the named collections a null entry removes
    the inherited one, and an entry of another kind (a joint's `type`, a body's `shape`)
    replaces it whole; everything else merges key by key (`deep_merge`)."""
    out = copy.deepcopy(base)
    for key, value in changes.items():
        inherited = out.get(key)
        if key not in COLLECTIONS or not (isinstance(value, dict) and isinstance(inherited, dict)):
            out = deep_merge(out, {key: value})
            continue
        kind = _KIND_KEY.get(key)
        for name, entry in value.items():
            old = inherited.get(name)
            if entry is None:
                if name in inherited:
                    del inherited[name]
                else:
                    problems.append(
                        Problem(
                            f"{key}.{name}",
                            f"'{key}.{name}: null' removes an inherited entry, but the base has "
                            f"none named '{name}'; inherited: {', '.join(inherited)}",
                        )
                    )
            elif (
                isinstance(entry, dict)
                and isinstance(old, dict)
                and not (kind and kind in entry and entry[kind] != old.get(kind))
            ):
                inherited[name] = deep_merge(old, entry)
            else:
                inherited[name] = copy.deepcopy(entry)
    return out


def _override_paths(overrides: Iterable[str]) -> list[tuple[str, tuple[str, ...]]]:
    """Each well-formed 'dotted.key=value' with its key path."""
    return [
        (item, tuple(item.split("=", 1)[0].strip().split("."))) for item in overrides if "=" in item
    ]


def apply_overrides(scene: dict, overrides: Iterable[str]) -> tuple[dict, list[Problem]]:
    """A copy of `scene` with each 'dotted.key=value' applied (value parsed as YAML), and the
    overrides that cannot apply (they are reported as `--set` problems)."""
    out = copy.deepcopy(scene)
    problems = []
    for item in overrides:
        if "=" not in item:
            problems.append(Problem(f"--set {item}", "expected dotted.key=value"))
            continue
        key, text = item.split("=", 1)
        parts = key.strip().split(".")
        try:
            value = parse_yaml(text)
        except yaml.YAMLError:
            value = text
        node = out
        for depth, part in enumerate(parts[:-1]):
            if not isinstance(node.get(part), dict):
                known = ", ".join(sorted(node)) if isinstance(node, dict) else ""
                where = ".".join(parts[: depth + 1])
                problems.append(
                    Problem(
                        key.strip(),
                        f"there is no section '{where}' in the scene; accepted here: {known}",
                    )
                )
                break
            node = node[part]
        else:
            node[parts[-1]] = value
    return out, problems


def _origin(problem: Problem, source: str, overrides: Sequence[str]) -> str:
    """Who wrote the key of `problem`: the `--set` override whose key it is (or lies inside,
    or holds), else the scene file."""
    if problem.key.startswith("--set "):
        return f"--set '{problem.key[6:]}'"
    key = tuple(re.sub(r"\[\d+\]", "", problem.key.removeprefix("scene.")).split("."))
    for item, path in _override_paths(overrides):
        common = min(len(key), len(path))
        if key[:common] == path[:common]:
            return f"--set '{item}'"
    return f"scene {source}"


def _raise(problems: list[Problem], source: str, overrides: Sequence[str]) -> None:
    """SceneError listing every problem, each with its origin (the file or a `--set`)."""
    if not problems:
        return
    lines = [f"{_origin(p, source, overrides)}: {p.text}" for p in problems]
    if len(lines) == 1:
        raise SceneError(lines[0])
    raise SceneError(
        f"{len(lines)} problems, all reported here:\n" + "\n".join(f"  - {x}" for x in lines)
    )


def _fill(data: Any, spec: dict) -> None:
    """Set each missing key of the mapping `data` that has a default in `spec` (nothing
    when `data` is not a mapping: validation reports that)."""
    if isinstance(data, dict):
        for key, field in spec.items():
            if key not in data and field.default is not NO_DEFAULT:
                data[key] = copy.deepcopy(field.default)


def with_defaults(scene: dict) -> dict:
    """A copy of `scene` with every optional key that has a default filled in (the defaults
    of the tables above; docs/scenes.md lists them). Safe on a scene that still has errors
    and on one already filled: it only adds keys that are missing."""
    out = copy.deepcopy(scene)
    _fill(out, TOP)
    for collection, spec in (("bodies", lambda b: BODY_COMMON), ("joints", _joint_table)):
        entries = out.get(collection)
        for entry in entries.values() if isinstance(entries, dict) else ():
            if isinstance(entry, dict):
                _fill(entry, spec(entry) or {})
                _fill(entry.get("lubricant"), LUBRICANT)
    for key, spec in (
        ("output", OUTPUT),
        ("drive", DRIVE),
        ("contact", CONTACT),
        ("simulation", SIMULATION),
        ("solver", SOLVER),
    ):
        _fill(out.get(key), spec)
    return out


def _joint_table(joint: dict) -> dict | None:
    """The table of keys of a joint's type (None for an unknown type)."""
    return {"revolute": REVOLUTE, "translational": TRANSLATIONAL, "weld": WELD}.get(
        joint.get("type")
    )


def _read_raw(
    name_or_path: str, chain: tuple[str, ...], problems: list[Problem]
) -> tuple[dict, str]:
    """The mapping of a scene with its `base` (and the base's base) merged in."""
    raw, source = _read_source(name_or_path)
    if "base" not in raw:
        return raw, source
    base = str(raw["base"])
    if base in chain:
        raise SceneError(f"scene {source}: 'base' = '{base}' starts a cycle of bases")
    base_raw, _ = _read_raw(base, (*chain, base), problems)
    return _inherit(base_raw, {k: v for k, v in raw.items() if k != "base"}, problems), source


def load_scene(name_or_path: str, overrides: Sequence[str] = ()) -> dict:
    """Load a built-in scene or a YAML file, apply overrides and validate.

    Returns the resolved scene: a plain mapping with every key present, defaults filled in
    (before the overrides, so that they can set keys inside a default such as
    `bodies.<name>.damping.kind`, and after, for what the overrides add). SceneError lists
    every problem at once, each named by its origin: the file or a `--set`."""
    problems: list[Problem] = []
    raw, source = _read_raw(name_or_path, (name_or_path,), problems)
    return _resolve(raw, source, overrides, problems)


def with_overrides(scene: dict, overrides: Sequence[str], source: str) -> dict:
    """A loaded scene with further overrides applied, defaults filled in again and validated,
    as :func:`load_scene` would give it: for a caller that reads a scene once and checks many
    sets of overrides (the workflow's plan). SceneError as load_scene's."""
    return _resolve(scene, source, overrides, [])


def _resolve(raw: dict, source: str, overrides: Sequence[str], problems: list[Problem]) -> dict:
    """The last steps of loading: defaults, overrides, defaults again, every problem at once."""
    scene, override_problems = apply_overrides(with_defaults(raw), overrides)
    scene = with_defaults(scene)
    _raise([*problems, *override_problems, *scene_problems(scene)], source, overrides)
    return scene


class OutputChannel(NamedTuple):
    """The channel the analyses read: a body, its point (a name, or [x, y] in the body's
    frame, m) and a global axis (x or y)."""

    body: str
    point: str | list[float]
    axis: str

    @property
    def label(self) -> str:
        """The channel in words: "slider y", "rocker end y", "rocker [0.1, 0.02] y"."""
        where = self.body if self.point == "centre" else f"{self.body} {self.point}"
        return f"{where} {self.axis}"


def output_channel(scene: dict) -> OutputChannel:
    """The output channel of a resolved scene (`output`, or the body named `slider` along y);
    ValueError naming the key when the scene gives none and has no slider."""
    output = scene.get("output") or SLIDER_OUTPUT
    if output["body"] not in scene["bodies"]:
        raise ValueError(
            f"scene '{scene['name']}' names no output channel and has no body 'slider': give "
            "output: {body: <name>, axis: x or y}, the channel the analyses read"
        )
    return OutputChannel(output["body"], output["point"], output["axis"])


def dump_scene(scene: dict) -> str:
    """The scene as YAML text, in the key order of the file."""
    return yaml.safe_dump(scene, sort_keys=False, default_flow_style=None, width=100)


# ---------------------------------------------------------------- validation


def _check_section(data: Any, spec: dict, where: str, problems: list[Problem]) -> bool:
    """Every key of `data` known to `spec`, every required key present, every value valid;
    a Problem for each that is not. True when the section has none."""
    if not isinstance(data, dict):
        problems.append(Problem(where, f"'{where}' must be a mapping of keys, not {data!r}"))
        return False
    count = len(problems)
    for key in data:
        if key not in spec:
            problems.append(
                Problem(
                    f"{where}.{key}",
                    f"unknown key '{where}.{key}'; accepted keys in '{where}': " + ", ".join(spec),
                )
            )
    for key, field in spec.items():
        if key not in data:
            if field.required:
                problems.append(
                    Problem(f"{where}.{key}", f"missing key '{where}.{key}' ({describe(field)})")
                )
        elif not check_value(data[key], field):
            problems.append(
                Problem(
                    f"{where}.{key}",
                    f"'{where}.{key}' = {data[key]!r} is not accepted; expected {describe(field)}",
                )
            )
    return len(problems) == count


def _check_name(
    value: Any, known: Iterable[str], where: str, what: str, problems: list[Problem]
) -> bool:
    """A Problem when `value` is not one of the `known` names; True when it is."""
    known = list(known)
    if value in known:
        return True
    problems.append(
        Problem(where, f"'{where}' names unknown {what} '{value}'; accepted: " + ", ".join(known))
    )
    return False


def _check_position(value: Any, where: str, problems: list[Problem]) -> None:
    """A Problem when `value` is not a point [x, y] (m)."""
    if not check_value(value, HINT["position"]):
        problems.append(
            Problem(
                where,
                f"'{where}' = {value!r} is not accepted; expected {describe(HINT['position'])}",
            )
        )


def key_field(scene: dict, key: str) -> Field | None:
    """What the dotted scene `key` accepts in the resolved `scene` (its `Field`: type, range,
    unit), e.g. `joints.A.clearance` or `drive.speed_rpm`; None for a key no table declares."""
    parts = key.split(".")
    sections = {
        "drive": DRIVE,
        "contact": CONTACT,
        "simulation": SIMULATION,
        "solver": SOLVER,
        "output": OUTPUT,
    }
    if len(parts) == 2 and parts[0] in sections:
        return sections[parts[0]].get(parts[1])
    if len(parts) == 3 and parts[0] == "bodies" and parts[1] in scene["bodies"]:
        body = scene["bodies"][parts[1]]
        return (BLOCK if body.get("shape") == "block" else BAR).get(parts[2])
    if len(parts) == 3 and parts[0] == "joints" and parts[1] in scene["joints"]:
        return (_joint_table(scene["joints"][parts[1]]) or {}).get(parts[2])
    if parts[:1] == ["joints"] and parts[2:3] == ["lubricant"] and len(parts) == 4:
        return LUBRICANT.get(parts[3])
    if len(parts) == 3 and parts[0] == "materials":
        return MATERIAL.get(parts[2])
    return TOP.get(key)


def body_points(body: dict) -> list[str]:
    """Names of the points a body offers to joints."""
    if body["kind"] == "beam":
        return ["start", "end"]
    names = ["centre"] + (["start", "end"] if body["shape"] == "bar" else [])
    return names + list(body["points"])


def _mapping(scene: dict, key: str) -> dict:
    """scene[key] when it is a mapping, else {} (its problem is reported by the top check)."""
    value = scene.get(key)
    return value if isinstance(value, dict) else {}


def scene_problems(scene: dict) -> list[Problem]:
    """Every problem of a resolved scene (defaults filled by `with_defaults`), in the order of
    the scene's sections; a check that needs a valid key is skipped when that key has one."""
    problems: list[Problem] = []
    _check_section(scene, TOP, "scene", problems)
    materials = _mapping(scene, "materials")
    for name, mat in materials.items():
        _check_section(mat, MATERIAL, f"materials.{name}", problems)
    for name, pos in _mapping(scene, "ground").items():
        _check_position(pos, f"ground.{name}", problems)
    bodies = _mapping(scene, "bodies")
    if GROUND in bodies:
        problems.append(
            Problem(f"bodies.{GROUND}", f"'bodies.{GROUND}' is reserved for the fixed frame")
        )
    valid = {}
    for name, body in bodies.items():
        if _check_body(name, body, materials, problems):
            valid[name] = body
    for name, joint in _mapping(scene, "joints").items():
        _check_joint(scene, name, joint, bodies, valid, problems)
    drive = scene.get("drive")
    if (
        drive is not None
        and _check_section(drive, DRIVE, "drive", problems)
        and _check_name(drive["body"], bodies, "drive.body", "body", problems)
        and drive["body"] in valid
        and valid[drive["body"]]["kind"] != "rigid"
    ):
        problems.append(Problem("drive.body", "'drive.body' must be a rigid body"))
    contact = scene.get("contact", {})
    if _check_section(contact, CONTACT, "contact", problems) and contact["v1"] <= contact["v0"]:
        problems.append(
            Problem(
                "contact.v1",
                f"'contact.v1' = {contact['v1']!r} must exceed 'contact.v0' = {contact['v0']!r}",
            )
        )
    output = scene.get("output")
    if output is not None and _check_section(output, OUTPUT, "output", problems):
        _check_name(output["body"], bodies, "output.body", "body", problems)
    _check_section(scene.get("simulation", {}), SIMULATION, "simulation", problems)
    _check_section(scene.get("solver", {}), SOLVER, "solver", problems)
    return problems


def _check_body(name: str, body: Any, materials: dict, problems: list[Problem]) -> bool:
    """Problems of `bodies.<name>`; True when it has none."""
    where = f"bodies.{name}"
    if not isinstance(body, dict):
        problems.append(Problem(where, f"'{where}' must be a mapping of keys, not {body!r}"))
        return False
    count = len(problems)
    shape = body.get("shape")
    if _check_section(body, BLOCK if shape == "block" else BAR, where, problems):
        _check_name(body["material"], materials, f"{where}.material", "material", problems)
        if body["hint"] is not None:
            _check_section(body["hint"], HINT, f"{where}.hint", problems)
        if body["kind"] in ("beam", "modal") and shape != "bar":
            problems.append(
                Problem(f"{where}.kind", f"'{where}.kind' = '{body['kind']}' needs shape 'bar'")
            )
        if body["kind"] == "beam" and body["points"]:
            problems.append(
                Problem(
                    f"{where}.points",
                    f"'{where}.points' is not accepted for a beam; joints attach to its "
                    "'start' and 'end' nodes",
                )
            )
        for pname, vec in body["points"].items():
            _check_position(vec, f"{where}.points.{pname}", problems)
        damping = body["damping"]
        if _check_section(damping, DAMPING, f"{where}.damping", problems):
            needed = {"stiffness": "coefficient", "modal": "ratio"}.get(damping["kind"])
            if needed and needed not in damping:
                problems.append(
                    Problem(
                        f"{where}.damping.{needed}",
                        f"'{where}.damping.kind' = '{damping['kind']}' needs "
                        f"'{where}.damping.{needed}' ({describe(DAMPING[needed])})",
                    )
                )
    return len(problems) == count


def _check_joint(
    scene: dict, name: str, joint: Any, bodies: dict, valid: dict, problems: list[Problem]
) -> None:
    """Problems of `joints.<name>`; the checks of its bodies' kinds and points need the
    bodies valid (`valid`), whose own problems are reported already."""
    where = f"joints.{name}"
    spec = _joint_table(joint) if isinstance(joint, dict) else None
    if spec is None:
        jt = joint.get("type") if isinstance(joint, dict) else joint
        problems.append(
            Problem(
                f"{where}.type",
                f"'{where}.type' = {jt!r} is not accepted; expected one of "
                "'revolute', 'translational', 'weld'",
            )
        )
        return
    if not _check_section(joint, spec, where, problems):
        return
    pair = joint["bodies"]
    if len(pair) != 2 or pair[0] == pair[1]:
        problems.append(
            Problem(
                f"{where}.bodies", f"'{where}.bodies' = {pair!r} must name two different bodies"
            )
        )
        return
    known = [GROUND, *bodies]
    if not all(
        [
            _check_name(b, known, f"{where}.bodies[{i}]", "body", problems)
            for i, b in enumerate(pair)
        ]
    ) or not all(b == GROUND or b in valid for b in pair):
        return
    if joint["type"] == "translational":
        if pair[0] != GROUND or bodies[pair[1]]["kind"] != "rigid":
            problems.append(
                Problem(
                    f"{where}.bodies",
                    f"'{where}' must guide a rigid body along the ground: "
                    f"bodies: [ground, <rigid body>], got {pair!r}",
                )
            )
        return
    points = joint["points"]
    if len(points) != 2:
        problems.append(Problem(f"{where}.points", f"'{where}.points' must list two point names"))
        return
    for i, (body, point) in enumerate(zip(pair, points, strict=True)):
        names = _mapping(scene, "ground") if body == GROUND else body_points(bodies[body])
        _check_name(point, names, f"{where}.points[{i}]", f"point of '{body}'", problems)
    if joint["type"] == "weld":
        if joint["clearance"] != 0.0:
            problems.append(
                Problem(f"{where}.clearance", f"'{where}.clearance' must be 0 for a weld")
            )
        if any(b != GROUND and bodies[b]["kind"] != "rigid" for b in pair):
            problems.append(Problem(f"{where}.bodies", f"'{where}' welds rigid bodies only"))
        for b in pair:
            if b != GROUND and bodies[b]["hint"] is None:
                problems.append(
                    Problem(
                        f"bodies.{b}.hint",
                        f"'{where}' (a weld) needs 'bodies.{b}.hint': the weld holds the "
                        "angle of the hints",
                    )
                )
    elif joint["clearance"] >= joint["bearing_radius"]:
        problems.append(
            Problem(
                f"{where}.clearance",
                f"'{where}.clearance' = {joint['clearance']!r} must be smaller than "
                f"'{where}.bearing_radius' = {joint['bearing_radius']!r}",
            )
        )
    elif joint["lubricant"] is not None:
        _check_lubricant(joint, f"{where}.lubricant", problems)


def _check_lubricant(joint: dict, where: str, problems: list[Problem]) -> None:
    """Problems of a revolute joint's `lubricant` block: its keys and a threshold below the
    clearance, within the finite bearing's table for such a bearing (sim.model.lubrication)."""
    lubricant = joint["lubricant"]
    if not _check_section(lubricant, LUBRICANT, where, problems) or joint["clearance"] == 0.0:
        return
    clearance = joint["clearance"]
    lowest = 0.0
    if bearing_model(lubricant["length"], joint["bearing_radius"] - clearance) == BEARING_FINITE:
        lowest = clearance * (1.0 - FINITE_ECCENTRICITY_MAX)
    if not lowest <= lubricant["threshold"] < clearance:
        problems.append(
            Problem(
                f"{where}.threshold",
                f"'{where}.threshold' = {lubricant['threshold']!r} is not accepted; expected "
                f"{lowest:.4g} ≤ x < {clearance!r} m: below the joint's clearance"
                + (", and a film no thinner than the finite bearing's table" if lowest else ""),
            )
        )

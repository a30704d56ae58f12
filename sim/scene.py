"""Scenes: load, override, validate.

A scene is a YAML mapping that describes one planar linkage and how to
simulate it (see `sim/scenes/sixbar.yaml`). It is loaded by built-in name
(`sixbar`, `slider-crank`) or by path. A file may start from a built-in scene
with `base: <name>` and list only what it changes. `--set dotted.key=value`
overrides any key; values are parsed as YAML scalars.

Every default is declared here, in the tables of keys below (`Field.default`); loading
fills them in, so the resolved scene has every key and no other module supplies a default.
Validation runs before any computation and raises `SceneError` naming the
source, the key, the offending value and what is accepted.
"""

import copy
import math
import re
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace
from importlib import resources
from pathlib import Path
from typing import Any

import yaml

from sim.quantities import SAMPLINGS
from sim.yaml_keys import DuplicateKeyError, dotted, key_lines

GROUND = "ground"


class SceneError(ValueError):
    """A scene that cannot be used, with a message naming the source and key."""


class _NoDefault:
    """Marks a key without a default (None is a default: null, computed)."""

    def __repr__(self) -> str:
        return "NO_DEFAULT"


NO_DEFAULT = _NoDefault()


@dataclass(frozen=True)
class Field:
    """What one key accepts: a type, an optional numeric range (inclusive unless
    `open_min`), or a fixed set of choices; `unit` is shown in messages. An optional key
    (`required=False`) may have a `default`, which loading fills in; a default of None
    accepts null, meaning "computed from the rest of the scene" (the comment beside the key
    says how)."""

    kind: str  # 'number', 'int', 'str', 'bool', 'vector2', 'vector3', 'list', 'mapping'
    minimum: float | None = None
    maximum: float | None = None
    open_min: bool = False
    choices: tuple[str, ...] = ()
    unit: str = ""
    required: bool = True
    default: Any = NO_DEFAULT


def _num(lo=None, hi=None, unit="", open_min=False, required=True, default=NO_DEFAULT) -> Field:
    return Field("number", lo, hi, open_min, unit=unit, required=required, default=default)


TOP = {
    "name": Field("str"),
    "description": Field("str", required=False, default=""),
    "assumptions": Field("list", required=False, default=[]),
    "base": Field("str", required=False),
    "gravity": Field("vector2", -1e3, 1e3, unit="m/s^2"),
    "materials": Field("mapping"),
    "ground": Field("mapping"),
    "bodies": Field("mapping"),
    "joints": Field("mapping"),
    "drive": Field("mapping", required=False),
    "contact": Field("mapping"),
    "simulation": Field("mapping"),
    "solver": Field("mapping"),
}
MATERIAL = {
    "youngs_modulus": _num(1e6, 1e15, "Pa", open_min=True),
    "poisson": _num(0.0, 0.499),
    "density": _num(1.0, 1e5, "kg/m^3"),
}
# The defaults are listed for users in README.md ("Scenes"); the ASSUMED ones also in
# docs/assumptions.md.
BODY_COMMON = {
    "kind": Field("str", choices=("rigid", "beam", "modal")),
    "shape": Field("str", choices=("bar", "block")),
    "material": Field("str"),
    "hint": Field("mapping"),
    # null: ASSUMED uniform body, bar ρ A L, block ρ L W D (sim.model.assembly)
    "mass": _num(0.0, 1e6, "kg", open_min=True, required=False, default=None),
    # null: ASSUMED uniform body about its centre, bar m L²/12, block m (L² + W²)/12
    "inertia": _num(0.0, 1e6, "kg m^2", open_min=True, required=False, default=None),
    # named points beyond `centre` (and `start`, `end` of a bar); none on a beam
    "points": Field("mapping", required=False, default={}),
    # ASSUMED ANCF elements of a beam (the paper gives none); unused while rigid
    "elements": Field("int", 1, 64, required=False, default=2),
    # bending modes of a modal link (docs/model.md, "Modal links"): one is within 1.4 % of the
    # ANCF beams' deflections on the six-bar at a quarter of the steps of three (0.7 %), whose
    # higher frequencies DOPRI5 must resolve; at most 4 (sim.model.modal's tabulated modes)
    "modes": Field("int", 1, 4, required=False, default=1),
    # free–free axial modes of a modal link after its bending modes (docs/model.md, "Modal
    # links"); 0 keeps the link axially rigid, whose 5.7-8.6 kHz axial ringing DOPRI5 cannot afford;
    # the peaks need them (docs/fidelity.md, "Modal links"); at most 3 (sim.model.modal)
    "axial_modes": Field("int", 0, 3, required=False, default=0),
    # none, as in the paper
    "damping": Field("mapping", required=False, default={"kind": "none"}),
}
BAR = {
    **BODY_COMMON,
    "length": _num(0.0, 100.0, "m", open_min=True),
    "section": Field("vector2", 0.0, 10.0, open_min=True, unit="m"),
}
BLOCK = {**BODY_COMMON, "size": Field("vector3", 0.0, 10.0, open_min=True, unit="m")}
HINT = {"position": Field("vector2", -1e3, 1e3, unit="m"), "angle_deg": _num(-720, 720, "deg")}
DAMPING = {
    "kind": Field("str", choices=("none", "stiffness", "modal")),
    "coefficient": _num(0.0, 1.0, "s", required=False),
    "ratio": _num(0.0, 1.0, required=False),
}
JOINT_COMMON = {
    "type": Field("str", choices=("revolute", "translational", "weld")),
    "bodies": Field("list"),
    "clearance": _num(0.0, 0.01, "m"),
}
REVOLUTE = {
    **JOINT_COMMON,
    "points": Field("list"),
    "bearing_radius": _num(0.0, 1.0, "m", open_min=True),
}
WELD = {**JOINT_COMMON, "points": Field("list")}
TRANSLATIONAL = {
    **JOINT_COMMON,
    "guide_point": Field("vector2", -1e3, 1e3, unit="m"),
    "guide_angle_deg": _num(-360, 360, "deg"),
}
DRIVE = {
    "body": Field("str"),
    "speed_rpm": _num(0.0, 1e5, "rpm", open_min=True),
    "initial_angle_deg": _num(-360, 360, "deg"),
}
CONTACT = {
    "restitution": _num(0.0, 1.0, open_min=True),
    "friction": _num(0.0, 2.0),
    "v0": _num(0.0, 1.0, "m/s", open_min=True),
    "v1": _num(0.0, 10.0, "m/s", open_min=True),
    "exponent": _num(1.0, 3.0),
    "corner_radius": _num(0.0, 1.0, "m", open_min=True),
    "min_impact_speed": _num(0.0, 1.0, "m/s", open_min=True),
    "slider_law": Field("str", choices=("winkler", "paper")),
}
SIMULATION = {
    "revolutions": _num(0.0, 1e6, "revolutions", open_min=True),
    "output_per_revolution": Field("int", 1, 1_000_000),
    "beam_start": Field("str", choices=("quasi-static", "straight")),
    # mean: the fast quantities (accelerations, drive torque, contact forces, deflections) are
    # recorded as means over each sample's window, free of aliasing; point: every quantity is
    # its value at the sample time (sim.quantities says which is which)
    "sampling": Field("str", choices=SAMPLINGS, required=False, default="mean"),
}
SOLVER = {
    "method": Field("str", choices=("dopri5", "generalized_alpha")),
    "rho_inf": _num(0.0, 1.0),
    "rtol": _num(1e-13, 1e-1),
    "atol": _num(1e-16, 1e-1),
    "max_step_fraction": _num(1e-7, 1.0, "crank periods", open_min=True),
    "baumgarte_alpha": _num(0.0, 1e4, "1/s"),
    "baumgarte_beta": _num(0.0, 1e4, "1/s"),
    "max_steps": Field("int", 1, 10**12),
    # minimal: a mechanism of rigid bodies and modal links whose ideal joints form a tree
    # integrates its joint angles and modal amplitudes (sim.model.tree; DOPRI5 only);
    # absolute: always coordinates under multipliers
    "coordinates": Field("str", choices=("minimal", "absolute"), required=False, default="minimal"),
}


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


def deep_merge(base: dict, changes: dict) -> dict:
    """A copy of `base` with `changes` merged in, mappings key by key."""
    out = copy.deepcopy(base)
    for key, value in changes.items():
        if isinstance(value, dict) and isinstance(out.get(key), dict):
            out[key] = deep_merge(out[key], value)
        else:
            out[key] = copy.deepcopy(value)
    return out


def apply_overrides(scene: dict, overrides: Iterable[str], source: str = "--set") -> dict:
    """A copy of `scene` with each 'dotted.key=value' applied (value parsed as YAML)."""
    out = copy.deepcopy(scene)
    for item in overrides:
        if "=" not in item:
            raise SceneError(f"{source} '{item}': expected dotted.key=value")
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
                raise SceneError(
                    f"{source} '{item}': there is no section '{where}' in the scene; "
                    f"accepted here: {known}"
                )
            node = node[part]
        node[parts[-1]] = value
    return out


def _fill(data: Any, spec: dict) -> None:
    """Set each missing key of the mapping `data` that has a default in `spec` (nothing
    when `data` is not a mapping: validation reports that)."""
    if isinstance(data, dict):
        for key, field in spec.items():
            if key not in data and field.default is not NO_DEFAULT:
                data[key] = copy.deepcopy(field.default)


def with_defaults(scene: dict) -> dict:
    """A copy of `scene` with every optional key that has a default filled in (the defaults
    of the tables above; README.md lists them). Safe on a scene that still has errors
    and on one already filled: it only adds keys that are missing."""
    out = copy.deepcopy(scene)
    _fill(out, TOP)
    bodies = out.get("bodies")
    for body in bodies.values() if isinstance(bodies, dict) else ():
        if isinstance(body, dict):
            _fill(body, BODY_COMMON)
    _fill(out.get("simulation"), SIMULATION)
    _fill(out.get("solver"), SOLVER)
    return out


def load_scene(name_or_path: str, overrides: Sequence[str] = ()) -> dict:
    """Load a built-in scene or a YAML file, apply overrides and validate.

    Returns the resolved scene: a plain mapping with every key present, defaults filled in
    (before the overrides, so that they can set keys inside a default such as
    `bodies.<name>.damping.kind`, and after, for what the overrides add)."""
    raw, source = _read_source(name_or_path)
    if "base" in raw:
        base_raw, _ = _read_source(str(raw["base"]))
        raw = deep_merge(base_raw, {k: v for k, v in raw.items() if k != "base"})
    scene = with_defaults(apply_overrides(with_defaults(raw), overrides))
    validate_scene(scene, source)
    return scene


def dump_scene(scene: dict) -> str:
    """The scene as YAML text, in the key order of the file."""
    return yaml.safe_dump(scene, sort_keys=False, default_flow_style=None, width=100)


# ---------------------------------------------------------------- validation


def _describe(field: Field) -> str:
    if field.default is None:
        return _describe(replace(field, default=NO_DEFAULT)) + ", or null (computed)"
    if field.choices:
        return "one of " + ", ".join(repr(c) for c in field.choices)
    lo = "" if field.minimum is None else f"{field.minimum:g} {'<' if field.open_min else '≤'} "
    hi = "" if field.maximum is None else f" ≤ {field.maximum:g}"
    unit = f" ({field.unit})" if field.unit else ""
    kind = {"vector2": "a list of 2 numbers", "vector3": "a list of 3 numbers"}.get(field.kind)
    if kind:
        return f"{kind}, each {lo}x{hi}{unit}" if (lo or hi) else kind + unit
    what = {"int": "a whole number", "number": "a number", "str": "a text", "bool": "true/false"}
    if lo or hi:
        return f"{what.get(field.kind, field.kind)} {lo}x{hi}{unit}"
    return what.get(field.kind, "a " + field.kind) + unit


def _check_number(x: Any, field: Field) -> bool:
    if isinstance(x, bool) or not isinstance(x, int | float) or not math.isfinite(x):
        return False
    if field.kind == "int" and not float(x).is_integer():
        return False
    if field.minimum is not None and (x < field.minimum or (field.open_min and x == field.minimum)):
        return False
    return field.maximum is None or x <= field.maximum


def _check_value(value: Any, field: Field) -> bool:
    if value is None and field.default is None:
        return True  # null: computed from the rest of the scene
    if field.kind in ("number", "int"):
        return _check_number(value, field)
    if field.kind == "str":
        return isinstance(value, str) and (not field.choices or value in field.choices)
    if field.kind == "bool":
        return isinstance(value, bool)
    if field.kind in ("vector2", "vector3"):
        size = 2 if field.kind == "vector2" else 3
        return (
            isinstance(value, list)
            and len(value) == size
            and all(_check_number(v, field) for v in value)
        )
    if field.kind == "list":
        return isinstance(value, list)
    return isinstance(value, dict)


def check_option(option: str, value: Any, field: Field) -> None:
    """Raise ValueError naming a command-line option whose value `field` does not accept, in
    the words of a scene key's message (`sim` reports it with exit code 2)."""
    if not _check_value(value, field):
        raise ValueError(f"{option} = {value!r} is not accepted; expected {_describe(field)}")


def _check_section(data: Any, spec: dict, where: str, source: str) -> None:
    """Every key of `data` known to `spec`, every required key present, every value valid."""
    if not isinstance(data, dict):
        raise SceneError(f"scene {source}: '{where}' must be a mapping of keys, not {data!r}")
    for key in data:
        if key not in spec:
            raise SceneError(
                f"scene {source}: unknown key '{where}.{key}'; accepted keys in '{where}': "
                + ", ".join(spec)
            )
    for key, field in spec.items():
        if key not in data:
            if field.required:
                raise SceneError(
                    f"scene {source}: missing key '{where}.{key}' ({_describe(field)})"
                )
            continue
        if not _check_value(data[key], field):
            raise SceneError(
                f"scene {source}: '{where}.{key}' = {data[key]!r} is not accepted; "
                f"expected {_describe(field)}"
            )


def _check_name(value: str, known: Iterable[str], where: str, what: str, source: str) -> None:
    known = list(known)
    if value not in known:
        raise SceneError(
            f"scene {source}: '{where}' names unknown {what} '{value}'; accepted: "
            + ", ".join(known)
        )


def body_points(body: dict) -> list[str]:
    """Names of the points a body offers to joints."""
    if body["kind"] == "beam":
        return ["start", "end"]
    names = ["centre"] + (["start", "end"] if body["shape"] == "bar" else [])
    return names + list(body["points"])


def validate_scene(scene: dict, source: str = "<scene>") -> None:
    """Raise SceneError for the first problem found in a resolved scene (defaults filled
    by `with_defaults`)."""
    _check_section({k: v for k, v in scene.items()}, TOP, "scene", source)
    for name, mat in scene["materials"].items():
        _check_section(mat, MATERIAL, f"materials.{name}", source)
    for name, pos in scene["ground"].items():
        if not _check_value(pos, HINT["position"]):
            raise SceneError(
                f"scene {source}: 'ground.{name}' = {pos!r} is not accepted; expected "
                f"{_describe(HINT['position'])}"
            )
    bodies = scene["bodies"]
    if GROUND in bodies:
        raise SceneError(f"scene {source}: 'bodies.{GROUND}' is reserved for the fixed frame")
    for name, body in bodies.items():
        where = f"bodies.{name}"
        if not isinstance(body, dict):
            raise SceneError(f"scene {source}: '{where}' must be a mapping of keys")
        shape = body.get("shape")
        spec = BLOCK if shape == "block" else BAR
        _check_section(body, spec, where, source)
        _check_name(body["material"], scene["materials"], f"{where}.material", "material", source)
        _check_section(body["hint"], HINT, f"{where}.hint", source)
        if body["kind"] in ("beam", "modal") and shape != "bar":
            raise SceneError(f"scene {source}: '{where}.kind' = '{body['kind']}' needs shape 'bar'")
        if body["kind"] == "beam" and body["points"]:
            raise SceneError(
                f"scene {source}: '{where}.points' is not accepted for a beam; "
                "joints attach to its 'start' and 'end' nodes"
            )
        for pname, vec in body["points"].items():
            if not _check_value(vec, HINT["position"]):
                raise SceneError(
                    f"scene {source}: '{where}.points.{pname}' = {vec!r} is not accepted; "
                    f"expected {_describe(HINT['position'])}"
                )
        _check_section(body["damping"], DAMPING, f"{where}.damping", source)
        needed = {"stiffness": "coefficient", "modal": "ratio"}.get(body["damping"]["kind"])
        if needed and needed not in body["damping"]:
            raise SceneError(
                f"scene {source}: '{where}.damping.kind' = '{body['damping']['kind']}' "
                f"needs '{where}.damping.{needed}' ({_describe(DAMPING[needed])})"
            )
    body_names = [GROUND, *bodies]
    for name, joint in scene["joints"].items():
        _validate_joint(scene, name, joint, body_names, source)
    if "drive" in scene:
        _check_section(scene["drive"], DRIVE, "drive", source)
        _check_name(scene["drive"]["body"], bodies, "drive.body", "body", source)
        if bodies[scene["drive"]["body"]]["kind"] != "rigid":
            raise SceneError(f"scene {source}: 'drive.body' must be a rigid body")
    _check_section(scene["contact"], CONTACT, "contact", source)
    if scene["contact"]["v1"] <= scene["contact"]["v0"]:
        raise SceneError(
            f"scene {source}: 'contact.v1' = {scene['contact']['v1']!r} must exceed "
            f"'contact.v0' = {scene['contact']['v0']!r}"
        )
    _check_section(scene["simulation"], SIMULATION, "simulation", source)
    _check_section(scene["solver"], SOLVER, "solver", source)
    if "drive" not in scene:
        raise SceneError(
            f"scene {source}: missing key 'scene.drive': the crank period sets the output "
            "rate, the sections and the duration"
        )


def _validate_joint(scene: dict, name: str, joint: Any, body_names: list, source: str) -> None:
    where = f"joints.{name}"
    if not isinstance(joint, dict) or joint.get("type") not in (
        "revolute",
        "translational",
        "weld",
    ):
        jt = joint.get("type") if isinstance(joint, dict) else joint
        raise SceneError(
            f"scene {source}: '{where}.type' = {jt!r} is not accepted; expected one of "
            "'revolute', 'translational', 'weld'"
        )
    spec = {"revolute": REVOLUTE, "translational": TRANSLATIONAL, "weld": WELD}[joint["type"]]
    _check_section(joint, spec, where, source)
    pair = joint["bodies"]
    if len(pair) != 2 or pair[0] == pair[1]:
        raise SceneError(
            f"scene {source}: '{where}.bodies' = {pair!r} must name two different bodies"
        )
    for i, body in enumerate(pair):
        _check_name(body, body_names, f"{where}.bodies[{i}]", "body", source)
    bodies = scene["bodies"]
    if joint["type"] == "translational":
        if pair[0] != GROUND or bodies[pair[1]]["kind"] != "rigid":
            raise SceneError(
                f"scene {source}: '{where}' must guide a rigid body along the ground: "
                f"bodies: [ground, <rigid body>], got {pair!r}"
            )
        return
    points = joint["points"]
    if len(points) != 2:
        raise SceneError(f"scene {source}: '{where}.points' must list two point names")
    for i, (body, point) in enumerate(zip(pair, points, strict=True)):
        known = scene["ground"] if body == GROUND else body_points(bodies[body])
        _check_name(point, known, f"{where}.points[{i}]", f"point of '{body}'", source)
    if joint["type"] == "weld":
        if joint["clearance"] != 0.0:
            raise SceneError(f"scene {source}: '{where}.clearance' must be 0 for a weld")
        if any(b != GROUND and bodies[b]["kind"] != "rigid" for b in pair):
            raise SceneError(f"scene {source}: '{where}' welds rigid bodies only")
    elif joint["clearance"] >= joint["bearing_radius"]:
        raise SceneError(
            f"scene {source}: '{where}.clearance' = {joint['clearance']!r} must be smaller "
            f"than '{where}.bearing_radius' = {joint['bearing_radius']!r}"
        )

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
from typing import Any, NamedTuple

import yaml

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
    accepts null, meaning "computed from the rest of the scene" (`doc` says how). `doc`
    says what the key means, for the reference page (docs/scenes.md, `sim.scene_reference`)."""

    kind: str  # 'number', 'int', 'str', 'bool', 'vector2', 'vector3', 'list', 'mapping'
    minimum: float | None = None
    maximum: float | None = None
    open_min: bool = False
    choices: tuple[str, ...] = ()
    unit: str = ""
    required: bool = True
    default: Any = NO_DEFAULT
    doc: str = ""


def _num(lo=None, hi=None, unit="", open_min=False, default=NO_DEFAULT, doc="") -> Field:
    """A number key; optional when it has a default."""
    return Field(
        "number",
        lo,
        hi,
        open_min,
        unit=unit,
        required=default is NO_DEFAULT,
        default=default,
        doc=doc,
    )


def _opt(kind: str, default: Any, doc: str, **limits: Any) -> Field:
    """An optional key of `kind` with its default."""
    return Field(kind, required=False, default=default, doc=doc, **limits)


# The defaults of `contact`, `simulation` and `solver` are the six-bar's (sim/scenes/sixbar.yaml
# relies on them); the ASSUMED ones are listed in its `assumptions` and docs/assumptions.md.
TOP = {
    "name": Field("str", doc="the scene's name, recorded in every output file"),
    "description": _opt("str", "", "free text"),
    "assumptions": _opt("list", [], "every value the source does not give, one text each"),
    "base": Field(
        "str",
        required=False,
        doc="a built-in scene or file this one starts from; the file lists only its changes, "
        "and `bodies.<name>: null` (likewise joints, ground, materials) removes an inherited "
        "entry",
    ),
    "gravity": _opt(
        "vector2", [0.0, -9.81], "gravity in the plane", minimum=-1e3, maximum=1e3, unit="m/s^2"
    ),
    "materials": Field("mapping", doc="materials by name (table `materials.<name>`)"),
    "ground": Field("mapping", doc="fixed points by name: `<name>: [x, y]` (m)"),
    "bodies": Field("mapping", doc="bodies by name (table `bodies.<name>`)"),
    "joints": Field("mapping", doc="joints by name (table `joints.<name>`)"),
    "drive": Field(
        "mapping",
        doc="the driven crank (table `drive`); its period sets the output "
        "rate, the sections and the duration",
    ),
    "contact": _opt("mapping", {}, "contact law of every clearance joint (table `contact`)"),
    "simulation": _opt("mapping", {}, "duration and output (table `simulation`)"),
    "solver": _opt("mapping", {}, "integrator settings (table `solver`)"),
    "output": _opt(
        "mapping",
        None,
        "the channel the analyses read (responses, peaks, per-revolution tables; table "
        "`output`); null: the body named `slider` along y, the six-bar's slider along its "
        "guide, which a scene without such a body replaces",
    ),
}
MATERIAL = {
    "youngs_modulus": _num(1e6, 1e15, "Pa", open_min=True, doc="Young's modulus E"),
    "poisson": _num(0.0, 0.499, doc="Poisson's ratio ν"),
    "density": _num(1.0, 1e5, "kg/m^3", doc="density ρ"),
}
HINT = {
    "position": Field("vector2", -1e3, 1e3, unit="m", doc="guess of the body's centre"),
    "angle_deg": _num(-720, 720, "deg", doc="guess of the body's angle"),
}
BODY_COMMON = {
    "kind": _opt(
        "str",
        "rigid",
        "rigid: three coordinates; beam: ANCF elements; modal: a "
        "floating frame with bending (and axial) modes (docs/model.md)",
        choices=("rigid", "beam", "modal"),
    ),
    "shape": _opt(
        "str",
        "bar",
        "bar: `length` and `section`, points `start`, `centre`, `end`; "
        "block: `size`, point `centre`",
        choices=("bar", "block"),
    ),
    "material": Field("str", doc="a name in `materials`"),
    "hint": _opt(
        "mapping",
        None,
        "pose guess for the assembly at the initial crank angle (table "
        "`bodies.<name>.hint`): the assembly closes every loop from it, so it picks the "
        "assembly branch; null: the assembly searches, takes the first branch it finds and "
        "says which (output attribute `assembly_branch`); a welded body needs one",
    ),
    "mass": _num(
        0.0,
        1e6,
        "kg",
        open_min=True,
        default=None,
        doc="null: ASSUMED uniform body, bar ρ A L, block ρ L W D",
    ),
    "inertia": _num(
        0.0,
        1e6,
        "kg m^2",
        open_min=True,
        default=None,
        doc="about the centre; null: ASSUMED uniform body, bar m L²/12, block m (L² + W²)/12",
    ),
    "points": _opt(
        "mapping",
        {},
        "named points beyond `centre` (and `start`, `end` of a bar), "
        "`<name>: [x, y]` in the body's frame (m); none on a beam",
    ),
    "elements": _opt(
        "int",
        2,
        "ANCF elements of a beam (ASSUMED: the paper gives none); unused unless `kind: beam`",
        minimum=1,
        maximum=64,
    ),
    "modes": _opt(
        "int",
        1,
        "bending modes of a modal link: one is within 1.4 % of the ANCF "
        "beams' deflections on the six-bar at a quarter of the steps of three "
        '(docs/model.md, "Modal links"); at most 4 (sim.model.modal\'s tabulated '
        "modes)",
        minimum=1,
        maximum=4,
    ),
    "axial_modes": _opt(
        "int",
        0,
        "free-free axial modes of a modal link after its bending "
        "modes; 0 keeps the link axially rigid, whose 5.7-8.6 kHz axial ringing "
        'DOPRI5 cannot afford; the peaks need them (docs/fidelity.md, "Modal '
        'links"); at most 3',
        minimum=0,
        maximum=3,
    ),
    "damping": _opt(
        "mapping",
        {"kind": "none"},
        "structural damping of a beam or modal link "
        "(table `bodies.<name>.damping`); none, as in the paper",
    ),
}
BAR = {
    **BODY_COMMON,
    "length": _num(0.0, 100.0, "m", open_min=True, doc="length of a bar, start to end"),
    "section": Field(
        "vector2",
        0.0,
        10.0,
        open_min=True,
        unit="m",
        doc="width and height of a bar's rectangular section (height in the plane of bending)",
    ),
}
BLOCK = {
    **BODY_COMMON,
    "size": Field(
        "vector3",
        0.0,
        10.0,
        open_min=True,
        unit="m",
        doc="length (along the guide), width and depth of a block",
    ),
}
DAMPING = {
    "kind": Field(
        "str",
        choices=("none", "stiffness", "modal"),
        doc="stiffness: Rayleigh β K; modal: a ratio at the first bending mode",
    ),
    "coefficient": Field(
        "number", 0.0, 1.0, unit="s", required=False, doc="β of `kind: stiffness`"
    ),
    "ratio": Field(
        "number",
        0.0,
        1.0,
        required=False,
        doc="ζ at the first pinned-pinned bending mode, `kind: modal`",
    ),
}
JOINT_COMMON = {
    "type": Field(
        "str",
        choices=("revolute", "translational", "weld"),
        doc="each type has its table of keys below",
    ),
    "bodies": Field(
        "list",
        doc="the two bodies it joins (`ground` for the fixed frame); a "
        "revolute clearance joint's bearing is on the first, its journal on the "
        "second; a translational joint is [ground, <rigid block>]",
    ),
    "clearance": _num(
        0.0,
        0.01,
        "m",
        default=0.0,
        doc="radial (revolute) or per-side (translational) clearance; 0 = an ideal joint",
    ),
}
REVOLUTE = {
    **JOINT_COMMON,
    "points": Field("list", doc="the point of each body that the joint pins together"),
    "bearing_radius": _num(
        0.0,
        1.0,
        "m",
        open_min=True,
        default=0.015,
        doc="bearing (hole) radius of a clearance joint, above `clearance` "
        "(ASSUMED, the six-bar's); unused when the joint is ideal",
    ),
}
WELD = {
    **JOINT_COMMON,
    "points": Field("list", doc="the points held together, at the angle of the bodies' hints"),
}
TRANSLATIONAL = {
    **JOINT_COMMON,
    "guide_point": Field("vector2", -1e3, 1e3, unit="m", doc="a point of the guide's axis"),
    "guide_angle_deg": _num(-360, 360, "deg", doc="direction of the guide's axis"),
}
DRIVE = {
    "body": Field("str", doc="the crank: a rigid body turned at constant speed"),
    "speed_rpm": _num(0.0, 1e5, "rpm", open_min=True, doc="crank speed"),
    "initial_angle_deg": _num(-360, 360, "deg", default=0.0, doc="crank angle at t = 0"),
}
CONTACT = {
    "restitution": _num(
        0.0,
        1.0,
        open_min=True,
        default=0.9,
        doc="coefficient of restitution of the Lankarani-Nikravesh damping",
    ),
    "friction": _num(0.0, 2.0, default=0.15, doc="Coulomb friction coefficient"),
    "v0": _num(
        0.0,
        1.0,
        "m/s",
        open_min=True,
        default=1.0e-4,
        doc="tangential speed below which friction sticks (Ambrósio's law)",
    ),
    "v1": _num(
        0.0,
        10.0,
        "m/s",
        open_min=True,
        default=1.0e-3,
        doc="tangential speed above which friction is fully dynamic; above `v0`",
    ),
    "exponent": _num(1.0, 3.0, default=1.5, doc="contact force exponent n (ASSUMED)"),
    "corner_radius": _num(
        0.0,
        1.0,
        "m",
        open_min=True,
        default=0.005,
        doc="radius of curvature of a slider's corner (ASSUMED); used by a "
        "translational clearance joint only",
    ),
    "min_impact_speed": _num(
        0.0,
        1.0,
        "m/s",
        open_min=True,
        default=1.0e-4,
        doc="guard of the Lankarani-Nikravesh damping for resting or grazing contact (ASSUMED)",
    ),
    "slider_law": _opt(
        "str",
        "winkler",
        "winkler: the paper's face law as an elastic "
        "foundation along each long edge, continuous into its one-corner "
        "(wedge) limit and energy-consistent; paper: face law for two corners, "
        "Hertz for one (creates energy at switches). Used by a translational "
        "clearance joint only",
        choices=("winkler", "paper"),
    ),
}
SIMULATION = {
    "revolutions": _num(
        0.0, 1e6, "revolutions", open_min=True, default=200, doc="duration in crank revolutions"
    ),
    "output_per_revolution": _opt(
        "int", 200, "output samples per crank revolution", minimum=1, maximum=1_000_000
    ),
    "beam_start": _opt(
        "str",
        "quasi-static",
        "beams and modal links start pre-deformed to "
        "the quasi-static solution at the initial crank angle (consistent: the "
        "rigid model's accelerations), or straight and unstressed; unused "
        "without them",
        choices=("quasi-static", "straight"),
    ),
}
SOLVER = {
    "method": _opt(
        "str",
        "dopri5",
        "dopri5: explicit adaptive Runge-Kutta; generalized_alpha: "
        "implicit, for stiff beams (ASSUMED: the paper names no integrator)",
        choices=("dopri5", "generalized_alpha"),
    ),
    "rho_inf": _num(
        0.0,
        1.0,
        default=0.9,
        doc="generalized_alpha only: spectral radius at infinity, 1 = no numerical damping "
        "(then the unresolved axial modes of short beam elements defeat Newton). Smaller damps "
        "more of the impact-excited beam vibration, which the energy audit then misses: "
        "flagship with beams, rtol 1e-4, 10 revolutions, energy error 2.6e-3 at 0.9, 1.3e-2 at "
        "0.8, 3.4e-2 at 0.5. Very stiff beams (E x 1000) want 0.5. On rigid links at 30 rpm, "
        "0.9 can settle joint A into sustained contact where DOPRI5 keeps rattling "
        "(docs/performance.md, micro-impacts): rigid links belong to dopri5",
    ),
    "rtol": _num(
        1e-13,
        1e-1,
        default=1.0e-5,
        doc="relative error tolerance per step; the default fidelity (docs/fidelity.md): the "
        "cheapest whose 200-revolution statistics (peaks, Lyapunov exponents, Poincaré points) "
        "stay within the spread of two tight references and whose energy audit stays below "
        "1e-3 (4.7e-4); 1e-6 costs 1.15 x as much, 1e-4 fails the audit (3.3e-3)",
    ),
    "atol": _num(1e-16, 1e-1, default=1.0e-7, doc="absolute error tolerance per step"),
    "max_step_fraction": _num(
        1e-7, 1.0, "crank periods", open_min=True, default=0.005, doc="largest step"
    ),
    "baumgarte_alpha": _num(
        0.0, 1e4, "1/s", default=10.0, doc="Baumgarte stabilization α of the constraints (ASSUMED)"
    ),
    "baumgarte_beta": _num(
        0.0, 1e4, "1/s", default=10.0, doc="Baumgarte stabilization β of the constraints (ASSUMED)"
    ),
    "max_steps": _opt(
        "int",
        100_000_000,
        "the run stops with a diagnosis after this many steps",
        minimum=1,
        maximum=10**12,
    ),
    "coordinates": _opt(
        "str",
        "minimal",
        "minimal: a mechanism of rigid bodies and modal "
        "links whose ideal joints form a tree integrates its joint angles and "
        "modal amplitudes (sim.model.tree; DOPRI5 only); absolute: always "
        "coordinates under multipliers",
        choices=("minimal", "absolute"),
    ),
}

OUTPUT = {
    "body": Field("str", doc="the body whose motion the analyses read"),
    "point": _opt(
        "str",
        "centre",
        "its point: the reference point, whose position, velocity and acceleration every run "
        "records",
        choices=("centre",),
    ),
    "axis": _opt("str", "y", "the global component read", choices=("x", "y")),
}
#: the output channel of a scene without `output`: the six-bar's slider along its guide
SLIDER_OUTPUT = {"body": "slider", "point": "centre", "axis": "y"}

#: Every table of keys, by the place its keys take in a scene (for the reference page).
TABLES: dict[str, dict[str, Field]] = {
    "scene": TOP,
    "materials.<name>": MATERIAL,
    "bodies.<name> (bar)": BAR,
    "bodies.<name> (block)": BLOCK,
    "bodies.<name>.hint": HINT,
    "bodies.<name>.damping": DAMPING,
    "joints.<name> (revolute)": REVOLUTE,
    "joints.<name> (translational)": TRANSLATIONAL,
    "joints.<name> (weld)": WELD,
    "drive": DRIVE,
    "contact": CONTACT,
    "simulation": SIMULATION,
    "solver": SOLVER,
    "output": OUTPUT,
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
    scene, override_problems = apply_overrides(with_defaults(raw), overrides)
    scene = with_defaults(scene)
    problems += override_problems + scene_problems(scene)
    _raise(problems, source, overrides)
    return scene


class OutputChannel(NamedTuple):
    """The channel the analyses read: a body, its point and a global axis (x or y)."""

    body: str
    point: str
    axis: str


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


def describe(field: Field) -> str:
    if field.default is None:
        return describe(replace(field, default=NO_DEFAULT)) + ", or null (computed)"
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
        raise ValueError(f"{option} = {value!r} is not accepted; expected {describe(field)}")


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
        elif not _check_value(data[key], field):
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
    if not _check_value(value, HINT["position"]):
        problems.append(
            Problem(
                where,
                f"'{where}' = {value!r} is not accepted; expected {describe(HINT['position'])}",
            )
        )


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

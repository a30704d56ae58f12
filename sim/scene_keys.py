"""The keys of a scene, declared once: for each place in a scene (`TABLES`), every key it
accepts with its type, range, unit, default and meaning (`Field`), and the checks of a value
against its `Field`. `sim.scene` loads and validates scenes with these tables; the reference
page docs/scenes.md is generated from them (`sim.scene_reference`).

Every default is declared here (`Field.default`); loading fills them in, so the resolved scene
has every key and no other module supplies a default.
"""

import math
from dataclasses import dataclass, replace
from typing import Any

from sim.model.contact_laws import (
    DEFAULT_LAW,
    DEFAULT_STIFFNESS,
    LAW_NAMES,
    STIFFNESS_LAWS,
)
from sim.quantities import SAMPLINGS


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

    kind: str  # 'number', 'int', 'str', 'bool', 'vector2', 'vector3', 'point', 'list', 'mapping'
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
#: the per-joint choice of a clearance joint's damping law (revolute and translational)
JOINT_LAW = {
    "law": _opt(
        "str",
        None,
        'damping law of this clearance joint (docs/model.md, "Contact laws"); null: the '
        "scene's `contact.law`",
        choices=LAW_NAMES,
    ),
}
REVOLUTE = {
    **JOINT_COMMON,
    **JOINT_LAW,
    "stiffness_law": _opt(
        "str",
        None,
        "stiffness law of this revolute clearance joint; null: the scene's `contact.stiffness_law`",
        choices=tuple(law.name for law in STIFFNESS_LAWS),
    ),
    "bearing_length": _num(
        0.0,
        1.0,
        "m",
        open_min=True,
        default=None,
        doc="axial length L of the bearing: Johnson's stiffness law only, which needs it "
        "(ASSUMED when given: the paper's model is planar)",
    ),
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
    "lubricant": _opt(
        "mapping",
        None,
        "an oil film in the clearance (table `joints.<name>.lubricant`, docs/model.md, "
        '"Lubricated revolute joints"); null: dry; unused when the joint is ideal',
    ),
}
LUBRICANT = {
    "viscosity": _num(1e-4, 10.0, "Pa s", doc="the oil's dynamic viscosity μ at its temperature"),
    "length": _num(
        0.0,
        1.0,
        "m",
        open_min=True,
        doc="bearing length L along the pin; L/D (D the journal's diameter) chooses the "
        "model: short bearing (Ocvirk) for L/D ≤ 0.5, long bearing (Sommerfeld) for L/D ≥ 2, "
        "a Reynolds solution tabulated for L/D between",
    ),
    "threshold": _num(
        0.0,
        1e-4,
        "m",
        open_min=True,
        default=1.5e-6,
        doc="minimum film thickness h_t below which the dry contact law takes over "
        "(smoothly, reaching it alone at zero film); below the joint's `clearance`, and for "
        "a finite bearing at least 5e-4 of it (its table's end). Default "
        "(ASSUMED): 3 σ, the film parameter Λ = h/σ = 3 where full-film lubrication ends "
        "(Hamrock, Fundamentals of Fluid Film Lubrication), σ = 0.5 µm the composite RMS "
        "roughness of a ground pin (0.35 µm) in a honed bore (0.35 µm)",
    ),
}
WELD = {
    **JOINT_COMMON,
    "points": Field("list", doc="the points held together, at the angle of the bodies' hints"),
}
TRANSLATIONAL = {
    **JOINT_COMMON,
    **JOINT_LAW,
    "guide_point": Field("vector2", -1e3, 1e3, unit="m", doc="a point of the guide's axis"),
    "guide_angle_deg": _num(-360, 360, "deg", doc="direction of the guide's axis"),
}
DRIVE = {
    "body": Field("str", doc="the crank: a rigid body turned at constant speed"),
    "speed_rpm": _num(0.0, 1e5, "rpm", open_min=True, doc="crank speed"),
    "initial_angle_deg": _num(-360, 360, "deg", default=0.0, doc="crank angle at t = 0"),
}
CONTACT = {
    "law": _opt(
        "str",
        DEFAULT_LAW,
        "damping law of every clearance joint without a `law` of its own (docs/model.md, "
        '"Contact laws"): lankarani-nikravesh (the paper\'s), hunt-crossley, flores and '
        "gonthier-carvalho remember the onset rate; tsuji has no memory",
        choices=LAW_NAMES,
    ),
    "restitution": _num(
        0.0,
        1.0,
        open_min=True,
        default=0.9,
        doc="nominal coefficient of restitution e of the damping law",
    ),
    "stiffness_law": _opt(
        "str",
        DEFAULT_STIFFNESS,
        "stiffness law of every revolute clearance joint without one of its own: hertz (point "
        "contact, the paper's) or johnson (conformal cylinders, needs the joint's "
        "`bearing_length`); slider corners and faces keep theirs",
        choices=tuple(law.name for law in STIFFNESS_LAWS),
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
        doc="guard of the damping laws with memory for resting or grazing contact (ASSUMED)",
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
    "sampling": _opt(
        "str",
        "mean",
        "mean: the fast quantities (accelerations, drive torque, contact forces, deflections) "
        "are recorded as means over each sample's window, free of aliasing; point: every "
        "quantity is its value at the sample time (sim.quantities says which is which)",
        choices=SAMPLINGS,
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
        "point",
        "centre",
        "its point whose position, velocity and acceleration the run records as "
        "`output_position`, `output_velocity` and `output_acceleration`: a named point of the "
        "body (`centre`, a bar's `start` and `end`, its own `points`; a beam's `start`, "
        "`centre`, `end`) or [x, y] in the body's frame (m; rigid bodies and modal links)",
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
    "joints.<name>.lubricant": LUBRICANT,
    "joints.<name> (translational)": TRANSLATIONAL,
    "joints.<name> (weld)": WELD,
    "drive": DRIVE,
    "contact": CONTACT,
    "simulation": SIMULATION,
    "solver": SOLVER,
    "output": OUTPUT,
}


def describe(field: Field) -> str:
    if field.default is None:
        return describe(replace(field, default=NO_DEFAULT)) + ", or null (computed)"
    if field.choices:
        return "one of " + ", ".join(repr(c) for c in field.choices)
    lo = "" if field.minimum is None else f"{field.minimum:g} {'<' if field.open_min else '≤'} "
    hi = "" if field.maximum is None else f" ≤ {field.maximum:g}"
    unit = f" ({field.unit})" if field.unit else ""
    if field.kind == "point":
        return "a point's name or [x, y] in the body's frame (m)"
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


def check_value(value: Any, field: Field) -> bool:
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
    if field.kind == "point":
        return isinstance(value, str) or check_value(value, replace(field, kind="vector2"))
    if field.kind == "list":
        return isinstance(value, list)
    return isinstance(value, dict)


def check_option(option: str, value: Any, field: Field) -> None:
    """Raise ValueError naming a command-line option whose value `field` does not accept, in
    the words of a scene key's message (`sim` reports it with exit code 2)."""
    if not check_value(value, field):
        raise ValueError(f"{option} = {value!r} is not accepted; expected {describe(field)}")

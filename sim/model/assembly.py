"""From a validated scene to a `System`, and the initial state.

Modelling only what a scene needs: a joint whose clearance is 0 becomes an
ideal constraint, a body of kind 'rigid' three coordinates, one of kind 'modal'
three plus its modes (`sim.model.modal`). `ideal=True` and
`rigid=True` build the all-ideal, all-rigid mechanism of the same scene, which
the initial position analysis solves and the studies use as the reference.
"""

import math

from sim.model.builder import Layout, SystemBuilder
from sim.model.contact import (
    corner_stiffness,
    effective_modulus,
    face_stiffness,
    revolute_stiffness,
)
from sim.model.contact_laws import (
    LAW_CODES,
    LAWS,
    STIFFNESS_CODES,
    STIFFNESS_JOHNSON,
    damping_coefficient,
)
from sim.model.system import (
    CON_PRISMATIC,
    CON_REVOLUTE,
    CON_WELD,
    SLIDER_LAWS,
    ContactLaw,
    System,
)
from sim.model.tree import spanning_tree
from sim.scene import GROUND, output_channel


class AssemblyError(RuntimeError):
    """The linkage cannot be put together as described."""


def body_mass_properties(body: dict, material: dict) -> tuple[float, float]:
    """Mass (kg) and centroidal inertia (kg m²) of a rigid body; docs/model.md:
    bars m = ρ A L, J = m L²/12; blocks m = ρ L W D, J = m (L² + W²)/12,
    unless the scene gives `mass` / `inertia`."""
    rho = material["density"]
    if body["shape"] == "bar":
        length = body["length"]
        m = rho * body["section"][0] * body["section"][1] * length
        j = m * length**2 / 12.0
    else:
        length, width, depth = body["size"]
        m = rho * length * width * depth
        j = m * (length**2 + width**2) / 12.0
    m = m if body["mass"] is None else body["mass"]
    return m, j if body["inertia"] is None else body["inertia"]


def stiffness_damping_coefficient(body: dict, material: dict) -> float:
    """The stiffness-proportional (Rayleigh) damping coefficient β (s) of a beam.

    `damping.kind: stiffness` gives β directly. `damping.kind: modal` gives a
    damping ratio ζ at the link's first bending mode, pinned at both ends,
    ω₁ = (π/L)² √(EI/ρA) (Euler–Bernoulli), so β = 2ζ/ω₁; being
    stiffness-proportional, a mode of frequency ω gets ζ ω/ω₁."""
    damping = body["damping"]
    if damping["kind"] == "stiffness":
        return damping["coefficient"]
    if damping["kind"] == "modal":
        width, height = body["section"]
        area = width * height
        omega1 = (math.pi / body["length"]) ** 2 * math.sqrt(
            material["youngs_modulus"] * width * height**3 / 12.0 / (material["density"] * area)
        )
        return 2.0 * damping["ratio"] / omega1
    return 0.0


def local_points(body: dict) -> dict[str, tuple[float, float]]:
    """Every named point of a rigid body or modal link in its frame (m): `centre` at the
    origin, a bar's `start` and `end` on its axis, and the scene's `points`."""
    pts = {"centre": (0.0, 0.0)}
    if body["shape"] == "bar":
        half = 0.5 * body["length"]
        pts.update(start=(-half, 0.0), end=(half, 0.0))
    pts.update({k: tuple(v) for k, v in body["points"].items()})
    return pts


def _joint_modulus(scene: dict, names: list[str]) -> float:
    """E* of the two bodies' materials; the ground takes its partner's material
    (an assumption listed in the scene)."""
    mats = [scene["materials"][scene["bodies"][n]["material"]] for n in names if n != GROUND]
    if len(mats) == 1:
        mats = mats * 2
    return effective_modulus(
        mats[0]["youngs_modulus"], mats[0]["poisson"], mats[1]["youngs_modulus"], mats[1]["poisson"]
    )


def build_system(scene: dict, *, ideal: bool = False, rigid: bool = False) -> tuple[System, Layout]:
    """Compile `scene` (validated, defaults filled) into arrays with a `SystemBuilder`:
    bodies in the scene's order, then its joints, then the drive. ideal/rigid force
    every joint ideal / every link rigid. With `solver.coordinates: minimal` and DOPRI5, a
    mechanism of rigid bodies and modal links whose ideal joints form a tree gets its hinges
    (sim.model.tree)."""
    contact = scene["contact"]
    builder = SystemBuilder(
        scene["gravity"],
        (scene["solver"]["baumgarte_alpha"], scene["solver"]["baumgarte_beta"]),
        ContactLaw(
            *(float(contact[f]) for f in ContactLaw._fields[:-1]),
            slider_law=SLIDER_LAWS[contact["slider_law"]],
        ),
        scene["ground"],
    )
    for name, body in scene["bodies"].items():
        _add_body(builder, name, body, scene["materials"][body["material"]], rigid)
    for name, joint in scene["joints"].items():
        _add_joint(builder, scene, name, joint, ideal)
    d = scene["drive"]
    builder.add_drive(d["body"], math.radians(d["initial_angle_deg"]), omega(scene))
    if scene.get("output") or "slider" in scene["bodies"]:  # else: the first body's centre
        channel = output_channel(scene)
        builder.set_output(channel.body, channel.point, "output.point")
    system, layout = builder.freeze()
    solver = scene["solver"]
    if solver["coordinates"] == "minimal" and solver["method"] == "dopri5":
        # generalized-α keeps the multiplier form: its Newton iteration is built on Φ_q
        system = system._replace(tree=spanning_tree(system))
    return system, layout


def _add_body(builder: SystemBuilder, name: str, body: dict, mat: dict, rigid: bool) -> None:
    """Body `name` of the scene, as its kind asks (rigid when `rigid`)."""
    kind = "rigid" if rigid else body["kind"]
    if kind == "beam":
        width, height = body["section"]
        builder.add_beam(
            name,
            body["length"],
            body["elements"],
            mat["density"] * (width * height),
            mat["youngs_modulus"] * (width * height),
            mat["youngs_modulus"] * (width * height**3 / 12.0),
            stiffness_damping_coefficient(body, mat),
        )
        return
    m, j = body_mass_properties(body, mat)
    if kind == "modal":
        width, height = body["section"]
        builder.add_modal_link(
            name,
            m,
            j,
            local_points(body),
            body["length"],
            mat["density"] * width * height,
            mat["youngs_modulus"] * width * height**3 / 12.0,
            mat["youngs_modulus"] * width * height,
            stiffness_damping_coefficient(body, mat),
            body["modes"],
            body["axial_modes"],
        )
        return
    builder.add_rigid_body(name, m, j, local_points(body))


def _add_joint(builder: SystemBuilder, scene: dict, name: str, joint: dict, ideal: bool) -> None:
    """Joint `name` of the scene: ideal when its clearance is 0 (or `ideal`), else a
    clearance joint."""
    pair = joint["bodies"]
    clearance = 0.0 if ideal else joint["clearance"]
    bodies = scene["bodies"]
    if joint["type"] == "translational":
        guide = (*joint["guide_point"], math.radians(joint["guide_angle_deg"]))
        slider = pair[1]
        if clearance == 0.0:
            builder.add_constraint(
                name, CON_PRISMATIC, (builder.body(slider, f"joints.{name}").offset,), guide
            )
            return
        length, width, depth = bodies[slider]["size"]
        mat = scene["materials"][bodies[slider]["material"]]
        e, nu = mat["youngs_modulus"], mat["poisson"]
        k_face = face_stiffness(length + depth, e, nu, e, nu)
        k_corner = corner_stiffness(scene["contact"]["corner_radius"], _joint_modulus(scene, pair))
        law = joint_law(scene, joint)
        mass = effective_mass(scene, pair)
        exponent = scene["contact"]["exponent"]
        damping = (
            LAW_CODES[law],
            _damping(scene, law, exponent, mass, k_corner),
            _damping(scene, law, 1.0, mass, k_face),
        )
        builder.add_slider_clearance(
            name, slider, guide, length, width, width + 2.0 * clearance, k_face, k_corner, damping
        )
        return
    where = f"joints.{name}.points"
    p0 = builder.add_point(pair[0], joint["points"][0], where)
    p1 = builder.add_point(pair[1], joint["points"][1], where)
    if joint["type"] == "weld":
        _add_weld(builder, scene, name, joint, p0, p1)
    elif clearance == 0.0:
        builder.add_constraint(name, CON_REVOLUTE, (p0, p1))
    else:
        r_b = joint["bearing_radius"]
        stiffness = revolute_stiffness_law(scene, name, joint, clearance)
        law = joint_law(scene, joint)
        if stiffness[0] == STIFFNESS_JOHNSON and not LAWS[LAW_CODES[law]].memory:
            raise AssemblyError(
                f"joints.{name}: the damping law '{law}' has no memory and needs a power-law "
                "stiffness; Johnson's law is not one (choose stiffness_law: hertz)"
            )
        coefficient = _damping(
            scene, law, scene["contact"]["exponent"], effective_mass(scene, pair), stiffness[1]
        )
        builder.add_revolute_clearance(
            name,
            p0,
            p1,
            r_b,
            clearance,
            stiffness,
            (LAW_CODES[law], coefficient),
            joint["lubricant"],
        )


def joint_law(scene: dict, joint: dict) -> str:
    """The damping law of a clearance joint: its own `law`, else the scene's `contact.law`."""
    return joint["law"] or scene["contact"]["law"]


def _damping(scene: dict, law: str, exponent: float, mass: float, stiffness: float) -> float:
    """The coefficient a joint stores for damping law `law` (sim.model.contact_laws)."""
    return damping_coefficient(law, scene["contact"]["restitution"], exponent, mass, stiffness)


def effective_mass(scene: dict, names: list[str]) -> float:
    """m* = m₁ m₂ / (m₁ + m₂) (kg) of the two bodies a clearance joint joins, each body's
    whole mass (the ground's infinite): the mass scale of the damping law without memory
    (an assumption, docs/assumptions.md)."""
    bodies = scene["bodies"]
    inverse = sum(
        1.0 / body_mass_properties(bodies[n], scene["materials"][bodies[n]["material"]])[0]
        for n in names
        if n != GROUND
    )
    return 1.0 / inverse


def revolute_stiffness_law(
    scene: dict, name: str, joint: dict, clearance: float
) -> tuple[int, float]:
    """The stiffness law's code and stiffness of revolute clearance `name`: Hertz K
    (N/m^n) or Johnson's line stiffness π L E* (N/m), by the joint's `stiffness_law`, else
    the scene's `contact.stiffness_law`."""
    code = STIFFNESS_CODES[joint["stiffness_law"] or scene["contact"]["stiffness_law"]]
    r_b = joint["bearing_radius"]
    e_star = _joint_modulus(scene, joint["bodies"])
    if code == STIFFNESS_JOHNSON:
        if joint["bearing_length"] is None:
            raise AssemblyError(
                f"joints.{name}: Johnson's stiffness law needs 'joints.{name}.bearing_length' "
                "(the bearing's axial length, m)"
            )
        return code, math.pi * joint["bearing_length"] * e_star
    return code, revolute_stiffness(r_b, r_b - clearance, e_star)


def _add_weld(
    builder: SystemBuilder, scene: dict, name: str, joint: dict, p0: int, p1: int
) -> None:
    """A weld of rigid bodies (the scene accepts no other): to the ground it is a clamp
    at the body's hint angle; between two bodies it keeps their relative angle at the
    hints'."""
    pair = joint["bodies"]
    bodies = scene["bodies"]
    if pair[0] == GROUND:
        theta = math.radians(bodies[pair[1]]["hint"]["angle_deg"])
        position = scene["ground"][joint["points"][0]]
        builder.add_clamp(name, pair[1], joint["points"][1], position, theta)
        return
    o1 = builder.body(pair[1], f"joints.{name}").offset
    o0 = builder.body(pair[0], f"joints.{name}").offset
    rel = math.radians(bodies[pair[1]]["hint"]["angle_deg"] - bodies[pair[0]]["hint"]["angle_deg"])
    builder.add_constraint(name, CON_WELD, (p0, p1, o0, o1), (rel,))


def omega(scene: dict) -> float:
    """Crank speed ω (rad/s) from drive.speed_rpm."""
    return 2.0 * math.pi * scene["drive"]["speed_rpm"] / 60.0


def crank_period(scene: dict) -> float:
    """Duration (s) of one crank revolution."""
    return 2.0 * math.pi / omega(scene)

"""From a validated scene to a `System`, and the initial state.

Modelling only what a scene needs: a joint whose clearance is 0 becomes an
ideal constraint, a body of kind 'rigid' three coordinates, one of kind 'modal'
three plus its modes (`sim.model.modal`). `ideal=True` and
`rigid=True` build the all-ideal, all-rigid mechanism of the same scene, which
the initial position analysis solves and the studies use as the reference.
"""

import math
from dataclasses import dataclass, field

import numpy as np

from sim.model import ancf, beams, modal
from sim.model.contact import (
    corner_stiffness,
    effective_modulus,
    face_stiffness,
    revolute_stiffness,
)
from sim.model.system import (
    CON_CLAMP,
    CON_CLAMP_NODE,
    CON_DRIVE,
    CON_PRISMATIC,
    CON_REVOLUTE,
    CON_ROWS,
    CON_WELD,
    POINT_GROUND,
    POINT_MODAL,
    POINT_NODE,
    POINT_RIGID,
    SLIDER_LAWS,
    System,
)
from sim.scene import GROUND, SceneError


class AssemblyError(RuntimeError):
    """The linkage cannot be put together as described."""


@dataclass
class Layout:
    """Names and coordinate offsets behind a `System`, for input and output."""

    bodies: list[str]
    offset: dict[str, int]
    is_beam: dict[str, bool]
    elements: dict[str, int]
    clearance_joints: list[str]  # revolute clearances first, then translational
    constraint_rows: list[tuple[str, int, int]]  # (joint or 'drive', first row, rows)
    points: dict[tuple[str, str], int] = field(default_factory=dict)
    modes: dict[str, int] = field(default_factory=dict)  # modal links' mode counts, else 0

    def joint_of_row(self, row: int) -> str:
        """The joint (or 'drive') that owns constraint row `row`."""
        for name, first, count in self.constraint_rows:
            if first <= row < first + count:
                return name
        raise IndexError(row)


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


def _local_points(body: dict) -> dict[str, tuple[float, float]]:
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
    """Compile `scene` into arrays. ideal/rigid force every joint ideal / every link rigid."""
    bodies = scene["bodies"]
    names = list(bodies)
    offset: dict[str, int] = {}
    is_beam: dict[str, bool] = {}
    elements: dict[str, int] = {}
    modes: dict[str, int] = {}
    n = 0
    for name in names:
        beam = bodies[name]["kind"] == "beam" and not rigid
        offset[name] = n
        is_beam[name] = beam
        elements[name] = bodies[name]["elements"] if beam else 0
        modal_link = bodies[name]["kind"] == "modal" and not rigid
        modes[name] = bodies[name]["modes"] if modal_link else 0
        n += 4 * (elements[name] + 1) if beam else 3 + modes[name]

    mass = np.zeros((n, n))
    gravity_force = np.zeros(n)
    g = np.asarray(scene["gravity"], dtype=float)
    blocks = []
    ref_idx = np.zeros((len(names), 4), dtype=np.int64)
    ref_coef = np.zeros((len(names), 4))
    ang_idx = np.zeros((len(names), 2), dtype=np.int64)
    beam_off, beam_nel, beam_f = [], [], []
    md = _ModalLinks()
    for b, name in enumerate(names):
        body = bodies[name]
        mat = scene["materials"][body["material"]]
        o = offset[name]
        if is_beam[name]:
            ne = elements[name]
            size = 4 * (ne + 1)
            area = body["section"][0] * body["section"][1]
            inertia = body["section"][0] * body["section"][1] ** 3 / 12.0
            rho_a = mat["density"] * area
            mass[o : o + size, o : o + size] = ancf.beam_mass_matrix(rho_a, body["length"], ne)
            gravity_force[o : o + size] = beams.beam_gravity_force(rho_a, body["length"], ne, g)
            blocks.append((o, o + size))
            el, shape = beams.midpoint_shape(body["length"], ne)
            ref_idx[b] = o + 4 * el + np.array([0, 2, 4, 6])
            ref_coef[b] = shape
            ang_idx[b] = (o, o + 4 * ne)
            beta = stiffness_damping_coefficient(body, mat)
            beam_off.append(o)
            beam_nel.append(ne)
            beam_f.append(
                (
                    body["length"] / ne,
                    mat["youngs_modulus"] * area,
                    mat["youngs_modulus"] * inertia,
                    beta,
                )
            )
        else:
            m, j = body_mass_properties(body, mat)
            mass[o, o] = mass[o + 1, o + 1] = m
            mass[o + 2, o + 2] = j
            # Mass-normalised modes: unit modal masses (sim.model.modal).
            for k in range(modes[name]):
                mass[o + 3 + k, o + 3 + k] = 1.0
            gravity_force[o : o + 2] = m * g
            blocks.append((o, o + 3 + modes[name]))
            ref_idx[b] = o
            ref_coef[b, 0] = 1.0
            ang_idx[b] = (o + 2, o + 2)
            if modes[name]:
                md.add(b, o, body, mat, modes[name])

    points: dict[tuple[str, str], int] = {}
    pt_kind, pt_off, pt_u, pt_modes, pt_modal = [], [], [], [], []

    def point(body: str, pname: str) -> int:
        key = (body, pname)
        if key not in points:
            points[key] = len(pt_kind)
            pt_modes.append(0)
            pt_modal.append(np.zeros((2, modal.MAX_MODES)))
            if body == GROUND:
                pt_kind.append(POINT_GROUND)
                pt_off.append(0)
                pt_u.append(tuple(scene["ground"][pname]))
            elif is_beam[body]:
                pt_kind.append(POINT_NODE)
                pt_off.append(offset[body] + (0 if pname == "start" else 4 * elements[body]))
                pt_u.append((0.0, 0.0))
            else:
                pt_kind.append(POINT_MODAL if modes[body] else POINT_RIGID)
                pt_off.append(offset[body])
                pt_u.append(_local_points(bodies[body])[pname])
                if modes[body]:
                    pt_modes[-1] = modes[body]
                    pt_modal[-1] = modal.point_coefficients(
                        pt_u[-1], bodies[body]["length"], _rho_a(scene, bodies[body]), modes[body]
                    )
        return points[key]

    con_type, con_row, con_i, con_f = [], [], [], []
    rows: list[tuple[str, int, int]] = []
    rj_pts, rj_f, tj_off, tj_f = [], [], [], []
    rev_names, trans_names = [], []
    m_rows = 0

    def constraint(owner: str, kind: int, ints=(0, 0, 0, 0), floats=(0.0, 0.0, 0.0)) -> None:
        nonlocal m_rows
        con_type.append(kind)
        con_row.append(m_rows)
        con_i.append(tuple(ints) + (0,) * (4 - len(ints)))
        con_f.append(tuple(floats) + (0.0,) * (3 - len(floats)))
        rows.append((owner, m_rows, CON_ROWS[kind]))
        m_rows += CON_ROWS[kind]

    contact = scene["contact"]
    for jname, joint in scene["joints"].items():
        pair = joint["bodies"]
        clearance = 0.0 if ideal else joint["clearance"]
        if joint["type"] == "translational":
            slider = pair[1]
            angle = math.radians(joint["guide_angle_deg"])
            px, py = joint["guide_point"]
            if clearance == 0.0:
                constraint(jname, CON_PRISMATIC, (offset[slider],), (px, py, angle))
                continue
            length, width, depth = bodies[slider]["size"]
            mat = scene["materials"][bodies[slider]["material"]]
            e, nu = mat["youngs_modulus"], mat["poisson"]
            tj_off.append(offset[slider])
            tj_f.append(
                (
                    px,
                    py,
                    angle,
                    length,
                    width,
                    width + 2.0 * clearance,
                    face_stiffness(length + depth, e, nu, e, nu),
                    corner_stiffness(contact["corner_radius"], _joint_modulus(scene, pair)),
                )
            )
            trans_names.append(jname)
            continue
        p0 = point(pair[0], joint["points"][0])
        p1 = point(pair[1], joint["points"][1])
        if joint["type"] == "weld":
            _weld(scene, jname, joint, p0, p1, offset, is_beam, constraint)
            continue
        if clearance == 0.0:
            constraint(jname, CON_REVOLUTE, (p0, p1))
            continue
        r_b = joint["bearing_radius"]
        r_j = r_b - clearance
        rj_pts.append((p0, p1))
        rj_f.append(
            (r_b, r_j, clearance, revolute_stiffness(r_b, r_j, _joint_modulus(scene, pair)))
        )
        rev_names.append(jname)

    drive_row = drive_coord = -1
    if "drive" in scene:
        d = scene["drive"]
        drive_coord = offset[d["body"]] + 2
        drive_row = m_rows
        constraint(
            "drive", CON_DRIVE, (drive_coord,), (math.radians(d["initial_angle_deg"]), omega(scene))
        )

    mass_inv = np.zeros_like(mass)
    for s, e in blocks:
        mass_inv[s:e, s:e] = np.linalg.inv(mass[s:e, s:e])
    system = System(
        n=n,
        m=m_rows,
        mass=mass,
        mass_inv=mass_inv,
        blk_start=np.array([s for s, _ in blocks], dtype=np.int64),
        blk_end=np.array([e for _, e in blocks], dtype=np.int64),
        gravity_force=gravity_force,
        pt_kind=np.array(pt_kind, dtype=np.int64),
        pt_off=np.array(pt_off, dtype=np.int64),
        pt_u=np.array(pt_u, dtype=float).reshape(-1, 2),
        pt_modes=np.array(pt_modes, dtype=np.int64),
        pt_modal=np.array(pt_modal, dtype=float).reshape(-1, 2, modal.MAX_MODES),
        con_type=np.array(con_type, dtype=np.int64),
        con_row=np.array(con_row, dtype=np.int64),
        con_i=np.array(con_i, dtype=np.int64).reshape(-1, 4),
        con_f=np.array(con_f, dtype=float).reshape(-1, 3),
        baumgarte=np.array([scene["solver"]["baumgarte_alpha"], scene["solver"]["baumgarte_beta"]]),
        drive_row=drive_row,
        drive_coord=drive_coord,
        rj_pts=np.array(rj_pts, dtype=np.int64).reshape(-1, 2),
        rj_f=np.array(rj_f, dtype=float).reshape(-1, 4),
        tj_off=np.array(tj_off, dtype=np.int64),
        tj_f=np.array(tj_f, dtype=float).reshape(-1, 8),
        contact=np.array(
            [
                contact["restitution"],
                contact["friction"],
                contact["v0"],
                contact["v1"],
                contact["min_impact_speed"],
                contact["exponent"],
                SLIDER_LAWS[contact["slider_law"]],
            ]
        ),
        beam_off=np.array(beam_off, dtype=np.int64),
        beam_nel=np.array(beam_nel, dtype=np.int64),
        beam_f=np.array(beam_f, dtype=float).reshape(-1, 4),
        **_stacked_beam_constants(beam_f),
        **md.arrays(),
        ref_idx=ref_idx,
        ref_coef=ref_coef,
        ang_idx=ang_idx,
        body_is_beam=np.array([1 if is_beam[nm] else 0 for nm in names], dtype=np.int64),
        body_modal=np.array([md.index.get(b, -1) for b in range(len(names))], dtype=np.int64),
    )
    layout = Layout(names, offset, is_beam, elements, rev_names + trans_names, rows, points, modes)
    return system, layout


def _rho_a(scene: dict, body: dict) -> float:
    """Mass per unit length ρA (kg/m) of a bar."""
    return scene["materials"][body["material"]]["density"] * body["section"][0] * body["section"][1]


class _ModalLinks:
    """The modal links' arrays of a `System` (md_*), gathered body by body."""

    def __init__(self) -> None:
        self.index: dict[int, int] = {}
        self.rows: list[tuple] = []

    def add(self, b: int, offset: int, body: dict, material: dict, modes: int) -> None:
        """Body b (coordinates from `offset`), a bar of kind 'modal' with `modes` modes."""
        length = body["length"]
        width, height = body["section"]
        rho_a = material["density"] * width * height
        ei = material["youngs_modulus"] * width * height**3 / 12.0
        omega = np.zeros(modal.MAX_MODES)
        omega[:modes] = modal.frequencies(length, rho_a, ei, modes)
        shape = np.zeros((3, modal.MAX_MODES))
        for i, x_bar in enumerate((-0.5 * length, 0.0, 0.5 * length)):
            shape[i, :modes] = modal.mode_shapes(x_bar, length, rho_a, modes)
        beta = stiffness_damping_coefficient(body, material)
        self.index[b] = len(self.rows)
        self.rows.append((offset, modes, omega, beta, shape, length))

    def arrays(self) -> dict:
        """The md_* fields of `System`."""
        cols = list(zip(*self.rows, strict=True)) or [()] * 6
        return {
            "md_off": np.array(cols[0], dtype=np.int64),
            "md_modes": np.array(cols[1], dtype=np.int64),
            "md_omega": np.array(cols[2], dtype=float).reshape(-1, modal.MAX_MODES),
            "md_beta": np.array(cols[3], dtype=float),
            "md_shape": np.array(cols[4], dtype=float).reshape(-1, 3, modal.MAX_MODES),
            "md_length": np.array(cols[5], dtype=float),
        }


def _stacked_beam_constants(beam_f: list[tuple[float, float, float, float]]) -> dict:
    """The ANCF quadrature constants of every beam, stacked along a first axis."""
    consts = [ancf.beam_constants(l, ea, ei) for l, ea, ei, _ in beam_f]
    fields = {
        "beam_dshape": ("dshape", (ancf.AXIAL_GAUSS_POINTS, 4)),
        "beam_axial_w": ("axial_weight", (ancf.AXIAL_GAUSS_POINTS,)),
        "beam_d2shape": ("d2shape", (ancf.BENDING_GAUSS_POINTS, 4)),
        "beam_bending_w": ("bending_weight", (ancf.BENDING_GAUSS_POINTS,)),
    }
    return {
        key: np.array([getattr(c, name) for c in consts], dtype=float).reshape(-1, *shape)
        for key, (name, shape) in fields.items()
    }


def _weld(scene, jname, joint, p0, p1, offset, is_beam, constraint) -> None:
    """A weld: to the ground it is a clamp of the body's pose at its hint (rigid)
    or of the node's position and slope (beam); between rigid bodies it keeps
    their relative angle at the hints'."""
    pair = joint["bodies"]
    bodies = scene["bodies"]
    if pair[0] == GROUND:
        body = bodies[pair[1]]
        theta = math.radians(body["hint"]["angle_deg"])
        gx, gy = scene["ground"][joint["points"][0]]
        if is_beam[pair[1]]:
            node = offset[pair[1]] + (0 if joint["points"][1] == "start" else 4 * body["elements"])
            constraint(jname, CON_CLAMP_NODE, (node,), (gx, gy, theta))
            return
        ux, uy = _local_points(body)[joint["points"][1]]
        c, s = math.cos(theta), math.sin(theta)
        constraint(
            jname,
            CON_CLAMP,
            (offset[pair[1]],),
            (gx - c * ux + s * uy, gy - s * ux - c * uy, theta),
        )
        return
    if is_beam[pair[0]] or is_beam[pair[1]]:
        raise SceneError(f"joints.{jname}: a weld between two bodies needs both rigid")
    rel = math.radians(bodies[pair[1]]["hint"]["angle_deg"] - bodies[pair[0]]["hint"]["angle_deg"])
    constraint(jname, CON_WELD, (p0, p1, offset[pair[0]], offset[pair[1]]), (rel,))


def omega(scene: dict) -> float:
    """Crank speed ω (rad/s) from drive.speed_rpm."""
    return 2.0 * math.pi * scene["drive"]["speed_rpm"] / 60.0


def crank_period(scene: dict) -> float:
    """Duration (s) of one crank revolution."""
    return 2.0 * math.pi / omega(scene)

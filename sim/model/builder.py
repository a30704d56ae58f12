"""Put a `System` together one body, point and joint at a time.

`SystemBuilder` knows nothing about scene files: `sim.model.assembly` walks a
scene and calls it. Each body kind is one `add_*` method (its coordinates, mass
block, gravity force, reference point and angle) plus one branch of `add_point`
(how its points move); each joint kind one method. `freeze` stacks what was added
into the arrays of `System` (sim/model/system.py) and the `Layout` that names them.
"""

import math
from dataclasses import dataclass, field

import numpy as np

from sim.model import ancf, beams, modal
from sim.model.lubrication import FILM, film_parameters, film_tables
from sim.model.system import (
    BEAM,
    CON_CLAMP,
    CON_CLAMP_NODE,
    CON_DRIVE,
    CON_ROWS,
    POINT_GROUND,
    POINT_MODAL,
    POINT_NODE,
    POINT_RIGID,
    REVOLUTE_CLEARANCE,
    TRANSLATIONAL_CLEARANCE,
    ContactLaw,
    System,
)
from sim.model.tree import HINGE
from sim.scene import GROUND, SceneError


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
    axial_modes: dict[str, int] = field(default_factory=dict)  # the axial ones among them

    def joint_of_row(self, row: int) -> str:
        """The joint (or 'drive') that owns constraint row `row`."""
        for name, first, count in self.constraint_rows:
            if first <= row < first + count:
                return name
        raise IndexError(row)


@dataclass(frozen=True)
class _Body:
    """What `add_point` needs to know of a body added earlier."""

    offset: int
    points: dict[str, tuple[float, float]]  # body-frame points (rigid and modal bodies)
    elements: int = 0  # > 0 for an ANCF beam
    modes: int = 0  # > 0 for a modal link
    length: float = 0.0  # m, modal links
    rho_a: float = 0.0  # kg/m, modal links
    axial: int = 0  # axial modes among a modal link's `modes` (the last ones)


class SystemBuilder:
    """Collects bodies, points, constraints, clearance joints and the drive of one system.

    Lengths in m, masses in kg, angles in rad, stiffnesses in the units of `System`.
    Bodies come first (their coordinates are numbered in the order added), then
    points and joints; `freeze` returns the compiled `System` and its `Layout`.
    """

    def __init__(
        self,
        gravity: tuple[float, float],
        baumgarte: tuple[float, float],
        contact: ContactLaw,
        ground: dict[str, tuple[float, float]],
    ) -> None:
        self._g = np.asarray(gravity, dtype=float)
        self._baumgarte = np.array(baumgarte, dtype=float)
        self._contact = contact
        self._ground = ground
        self._bodies: dict[str, _Body] = {}
        self._blocks: list[tuple[int, np.ndarray, np.ndarray]] = []  # offset, M block, Q_g
        self._ref: list[tuple[np.ndarray, np.ndarray, tuple[int, int]]] = []
        self._beams: list[tuple[int, int, tuple[float, float, float, float]]] = []
        self._modal: list[tuple] = []
        self._points: dict[tuple[str, str], int] = {}
        self._pt: list[tuple[int, int, tuple[float, float], int, np.ndarray]] = []
        self._con: list[tuple[int, int, tuple, tuple]] = []
        self._rows: list[tuple[str, int, int]] = []
        self._m = 0
        self._rj: list[tuple[str, tuple[int, int], tuple[float, ...]]] = []
        self._rj_film: list[tuple] = []  # FILM rows, one for each of _rj
        self._tj: list[tuple[str, int, tuple[float, ...]]] = []
        self._drive = (-1, -1)
        # (point, body) of the output point (`set_output`); by default the first body's centre
        self._output = (-1, 0)
        self._n = 0

    # Bodies ------------------------------------------------------------------------

    def _new_body(self, name: str, size: int) -> int:
        if name == GROUND:
            raise SceneError(f"bodies.{GROUND}: the name is reserved for the ground")
        if name in self._bodies:
            raise SceneError(f"bodies.{name}: added twice")
        offset = self._n
        self._n += size
        return offset

    def add_rigid_body(
        self, name: str, mass: float, inertia: float, points: dict[str, tuple[float, float]]
    ) -> int:
        """A rigid body, coordinates (x, y, θ) of its centre of mass; returns its offset."""
        return self._add_framed(name, mass, inertia, points, 0, ())

    def add_modal_link(
        self,
        name: str,
        mass: float,
        inertia: float,
        points: dict[str, tuple[float, float]],
        length: float,
        rho_a: float,
        ei: float,
        ea: float,
        beta: float,
        modes: int,
        axial: int = 0,
    ) -> int:
        """A modal link (sim.model.modal): (x, y, θ) of its mean-axis frame, then `modes`
        free–free bending modes and `axial` free–free axial modes of a bar of `length`, ρA
        (kg/m), EI (N m²), EA (N), stiffness damping β (s); returns its offset."""
        omega = np.zeros(modal.MAX_MODES)
        omega[:modes] = modal.frequencies(length, rho_a, ei, modes)
        omega[modes : modes + axial] = modal.axial_frequencies(length, rho_a, ea, axial)
        # transverse shapes at start, middle and end (the axial modes have none)
        shape = np.zeros((3, modal.MAX_MODES))
        for i, x_bar in enumerate((-0.5 * length, 0.0, 0.5 * length)):
            shape[i, :modes] = modal.mode_shapes(x_bar, length, rho_a, modes)
        link = (omega, beta, shape, length)
        return self._add_framed(name, mass, inertia, points, modes + axial, link, rho_a, axial)

    def _add_framed(self, name, mass, inertia, points, modes, link, rho_a=0.0, axial=0) -> int:
        """A body whose first coordinates are (x, y, θ) of a frame, then `modes` modal ones
        (the last `axial` of them axial)."""
        o = self._new_body(name, 3 + modes)
        block = np.zeros((3 + modes, 3 + modes))
        block[0, 0] = block[1, 1] = mass
        block[2, 2] = inertia
        # Mass-normalised modes: unit modal masses (sim.model.modal).
        for k in range(modes):
            block[3 + k, 3 + k] = 1.0
        gravity = np.zeros(3 + modes)
        gravity[:2] = mass * self._g
        self._blocks.append((o, block, gravity))
        self._ref.append((np.full(4, o), np.array([1.0, 0.0, 0.0, 0.0]), (o + 2, o + 2)))
        if modes:
            self._modal.append((o, modes, *link))
        length = link[3] if modes else 0.0
        self._bodies[name] = _Body(o, points, 0, modes, length, rho_a, axial)
        return o

    def add_beam(
        self,
        name: str,
        length: float,
        elements: int,
        rho_a: float,
        ea: float,
        ei: float,
        beta: float,
    ) -> int:
        """An ANCF beam of `elements` elements (sim.model.ancf), coordinates per node
        (r_x, r_y, ∂r_x/∂x, ∂r_y/∂x); EA in N, EI in N m², damping β in s; returns its offset."""
        size = 4 * (elements + 1)
        o = self._new_body(name, size)
        gravity = beams.beam_gravity_force(rho_a, length, elements, self._g)
        self._blocks.append((o, ancf.beam_mass_matrix(rho_a, length, elements), gravity))
        el, shape = beams.midpoint_shape(length, elements)
        self._ref.append((o + 4 * el + np.array([0, 2, 4, 6]), shape, (o, o + 4 * elements)))
        self._beams.append((o, elements, (length / elements, ea, ei, beta)))
        self._bodies[name] = _Body(o, {}, elements)
        return o

    def body(self, name: str, where: str) -> _Body:
        """The body `name`, added earlier; `where` names the scene key asking for it."""
        if name not in self._bodies:
            raise SceneError(f"{where}: unknown body {name!r}; known: {sorted(self._bodies)}")
        return self._bodies[name]

    # Points and joints ---------------------------------------------------------------

    def add_point(self, body: str, name: str | list[float], where: str) -> int:
        """Index of point `name` of `body` (or of the ground), added on first use; `name`
        may also be [x, y] in the frame of a rigid body or modal link (m)."""
        named = isinstance(name, str)
        key = (body, name if named else tuple(name))
        if key in self._points:
            return self._points[key]
        coeff = np.zeros((2, modal.MAX_MODES))
        if body == GROUND:
            if name not in self._ground:
                raise SceneError(f"{where}: the ground has no point {name!r}")
            point = (POINT_GROUND, 0, tuple(self._ground[name]), 0, coeff)
        else:
            b = self.body(body, where)
            if b.elements:
                if name not in ("start", "end"):
                    raise SceneError(f"{where}: beam {body!r} offers 'start' and 'end' only")
                node = b.offset + (0 if name == "start" else 4 * b.elements)
                point = (POINT_NODE, node, (0.0, 0.0), 0, coeff)
            else:
                if named and name not in b.points:
                    raise SceneError(
                        f"{where}: body {body!r} has no point {name!r}; known: {sorted(b.points)}"
                    )
                u = b.points[name] if named else (float(name[0]), float(name[1]))
                if b.modes:
                    bending = b.modes - b.axial
                    coeff = modal.point_coefficients(u, b.length, b.rho_a, bending, b.axial)
                kind = POINT_MODAL if b.modes else POINT_RIGID
                point = (kind, b.offset, u, b.modes, coeff)
        self._points[key] = len(self._pt)
        self._pt.append(point)
        return self._points[key]

    def set_output(self, body: str, point: str | list[float], where: str) -> None:
        """The output point: `point` of `body` (`add_point`), or its reference point for
        `centre` (a beam's mid-span, a rigid body's or modal link's frame origin)."""
        b = self.body(body, where)
        index = list(self._bodies).index(body)
        if point == "centre":
            self._output = (-1, index)
        elif b.elements and point not in ("start", "end"):
            raise SceneError(f"{where}: beam {body!r} offers 'start', 'centre' and 'end' only")
        else:
            self._output = (self.add_point(body, point, where), index)

    def add_constraint(self, owner: str, kind: int, ints: tuple = (), floats: tuple = ()) -> None:
        """An ideal constraint of type `kind` (CON_* of sim.model.system) with its integer
        and float parameters; its CON_ROWS[kind] rows follow the earlier ones."""
        self._con.append((kind, self._m, ints, floats))
        self._rows.append((owner, self._m, CON_ROWS[kind]))
        self._m += CON_ROWS[kind]

    def add_clamp(
        self, owner: str, body: str, point: str, position: tuple[float, float], angle: float
    ) -> None:
        """Hold point `point` of `body` at the global `position` (m) with the body at
        `angle` (rad): a rigid body's pose (CON_CLAMP), or a beam end node's position and
        slope (CON_CLAMP_NODE). The scene's welds to the ground come here."""
        where = f"joints.{owner}"
        b = self.body(body, where)
        gx, gy = position
        if b.elements:
            node = self.add_point(body, point, where)  # checks the point is an end
            self.add_constraint(owner, CON_CLAMP_NODE, (self._pt[node][1],), (gx, gy, angle))
            return
        if b.modes:
            raise SceneError(f"{where}: a modal link cannot be clamped (its frame is floating)")
        if point not in b.points:
            raise SceneError(f"{where}: body {body!r} has no point {point!r}")
        ux, uy = b.points[point]
        c, s = math.cos(angle), math.sin(angle)
        pose = (gx - c * ux + s * uy, gy - s * ux - c * uy, angle)
        self.add_constraint(owner, CON_CLAMP, (b.offset,), pose)

    def add_revolute_clearance(
        self,
        owner: str,
        p0: int,
        p1: int,
        bearing_radius: float,
        clearance: float,
        stiffness: tuple[int, float],
        damping: tuple[int, float],
        lubricant: dict | None = None,
    ) -> None:
        """A revolute clearance joint between bearing point p0 and journal point p1: its
        stiffness law's code and stiffness, its damping law's code and coefficient
        (sim.model.contact_laws, sim.model.system.REVOLUTE_CLEARANCE), with the oil film of
        a `lubricant` block (sim.model.lubrication) or dry (None)."""
        journal_radius = bearing_radius - clearance
        law, k = stiffness
        fields = (bearing_radius, journal_radius, clearance, k, law, *damping)
        self._rj.append((owner, (p0, p1), fields))
        self._rj_film.append(film_parameters(lubricant, journal_radius))

    def add_slider_clearance(
        self,
        owner: str,
        slider: str,
        guide: tuple[float, float, float],
        length: float,
        width: float,
        gap_width: float,
        k_face: float,
        k_corner: float,
        damping: tuple[int, float, float],
    ) -> None:
        """A translational clearance joint: rigid body `slider` (length × width) in a ground
        guide through guide[:2] at angle guide[2] of width `gap_width`; face stiffness
        (N/m) and corner Hertz stiffness (N/m^1.5); its damping law's code and its
        coefficients at a corner and at a face (sim.model.clearance,
        sim.model.system.TRANSLATIONAL_CLEARANCE)."""
        o = self.body(slider, f"joints.{owner}").offset
        px, py, angle = guide
        frame = (px, py, angle, math.cos(angle), math.sin(angle))
        fields = (*frame, length, width, gap_width, k_face, k_corner, *damping)
        self._tj.append((owner, o, fields))

    def add_drive(self, body: str, initial_angle: float, omega: float) -> None:
        """Prescribe the angle of rigid `body`: θ = initial_angle + omega t (rad, rad/s)."""
        coord = self.body(body, "drive.body").offset + 2
        self._drive = (self._m, coord)
        self.add_constraint("drive", CON_DRIVE, (coord,), (initial_angle, omega))

    # Result ------------------------------------------------------------------------

    def freeze(self) -> tuple[System, Layout]:
        """The `System` and `Layout` of everything added."""
        n = self._n
        mass = np.zeros((n, n))
        mass_inv = np.zeros((n, n))
        gravity_force = np.zeros(n)
        for o, block, gravity in self._blocks:
            e = o + block.shape[0]
            mass[o:e, o:e] = block
            mass_inv[o:e, o:e] = np.linalg.inv(block)
            gravity_force[o:e] = gravity
        names = list(self._bodies)
        pts = list(zip(*self._pt, strict=True)) or [()] * 5
        con = list(zip(*self._con, strict=True)) or [()] * 4
        beam_f = [f for _, _, f in self._beams]
        md = list(zip(*self._modal, strict=True)) or [()] * 6
        drive_row, drive_coord = self._drive
        films = np.array(self._rj_film, dtype=FILM)
        system = System(
            n=n,
            m=self._m,
            mass=mass,
            mass_inv=mass_inv,
            blk_start=np.array([o for o, _, _ in self._blocks], dtype=np.int64),
            blk_end=np.array([o + b.shape[0] for o, b, _ in self._blocks], dtype=np.int64),
            gravity_force=gravity_force,
            pt_kind=np.array(pts[0], dtype=np.int64),
            pt_off=np.array(pts[1], dtype=np.int64),
            pt_u=np.array(pts[2], dtype=float).reshape(-1, 2),
            pt_modes=np.array(pts[3], dtype=np.int64),
            pt_modal=np.array(pts[4], dtype=float).reshape(-1, 2, modal.MAX_MODES),
            con_type=np.array(con[0], dtype=np.int64),
            con_row=np.array(con[1], dtype=np.int64),
            con_i=np.array([_padded(i, 4, 0) for i in con[2]], dtype=np.int64).reshape(-1, 4),
            con_f=np.array([_padded(f, 3, 0.0) for f in con[3]], dtype=float).reshape(-1, 3),
            baumgarte=self._baumgarte,
            drive_row=drive_row,
            drive_coord=drive_coord,
            rj_pts=np.array([p for _, p, _ in self._rj], dtype=np.int64).reshape(-1, 2),
            rj=np.array([f for _, _, f in self._rj], dtype=REVOLUTE_CLEARANCE),
            rj_film=films,
            rj_film_table=film_tables(films, np.array([f[1] for _, _, f in self._rj])),
            tj_off=np.array([o for _, o, _ in self._tj], dtype=np.int64),
            tj=np.array([f for _, _, f in self._tj], dtype=TRANSLATIONAL_CLEARANCE),
            contact=self._contact,
            beam_off=np.array([o for o, _, _ in self._beams], dtype=np.int64),
            beam_nel=np.array([ne for _, ne, _ in self._beams], dtype=np.int64),
            beam=np.array(beam_f, dtype=BEAM),
            **_stacked_beam_constants(beam_f),
            md_off=np.array(md[0], dtype=np.int64),
            md_modes=np.array(md[1], dtype=np.int64),
            md_omega=np.array(md[2], dtype=float).reshape(-1, modal.MAX_MODES),
            md_beta=np.array(md[3], dtype=float),
            md_shape=np.array(md[4], dtype=float).reshape(-1, 3, modal.MAX_MODES),
            md_length=np.array(md[5], dtype=float),
            ref_idx=np.array([i for i, _, _ in self._ref], dtype=np.int64).reshape(-1, 4),
            ref_coef=np.array([c for _, c, _ in self._ref], dtype=float).reshape(-1, 4),
            ang_idx=np.array([a for _, _, a in self._ref], dtype=np.int64).reshape(-1, 2),
            body_is_beam=np.array(
                [int(b.elements > 0) for b in self._bodies.values()], dtype=np.int64
            ),
            body_modal=_modal_index(self._bodies.values()),
            out_pt=self._output[0],
            out_body=self._output[1],
            tree=np.zeros(0, dtype=HINGE),
        )
        layout = Layout(
            names,
            {nm: b.offset for nm, b in self._bodies.items()},
            {nm: b.elements > 0 for nm, b in self._bodies.items()},
            {nm: b.elements for nm, b in self._bodies.items()},
            [nm for nm, _, _ in self._rj] + [nm for nm, _, _ in self._tj],
            self._rows,
            self._points,
            {nm: b.modes for nm, b in self._bodies.items()},
            {nm: b.axial for nm, b in self._bodies.items()},
        )
        return system, layout


def _padded(values: tuple, width: int, fill) -> tuple:
    return tuple(values) + (fill,) * (width - len(values))


def _modal_index(bodies) -> np.ndarray:
    """Index of each body among the modal links (md_*), −1 for other bodies."""
    index, count = [], 0
    for b in bodies:
        index.append(count if b.modes else -1)
        count += 1 if b.modes else 0
    return np.array(index, dtype=np.int64)


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

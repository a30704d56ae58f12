"""Clearance contact for the Exudyn model, written anew from docs/model.md on purpose.

Exudyn has no clearance joint, so the cross-check applies the contact laws of docs/model.md through
a force user function. They are implemented here a second time, in plain Python and from the
equations rather than from `sim.model.clearance`, so that the cross-check also checks our
compiled implementation of the laws. Parameters (radii, stiffnesses, restitution, friction)
are the resolved scene's, read from the compiled `System`: one set of numbers, two codes.

A contact sees a local coordinate vector x (and its rate v): the concatenated coordinates of
the bodies it touches, in Exudyn's node order. A point on a body is
  GROUND  fixed global position u (m);
  RIGID   body-frame vector u (m) from the centre of mass of a rigid body whose (x, y, θ)
          start at `first` in x;
  NODE    the position (x, y) of a beam node whose coordinates start at `first`.
A force f (N) at a point plus a global offset o (m) adds Q = (∂r/∂x)ᵀ f: f on (x, y) and,
on a rigid body, the moment (A u + o) × f on θ. A beam node has no rotational coordinate, so
the offset of a contact point on it carries no moment (docs/model.md: pins act on node positions).

Revolute clearance (bearing B on the first body, journal J on the second; Flores & Ambrósio,
Comput. Struct. 82, 2004): e = r_J − r_B, n = e/|e|, t = k × n, δ = |e| − c, δ̇ = n·ė. In
contact (δ > 0) the normal force of the joint's damping law on its elastic force, e.g.
Lankarani–Nikravesh (J. Mech. Des. 112, 1990)
    F_n = max(0, K δ^p [1 + 3(1 − c_e²) δ̇ / (4 max(δ̇⁻, v_min))]),
and the modified Coulomb friction F_t = −μ c_d(|v_t|) F_n sign(v_t) (Ambrósio 2002), v_t the
slip of the material points Q_J = r_J + R_J n and Q_B = r_B + R_B n along t; the force
−F_n n + F_t t acts on the journal at Q_J and its opposite on the bearing at Q_B.

Translational clearance, continuous (Winkler) slider law: each long edge of the slider facing a
guide wall is pressed into an elastic foundation of stiffness K_face / L per unit length. With
end depths δa, δb the penetrated part is the edge (a trapezoid, force K_face (δa + δb)/2) or a
triangle of length ℓ = L δa / (δa − δb) from the deeper end (force K_face δa ℓ / (2 L)); the
force acts at the centroid of that area, with the joint's damping law from the normal rate of
the material point there and friction along the guide from its slip.

The damping laws and Johnson's stiffness are the one exception to "written anew": they are
evaluated by the compiled kernels themselves (`sim.model.contact.normal_force`,
`sim.model.contact.johnson_elastic`, called from Python), so that each law exists once, as
one entry of `sim.model.contact_laws.LAWS`; the laws are checked on their own against
closed forms and an independent integration (`sim restitution`, tests/model/test_contact_laws.py).

The onset rate δ̇⁻ of each contact is a memory: `ContactMemory` sets it once per step, at the
step's start, to the normal rate interpolated linearly to the crossing δ = 0 between the last
two step starts (our own integrator locates the crossing exactly). A contact that began inside
the current step has no memory yet and uses its current rate, as our integrator does before it
has located a crossing.
"""

import math
from dataclasses import dataclass, field

import numpy as np

from sim.model.contact import johnson_elastic, normal_force
from sim.model.contact_laws import STIFFNESS_JOHNSON
from sim.model.system import (
    System,
)

GROUND, RIGID, NODE = 0, 1, 2


@dataclass(frozen=True)
class Point:
    """A material point in a contact's local coordinates (see the module docstring)."""

    kind: int
    first: int = 0
    u: tuple[float, float] = (0.0, 0.0)

    def arm(self, x: np.ndarray) -> tuple[float, float]:
        """A u (m): the point's offset from its body's centre, zero for nodes and ground."""
        if self.kind != RIGID:
            return 0.0, 0.0
        c, s = math.cos(x[self.first + 2]), math.sin(x[self.first + 2])
        return c * self.u[0] - s * self.u[1], s * self.u[0] + c * self.u[1]

    def position(self, x: np.ndarray) -> tuple[float, float]:
        """Global position (m)."""
        if self.kind == GROUND:
            return self.u
        ax, ay = self.arm(x)
        return x[self.first] + ax, x[self.first + 1] + ay

    def velocity(self, x, v, ox: float = 0.0, oy: float = 0.0) -> tuple[float, float]:
        """Velocity (m/s) of the material point at the point plus global offset (ox, oy)."""
        if self.kind == GROUND:
            return 0.0, 0.0
        if self.kind == NODE:
            return v[self.first], v[self.first + 1]
        ax, ay = self.arm(x)
        w = v[self.first + 2]
        return v[self.first] - w * (ay + oy), v[self.first + 1] + w * (ax + ox)

    def add_force(self, x, fx: float, fy: float, ox: float, oy: float, out: np.ndarray) -> None:
        """out += (∂r/∂x)ᵀ f for a force f (N) at the point plus global offset (ox, oy) (m)."""
        if self.kind == GROUND:
            return
        out[self.first] += fx
        out[self.first + 1] += fy
        if self.kind == RIGID:
            ax, ay = self.arm(x)
            out[self.first + 2] += (ax + ox) * fy - (ay + oy) * fx


@dataclass(frozen=True)
class Law:
    """Contact law constants: friction μ, Coulomb tolerances v0 < v1 (m/s), the damping guard
    v_min (m/s) and the Hertz exponent p; the joint's damping law code and its coefficient
    (sim.model.contact_laws)."""

    code: int
    damping: float
    friction: float
    v0: float
    v1: float
    min_impact_speed: float
    exponent: float

    @classmethod
    def from_system(cls, system: System, joint: np.void, damping: str = "damping") -> "Law":
        """The contact law constants compiled into `system`, with the damping law of a joint's
        data (`system.rj[j]` or `system.tj[j]`) and its coefficient field `damping`."""
        c = system.contact
        return cls(
            code=int(joint["law"]),
            damping=float(joint[damping]),
            friction=c.friction,
            v0=c.v0,
            v1=c.v1,
            min_impact_speed=c.min_impact_speed,
            exponent=c.exponent,
        )

    def hysteresis(
        self, elastic: float, delta: float, rate: float, onset: float, exponent: float
    ) -> float:
        """Normal force (N) of the damping law on its elastic part (N) at penetration δ (m),
        never negative (`sim.model.contact.normal_force`)."""
        return normal_force(
            self.code, self.damping, elastic, delta, rate, onset, exponent, self.min_impact_speed
        )

    def friction_force(self, normal: float, slip: float) -> float:
        """Modified Coulomb friction (N) against the slip velocity (m/s)."""
        speed = abs(slip)
        if speed <= self.v0 or normal == 0.0:
            return 0.0
        share = 1.0 if speed >= self.v1 else (speed - self.v0) / (self.v1 - self.v0)
        return -math.copysign(self.friction * share * normal, slip)


@dataclass
class ContactMemory:
    """Per gap: in-contact flag, onset rate δ̇⁻ (m/s) and the last step start's (δ, δ̇)."""

    size: int
    flag: np.ndarray = field(init=False)
    onset: np.ndarray = field(init=False)
    last: np.ndarray = field(init=False)

    def __post_init__(self) -> None:
        self.flag = np.zeros(self.size, dtype=bool)
        self.onset = np.zeros(self.size)
        self.last = np.full((self.size, 2), np.nan)

    def update(self, gaps: list[tuple[float, float]]) -> None:
        """Enter or leave contact at a step's start from each gap's (δ, δ̇) there."""
        for g, (delta, rate) in enumerate(gaps):
            d0, r0 = self.last[g]
            if delta > 0.0 and not self.flag[g]:
                self.flag[g] = True
                crossing = -d0 / (delta - d0) if d0 < 0.0 else 1.0
                self.onset[g] = r0 + crossing * (rate - r0) if d0 < 0.0 else rate
            elif delta <= 0.0:
                self.flag[g] = False
            self.last[g] = delta, rate

    def onset_rate(self, g: int, rate: float) -> float:
        """δ̇⁻ of gap g: its memory, or the current rate before the step that flags it."""
        return self.onset[g] if self.flag[g] else rate


@dataclass
class RevoluteClearance:
    """Journal J in bearing B: radii R_B, R_J (m), clearance c (m), stiffness K (N/m^p) and
    its law's code (Hertz; Johnson's with K = π L E*, N/m)."""

    bearing: Point
    journal: Point
    r_bearing: float
    r_journal: float
    clearance: float
    stiffness: float
    stiffness_law: int
    law: Law
    memory: ContactMemory = field(init=False)

    def __post_init__(self) -> None:
        self.memory = ContactMemory(1)

    @classmethod
    def from_system(
        cls, system: System, j: int, bearing: Point, journal: Point
    ) -> "RevoluteClearance":
        """Revolute clearance j of the compiled `system`, between the given points."""
        f = system.rj[j]
        return cls(
            bearing=bearing,
            journal=journal,
            r_bearing=f["bearing_radius"],
            r_journal=f["journal_radius"],
            clearance=f["clearance"],
            stiffness=f["stiffness"],
            stiffness_law=int(f["stiffness_law"]),
            law=Law.from_system(system, f),
        )

    def gaps(self, x: np.ndarray, v: np.ndarray) -> list[tuple[float, float]]:
        """[(δ, δ̇)] of the joint (m, m/s)."""
        ex, ey, e, vx, vy = self._eccentricity(x, v)
        rate = (ex * vx + ey * vy) / e if e > 0.0 else 0.0
        return [(e - self.clearance, rate)]

    def _eccentricity(self, x, v):
        bx, by = self.bearing.position(x)
        jx, jy = self.journal.position(x)
        bvx, bvy = self.bearing.velocity(x, v)
        jvx, jvy = self.journal.velocity(x, v)
        ex, ey = jx - bx, jy - by
        return ex, ey, math.hypot(ex, ey), jvx - bvx, jvy - bvy

    def force(self, x: np.ndarray, v: np.ndarray) -> np.ndarray:
        """Generalized contact forces on x (N, N m)."""
        out = np.zeros(x.size)
        ex, ey, e, vx, vy = self._eccentricity(x, v)
        delta = e - self.clearance
        if delta <= 0.0:
            return out
        nx, ny = ex / e, ey / e
        rate = nx * vx + ny * vy
        law = self.law
        if self.stiffness_law == STIFFNESS_JOHNSON:
            elastic, _ = johnson_elastic(self.stiffness, self.clearance, delta)
        else:
            elastic = self.stiffness * delta**law.exponent
        fn = law.hysteresis(elastic, delta, rate, self.memory.onset_rate(0, rate), law.exponent)
        ojx, ojy = self.r_journal * nx, self.r_journal * ny
        obx, oby = self.r_bearing * nx, self.r_bearing * ny
        jvx, jvy = self.journal.velocity(x, v, ojx, ojy)
        bvx, bvy = self.bearing.velocity(x, v, obx, oby)
        ft = law.friction_force(fn, -ny * (jvx - bvx) + nx * (jvy - bvy))
        fx, fy = -fn * nx - ft * ny, -fn * ny + ft * nx
        self.journal.add_force(x, fx, fy, ojx, ojy, out)
        self.bearing.add_force(x, -fx, -fy, obx, oby, out)
        return out


# Slider corners in its body frame (x along its length, y across), in order around the block.
CORNERS = ((1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0))
WALLS = (1.0, -1.0)  # wall side s: the guide wall at +H/2 and at −H/2 along the guide normal


@dataclass
class SliderClearance:
    """Rigid slider (length L, width W, m) in a ground guide through `origin` with direction
    angle `angle` (rad) and gap width H (m); face stiffness K_face (N/m)."""

    slider: Point
    origin: tuple[float, float]
    angle: float
    length: float
    width: float
    gap_width: float
    face_stiffness: float
    law: Law
    memory: ContactMemory = field(init=False)

    def __post_init__(self) -> None:
        self.memory = ContactMemory(len(CORNERS) * len(WALLS))
        c, s = math.cos(self.angle), math.sin(self.angle)
        self.tangent, self.normal = (c, s), (-s, c)

    @classmethod
    def from_system(cls, system: System, j: int, slider: Point) -> "SliderClearance":
        """Translational clearance j (counted among the translational ones) of `system`."""
        f = system.tj[j]
        return cls(
            slider=slider,
            origin=(f["px"], f["py"]),
            angle=f["angle"],
            length=f["length"],
            width=f["width"],
            gap_width=f["gap_width"],
            face_stiffness=f["k_face"],
            law=Law.from_system(system, f, "face_damping"),
        )

    def _corner(self, x, v, i: int, side: float):
        """Penetration δ (m), its rate (m/s) and global offset (m) of corner i at wall `side`."""
        o = self.slider.first
        c, s = math.cos(x[o + 2]), math.sin(x[o + 2])
        ux, uy = 0.5 * CORNERS[i][0] * self.length, 0.5 * CORNERS[i][1] * self.width
        ax, ay = c * ux - s * uy, s * ux + c * uy
        nx, ny = self.normal
        lateral = (x[o] + ax - self.origin[0]) * nx + (x[o + 1] + ay - self.origin[1]) * ny
        w = v[o + 2]
        rate = side * ((v[o] - w * ay) * nx + (v[o + 1] + w * ax) * ny)
        return side * lateral - 0.5 * self.gap_width, rate, ax, ay

    def gaps(self, x: np.ndarray, v: np.ndarray) -> list[tuple[float, float]]:
        """[(δ, δ̇)] of corner i at wall w as gap 2 i + w (m, m/s)."""
        return [self._corner(x, v, i, side)[:2] for i in range(len(CORNERS)) for side in WALLS]

    def force(self, x: np.ndarray, v: np.ndarray) -> np.ndarray:
        """Generalized contact forces on x (N, N m)."""
        out = np.zeros(x.size)
        o = self.slider.first
        for w, side in enumerate(WALLS):
            # The long edge facing this wall: corners 0, 1 have the outward normal body +y.
            up = -math.sin(x[o + 2]) * self.normal[0] + math.cos(x[o + 2]) * self.normal[1]
            a = 0 if side * up > 0.0 else 2
            da, ra, aax, aay = self._corner(x, v, a, side)
            db, rb, abx, aby = self._corner(x, v, a + 1, side)
            if da <= 0.0 and db <= 0.0:
                continue
            if da > 0.0 and db > 0.0:
                elastic = 0.5 * self.face_stiffness * (da + db)
                frac = (da + 2.0 * db) / (3.0 * (da + db))
            elif da > 0.0:
                elastic = 0.5 * self.face_stiffness * da * da / (da - db)
                frac = da / (da - db) / 3.0
            else:
                elastic = 0.5 * self.face_stiffness * db * db / (db - da)
                frac = 1.0 - db / (db - da) / 3.0
            rate = ra + frac * (rb - ra)
            ga, gb = 2 * a + w, 2 * (a + 1) + w
            mem = self.memory
            if mem.flag[ga] or mem.flag[gb]:
                onset = max(mem.onset[g] if mem.flag[g] else 0.0 for g in (ga, gb))
            else:
                onset = rate
            fn = self.law.hysteresis(elastic, max(da, db), rate, onset, 1.0)
            cx, cy = aax + frac * (abx - aax), aay + frac * (aby - aay)
            vx, vy = self.slider.velocity(x, v, cx, cy)
            tx, ty = self.tangent
            ft = self.law.friction_force(fn, vx * tx + vy * ty)
            nx, ny = self.normal
            self.slider.add_force(
                x, -side * fn * nx + ft * tx, -side * fn * ny + ft * ty, cx, cy, out
            )
        return out

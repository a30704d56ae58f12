"""A resolved scene as an Exudyn model, started from our own initial state.

Built from the same inputs as our run: the resolved scene, the compiled `System` and `Layout`
of `sim.run.prepare` (points, clearance joints, beam and contact constants) and its initial
state y = (q, q̇, ...), so both codes start from the same coordinates. Exudyn's items
(Gerstmayr, Exudyn documentation, version 1.13):

- rigid body: NodeRigidBody2D (x, y, θ of the centre of mass) + ObjectRigidBody2D;
- beam: NodePoint2DSlope1 per node (r, ∂r/∂x) + ObjectANCFCable2D per element. Its elastic
  law differs from ours: axial strain |r'| − 1 and the material curvature (r' × r'')/|r'|²
  with Gauss quadrature, where we use the Green strain (r'·r' − 1)/2 and the constant
  bending stiffness ∫ EI S''ᵀS'' (|r''|²); `sim.crosscheck.compare.elastic_law_difference`
  measures what that changes. Stiffness-proportional damping β maps to axial and bending
  damping β EA and β EI;
- gravity: LoadMassProportional on every body and element;
- ideal revolute: ObjectJointRevolute2D between position markers (a beam end is its node);
- ideal translational: ObjectJointPrismatic2D, the slider's body y axis normal to the guide;
- drive: ObjectConnectorCoordinate θ_crank − θ_ref = θ0 + ω t − θ_ref; its Lagrange multiplier
  λ enters the equations as +Φ_qᵀλ on the left (Exudyn's convention, as ours), so the driving
  torque on the crank is −λ;
- clearance joints: ObjectGenericODE2 without mass on the nodes of the two bodies, whose force
  user function applies `sim.crosscheck.contact`. Exudyn's connectors see only the relative
  position and velocity of two marker points; the contact law needs each body's own angular
  velocity (slip of the contact surfaces) and moments about the pin centres, which only a
  force on the bodies' coordinates carries. A pre-step function keeps the onset memories.
- or, with `builtin_contact`, a revolute clearance between rigid bodies (or ground) as Exudyn's
  own ObjectContactSphereSphere: the journal a sphere of radius R_J in the hollow sphere
  (isHollowSphere1) of radius R_B, so that in planar motion its overlap is δ = |e| − c, with
  the joint's stiffness K, exponent n, restitution e and v_min, its damping law Exudyn's
  `impactModel` of the same formula (`EXUDYN_IMPACT_MODELS`), friction 0. Nothing of ours
  computes that contact force: the contact law itself is compared.
"""

import math
from dataclasses import dataclass, field

import exudyn as exu
import numpy as np
from exudyn import itemInterface as item

from sim.crosscheck import contact
from sim.crosscheck.recorder import Recorder
from sim.model.assembly import Layout, body_mass_properties, omega
from sim.model.beams import midpoint_shape
from sim.model.contact_laws import LAWS, STIFFNESS_HERTZ
from sim.model.system import (
    POINT_GROUND,
    POINT_RIGID,
    SLIDER_LAW_WINKLER,
    System,
)

VARIABLE = exu.OutputVariableType

#: Our damping laws (`sim.model.contact_laws.LAWS`) that Exudyn's ObjectContactSphereSphere has,
#: by its `impactModel` (Exudyn documentation 1.13, ObjectContactSphereSphere): 1 Hunt–Crossley,
#: λ = (K/δ̇⁻)(3/2)(e − 1); 2 Carvalho–Martins above e = 1/3, Gonthier et al. below,
#: λ = (K/δ̇⁻)(3/2)(e − 1)(11 − e)/(1 + 9e), resp. (K/δ̇⁻)(e² − 1)/e; F = K δⁿ − λ δⁿ δ̇ with
#: δ̇⁻ = max(v_min, the rate at the end of the first step in contact). Same χ as ours;
#: Exudyn does not clip the force at 0 (tension needs δ̇ < −δ̇⁻/χ, never in a free impact).
EXUDYN_IMPACT_MODELS: dict[str, int] = {"hunt-crossley": 1, "gonthier-carvalho": 2}


class CrossCheckError(ValueError):
    """The scene uses something the Exudyn model does not build."""


@dataclass
class Contact:
    """One clearance joint in Exudyn: its law, the nodes it acts on and their reference."""

    law: contact.RevoluteClearance | contact.SliderClearance
    nodes: list
    reference: np.ndarray
    coordinates: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))

    def force(self, mbs, t, item_number, q, q_t) -> np.ndarray:
        """ObjectGenericODE2 force user function: generalized forces on the RHS."""
        return self.law.force(self.reference + np.asarray(q), np.asarray(q_t))


@dataclass
class PointSensors:
    """Sensors (or a fixed ground position) of one material point: position and velocity."""

    ground: tuple[float, float] | None = None
    position: object = None
    velocity: object = None


@dataclass
class ExudynModel:
    """The assembled Exudyn system and what the run reads from it."""

    container: object
    mbs: object
    layout: Layout
    reference_point: dict[str, dict[str, object]]  # body → Position/Velocity/Acceleration
    angle: dict[str, tuple]  # body → (rotation sensor,) or (end node 0, end node n) sensors
    drive: object
    joint_points: dict[str, tuple[PointSensors, PointSensors]]  # clearance joint → (B, J)
    contacts: list[Contact]
    builtin: dict[str, object]  # joint with Exudyn's own contact → its contact force sensor
    # Running peaks over all steps (|acceleration| per body and axis, then |torque|), from the
    # coordinate accelerations: Exudyn numbers its coordinates node by node, as we do.
    peak_idx: np.ndarray  # (body, axis, 4) coordinates combined into each reference point
    peak_coef: np.ndarray  # (body, 1, 4) their coefficients
    drive_row: int  # the drive's Lagrange multiplier among Exudyn's algebraic coordinates
    peaks: np.ndarray
    recorder: Recorder


class _Builder:
    """Adds the scene's items to an Exudyn MainSystem (one use)."""

    def __init__(
        self, scene: dict, system: System, layout: Layout, y: np.ndarray, builtin_contact: bool
    ):
        self.scene, self.system, self.layout = scene, system, layout
        self.builtin_contact = builtin_contact
        self.builtin: dict[str, object] = {}  # clearance joint → contact force sensor
        self.q0, self.qd0 = y[: system.n], y[system.n : 2 * system.n]
        self.container = exu.SystemContainer()
        self.mbs = self.container.AddSystem()
        self.ground = self.mbs.AddObject(item.ObjectGround())
        self.nodes: dict[str, list] = {}  # rigid: [node]; beam: nodes 0..n
        self.objects: dict[str, list] = {}  # rigid: [body]; beam: elements
        self.sensors: list = []
        gx, gy = scene["gravity"]
        self.gravity = [gx, gy, 0.0]

    # ------------------------------------------------------------------ bodies
    def bodies(self) -> None:
        for name in self.layout.bodies:
            if self.layout.is_beam[name]:
                self._beam(name)
            else:
                self._rigid(name)

    def _gravity(self, body) -> None:
        marker = self.mbs.AddMarker(item.MarkerBodyMass(bodyNumber=body))
        self.mbs.AddLoad(item.LoadMassProportional(markerNumber=marker, loadVector=self.gravity))

    def _rigid(self, name: str) -> None:
        body = self.scene["bodies"][name]
        o = self.layout.offset[name]
        mass, inertia = body_mass_properties(body, self.scene["materials"][body["material"]])
        node = self.mbs.AddNode(
            item.NodeRigidBody2D(
                referenceCoordinates=list(self.q0[o : o + 3]),
                initialVelocities=list(self.qd0[o : o + 3]),
            )
        )
        obj = self.mbs.AddObject(
            item.ObjectRigidBody2D(mass=mass, inertia=inertia, nodeNumber=node)
        )
        self._gravity(obj)
        self.nodes[name], self.objects[name] = [node], [obj]

    def _beam(self, name: str) -> None:
        body = self.scene["bodies"][name]
        o = self.layout.offset[name]
        ne = self.layout.elements[name]
        k = int(np.flatnonzero(self.system.beam_off == o)[0])
        beam = self.system.beam[k]
        el_len, ea, ei, beta = (beam[f] for f in ("element_length", "ea", "ei", "damping"))
        density = self.scene["materials"][body["material"]]["density"]
        mass_per_length = density * body["section"][0] * body["section"][1]
        nodes = [
            self.mbs.AddNode(
                item.NodePoint2DSlope1(
                    referenceCoordinates=list(self.q0[o + 4 * i : o + 4 * i + 4]),
                    initialVelocities=list(self.qd0[o + 4 * i : o + 4 * i + 4]),
                )
            )
            for i in range(ne + 1)
        ]
        elements = []
        for e in range(ne):
            element = self.mbs.AddObject(
                item.ObjectANCFCable2D(
                    length=el_len,
                    massPerLength=mass_per_length,
                    bendingStiffness=ei,
                    axialStiffness=ea,
                    bendingDamping=beta * ei,
                    axialDamping=beta * ea,
                    nodeNumbers=[nodes[e], nodes[e + 1]],
                )
            )
            self._gravity(element)
            elements.append(element)
        self.nodes[name], self.objects[name] = nodes, elements

    # ------------------------------------------------------------------ points
    def _point(self, body: str, pname: str) -> tuple[int, object, tuple[float, float]]:
        """(kind, rigid body or beam node, body-frame or ground vector) of a joint point."""
        k = self.layout.points[(body, pname)]
        u = tuple(float(c) for c in self.system.pt_u[k])
        kind = int(self.system.pt_kind[k])
        if kind == POINT_GROUND:
            return contact.GROUND, None, u
        if kind == POINT_RIGID:
            return contact.RIGID, self.objects[body][0], u
        node = (int(self.system.pt_off[k]) - self.layout.offset[body]) // 4
        return contact.NODE, self.nodes[body][node], u

    def _position_marker(self, body: str, pname: str):
        kind, owner, u = self._point(body, pname)
        if kind == contact.NODE:
            return self.mbs.AddMarker(item.MarkerNodePosition(nodeNumber=owner))
        target = self.ground if kind == contact.GROUND else owner
        return self.mbs.AddMarker(
            item.MarkerBodyPosition(bodyNumber=target, localPosition=[u[0], u[1], 0.0])
        )

    def _sensor(self, owner, variable: str, local=None, node: bool = False):
        """A stored sensor of a node, or of a body's material point at `local` (m)."""
        kind = getattr(VARIABLE, variable)
        if node:
            sensor = item.SensorNode(nodeNumber=owner, outputVariableType=kind, writeToFile=False)
        else:
            sensor = item.SensorBody(
                bodyNumber=owner,
                localPosition=[local[0], local[1], 0.0],
                outputVariableType=kind,
                writeToFile=False,
            )
        self.sensors.append(self.mbs.AddSensor(sensor))
        return self.sensors[-1]

    def _point_sensors(self, body: str, pname: str) -> PointSensors:
        kind, owner, u = self._point(body, pname)
        if kind == contact.GROUND:
            return PointSensors(ground=u)
        node = kind == contact.NODE
        return PointSensors(
            position=self._sensor(owner, "Position", u, node),
            velocity=self._sensor(owner, "Velocity", u, node),
        )

    # ------------------------------------------------------------------ joints
    def joints(self) -> tuple[list[Contact], dict]:
        contacts, joint_points = [], {}
        clearance = self.layout.clearance_joints
        for name, joint in self.scene["joints"].items():
            kind = joint["type"]
            if kind == "weld":
                raise CrossCheckError(
                    f"joints.{name}: the Exudyn cross-check builds revolute and translational "
                    "joints only (no weld)"
                )
            if name in clearance:
                j = clearance.index(name)
                if kind == "revolute":
                    if joint["lubricant"] is not None:
                        raise CrossCheckError(
                            f"joints.{name}.lubricant: the Exudyn cross-check has no oil film"
                        )
                    if self.builtin_contact:
                        self.builtin[name] = self._sphere_contact(name, joint, j)
                    else:
                        contacts.append(self._revolute_clearance(joint, j))
                    joint_points[name] = tuple(
                        self._point_sensors(b, p)
                        for b, p in zip(joint["bodies"], joint["points"], strict=True)
                    )
                else:
                    contacts.append(self._slider_clearance(joint, j))
                continue
            if kind == "revolute":
                markers = [
                    self._position_marker(b, p)
                    for b, p in zip(joint["bodies"], joint["points"], strict=True)
                ]
                self.mbs.AddObject(item.ObjectJointRevolute2D(markerNumbers=markers))
            else:
                self._prismatic(joint)
        return contacts, joint_points

    def _prismatic(self, joint: dict) -> None:
        slider = joint["bodies"][1]
        if self.layout.is_beam[slider]:
            raise CrossCheckError(f"bodies.{slider}: a translational joint needs a rigid slider")
        angle = math.radians(joint["guide_angle_deg"])
        px, py = joint["guide_point"]
        guide = self.mbs.AddMarker(
            item.MarkerBodyRigid(bodyNumber=self.ground, localPosition=[px, py, 0.0])
        )
        body = self.mbs.AddMarker(
            item.MarkerBodyRigid(bodyNumber=self.objects[slider][0], localPosition=[0.0] * 3)
        )
        self.mbs.AddObject(
            item.ObjectJointPrismatic2D(
                markerNumbers=[guide, body],
                axisMarker0=[math.cos(angle), math.sin(angle), 0.0],
                normalMarker1=[0.0, 1.0, 0.0],
                constrainRotation=True,
            )
        )

    def _local(self, specs) -> tuple[list[contact.Point], list, np.ndarray]:
        """Contact points in local coordinates: the nodes they use and their reference."""
        points, nodes, reference = [], [], []
        for kind, owner, u in specs:
            if kind == contact.GROUND:
                points.append(contact.Point(contact.GROUND, 0, u))
                continue
            node = owner if kind == contact.NODE else self.mbs.GetObject(owner)["nodeNumber"]
            ref = self.mbs.GetNodeParameter(node, "referenceCoordinates")
            points.append(contact.Point(kind, sum(len(r) for r in reference), u))
            nodes.append(node)
            reference.append(np.asarray(ref, dtype=float))
        return points, nodes, np.concatenate(reference)

    def _generic(self, law, nodes, reference) -> Contact:
        entry = Contact(law=law, nodes=nodes, reference=reference)
        size = reference.size
        self.mbs.AddObject(
            item.ObjectGenericODE2(
                nodeNumbers=nodes, massMatrix=np.zeros((size, size)), forceUserFunction=entry.force
            )
        )
        return entry

    def _revolute_clearance(self, joint, j) -> Contact:
        specs = [self._point(b, p) for b, p in zip(joint["bodies"], joint["points"], strict=True)]
        (bearing, journal), nodes, reference = self._local(specs)
        law = contact.RevoluteClearance.from_system(self.system, j, bearing, journal)
        return self._generic(law, nodes, reference)

    def _sphere_contact(self, name: str, joint: dict, j: int):
        """Revolute clearance j as Exudyn's ObjectContactSphereSphere (see the module
        docstring); returns the sensor of its contact force (Exudyn's `Force`, N)."""
        f = self.system.rj[j]
        c = self.system.contact
        law = LAWS[int(f["law"])].name
        checks = {
            "law": (law in EXUDYN_IMPACT_MODELS, f"one of {', '.join(EXUDYN_IMPACT_MODELS)}"),
            "stiffness_law": (int(f["stiffness_law"]) == STIFFNESS_HERTZ, "hertz"),
        }
        for key, (ok, accepted) in checks.items():
            if not ok:
                raise CrossCheckError(
                    f"joints.{name}.{key}: Exudyn's own contact (builtin_contact) needs {accepted}"
                )
        if c.friction != 0.0:
            raise CrossCheckError(
                f"contact.friction = {c.friction}: Exudyn's own contact is compared without "
                "friction (its friction law is not ours); set it to 0"
            )
        markers = []
        for body, pname in zip(joint["bodies"], joint["points"], strict=True):
            kind, owner, u = self._point(body, pname)
            if kind == contact.NODE:
                raise CrossCheckError(
                    f"joints.{name}: Exudyn's own contact needs rigid bodies (or ground), "
                    f"'{body}' is a beam"
                )
            target = self.ground if kind == contact.GROUND else owner
            markers.append(
                self.mbs.AddMarker(
                    item.MarkerBodyRigid(bodyNumber=target, localPosition=[u[0], u[1], 0.0])
                )
            )
        bearing, journal = markers
        # its history: gap (m; starting apart), tangential speed, impact speed, plastic overlap
        data = self.mbs.AddNode(
            item.NodeGenericData(numberOfDataCoordinates=4, initialCoordinates=[1.0, 0, 0, 0])
        )
        obj = self.mbs.AddObject(
            item.ObjectContactSphereSphere(
                markerNumbers=[journal, bearing],
                nodeNumber=data,
                spheresRadii=[float(f["journal_radius"]), float(f["bearing_radius"])],
                isHollowSphere1=True,
                contactStiffness=float(f["stiffness"]),
                contactStiffnessExponent=c.exponent,
                restitutionCoefficient=float(self.scene["contact"]["restitution"]),
                minimumImpactVelocity=c.min_impact_speed,
                impactModel=EXUDYN_IMPACT_MODELS[law],
            )
        )
        force = item.SensorObject(
            objectNumber=obj, outputVariableType=VARIABLE.Force, writeToFile=False
        )
        self.sensors.append(self.mbs.AddSensor(force))
        return self.sensors[-1]

    def _slider_clearance(self, joint, j) -> Contact:
        if self.system.contact.slider_law != SLIDER_LAW_WINKLER:
            raise CrossCheckError(
                "contact.slider_law: the Exudyn cross-check implements 'winkler' only"
            )
        slider = joint["bodies"][1]
        if self.layout.is_beam[slider]:
            raise CrossCheckError(f"bodies.{slider}: a translational joint needs a rigid slider")
        node = self.nodes[slider][0]
        reference = np.asarray(self.mbs.GetNodeParameter(node, "referenceCoordinates"), float)
        centre = contact.Point(contact.RIGID, 0, (0.0, 0.0))
        law = contact.SliderClearance.from_system(
            self.system, j - self.system.rj_pts.shape[0], centre
        )
        return self._generic(law, [node], reference)

    # ------------------------------------------------------------------ drive, sensors
    def drive(self):
        drive = self.scene["drive"]
        name = drive["body"]
        if self.layout.is_beam[name]:
            raise CrossCheckError(f"drive.body: '{name}' must be rigid")
        w = omega(self.scene)
        shift = math.radians(drive["initial_angle_deg"]) - self.q0[self.layout.offset[name] + 2]
        fixed = self.mbs.AddNode(item.NodePointGround(referenceCoordinates=[0.0] * 3))
        markers = [
            self.mbs.AddMarker(item.MarkerNodeCoordinate(nodeNumber=fixed, coordinate=0)),
            self.mbs.AddMarker(
                item.MarkerNodeCoordinate(nodeNumber=self.nodes[name][0], coordinate=2)
            ),
        ]
        constraint = self.mbs.AddObject(
            item.ObjectConnectorCoordinate(
                markerNumbers=markers,
                offsetUserFunction=lambda mbs, t, i, offset: shift + w * t,
                offsetUserFunction_t=lambda mbs, t, i, offset: w,
            )
        )
        force = item.SensorObject(
            objectNumber=constraint, outputVariableType=VARIABLE.Force, writeToFile=False
        )
        self.sensors.append(self.mbs.AddSensor(force))
        return constraint, self.sensors[-1]

    def reference_points(self) -> tuple[dict, dict]:
        """Sensors of each body's reference point (centre of mass or beam mid-length) and of
        its angle (rigid: θ; beam: its end nodes, for the chord)."""
        points, angles = {}, {}
        kinds = ("Position", "Velocity", "Acceleration")
        for name in self.layout.bodies:
            nodes = self.nodes[name]
            if not self.layout.is_beam[name]:
                points[name] = {v: self._sensor(nodes[0], v, node=True) for v in kinds}
                angles[name] = (self._sensor(nodes[0], "Rotation", node=True),)
                continue
            length = self.scene["bodies"][name]["length"]
            element, _ = midpoint_shape(length, len(nodes) - 1)
            middle = (0.5 * length - element * length / (len(nodes) - 1), 0.0)
            owner = self.objects[name][element]
            points[name] = {v: self._sensor(owner, v, middle) for v in kinds}
            angles[name] = tuple(
                self._sensor(n, "Position", node=True) for n in (nodes[0], nodes[-1])
            )
        return points, angles


def build_model(
    scene: dict, system: System, layout: Layout, y: np.ndarray, builtin_contact: bool = False
) -> ExudynModel:
    """The Exudyn model of `scene` as compiled into `system` / `layout`, started from y; with
    `builtin_contact`, its revolute clearances as Exudyn's own contact (module docstring)."""
    builder = _Builder(scene, system, layout, y, builtin_contact)
    builder.bodies()
    contacts, joint_points = builder.joints()
    constraint, torque = builder.drive()
    points, angles = builder.reference_points()
    mbs = builder.mbs
    mbs.Assemble()
    data = mbs.systemData
    for name in layout.bodies:
        step = 4 if layout.is_beam[name] else 3
        for i, node in enumerate(builder.nodes[name]):
            if data.GetNodeLTGODE2(node)[0] != layout.offset[name] + step * i:
                raise CrossCheckError(f"Exudyn numbered the coordinates of '{name}' unlike sim")
    for entry in contacts:
        entry.coordinates = np.concatenate([data.GetNodeLTGODE2(n) for n in entry.nodes])
    model = ExudynModel(
        container=builder.container,
        mbs=mbs,
        layout=layout,
        reference_point=points,
        angle=angles,
        drive=torque,
        joint_points=joint_points,
        contacts=contacts,
        builtin=builder.builtin,
        peak_idx=system.ref_idx[:, None, :] + np.arange(2)[None, :, None],
        peak_coef=system.ref_coef[:, None, :],
        drive_row=int(data.GetObjectLTGAE(constraint)[0]),
        peaks=np.zeros(2 * len(layout.bodies) + 1),
        recorder=Recorder(builder.sensors),
    )
    mbs.SetPreStepUserFunction(lambda mbs, t: _pre_step(model, t))
    return model


def _pre_step(model: ExudynModel, t: float) -> bool:
    """Before each step (ending at t): record an output sample if the step starts at an
    output time, update the contact onset memories and the running peaks of |acceleration|
    per body and axis and |driving torque| over every step's start."""
    data = model.mbs.systemData
    model.recorder.take(model.mbs, data.GetTime(exu.ConfigurationType.StartOfStep), t)
    q, v = data.GetODE2Coordinates(), data.GetODE2Coordinates_t()
    for entry in model.contacts:
        c = entry.coordinates
        entry.law.memory.update(entry.law.gaps(entry.reference + q[c], v[c]))
    acc = data.GetODE2Coordinates_tt()
    reference = np.abs(np.sum(model.peak_coef * acc[model.peak_idx], axis=-1))
    np.maximum(model.peaks[:-1], reference.ravel(), out=model.peaks[:-1])
    model.peaks[-1] = max(model.peaks[-1], abs(data.GetAECoordinates()[model.drive_row]))
    return True

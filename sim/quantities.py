"""Every output quantity of a run, declared once: name, dimensions, units, long name and how
it is recorded.

The integrator's sample rows and peak vector (`sim.solve.record.column_layout` and
`peak_layout`, filled by the compiled `sim.solve.record.write_row` and
`sim.solve.stepping._update_peaks`), the netCDF writer and decoder (`sim.results`) and the
cross-check's output (`sim.crosscheck.run`) all follow this table. Adding an output quantity
means one entry here and, for a sampled quantity, its line in `write_row` (a peak: its lines
in `_update_peaks` and the peak count of `sim.run`). Units are CF / UDUNITS strings (CF
conventions 1.8).
"""

from typing import NamedTuple

# How a quantity is recorded.
SAMPLE = "sample"  # a block of columns of every sample row, at each output time
SECTION = "section"  # a sampled quantity (`source`) at each crank revolution (Poincaré section)
PEAK = "peak"  # largest |source| over every accepted step and every sample of the run
REVOLUTION_PEAK = "revolution peak"  # as PEAK, over the revolution ending at each section
REVOLUTION_COUNT = "revolution count"  # counted by the integrator in each revolution
DERIVED = "derived"  # computed from other quantities when the dataset is built

AXES = ["x", "y"]  # the `axis` coordinate (translational joints: across, along the guide)


class Quantity(NamedTuple):
    """One output variable: its name in the dataset, its dimensions, units (CF), long name,
    how it is recorded (SAMPLE, SECTION, ...) and, for a SECTION or a peak, the sampled
    quantity it is taken from."""

    name: str
    dims: tuple[str, ...]
    units: str
    long_name: str
    recorded: str
    source: str = ""


class Coordinate(NamedTuple):
    """One dimension's coordinate: its name, long name and units (empty: a label, no units)."""

    name: str
    long_name: str
    units: str = ""


COORDINATES = (
    Coordinate("time", "time since the start of the simulation", "s"),
    Coordinate("body", "body name"),
    Coordinate("axis", "component (global x, y; translational joints: across, along)"),
    Coordinate("joint", "clearance joint name"),
    Coordinate("revolution", "crank revolutions completed at the section", "1"),
)

_PEAK = "over every accepted step and sample"
_REVOLUTION = f"{_PEAK} of the revolution ending at the section"

# In the order of the sample row's columns and of the dataset's variables.
QUANTITIES = (
    Quantity("crank_angle", ("time",), "rad", "crank angle from +x, counter-clockwise", SAMPLE),
    Quantity(
        "position",
        ("time", "body", "axis"),
        "m",
        "position of the body's reference point",
        SAMPLE,
    ),
    Quantity(
        "velocity",
        ("time", "body", "axis"),
        "m s-1",
        "velocity of the body's reference point",
        SAMPLE,
    ),
    Quantity(
        "acceleration",
        ("time", "body", "axis"),
        "m s-2",
        "acceleration of the body's reference point",
        SAMPLE,
    ),
    Quantity(
        "angle",
        ("time", "body"),
        "rad",
        "body angle (beams: angle of the chord between end nodes)",
        SAMPLE,
    ),
    Quantity(
        "deflection",
        ("time", "body"),
        "m",
        "mid-span transverse deflection from the chord of the end nodes (beams; 0 if rigid)",
        SAMPLE,
    ),
    Quantity("drive_torque", ("time",), "N m", "driving torque applied to the crank", SAMPLE),
    Quantity(
        "eccentricity",
        ("time", "joint", "axis"),
        "m",
        "journal centre minus bearing centre; slider: x across, y along guide",
        SAMPLE,
    ),
    Quantity(
        "eccentricity_rate",
        ("time", "joint", "axis"),
        "m s-1",
        "rate of the eccentricity",
        SAMPLE,
    ),
    Quantity(
        "penetration",
        ("time", "joint"),
        "m",
        "contact penetration depth (deepest, zero when apart)",
        SAMPLE,
    ),
    Quantity(
        "normal_force",
        ("time", "joint"),
        "N",
        "contact normal force (sum over contact points)",
        SAMPLE,
    ),
    Quantity(
        "friction_force",
        ("time", "joint"),
        "N",
        "contact friction force along the tangent (sum over contact points)",
        SAMPLE,
    ),
    Quantity(
        "in_contact",
        ("time", "joint"),
        "1",
        "contact state: 0 apart, 1 point contact, 2 face contact",
        SAMPLE,
    ),
    Quantity(
        "constraint_violation",
        ("time",),
        "m",
        "Euclidean norm of the ideal constraint residuals",
        SAMPLE,
    ),
    Quantity("kinetic_energy", ("time",), "J", "kinetic energy", SAMPLE),
    Quantity("potential_energy", ("time",), "J", "gravitational potential energy", SAMPLE),
    Quantity("strain_energy", ("time",), "J", "elastic strain energy of the beams", SAMPLE),
    Quantity(
        "contact_energy",
        ("time",),
        "J",
        "elastic energy stored in contact deformation",
        SAMPLE,
    ),
    Quantity("drive_work", ("time",), "J", "work done by the drive since the start", SAMPLE),
    Quantity(
        "dissipated_energy",
        ("time",),
        "J",
        "energy dissipated by contact damping and friction since the start",
        SAMPLE,
    ),
    Quantity(
        "section_eccentricity",
        ("revolution", "joint", "axis"),
        "m",
        "eccentricity at each crank revolution (Poincare section)",
        SECTION,
        "eccentricity",
    ),
    Quantity(
        "section_eccentricity_rate",
        ("revolution", "joint", "axis"),
        "m s-1",
        "eccentricity rate at each crank revolution",
        SECTION,
        "eccentricity_rate",
    ),
    Quantity(
        "section_position",
        ("revolution", "body", "axis"),
        "m",
        "reference point position at each crank revolution",
        SECTION,
        "position",
    ),
    Quantity(
        "section_velocity",
        ("revolution", "body", "axis"),
        "m s-1",
        "reference point velocity at each crank revolution",
        SECTION,
        "velocity",
    ),
    Quantity(
        "peak_acceleration",
        ("body", "axis"),
        "m s-2",
        f"largest |acceleration| {_PEAK}",
        PEAK,
        "acceleration",
    ),
    Quantity(
        "peak_drive_torque",
        (),
        "N m",
        f"largest |driving torque| {_PEAK}",
        PEAK,
        "drive_torque",
    ),
    Quantity(
        "peak_normal_force",
        ("joint",),
        "N",
        f"largest contact normal force {_PEAK}",
        PEAK,
        "normal_force",
    ),
    Quantity(
        "energy_error",
        ("time",),
        "J",
        "energy balance residual T+V+U+U_c-W+D minus its initial value",
        DERIVED,
    ),
    Quantity(
        "revolution_peak_acceleration",
        ("revolution", "body", "axis"),
        "m s-2",
        f"largest |acceleration| {_REVOLUTION}",
        REVOLUTION_PEAK,
        "acceleration",
    ),
    Quantity(
        "revolution_peak_drive_torque",
        ("revolution",),
        "N m",
        f"largest |driving torque| {_REVOLUTION}",
        REVOLUTION_PEAK,
        "drive_torque",
    ),
    Quantity(
        "revolution_peak_normal_force",
        ("revolution", "joint"),
        "N",
        f"largest contact normal force {_REVOLUTION}",
        REVOLUTION_PEAK,
        "normal_force",
    ),
    Quantity(
        "revolution_contact_events",
        ("revolution",),
        "1",
        "contact onsets and separations located in the revolution ending at the section",
        REVOLUTION_COUNT,
    ),
)

BY_NAME = {q.name: q for q in QUANTITIES}
COORDINATE_BY_NAME = {c.name: c for c in COORDINATES}


def recorded(how: str) -> tuple[Quantity, ...]:
    """The quantities recorded as `how` (SAMPLE, SECTION, ...), in the table's order."""
    return tuple(q for q in QUANTITIES if q.recorded == how)


def shape(dims: tuple[str, ...], n_bodies: int, n_joints: int) -> tuple[int, ...]:
    """Sizes of the dimensions `dims` (without `time` or `revolution`) for a system of
    n_bodies bodies and n_joints clearance joints."""
    sizes = {"body": n_bodies, "joint": n_joints, "axis": len(AXES)}
    return tuple(sizes[d] for d in dims)


def attributes(name: str) -> dict[str, str]:
    """The CF attributes (units, long_name) of a declared variable or coordinate."""
    if name in BY_NAME:
        q = BY_NAME[name]
        return {"units": q.units, "long_name": q.long_name}
    c = COORDINATE_BY_NAME[name]
    return {"units": c.units, "long_name": c.long_name} if c.units else {"long_name": c.long_name}

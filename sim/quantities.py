"""Every output quantity of a run, declared once: name, dimensions, units, long name and how
it is recorded.

The integrator's sample rows and peak vector (`sim.solve.record.column_layout` and
`peak_layout`, filled by the compiled `sim.solve.record.write_row` and
`sim.solve.stepping._update_peaks`), the netCDF writer and decoder (`sim.results`) and the
cross-check's output (`sim.crosscheck.run`) all follow this table. Adding an output quantity
means one entry here and, for a sampled quantity, its block in `write_row` (a peak: its
slot in `sim.solve.record.PeakSlots`, which `_update_peaks` writes through). Units are CF /
UDUNITS strings (CF conventions 1.8).

How a sample is taken (`sampling`, the scene's `simulation.sampling`):
- POINT: the value at the sample time. Content above the Nyquist frequency 1/(2 Δt) folds
  back into the recorded band: positions, velocities and the energies, smooth at the output
  rate, are recorded so.
- INTERVAL_MEAN: the mean over the sample's window, the part inside the run of
  [t − Δt/2, t + Δt/2] (Δt the output interval): what an instrument that integrates over its
  sample interval reports. A centred boxcar: gain sin(π f Δt)/(π f Δt), −3 dB at 0.443/Δt,
  zero at multiples of 1/Δt and no delay, so the flexible links' ringing (5–10 kHz) reaches
  the recorded band attenuated by at least π f Δt instead of folded in at full amplitude. A
  quantity with a `source` is formed exactly from the integrator's state at the window's
  ends: the difference of `source` over the window divided by the window's length (`per`
  empty) or by the difference of `per` (the drive torque: drive work per crank angle);
  without, it is the trapezoid rule over the accepted steps' ends, split at the window's
  ends. The first and last samples average over the half window inside the run; with
  `simulation.sampling: point` every quantity is a POINT sample.
"""

from typing import NamedTuple

# How a quantity is recorded.
SAMPLE = "sample"  # a block of columns of every sample row, at each output time
SECTION = "section"  # a sampled quantity (`source`) at each crank revolution (Poincaré section)
PEAK = "peak"  # largest |source| over every accepted step and every sample of the run
REVOLUTION_PEAK = "revolution peak"  # as PEAK, over the revolution ending at each section
REVOLUTION_COUNT = "revolution count"  # counted by the integrator in each revolution
DERIVED = "derived"  # computed from other quantities when the dataset is built

# How a SAMPLE quantity's value at a sample time is taken (see the module's docstring).
POINT = "point"
INTERVAL_MEAN = "interval mean"
SAMPLINGS = ("mean", "point")  # the scene's simulation.sampling: interval means, or points

AXES = ["x", "y"]  # the `axis` coordinate (translational joints: across, along the guide)


class Quantity(NamedTuple):
    """One output variable: its name in the dataset, its dimensions, units (CF), long name,
    how it is recorded (SAMPLE, SECTION, ...); for a SECTION or a peak, the sampled quantity
    it is taken from (`source`). A SAMPLE quantity's `sampling` (POINT or INTERVAL_MEAN); an
    interval mean with a `source` is that quantity's difference over the window per the
    window's length, or per the difference of `per`."""

    name: str
    dims: tuple[str, ...]
    units: str
    long_name: str
    recorded: str
    source: str = ""
    sampling: str = POINT
    per: str = ""


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

_PEAK = "over every accepted step's end and every sample time (point values)"
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
        "velocity",
        INTERVAL_MEAN,
    ),
    Quantity(
        "output_position",
        ("time", "axis"),
        "m",
        "position of the output point (the scene's `output`: a point of a body)",
        SAMPLE,
    ),
    Quantity("output_velocity", ("time", "axis"), "m s-1", "velocity of the output point", SAMPLE),
    Quantity(
        "output_acceleration",
        ("time", "axis"),
        "m s-2",
        "acceleration of the output point",
        SAMPLE,
        "output_velocity",
        INTERVAL_MEAN,
    ),
    Quantity(
        "angle",
        ("time", "body"),
        "rad",
        "body angle (beams: angle of the chord between end nodes)",
        SAMPLE,
    ),
    Quantity(
        "angular_velocity",
        ("time", "body"),
        "rad s-1",
        "rate of the body angle (beams: of the chord; modal links: of the floating frame)",
        SAMPLE,
    ),
    Quantity(
        "angular_acceleration",
        ("time", "body"),
        "rad s-2",
        "second derivative of the body angle (beams: of the chord; modal links: of the frame)",
        SAMPLE,
        "angular_velocity",
        INTERVAL_MEAN,
    ),
    Quantity(
        "deflection",
        ("time", "body"),
        "m",
        "mid-span transverse deflection from the chord of the end nodes (beams; 0 if rigid)",
        SAMPLE,
        sampling=INTERVAL_MEAN,
    ),
    Quantity(
        "drive_torque",
        ("time",),
        "N m",
        "driving torque applied to the crank",
        SAMPLE,
        "drive_work",
        INTERVAL_MEAN,
        per="crank_angle",
    ),
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
        sampling=INTERVAL_MEAN,
    ),
    Quantity(
        "friction_force",
        ("time", "joint"),
        "N",
        "contact friction force along the tangent (sum over contact points)",
        SAMPLE,
        sampling=INTERVAL_MEAN,
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
        "peak_output_acceleration",
        ("axis",),
        "m s-2",
        f"largest |acceleration| of the output point {_PEAK}",
        PEAK,
        "output_acceleration",
    ),
    Quantity(
        "peak_angular_velocity",
        ("body",),
        "rad s-1",
        f"largest |angular velocity| {_PEAK}",
        PEAK,
        "angular_velocity",
    ),
    Quantity(
        "peak_angular_acceleration",
        ("body",),
        "rad s-2",
        f"largest |angular acceleration| {_PEAK}",
        PEAK,
        "angular_acceleration",
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
        "revolution_peak_output_acceleration",
        ("revolution", "axis"),
        "m s-2",
        f"largest |acceleration| of the output point {_REVOLUTION}",
        REVOLUTION_PEAK,
        "output_acceleration",
    ),
    Quantity(
        "revolution_peak_angular_velocity",
        ("revolution", "body"),
        "rad s-1",
        f"largest |angular velocity| {_REVOLUTION}",
        REVOLUTION_PEAK,
        "angular_velocity",
    ),
    Quantity(
        "revolution_peak_angular_acceleration",
        ("revolution", "body"),
        "rad s-2",
        f"largest |angular acceleration| {_REVOLUTION}",
        REVOLUTION_PEAK,
        "angular_acceleration",
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


def sampling_of(q: Quantity, sampling: str) -> str:
    """How the SAMPLE quantity q is taken in a run whose simulation.sampling is `sampling`."""
    return q.sampling if sampling == "mean" else POINT


def bandwidth(how: str, interval: float) -> str:
    """What a sample taken as `how` (POINT, INTERVAL_MEAN) every `interval` s passes."""
    if how == INTERVAL_MEAN:
        return (
            f"centred boxcar of {interval:.6g} s: -3 dB at {0.443 / interval:.6g} Hz, "
            f"zeros at multiples of {1 / interval:.6g} Hz, no delay"
        )
    return f"unfiltered: content above {0.5 / interval:.6g} Hz (Nyquist) folds into the band"


def attributes(name: str, interval: float | None = None, sampling: str = "mean") -> dict[str, str]:
    """The CF attributes (units, long_name) of a declared variable or coordinate; a SAMPLE
    quantity's also say how it is sampled (`sampling`: POINT or INTERVAL_MEAN) and, given the
    output `interval` (s) and the run's simulation.sampling, the `bandwidth` that passes."""
    if name in BY_NAME:
        q = BY_NAME[name]
        attrs = {"units": q.units, "long_name": q.long_name}
        if q.recorded == SAMPLE and interval is not None:
            how = sampling_of(q, sampling)
            attrs.update(sampling=how, bandwidth=bandwidth(how, interval))
        return attrs
    c = COORDINATE_BY_NAME[name]
    return {"units": c.units, "long_name": c.long_name} if c.units else {"long_name": c.long_name}

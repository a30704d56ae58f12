"""The compiled description of a planar multibody system.

A scene is turned (by `sim.model.assembly`) into one `System`: plain arrays and
numbers that the numba kernels read. Nothing here knows about six-bars; a scene
is data.

Generalized coordinates q (n entries):
  rigid body: (x, y, θ) of its centre of mass, θ the angle of its body frame;
  ANCF beam: per node (r_x, r_y, ∂r_x/∂x, ∂r_y/∂x);
  modal link: (x, y, θ) of its mean-axis frame, then its k modal amplitudes
              (sim.model.modal).

Points (where joints attach), by kind:
  POINT_GROUND  fixed global position u;
  POINT_RIGID   body-frame vector u from the centre of mass of the rigid body whose
                coordinates start at `off`;
  POINT_NODE    position coordinates of a beam node starting at `off` (u unused);
  POINT_MODAL   body-frame vector u from the frame origin of the modal link at `off`,
                displaced locally by Σ_k pt_modal[:, k] q_k over its pt_modes modes.

Ideal constraints (rows Φ(q, t) = 0), by type, with their integer and float
parameters (`con_i`, `con_f`):
  CON_REVOLUTE   points i0, i1 coincide                         (2 rows)
  CON_PRISMATIC  rigid body at offset i0 slides along a ground guide through
                 (f0, f1) with direction angle f2; its body x axis along the
                 guide and its centre on the guide line                (2 rows)
  CON_DRIVE      coordinate i0 equals f0 + f1 t (prescribed angle)       (1 row)
  CON_CLAMP      rigid body at offset i0 held at (f0, f1, f2)            (3 rows)
  CON_CLAMP_NODE beam node at offset i0 held at position (f0, f1) and slope
                 (cos f2, sin f2)                                      (4 rows)
  CON_WELD       points i0, i1 coincide and the two rigid bodies keep the
                 relative angle f0 (body offsets in i2, i3)             (3 rows)
"""

from typing import NamedTuple

import numpy as np

POINT_GROUND, POINT_RIGID, POINT_NODE, POINT_MODAL = 0, 1, 2, 3

CON_REVOLUTE, CON_PRISMATIC, CON_DRIVE, CON_CLAMP, CON_CLAMP_NODE, CON_WELD = range(6)
CON_ROWS = (2, 2, 1, 3, 4, 3)

# Column layout of the per-joint contact outputs written by the force kernels.
OUT_PENETRATION, OUT_NORMAL_FORCE, OUT_FRICTION_FORCE, OUT_STATE, OUT_RATE = range(5)
N_JOINT_OUT = 5

# Slider–guide contact laws (ContactLaw.slider_law).
SLIDER_LAW_PAPER, SLIDER_LAW_WINKLER = 0, 1
SLIDER_LAWS = {"paper": SLIDER_LAW_PAPER, "winkler": SLIDER_LAW_WINKLER}


class ContactLaw(NamedTuple):
    """The contact parameters shared by every clearance joint (docs/model.md,
    sim.model.contact); each joint's damping law and coefficient are in its own data."""

    friction: float  # Coulomb coefficient μ
    v0: float  # m/s, modified Coulomb law: no friction below this slip speed
    v1: float  # m/s, full friction above it (linear in between)
    min_impact_speed: float  # m/s, v_min: floor of the impact speed in the damping term
    exponent: float  # Hertz exponent n of the revolute and corner forces
    slider_law: int  # SLIDER_LAW_PAPER or SLIDER_LAW_WINKLER


# Per-joint and per-beam float parameters: numba structured arrays, read in kernels as
# `sys.tj[j].gap_width` (the same loads as a column of a 2-D array, without its stride
# multiplication) and in Python as `system.tj["gap_width"]`.
REVOLUTE_CLEARANCE = np.dtype(
    [
        ("bearing_radius", np.float64),  # m
        ("journal_radius", np.float64),  # m
        ("clearance", np.float64),  # radial clearance, m
        # Hertz stiffness K, N/m^n; under Johnson's law the line stiffness π L E*, N/m
        ("stiffness", np.float64),
        ("stiffness_law", np.int64),  # code in sim.model.contact_laws.STIFFNESS_LAWS
        ("law", np.int64),  # damping law: code in sim.model.contact_laws.LAWS
        # its coefficient: χ, or c in N s/m^((n+1)/2) for a law without memory
        ("damping", np.float64),
    ],
    align=True,
)
TRANSLATIONAL_CLEARANCE = np.dtype(
    [
        ("px", np.float64),  # a point of the guide's centre line, m
        ("py", np.float64),
        ("angle", np.float64),  # direction of the guide, rad
        # its cos and sin, once: every evaluation reads the guide's frame (guide_frame)
        ("cos_angle", np.float64),
        ("sin_angle", np.float64),
        ("length", np.float64),  # slider length along the guide, m
        ("width", np.float64),  # slider width across it, m
        ("gap_width", np.float64),  # guide width, slider width plus twice the clearance, m
        ("k_face", np.float64),  # face stiffness, N/m (force per mean penetration)
        ("k_corner", np.float64),  # corner Hertz stiffness, N/m^1.5
        ("law", np.int64),  # damping law: code in sim.model.contact_laws.LAWS
        ("damping", np.float64),  # its coefficient at a corner (as REVOLUTE_CLEARANCE's)
        ("face_damping", np.float64),  # and at a face (n = 1 and k_face without memory)
    ],
    align=True,
)
BEAM = np.dtype(
    [
        ("element_length", np.float64),  # m
        ("ea", np.float64),  # axial stiffness EA, N
        ("ei", np.float64),  # bending stiffness EI, N m²
        ("damping", np.float64),  # stiffness-proportional damping coefficient β, s
    ],
    align=True,
)


class System(NamedTuple):
    """Arrays describing one planar multibody system (see the module docstring)."""

    n: int  # generalized coordinates
    m: int  # constraint equations
    mass: np.ndarray  # (n, n) constant mass matrix M
    mass_inv: np.ndarray  # (n, n) M⁻¹, block diagonal
    blk_start: np.ndarray  # (nb,) first coordinate of each mass block
    blk_end: np.ndarray  # (nb,) one past the last coordinate of each block
    gravity_force: np.ndarray  # (n,) constant generalized gravity force Q_g
    pt_kind: np.ndarray  # (np,) point kinds
    pt_off: np.ndarray  # (np,) coordinate offset of the owning body or node
    pt_u: np.ndarray  # (np, 2) body-frame vector or ground position, m
    pt_modes: np.ndarray  # (np,) modes of the owning modal link, 0 for other points
    pt_modal: np.ndarray  # (np, 2, MAX_MODES) ∂(local displacement)/∂q_k, see modal.py
    con_type: np.ndarray  # (nc,)
    con_row: np.ndarray  # (nc,) first row of each constraint
    con_i: np.ndarray  # (nc, 4) integer parameters
    con_f: np.ndarray  # (nc, 3) float parameters
    baumgarte: np.ndarray  # (2,) α and β of the Baumgarte stabilisation, 1/s
    drive_row: int  # row of the drive constraint, -1 if none
    drive_coord: int  # coordinate the drive prescribes, -1 if none
    rj_pts: np.ndarray  # (nr, 2) bearing and journal point of each revolute clearance
    rj: np.ndarray  # (nr,) REVOLUTE_CLEARANCE parameters
    rj_film: np.ndarray  # (nr,) sim.model.lubrication.FILM: each one's oil film, if any
    rj_film_table: np.ndarray  # (nr, ε, α, 2) finite bearings' film table (film_tables)
    tj_off: np.ndarray  # (nt,) slider body offset of each translational clearance
    tj: np.ndarray  # (nt,) TRANSLATIONAL_CLEARANCE parameters
    contact: ContactLaw
    beam_off: np.ndarray  # (nbm,) first coordinate of each beam
    beam_nel: np.ndarray  # (nbm,) elements per beam
    beam: np.ndarray  # (nbm,) BEAM parameters
    beam_dshape: np.ndarray  # (nbm, ga, 4) ANCF constants, see sim.model.ancf.beam_constants
    beam_axial_w: np.ndarray  # (nbm, ga)
    beam_d2shape: np.ndarray  # (nbm, gb, 4)
    beam_bending_w: np.ndarray  # (nbm, gb)
    md_off: np.ndarray  # (nmd,) first coordinate (frame x) of each modal link
    md_modes: np.ndarray  # (nmd,) its number of modes k
    md_omega: np.ndarray  # (nmd, MAX_MODES) free–free angular frequencies ω_k, rad/s
    md_beta: np.ndarray  # (nmd,) stiffness-proportional damping coefficient β, s
    md_shape: np.ndarray  # (nmd, 3, MAX_MODES) ψ_k at start, middle and end, kg^-½
    md_length: np.ndarray  # (nmd,) link length L, m
    ref_idx: np.ndarray  # (nbody, 4) coordinates combined into each reference point
    ref_coef: np.ndarray  # (nbody, 4) their coefficients (shape functions)
    ang_idx: np.ndarray  # (nbody, 2) angle coordinate (rigid) or chord nodes (beam)
    body_is_beam: np.ndarray  # (nbody,) 1 for beams
    body_modal: np.ndarray  # (nbody,) index of the modal link (md_*), −1 for other bodies
    out_pt: int  # the output point (the scene's `output`), −1: body out_body's reference point
    out_body: int  # the body the output point belongs to
    tree: np.ndarray  # (hinges,) sim.model.tree.HINGE: minimal coordinates, empty if unused


def n_clearance_joints(system: System) -> int:
    """Number of clearance joints (revolute first, then translational)."""
    return system.rj_pts.shape[0] + system.tj_off.shape[0]

"""Structural damping of a beam link (`bodies.<name>.damping`): the modal ratio is
met at the link's first pinned–pinned bending mode of the discretised beam, and a
damped flexible six-bar loses its impact-excited ringing."""

import numpy as np
from scipy.linalg import eigh

from sim.model.ancf import (
    beam_constants,
    beam_elastic_jacobian,
    beam_mass_matrix,
    straight_beam_coordinates,
)
from sim.model.assembly import stiffness_damping_coefficient
from sim.run import simulate
from sim.scene import load_scene

STEEL = {"youngs_modulus": 207.0e9, "poisson": 0.3, "density": 7801.0}
ROD4 = {"length": 0.45, "section": [0.06, 0.02], "kind": "beam", "shape": "bar"}


def pinned_pinned_first_frequency(body: dict, material: dict, elements: int) -> float:
    """ω₁ (rad/s) of the ANCF model of the link, both end positions held, slopes free."""
    width, height = body["section"]
    area, inertia = width * height, width * height**3 / 12.0
    e, rho = material["youngs_modulus"], material["density"]
    length = body["length"]
    constants = beam_constants(length / elements, e * area, e * inertia)
    q = straight_beam_coordinates(np.zeros(2), np.array([length, 0.0]), elements)
    stiffness = np.zeros((q.size, q.size))
    beam_elastic_jacobian(
        q,
        constants.dshape,
        constants.axial_weight,
        constants.d2shape,
        constants.bending_weight,
        stiffness,
    )
    mass = beam_mass_matrix(rho * area, length, elements)
    held = {0, 1, q.size - 4, q.size - 3}
    free = [i for i in range(q.size) if i not in held]
    squared = eigh(stiffness[np.ix_(free, free)], mass[np.ix_(free, free)], eigvals_only=True)
    return float(np.sqrt(squared[0]))


def test_modal_ratio_is_met_at_the_first_pinned_pinned_mode():
    """β = 2ζ/ω₁ with the Euler–Bernoulli ω₁; on the 8-element ANCF link (whose ω₁
    is within 1e-4 of Euler–Bernoulli) the first mode gets ζ = β ω₁ / 2."""
    body = {**ROD4, "damping": {"kind": "modal", "ratio": 0.02}}
    beta = stiffness_damping_coefficient(body, STEEL)
    omega1 = pinned_pinned_first_frequency(body, STEEL, 8)
    assert abs(0.5 * beta * omega1 / 0.02 - 1.0) < 1e-3
    direct = {**ROD4, "damping": {"kind": "stiffness", "coefficient": 3e-5}}
    assert stiffness_damping_coefficient(direct, STEEL) == 3e-5
    assert stiffness_damping_coefficient({**ROD4, "damping": {"kind": "none"}}, STEEL) == 0.0


def test_damping_removes_the_ringing_of_a_straight_start():
    """Started straight, the beams ring; 5 % modal damping takes the ringing out of
    the slider acceleration within a fifth of a revolution, while the undamped
    ringing persists (no damping by default, as in the paper)."""
    beams = [f"bodies.{b}.kind=beam" for b in ("rod2", "rod3", "rod4")]
    sets = [
        *beams,
        "solver.method=generalized_alpha",
        "simulation.beam_start=straight",
        "simulation.revolutions=0.25",
        "simulation.output_per_revolution=2000",
    ]
    rigid = simulate(load_scene("sixbar", sets), rigid=True)
    damped_sets = [
        *sets,
        *(f"bodies.{b}.damping={{kind: modal, ratio: 0.05}}" for b in ("rod2", "rod3", "rod4")),
    ]
    late = slice(400, None)  # the last 0.05 revolution
    ref = rigid.acceleration.sel(body="slider", axis="y").values[late]

    def late_ringing(ds) -> float:
        return float(
            np.max(np.abs(ds.acceleration.sel(body="slider", axis="y").values[late] - ref))
        )

    undamped = late_ringing(simulate(load_scene("sixbar", sets)))
    damped = late_ringing(simulate(load_scene("sixbar", damped_sets)))
    assert damped < 0.2 * undamped

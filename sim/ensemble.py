"""Ensemble members: one scene run from slightly perturbed initial states.

A chaotic run's statistics are one draw of many; an ensemble repeats the run from initial
states a hair apart. Member 0 is the nominal run (no perturbation, so an ensemble of one is the
plain run). Member k ≥ 1 starts at the initial crank angle (`drive.initial_angle_deg`, an
existing scene key: the assembly closes the loops there) shifted by a normal draw of standard
deviation `size_deg` from the generator seeded with `base_seed + k` (numpy's PCG64), so
members are reproducible and two ensembles with different base seeds are different draws.

Measured (sixbar, A and B 0.4 mm, 150 rpm, rigid, DOPRI5 at rtol 1e-5): a shift of 1e-10 deg
already moves journal A's Poincaré point by 0.1 clearance after the first revolution, as
much as 1e-7 deg does; the members are apart within the transient whatever the size, so the
size only needs to stay far below anything physical.
"""

from dataclasses import dataclass

import numpy as np

#: default standard deviation of the initial crank angle's shift (deg): 1e-9 deg moves joint
#: A (crank 0.1 m) by 1.7e-12 m, 1.7e-8 of the smallest clearance studied (0.1 mm)
DEFAULT_SIZE_DEG = 1.0e-9
PERTURBED_KEY = "drive.initial_angle_deg"


@dataclass(frozen=True)
class Member:
    """One ensemble member: its index, its seed (base seed + index; -1 for the nominal run)
    and the shift of the initial crank angle it starts from (deg)."""

    index: int = 0
    seed: int = -1
    shift_deg: float = 0.0

    def attrs(self) -> dict:
        """The member's provenance, as netCDF global attributes."""
        return {
            "ensemble_member": self.index,
            "ensemble_seed": self.seed,
            "perturbation": f"initial crank angle ({PERTURBED_KEY}) shifted by shift_deg",
            "perturbation_shift_deg": self.shift_deg,
        }


def member(index: int, base_seed: int, size_deg: float = DEFAULT_SIZE_DEG) -> Member:
    """Member `index` of the ensemble with `base_seed`: the nominal run for index 0, else a
    shift of the initial crank angle of standard deviation `size_deg` (deg)."""
    if index < 0:
        raise ValueError(f"ensemble member index must be >= 0, got {index}")
    if index == 0:
        return Member()
    seed = base_seed + index
    shift = size_deg * float(np.random.default_rng(seed).standard_normal())
    return Member(index=index, seed=seed, shift_deg=shift)


def perturbed(scene: dict, who: Member) -> dict:
    """A copy of the resolved `scene` that starts as member `who` does."""
    if who.shift_deg == 0.0:
        return scene
    drive = dict(
        scene["drive"], initial_angle_deg=scene["drive"]["initial_angle_deg"] + who.shift_deg
    )
    return dict(scene, drive=drive)

"""Independent cross-check with Exudyn, in place of the paper's comparison with ADAMS.

The same resolved scene, started from the same initial state, is built and integrated in
Exudyn (an open-source flexible multibody code: Gerstmayr, Multibody Syst. Dyn. 60, 2024; install
with ``pip install -e '.[crosscheck]'``) and compared with our run:

- `sim.crosscheck.contact`: the clearance contact laws for Exudyn, written anew from docs/model.md;
- `sim.crosscheck.model`: the scene as an Exudyn model (needs exudyn); its revolute clearances
  take our laws through a user function, or, to compare the contact law itself, Exudyn's own
  contact object under the same law (`EXUDYN_IMPACT_MODELS`);
- `sim.crosscheck.recorder`: Exudyn's sensor values at our output times;
- `sim.crosscheck.run`: `simulate_exudyn`, an output Dataset with our variable names, and
  `run_both` for timed pairs (needs exudyn);
- `sim.crosscheck.compare`: agreement measures (error norms, filtered and spectral
  comparisons, peak and Poincaré statistics, a single impact, the two elastic laws);
- `sim.crosscheck.figures`: the two codes overlaid, their differences and statistics.

Remaining differences by design: Exudyn integrates with fixed steps (trapezoidal rule with
index-2 constraints, or generalized-α), satisfies the constraints by its Newton iteration and
takes the contact onset rate at step starts; we integrate with adaptive DOPRI5 (or our
generalized-α), Baumgarte-stabilised constraints and located contact events. The beams' elastic
laws differ slightly (`sim.crosscheck.model`).
"""

import importlib.util


def exudyn_available() -> bool:
    """True when the exudyn package can be imported."""
    return importlib.util.find_spec("exudyn") is not None

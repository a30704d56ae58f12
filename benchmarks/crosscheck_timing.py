"""Wall time of sim and of Exudyn on the three cross-check cases, in one process on one core.

    python benchmarks/crosscheck_timing.py [--revolutions-scale 1.0]

Prints, per case, each code's wall time (s), real-time factor (simulated over wall time) and
Exudyn's fixed step, and the agreement figure of the case; then how much our beam law and
Exudyn's differ at the flexible case's initial state. The cases are those of the
cross-check study (config/config.yaml `cross-check`): rigid ideal (1 revolution sampled 400
times, Exudyn 1e-4 s steps), flexible ideal (rod2–rod4 two-element ANCF beams, 0.25 revolution
sampled at 50 kHz, Exudyn 5e-6 s steps), A and B at 0.5 mm (2 revolutions, Exudyn 1e-5 s
steps). sim integrates with its scene's solver (DOPRI5, rtol 1e-6), its kernels compiled
before the timed run. Needs exudyn
(pip install -e '.[crosscheck]'). Run it on an idle machine: both codes share it.
"""

import argparse

from sim.crosscheck.compare import deterministic, elastic_law_difference
from sim.crosscheck.run import ExudynSettings, run_both
from sim.run import prepare
from sim.scene import load_scene

BEAMS = [f"bodies.{b}.kind=beam" for b in ("rod2", "rod3", "rod4")]
CASES = {
    "rigid ideal": ([], 1.0, 400, ExudynSettings(steps_per_sample=10), None),
    "flexible ideal": (
        BEAMS,
        0.25,
        20000,
        ExudynSettings(steps_per_sample=4, newton_relative_tolerance=1e-8),
        100.0,
    ),
    "A, B 0.5 mm": (
        ["joints.A.clearance=5e-4", "joints.B.clearance=5e-4"],
        2.0,
        400,
        ExudynSettings(steps_per_sample=100, newton_relative_tolerance=1e-8),
        None,
    ),
}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--revolutions-scale", type=float, default=1.0)
    args = parser.parse_args()
    print(f"{'case':16s} {'code':7s} {'wall s':>8s} {'RTF':>8s} {'step s':>9s}  agreement")
    for case, (sets, revolutions, per_rev, settings, cutoff) in CASES.items():
        scene = load_scene(
            "sixbar",
            [
                *sets,
                f"simulation.revolutions={revolutions * args.revolutions_scale}",
                f"simulation.output_per_revolution={per_rev}",
            ],
        )
        ours, theirs = run_both(scene, settings)
        if len(ours.joint):
            agreement = "chaotic: compared by statistics (cross-check study)"
        else:
            metrics = deterministic(ours, theirs, cutoff)
            band = "low" if cutoff else "raw"
            agreement = f"max |Δ| / peak ({band}): " + ", ".join(
                f"{name} {metrics[name][band]['max']:.2g}"
                for name in ("acceleration", "drive_torque")
            )
        for code, ds in (("sim", ours), ("exudyn", theirs)):
            step = f"{ds.attrs['solver_step_s']:9.2g}" if code == "exudyn" else f"{'adaptive':>9s}"
            print(
                f"{case:16s} {code:7s} {ds.attrs['solver_wall_time_s']:8.3g} "
                f"{ds.attrs['real_time_factor']:8.3g} {step}  "
                + (agreement if code == "exudyn" else "")
            )
    print_elastic_laws()


def print_elastic_laws() -> None:
    """Our beam law against Exudyn's at the flexible case's initial (quasi-static) state."""
    scene = load_scene("sixbar", BEAMS)
    start = prepare(scene, revolutions=0.0)
    system, q = start.system, start.y[: start.system.n]
    print("elastic laws at the initial state (ours against Exudyn's ANCFCable2D law):")
    for k, name in enumerate(b for b in start.layout.bodies if start.layout.is_beam[b]):
        o, ne = system.beam_off[k], system.beam_nel[k]
        beam = system.beam[k]
        diff = elastic_law_difference(
            q[o : o + 4 * (ne + 1)].copy(), beam["element_length"], beam["ea"], beam["ei"]
        )
        print(
            f"  {name}: max |ΔF| {diff['force']:.2g} of max |F|, strain energy {diff['energy']:.2g}"
        )


if __name__ == "__main__":
    main()

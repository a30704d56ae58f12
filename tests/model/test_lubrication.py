"""The lubricated revolute clearance joint (sim.model.lubrication) against closed forms:

- the film force of the compiled kernels: the short bearing against a quadrature of Ocvirk's
  pressure over its positive part, the long bearing's steady forces against Pinkus &
  Sternlicht's half-Sommerfeld closed form, both bearings' pure squeeze against the closed
  forms, and the film's power never positive;
- the finite bearing: its Reynolds solver tends to the short bearing as L/D → 0, and the
  kernel's interpolation of the stored table follows the solver between its points;
- a journal under its weight turned at constant speed, through `simulate`, settles at the
  short bearing's steady eccentricity (from the Sommerfeld number) and attitude angle, and
  at L/D = 1 at the finite bearing's;
- the energy audits of lubricated runs of the six-bar (long bearing) and the four-bar (short
  bearing) close, and the dissipated energy never falls;
- a bearing length for which no model holds is refused, naming the key and the range.
"""

import math

import numpy as np
import pytest
from scipy import integrate, optimize

from sim.model.finite_bearing import force_integrals
from sim.model.lubrication import (
    BEARING_FINITE,
    FILM,
    film_tables,
    finite_bearing_force,
    long_bearing_force,
    short_bearing_force,
    sommerfeld_angle,
)
from sim.run import simulate
from sim.scene import SceneError, load_scene

MU, R, L, C = 0.05, 0.01, 0.008, 1.0e-4  # Pa s, m, m, m: a bearing for the kernel checks


def short_reference(eps: float, vr: float, vt: float) -> tuple[float, float]:
    """(F_n, F_t) (N) of a short bearing by quadrature: Ocvirk's pressure integrated over the
    length, μ L³ (V·n_ψ)/h³, kept where positive (Gümbel), over the circumference."""

    def component(psi: float, k: int) -> float:
        squeeze = vr * math.cos(psi) + vt * math.sin(psi)
        p = MU * L**3 * max(squeeze, 0.0) / (C * (1.0 - eps * math.cos(psi))) ** 3
        return -p * R * (math.cos(psi) if k == 0 else math.sin(psi))

    return tuple(
        integrate.quad(component, -math.pi, math.pi, args=(k,), points=[0.0], limit=400)[0]
        for k in (0, 1)
    )


def test_sommerfeld_angle_is_the_substitution():
    for eps in (0.0, 0.4, 0.95):
        for psi in np.linspace(-4.0, 4.0, 17):
            gamma = sommerfeld_angle(psi, eps)
            assert math.cos(gamma) == pytest.approx(
                (math.cos(psi) - eps) / (1.0 - eps * math.cos(psi)), abs=1e-12
            )


@pytest.mark.parametrize(
    "eps, vr, vt",
    [
        (0.5, 0.01, 0.0),
        (0.5, 0.0, -0.02),
        (0.8, 0.003, -0.01),
        (0.95, -0.002, 0.01),
        (0.0, 0.01, 0.01),
    ],
)
def test_short_bearing_force_is_the_positive_pressure_integral(eps, vr, vt):
    # closed form over the π-film against the quadrature: only round-off apart
    assert short_bearing_force(eps, vr, vt, MU, R, L, C) == pytest.approx(
        short_reference(eps, vr, vt), rel=1e-8, abs=1e-9
    )


@pytest.mark.parametrize("eps", [0.2, 0.6, 0.9, 0.99])
def test_long_bearing_steady_force_is_pinkus_sternlicht(eps):
    # journal at ω, bearing still: ω̄ = ω/2 and V = (0, −c ε ω̄). Pinkus & Sternlicht (1961),
    # half-Sommerfeld: W_r = K 2ε²/((2 + ε²)(1 − ε²)), W_t = K π ε/((2 + ε²)√(1 − ε²)),
    # K = 6 μ ω R³ L/c². The kernel's trapezoid rule is within 1e-4 (LONG_NODES).
    omega = 20.0
    fn, ft = long_bearing_force(eps, 0.0, -C * eps * omega / 2.0, MU, R, L, C)
    k = 6.0 * MU * omega * R**3 * L / C**2
    assert -fn == pytest.approx(k * 2 * eps**2 / ((2 + eps**2) * (1 - eps**2)), rel=2e-4)
    assert ft == pytest.approx(k * math.pi * eps / ((2 + eps**2) * math.sqrt(1 - eps**2)), rel=2e-4)


@pytest.mark.parametrize("eps", [0.0, 0.3, 0.7, 0.95])
def test_pure_squeeze_follows_the_closed_forms(eps):
    rate = 0.05  # ε̇, 1/s: the journal pushed along e without rotation
    vr = C * rate

    # short bearing, p > 0 on the half |ψ| < π/2 facing the motion (π/2 ∓ asin ε away
    # from it): F_n = −(μ R L³ ε̇/c²) g(±ε)/(1 − ε²)^(5/2),
    # g(ε) = (1 + 2ε²)(π/2 + asin ε) + 3ε√(1 − ε²)
    def g(x: float) -> float:
        return (1 + 2 * x * x) * (math.pi / 2 + math.asin(x)) + 3 * x * math.sqrt(1 - x * x)

    scale = MU * R * L**3 * rate / C**2 / (1 - eps**2) ** 2.5
    fn, ft = short_bearing_force(eps, vr, 0.0, MU, R, L, C)
    assert fn == pytest.approx(-scale * g(eps), rel=1e-10)
    assert ft == pytest.approx(0.0, abs=1e-12 * scale)
    # moving away, the film faces the thick side
    assert short_bearing_force(eps, -vr, 0.0, MU, R, L, C)[0] == pytest.approx(
        scale * g(-eps), rel=1e-10
    )
    # long bearing, pressure zero at the thickest film and positive all round when the
    # journal closes in: F_n = −12 π μ R³ L ε̇/(c² (1 − ε²)^(3/2)) (Pinkus & Sternlicht);
    # moving away, the film cavitates everywhere
    fn, ft = long_bearing_force(eps, vr, 0.0, MU, R, L, C)
    exact = -12 * math.pi * MU * R**3 * L * rate / (C**2 * (1 - eps**2) ** 1.5)
    assert fn == pytest.approx(exact, rel=1e-6)
    assert ft == pytest.approx(0.0, abs=1e-9 * abs(exact))
    assert long_bearing_force(eps, -vr, 0.0, MU, R, L, C) == (0.0, 0.0)


def finite_table(ratio: float) -> np.ndarray:
    """The finite bearing's table at L/D `ratio` for a journal of radius 1 m."""
    film = np.array([(BEARING_FINITE, 1.0, 2.0 * ratio, 1e-6)], dtype=FILM)
    return film_tables(film, np.array([1.0]))[0]


def test_the_film_never_does_work():
    # F·V ≤ 0 for every model at any eccentricity and relative velocity (module docstring)
    rng = np.random.default_rng(1)
    table = finite_table(1.2)
    for _ in range(300):
        eps = rng.uniform(0.0, 0.999)
        vr, vt = rng.normal(0.0, 0.01, 2)
        forces = [
            force(eps, vr, vt, MU, R, L, C) for force in (short_bearing_force, long_bearing_force)
        ]
        forces.append(finite_bearing_force(table, eps, vr, vt, MU, R, C))
        for fn, ft in forces:
            assert fn * vr + ft * vt <= 1e-12 * math.hypot(fn, ft) * math.hypot(vr, vt)


@pytest.mark.parametrize("eps", [0.3, 0.9])
def test_finite_bearing_tends_to_the_short_one(eps):
    # L/D = 0.02: G = (2λ³/3) ∫ (V̂·n)⁺ n dψ/H³, the short bearing's π-film, i.e. its force
    # with μ = R = c = 1, L = 2λ, over −12. Measured 0.13 % (ε = 0.3), 0.56 % (0.9): the
    # rest is the circumferential flow a bearing of finite length keeps.
    ratio = 0.02
    angles = np.array([0.0, -math.pi / 2, 0.7, 2.5])
    finite = force_integrals(ratio, eps, angles, grid=(256, 32))
    for alpha, g in zip(angles, finite, strict=True):
        short = short_bearing_force(eps, math.cos(alpha), math.sin(alpha), 1.0, 1.0, 2 * ratio, 1.0)
        reference = -np.array(short) / 12.0
        assert np.abs(g - reference).max() <= 1e-2 * np.abs(reference).max()


@pytest.mark.parametrize("ratio", [1.0, 0.61, 1.37, 1.93])
def test_finite_bearing_kernel_follows_the_solver(ratio):
    # the stored table at the table's L/D (1.0) and between (power of L/D), interpolated in
    # ε and α by the kernel, against a fresh solution at random states. Errors relative to
    # the squeeze force at the same ε (the scale of the joint's force there): measured
    # 9e-4 on the table's L/D, up to 2e-3 between
    rng = np.random.default_rng(int(ratio * 100))
    table = finite_table(ratio)
    for _ in range(6):
        eps = 1.0 - math.exp(-rng.uniform(0.0, 7.5))
        alpha = rng.uniform(-math.pi, math.pi)
        got = finite_bearing_force(table, eps, math.cos(alpha), math.sin(alpha), 1.0, 1.0, 1.0)
        solved = -12.0 * force_integrals(ratio, eps, np.array([alpha, 0.0]))
        assert np.abs(np.array(got) - solved[0]).max() <= 4e-3 * np.abs(solved[1]).max()


JOURNAL = """
name: journal
description: a 1 kg journal under its weight in a lubricated bearing, turned at constant speed
materials:
  steel: {{youngs_modulus: 207.0e9, poisson: 0.3, density: 7801.0}}
ground:
  O: [0.0, 0.0]
bodies:
  rotor: {{shape: bar, length: 0.05, section: [0.02, 0.02], material: steel, mass: 1.0,
          inertia: 1.0e-4}}
joints:
  O:
    type: revolute
    bodies: [ground, rotor]
    points: [O, centre]
    clearance: 1.0e-4
    bearing_radius: 0.015
    lubricant: {{viscosity: {viscosity}, length: {length}}}
drive: {{body: rotor, speed_rpm: 1000.0}}
output: {{body: rotor, axis: y}}
simulation: {{revolutions: 10}}
"""
CLEARANCE, RADIUS = 1.0e-4, 0.015 - 1.0e-4  # m: the journal's
OMEGA, LOAD = 1000.0 * 2.0 * math.pi / 60.0, 9.81  # rad/s, N


def settled_journal(tmp_path, viscosity: float, length: float) -> tuple[float, float]:
    """(ε, attitude angle φ (rad) from the load towards the journal's turning) where the
    journal of JOURNAL is after 10 revolutions (0.6 s; the film damps the fall in about
    0.2 s)."""
    path = tmp_path / "journal.yaml"
    path.write_text(JOURNAL.format(viscosity=viscosity, length=length))
    ds = simulate(load_scene(str(path)))
    assert ds.attrs["energy_error_relative"] < 1e-6
    ex, ey = ds.eccentricity.sel(joint="O").values[-1]
    return math.hypot(ex, ey) / CLEARANCE, math.atan2(ex, -ey)


def test_journal_settles_at_the_short_bearing_steady_state(tmp_path):
    # L/D = 0.01/0.0298 = 0.34. Ocvirk's steady load (Frêne et al. §8.3):
    # W = (μ U L³/(4c²)) ε √(π²(1 − ε²) + 16ε²)/(1 − ε²)², U = R ω; attitude angle between
    # the load and the line of centres tan φ = π √(1 − ε²)/(4ε), the journal displaced to the
    # side its bottom turns to. Measured: both within 1e-7.
    mu, length = 0.05, 0.01

    def excess(eps: float) -> float:
        root = math.sqrt(math.pi**2 * (1 - eps**2) + 16 * eps**2)
        scale = mu * RADIUS * OMEGA * length**3 / (4 * CLEARANCE**2)
        return scale * eps * root / (1 - eps**2) ** 2 - LOAD

    eps = optimize.brentq(excess, 1e-6, 0.999)
    settled, attitude = settled_journal(tmp_path, mu, length)
    assert settled == pytest.approx(eps, abs=1e-4)  # 0.598
    assert attitude == pytest.approx(
        math.atan(math.pi * math.sqrt(1 - eps**2) / (4 * eps)), abs=1e-4
    )


def test_journal_settles_at_the_finite_bearing_steady_state(tmp_path):
    # L/D = 1: the steady state the finite bearing's table gives, |F| = W at
    # V = (0, −c ε ω/2) and tan φ = F_t/(−F_n), by root finding on the kernel's force
    mu, length = 0.005, 2.0 * RADIUS
    film = np.array([(BEARING_FINITE, mu, length, 1.5e-6)], dtype=FILM)
    table = film_tables(film, np.array([RADIUS]))[0]

    def force(eps: float) -> tuple[float, float]:
        vt = -CLEARANCE * eps * OMEGA / 2.0
        return finite_bearing_force(table, eps, 0.0, vt, mu, RADIUS, CLEARANCE)

    eps = optimize.brentq(lambda e: math.hypot(*force(e)) - LOAD, 1e-3, 0.999)
    fn, ft = force(eps)
    settled, attitude = settled_journal(tmp_path, mu, length)
    assert settled == pytest.approx(eps, abs=1e-4)
    assert attitude == pytest.approx(math.atan2(ft, -fn), abs=1e-4)


@pytest.mark.parametrize(
    "scene, overrides",
    [
        ("sixbar-lubricated", ["simulation.revolutions=1"]),
        (
            "fourbar",
            ["joints.B.lubricant={viscosity: 0.05, length: 0.01}", "simulation.revolutions=2"],
        ),
    ],
)
def test_energy_audit_of_a_lubricated_run_closes(scene, overrides):
    # the six-bar's joint A a long bearing whose film thins below the threshold and hands
    # over to the dry law (one impact), the four-bar's B a short one (L/D = 0.34) at ε up to
    # 0.98: the film's power is booked as dissipated, and the audit closes as a dry run's
    # (measured 1.4e-5 and 8.6e-7)
    ds = simulate(load_scene(scene, overrides))
    dissipated = ds.dissipated_energy.values
    assert dissipated[-1] > 0.0
    # the film never creates (test_the_film_never_does_work); the integrated energy may dip
    # by the integrator's error where the squeeze power peaks within a step (DOPRI5 weighs
    # one stage negatively): measured 2.8e-7 of the total on the six-bar
    assert np.all(np.diff(dissipated) >= -1e-6 * dissipated[-1])
    assert ds.attrs["energy_error_relative"] < 1e-4


def test_threshold_outside_its_range_is_refused():
    with pytest.raises(SceneError, match=r"joints\.A\.lubricant\.threshold.*< 5e-05 m"):
        load_scene(
            "sixbar-lubricated", ["joints.A.clearance=5e-5", "joints.A.lubricant.threshold=8e-5"]
        )
    # a finite bearing (L/D = 1.02) film thinner than its table's end, 5e-4 of the clearance
    with pytest.raises(SceneError, match=r"joints\.B\.lubricant\.threshold.*1\.5e-07 ≤ x"):
        load_scene(
            "fourbar", ["joints.B.lubricant={viscosity: 0.05, length: 0.03, threshold: 1.0e-7}"]
        )

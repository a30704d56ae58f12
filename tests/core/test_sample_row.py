"""Each sampled quantity lands in its own columns (sim.quantities, sim.solve.record.write_row).

The slider-crank of sim/scenes/slider-crank.yaml (crank r = 0.05 m, rod l = 0.20 m, slider
on the horizontal guide through the crank pivot O, steel, 300 rpm from φ = 0) has closed
forms for every quantity while its joints are ideal and its links rigid: φ = ω t, the
slider at x = r cos φ + √(l² − r² sin² φ), the rod at angle −asin(r sin φ / l), the
energies from the masses ρ A L (bars) and ρ a b d (block). With clearance in A (revolute) and
B (translational), the joint columns are checked against the body columns they follow from
and against the contact law's structure. A quantity written into another's columns fails
these comparisons: every block is compared with a reference that differs from its neighbours'.
"""

import json

import numpy as np
import pytest

from sim.quantities import (
    BY_NAME,
    INTERVAL_MEAN,
    PEAK,
    POINT,
    QUANTITIES,
    REVOLUTION_PEAK,
    SAMPLE,
    SECTION,
    recorded,
)

R, L = 0.05, 0.20  # m: crank, rod
OMEGA = 2 * np.pi * 300 / 60  # rad/s
RHO, G = 7801.0, 9.81
MASS = {
    "crank": RHO * R * 0.02 * 0.01,
    "rod": RHO * L * 0.02 * 0.01,
    "slider": RHO * 0.06 * 0.04 * 0.02,
}
INERTIA = {"crank": MASS["crank"] * R**2 / 12, "rod": MASS["rod"] * L**2 / 12}


def slider_x(phi):
    """Slider position along the guide (m) at crank angle phi (closed form)."""
    return R * np.cos(phi) + np.sqrt(L**2 - (R * np.sin(phi)) ** 2)


def closed_forms(t):
    """Body reference points (centres), velocities, rod angle and rod angular rate at times t
    of the ideal rigid slider-crank."""
    phi = OMEGA * t
    xs = slider_x(phi)
    root = np.sqrt(L**2 - (R * np.sin(phi)) ** 2)
    xs_d = -R * OMEGA * np.sin(phi) * (1 + R * np.cos(phi) / root)
    xs_dd = -(OMEGA**2) * (
        R * np.cos(phi)
        + R**2 * np.cos(2 * phi) / root
        + R**4 * (np.sin(phi) * np.cos(phi)) ** 2 / root**3
    )
    tip = R * np.stack([np.cos(phi), np.sin(phi)], axis=1)
    tip_d = R * OMEGA * np.stack([-np.sin(phi), np.cos(phi)], axis=1)
    zero = np.zeros_like(t)
    slider = np.stack([xs, zero], axis=1)
    slider_d = np.stack([xs_d, zero], axis=1)
    rod_angle = -np.arcsin(R * np.sin(phi) / L)
    rod_rate = -R * OMEGA * np.cos(phi) / (L * np.cos(rod_angle))
    # d/dt of rod_rate = −(r ω / l) cos φ / cos θ
    rod_acceleration = (R * OMEGA**2 / L) * np.sin(phi) / np.cos(rod_angle) - (
        R * OMEGA / L
    ) * np.cos(phi) * np.sin(rod_angle) * rod_rate / np.cos(rod_angle) ** 2
    return {
        "position": {"crank": tip / 2, "rod": (tip + slider) / 2, "slider": slider},
        "velocity": {"crank": tip_d / 2, "rod": (tip_d + slider_d) / 2, "slider": slider_d},
        "crank_acceleration": -(OMEGA**2) * tip / 2,
        "slider_acceleration": np.stack([xs_dd, zero], axis=1),
        "rod_angle": rod_angle,
        "rod_rate": rod_rate,
        "rod_acceleration": rod_acceleration,
    }


def windows(t):
    """Each sample's window: the part inside the run of [t − Δt/2, t + Δt/2]."""
    half = 0.5 * (t[1] - t[0])
    return np.maximum(t - half, t[0]), np.minimum(t + half, t[-1])


def window_mean_of_rate(f, t):
    """Mean over each sample's window of the rate of f (closed form of t): its difference
    over the window per the window's length."""
    a, b = windows(t)
    return (f(b) - f(a)) / (b - a)[:, None] if f(a).ndim > 1 else (f(b) - f(a)) / (b - a)


@pytest.fixture(scope="module")
def ideal(run):
    return run(
        "slider-crank",
        "simulation.revolutions=1",
        "simulation.output_per_revolution=400",
        "solver.rtol=1e-9",
        "solver.atol=1e-11",
    )


@pytest.fixture(scope="module")
def ideal_points(run):
    return run(
        "slider-crank",
        "simulation.revolutions=1",
        "simulation.output_per_revolution=400",
        "simulation.sampling=point",
        "solver.rtol=1e-9",
        "solver.atol=1e-11",
    )


CLEARANCE = ("joints.A.clearance=5e-4", "joints.B.clearance=5e-4", "contact.friction=0.1")


@pytest.fixture(scope="module")
def clearance(run):
    return run(
        "slider-crank",
        "simulation.revolutions=1",
        "simulation.output_per_revolution=2000",
        *CLEARANCE,
    )


@pytest.fixture(scope="module")
def clearance_points(run):
    """The same run's point samples at twice the rate: DOPRI5's steps do not depend on the
    output times, so its even samples are the other run's sample times and its odd samples
    the ends of their windows, read on the same continuous extension."""
    return run(
        "slider-crank",
        "simulation.revolutions=1",
        "simulation.output_per_revolution=4000",
        "simulation.sampling=point",
        *CLEARANCE,
    )


def test_the_table_is_consistent():
    # A section or a peak is taken from a sampled quantity, over the same dimensions; the
    # per-revolution peaks follow the peaks' order (they share the integrator's layout).
    for q in QUANTITIES:
        if q.recorded in (SECTION, PEAK, REVOLUTION_PEAK):
            source = BY_NAME[q.source]
            assert source.recorded == SAMPLE, q.name
            lead = {SECTION: ("revolution",), PEAK: (), REVOLUTION_PEAK: ("revolution",)}
            assert q.dims == lead[q.recorded] + source.dims[1:], q.name
    assert [q.source for q in recorded(REVOLUTION_PEAK)] == [q.source for q in recorded(PEAK)]


def test_a_run_file_holds_every_quantity_with_its_dims_and_attributes(
    ideal, ideal_points, clearance
):
    for ds, sampling in ((ideal, "mean"), (ideal_points, "point"), (clearance, "mean")):
        assert set(ds.data_vars) == {q.name for q in QUANTITIES}
        interval = float(ds.time[1] - ds.time[0])
        for q in QUANTITIES:
            assert ds[q.name].dims == q.dims, q.name
            attrs = ds[q.name].attrs
            assert {k: attrs[k] for k in ("units", "long_name")} == {
                "units": q.units,
                "long_name": q.long_name,
            }, q.name
            if q.recorded != SAMPLE:
                assert set(attrs) == {"units", "long_name"}, q.name
                continue
            how = q.sampling if sampling == "mean" else POINT
            assert attrs["sampling"] == how, q.name
            # the boxcar's −3 dB frequency, or the Nyquist frequency of a point sample
            edge = 0.443 / interval if how == INTERVAL_MEAN else 0.5 / interval
            assert f"{edge:.6g} Hz" in attrs["bandwidth"], q.name
    assert list(clearance.joint.values) == ["A", "B"]
    fast = {q.name for q in recorded(SAMPLE) if q.sampling == INTERVAL_MEAN}
    assert fast == {
        "acceleration",
        "output_acceleration",
        "angular_acceleration",
        "deflection",
        "drive_torque",
        "normal_force",
        "friction_force",
    }


def test_kinematic_columns_of_the_ideal_rigid_slider_crank(ideal, ideal_points):
    # Bounds: the run's tolerance is 1e-9; the constraints hold the linkage to round-off
    # and the drive to the crank angle: measured below 2e-11 of each quantity's scale, so
    # 1e-7 (accelerations 1e-6) leaves a margin above 1000. The interval means of the
    # accelerations are the velocities' differences over each window per its length
    # (sim.solve.means), compared with the same of the closed form; the point samples with
    # the closed form's accelerations.
    t = ideal.time.values
    ref = closed_forms(t)
    np.testing.assert_allclose(ideal.crank_angle, OMEGA * t, rtol=0, atol=1e-7)
    angle = ideal.angle.sel(body=["crank", "rod", "slider"]).values
    np.testing.assert_allclose(angle[:, 0], OMEGA * t, rtol=0, atol=1e-7)
    np.testing.assert_allclose(angle[:, 1], ref["rod_angle"], rtol=0, atol=1e-7)
    np.testing.assert_allclose(angle[:, 2], 0.0, rtol=0, atol=1e-7)
    for what, scale in (("position", R), ("velocity", R * OMEGA)):
        for body, expected in ref[what].items():
            got = ideal[what].sel(body=body).values
            np.testing.assert_allclose(got, expected, rtol=0, atol=1e-7 * scale, err_msg=what)
    acc = R * OMEGA**2
    for body in ("crank", "slider"):
        means = window_mean_of_rate(lambda s, b=body: closed_forms(s)["velocity"][b], t)
        np.testing.assert_allclose(
            ideal.acceleration.sel(body=body), means, rtol=0, atol=1e-6 * acc, err_msg=body
        )
    # a window's mean differs from the point value at its centre by the acceleration's second
    # derivative times Δt²/24 (1e-4 of the scale here): the means are not point samples
    assert np.abs(ideal.acceleration.sel(body="slider") - ref["slider_acceleration"]).max() > (
        1e-5 * acc
    )
    np.testing.assert_allclose(
        ideal_points.acceleration.sel(body="crank"),
        ref["crank_acceleration"],
        rtol=0,
        atol=1e-6 * acc,
    )
    np.testing.assert_allclose(
        ideal_points.acceleration.sel(body="slider"),
        ref["slider_acceleration"],
        rtol=0,
        atol=1e-6 * acc,
    )
    # the output point: the scene's default, the slider's centre, in its own columns
    for what, scale in (("position", R), ("velocity", R * OMEGA)):
        got = ideal[f"output_{what}"].values
        np.testing.assert_allclose(got, ref[what]["slider"], rtol=0, atol=1e-7 * scale)
    means = window_mean_of_rate(lambda s: closed_forms(s)["velocity"]["slider"], t)
    np.testing.assert_allclose(ideal.output_acceleration, means, rtol=0, atol=1e-6 * acc)
    np.testing.assert_allclose(
        ideal_points.output_acceleration, ref["slider_acceleration"], rtol=0, atol=1e-6 * acc
    )
    assert np.all(ideal.deflection.values == 0.0)  # rigid links
    assert ideal.sizes["joint"] == 0  # ideal joints: no joint columns
    assert float(ideal.constraint_violation.max()) < 1e-9  # m
    assert np.all(ideal.constraint_violation.values >= 0.0)


def test_angular_columns_of_the_ideal_rigid_slider_crank(ideal, ideal_points):
    # The connecting rod's angular velocity (point samples in both modes) and angular
    # acceleration (the mean of each window: the closed-form rate's difference over it per
    # its length; point mode: the closed form's derivative). Bounds as the accelerations'
    # above: the run's tolerance 1e-9 puts every column within 2e-11 of its scale
    # (measured), 1e-7 (velocities) and 1e-6 (accelerations) leave a margin above 1000.
    t = ideal.time.values
    ref = closed_forms(t)
    rate, acc = OMEGA * R / L, OMEGA**2 * R / L  # the rod's scales
    for ds in (ideal, ideal_points):
        w = ds.angular_velocity.sel(body=["crank", "rod", "slider"]).values
        np.testing.assert_allclose(w[:, 0], OMEGA, rtol=0, atol=1e-7 * OMEGA)
        np.testing.assert_allclose(w[:, 1], ref["rod_rate"], rtol=0, atol=1e-7 * rate)
        np.testing.assert_allclose(w[:, 2], 0.0, rtol=0, atol=1e-7 * rate)
        a = ds.angular_acceleration.sel(body=["crank", "rod", "slider"]).values
        np.testing.assert_allclose(a[:, [0, 2]], 0.0, rtol=0, atol=1e-6 * acc)
    means = window_mean_of_rate(lambda s: closed_forms(s)["rod_rate"], t)
    rod = ideal.angular_acceleration.sel(body="rod").values
    np.testing.assert_allclose(rod, means, rtol=0, atol=1e-6 * acc)
    rod = ideal_points.angular_acceleration.sel(body="rod").values
    np.testing.assert_allclose(rod, ref["rod_acceleration"], rtol=0, atol=1e-6 * acc)
    # the peaks: over every step and sample of the revolution, the closed form's extremes
    # (|θ̇| at φ = 0, |θ̈| near φ = ±π/2) within the same bounds; samples 400 a revolution
    # miss the extreme by at most the curvature over half a sample, far below 1e-3
    phi = np.linspace(0.0, 2 * np.pi, 200_001)
    fine = closed_forms(phi / OMEGA)
    for ds in (ideal, ideal_points):
        assert float(ds.peak_angular_velocity.sel(body="rod")) == pytest.approx(
            np.abs(fine["rod_rate"]).max(), rel=1e-3
        )
        assert float(ds.peak_angular_acceleration.sel(body="rod")) == pytest.approx(
            np.abs(fine["rod_acceleration"]).max(), rel=1e-3
        )
        np.testing.assert_array_equal(
            ds.revolution_peak_angular_acceleration.max("revolution"),
            ds.peak_angular_acceleration,
        )


def test_energy_columns_of_the_ideal_rigid_slider_crank(ideal):
    t = ideal.time.values
    ref = closed_forms(t)
    kinetic = sum(
        0.5 * MASS[b] * (ref["velocity"][b] ** 2).sum(axis=1) for b in ("crank", "rod", "slider")
    )
    kinetic += 0.5 * INERTIA["crank"] * OMEGA**2 + 0.5 * INERTIA["rod"] * ref["rod_rate"] ** 2
    potential = sum(MASS[b] * G * ref["position"][b][:, 1] for b in ("crank", "rod", "slider"))
    scale = float(kinetic.max())
    # Bounds: the velocities match the closed forms to 1e-7 (above), so the energies to
    # 2e-7 of the kinetic energy's scale; 1e-6 leaves a margin of 5 (measured: 1e-10).
    np.testing.assert_allclose(ideal.kinetic_energy, kinetic, rtol=0, atol=1e-6 * scale)
    np.testing.assert_allclose(ideal.potential_energy, potential, rtol=0, atol=1e-6 * scale)
    # No dissipation: the drive's work is the gain of T + V.
    gain = kinetic + potential - kinetic[0] - potential[0]
    np.testing.assert_allclose(ideal.drive_work, gain, rtol=0, atol=1e-6 * scale)
    for name in ("strain_energy", "contact_energy", "dissipated_energy"):
        assert np.all(ideal[name].values == 0.0), name
    # The torque's power is the rate of that gain: d(T + V)/dt = τ ω, compared as the
    # trapezoid integral of τ ω over the 400 samples of the revolution; the trapezoid's
    # error falls as Δt² (measured 1.5e-3 of the scale at 100 samples, so 9e-5 at 400):
    # the bound 1e-3 leaves a margin of 10.
    power = ideal.drive_torque.values * OMEGA
    integral = np.concatenate([[0.0], np.cumsum(0.5 * (power[1:] + power[:-1]) * np.diff(t))])
    np.testing.assert_allclose(integral, gain, rtol=0, atol=1e-3 * scale)


def test_interval_means_are_the_state_differences_over_each_window(clearance, clearance_points):
    means, points = clearance, clearance_points
    # sampling does not steer the steps: on one machine both runs take the same ones
    assert points.attrs["solver_accepted_steps"] == means.attrs["solver_accepted_steps"]
    n = means.sizes["time"] - 1
    # the windows' ends among the point samples: t = 0, halfway between samples, the end
    edges = np.r_[0, np.arange(1, 2 * n, 2), 2 * n]
    t = points.time.values[edges]
    np.testing.assert_allclose(
        t,
        np.r_[0, means.time.values[:-1] + 0.5 * np.diff(means.time)[0], means.time.values[-1]],
        rtol=0,
        atol=1e-15,
    )
    span = np.diff(t)

    def over_windows(x, per=None):
        ends = x.values[edges]
        change = ends[1:] - ends[:-1]
        return change / (
            np.diff(per.values[edges])
            if per is not None
            else span.reshape(-1, *[1] * (change.ndim - 1))
        )

    # Bound: the two runs read the same continuous extension at times equal to round-off
    # (1e-16 s here) and divide by windows equal to round-off; the velocities' change over
    # that time, amplified by 1/Δt = 1e4 s⁻¹, stays below 1e-10 of each quantity's peak.
    for name, source, per in (
        ("acceleration", "velocity", None),
        ("angular_acceleration", "angular_velocity", None),
        ("drive_torque", "drive_work", "crank_angle"),
    ):
        expected = over_windows(points[source], points[per] if per else None)
        scale = float(np.abs(expected).max())
        np.testing.assert_allclose(
            means[name].values, expected, rtol=0, atol=1e-10 * scale, err_msg=name
        )
    # the point quantities are the same samples
    for name in ("position", "velocity", "angular_velocity", "eccentricity", "penetration"):
        np.testing.assert_array_equal(means[name].values, points[name].values[::2], err_msg=name)


def test_joint_columns_follow_the_body_columns_and_the_contact_law(clearance, clearance_points):
    # the contact law holds between the point values of one instant: point samples
    ds = clearance_points
    pos, vel, angle = ds.position, ds.velocity, ds.angle
    # B guides the slider along x through O: x across the guide is the slider's y, y along
    # it is the slider's x, exactly (the slider's centre is its reference point).
    ecc_b = ds.eccentricity.sel(joint="B").values
    np.testing.assert_array_equal(ecc_b[:, 0], pos.sel(body="slider", axis="y").values)
    np.testing.assert_array_equal(ecc_b[:, 1], pos.sel(body="slider", axis="x").values)
    rate_b = ds.eccentricity_rate.sel(joint="B").values
    np.testing.assert_array_equal(rate_b[:, 0], vel.sel(body="slider", axis="y").values)
    np.testing.assert_array_equal(rate_b[:, 1], vel.sel(body="slider", axis="x").values)

    # A: journal (the crank's end) minus bearing centre (the rod's start), from the bodies'
    # centres and angles; round-off only.
    def end(body, sign, half):
        th = angle.sel(body=body).values
        p = pos.sel(body=body).values
        return p + sign * half * np.stack([np.cos(th), np.sin(th)], axis=1)

    ecc_a = end("crank", 1, R / 2) - end("rod", -1, L / 2)
    np.testing.assert_allclose(ds.eccentricity.sel(joint="A"), ecc_a, rtol=0, atol=1e-12)
    # The rate of A's eccentricity is its time derivative: compared by the trapezoid rule
    # over the 4000 samples of the revolution, the error is the impacts' share (measured
    # 2.6e-6 m; 1.2e-5 m at 2000 samples), bound 5e-5 m (margin 19), a tenth of the
    # clearance 5e-4 m.
    t = ds.time.values
    rate_a = ds.eccentricity_rate.sel(joint="A").values
    integral = np.cumsum(0.5 * (rate_a[1:] + rate_a[:-1]) * np.diff(t)[:, None], axis=0)
    np.testing.assert_allclose(ecc_a[1:] - ecc_a[0], integral, rtol=0, atol=5e-5)
    # The contact columns: a force and a stored energy only while penetrating, the state
    # 1 or 2 exactly then, friction within Coulomb's cone.
    pen = ds.penetration.values
    force = ds.normal_force.values
    state = ds.in_contact.values
    assert np.all(pen >= 0.0) and pen.max() > 0.0
    assert set(np.unique(state)) <= {0.0, 1.0, 2.0} and state.max() > 0
    np.testing.assert_array_equal(state > 0, pen > 0)
    assert np.all(force[pen == 0] == 0.0) and force.max() > 0.0
    assert np.all(np.abs(ds.friction_force.values) <= 0.1 * force * (1 + 1e-12))
    assert np.abs(ds.friction_force.values).max() > 0.0
    contact_energy = ds.contact_energy.values
    apart = (pen == 0).all(axis=1)
    assert np.all(contact_energy[apart] == 0.0) and contact_energy.max() > 0.0
    dissipated = ds.dissipated_energy.values
    # nondecreasing up to round-off (measured steps down to -4e-14 J), as test_energy checks
    assert np.all(np.diff(dissipated) >= -1e-9 * dissipated[-1]) and dissipated[-1] > 0.0
    assert ds.attrs["energy_error_relative"] < 1e-4
    assert np.all(ds.deflection.values == 0.0) and np.all(ds.strain_energy.values == 0.0)
    # The interval means keep what holds at every instant with positive weights: forces
    # pushing, friction within Coulomb's cone of the mean normal force.
    force, friction = clearance.normal_force.values, clearance.friction_force.values
    assert np.all(force >= 0.0) and force.max() > 0.0
    assert np.all(np.abs(friction) <= 0.1 * force * (1 + 1e-12) + 1e-12 * force.max())


def test_sampling_is_a_scene_key_with_a_default_and_a_command_line_option(tmp_path, capsys):
    import xarray as xr

    from sim.cli import main
    from sim.scene import SceneError, load_scene

    assert load_scene("slider-crank")["simulation"]["sampling"] == "mean"
    with pytest.raises(SceneError, match=r"'simulation.sampling' = 'pointy'.*'mean', 'point'"):
        load_scene("slider-crank", ["simulation.sampling=pointy"])
    with pytest.raises(SystemExit):  # argparse refuses a value it does not offer
        main(["run", "slider-crank", "-o", "unused.nc", "--sampling", "pointy"])
    capsys.readouterr()
    path = tmp_path / "points.nc"
    quarter = "simulation.revolutions=0.25"
    assert (
        main(
            ["run", "slider-crank", "-o", str(path), "-q", "--set", quarter, "--sampling", "point"]
        )
        == 0
    )
    with xr.open_dataset(path) as ds:
        assert json.loads(ds.attrs["scene"])["simulation"]["sampling"] == "point"
        assert ds.acceleration.attrs["sampling"] == POINT
        assert ds.position.attrs["sampling"] == POINT

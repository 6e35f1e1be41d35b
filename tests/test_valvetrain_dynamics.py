"""Valvetrain dynamics: quasi-static limit, energy balance, surge, jump, outputs, failures."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp
from scipy.linalg import eigh

from tribodyn import InputError
from tribodyn.valvetrain import (
    AccelerationCam,
    FilmTableTribology,
    Frictionless,
    TabulatedCam,
    TribologyModel,
    ValvetrainModel,
    ValvetrainParameters,
    compare_results,
    jump_speed,
    simulate_valvetrain,
    speed_sweep,
)

CAM = AccelerationCam()
P0 = ValvetrainParameters()


@pytest.fixture(scope="module")
def explicit_3000():
    return simulate_valvetrain(CAM, P0, engine_speed=3000.0, tribology="explicit")


@pytest.fixture(scope="module")
def frictionless_3000():
    return simulate_valvetrain(CAM, P0, engine_speed=3000.0, tribology=None)


def assert_follows_the_cam(r):
    """Through the lift event the tappet follows the cam to within its contact and
    tappet–valve deflections (tens of µm), and the contact force rises above the preload
    (what a valvetrain that stayed at its starting state would not do)."""
    ev = r.cam_lift > 1e-3
    assert np.max(np.abs(r.tappet_displacement[ev] - r.cam_lift[ev])) < 1e-4
    assert r.contact_force.max() > 1.5 * P0.spring_preload


def quasi_static(r, p, m_eff):
    return (
        p.spring_preload + p.spring_rate * r.cam_lift + m_eff * r.cam_speed**2 * r.lift_acceleration
    )


# -- quasi-static limit ------------------------------------------------------------------
@pytest.mark.parametrize("n_spring", [0, 8])
def test_low_speed_contact_force_is_quasi_static(n_spring):
    p = ValvetrainParameters(spring_masses=n_spring)
    r = simulate_valvetrain(CAM, p, engine_speed=300.0, tribology=None)
    assert r.converged, r.message
    m_eff = p.valve_mass + p.tappet_mass + p.spring_mass / 3.0
    ev = r.cam_lift > 20e-6  # valve open (chain preload taken up)
    F_qs = quasi_static(r, p, m_eff)
    err = np.abs(r.contact_force[ev] / F_qs[ev] - 1.0)
    assert err.max() < 0.01
    # Base circle: the seat carries the preload, the cam contact nothing.
    base = r.cam_lift == 0.0
    assert np.all(r.contact_force[base] < 1.0)
    np.testing.assert_allclose(r.seat_force[base], p.spring_preload, rtol=0.01)


def test_inertia_term_recovers_effective_mass():
    """At 1000 rpm the inertial part F − F₀ − k s regresses on ω² s'' with slope m_eff."""
    p = ValvetrainParameters(spring_masses=8)
    r = simulate_valvetrain(CAM, p, engine_speed=1000.0, tribology=None)
    ev = r.cam_lift > 20e-6
    x = r.cam_speed**2 * r.lift_acceleration[ev]
    y = r.contact_force[ev] - p.spring_preload - p.spring_rate * r.cam_lift[ev]
    slope = np.linalg.lstsq(np.vstack([x, np.ones_like(x)]).T, y, rcond=None)[0][0]
    assert slope == pytest.approx(p.valve_mass + p.tappet_mass + p.spring_mass / 3, rel=0.02)


# -- energy ------------------------------------------------------------------------------
@pytest.mark.parametrize("fixture", ["explicit_3000", "frictionless_3000"])
def test_energy_balance_over_the_cycle(fixture, request):
    r = request.getfixturevalue(fixture)
    assert r.converged, r.message
    # Cam work from the output torque alone (independent of the integrated accumulators).
    P = r.cam_torque * r.cam_speed
    W = np.concatenate([[0.0], np.cumsum(0.5 * (P[1:] + P[:-1]) * np.diff(r.time))])
    balance = (
        r.kinetic_energy
        - r.kinetic_energy[0]
        + r.elastic_energy
        - r.elastic_energy[0]
        + r.dissipated_energy
    )
    # Over the full cycle ...
    assert abs(W[-1] - balance[-1]) <= 0.01 * abs(W[-1])
    # ... and at every instant, relative to the largest work done (valve at the nose).
    assert np.max(np.abs(W - balance)) <= 0.01 * np.max(np.abs(W))
    # Spring + contact energy at the nose ≈ F₀L + kL²/2 (the valve is at rest there).
    nose = np.argmax(r.cam_lift)
    L = r.cam_lift[nose]
    assert r.elastic_energy[nose] == pytest.approx(250 * L + 33750 * L**2 / 2, rel=0.02)
    assert abs(r.energy["relative_residual"]) < 1e-3


def test_friction_outputs_are_consistent(explicit_3000):
    r = explicit_3000
    assert_follows_the_cam(r)
    rb = CAM.base_radius
    np.testing.assert_allclose(
        r.cam_torque,
        r.contact_force * r.contact_offset + r.friction_force * (rb + r.cam_lift),
        rtol=1e-12,
    )
    np.testing.assert_allclose(r.friction_power, r.friction_force * r.sliding_speed, rtol=1e-12)
    moving = np.abs(r.tappet_velocity) > 0.1
    assert np.all(np.sign(r.bore_friction_force[moving]) == -np.sign(r.tappet_velocity[moving]))
    assert r.friction_force.max() > 0.0
    # Base circle kinematics in the dynamic result are exact.
    base = (r.cam_lift == 0.0) & (r.lift_acceleration == 0.0)
    assert base.sum() > 1000
    assert np.all(r.entrainment_speed[base] == r.cam_speed * rb / 2)
    assert np.all(r.sliding_speed[base] == r.cam_speed * rb)


def test_bore_friction_raises_opening_force():
    """Bore friction μ_b F_f opposes tappet motion: on opening it adds to the contact force."""
    base = simulate_valvetrain(
        CAM, P0.replace(bore_friction_coefficient=0.0), engine_speed=1000.0, tribology="explicit"
    )
    fric = simulate_valvetrain(
        CAM, P0.replace(bore_friction_coefficient=0.5), engine_speed=1000.0, tribology="explicit"
    )
    dF = fric.contact_force - base.contact_force
    expected = 0.5 * fric.friction_force * np.sign(fric.tappet_velocity)
    for side in (fric.tappet_velocity > 0.2, fric.tappet_velocity < -0.2):
        # opening: extra push needed; closing: the bore holds the tappet back (less force)
        assert np.mean(dF[side]) == pytest.approx(np.mean(expected[side]), rel=0.05)


@pytest.mark.parametrize("n_spring", [0, 3])
def test_analytic_jacobian_matches_finite_differences(n_spring):
    model = ValvetrainModel(
        CAM, ValvetrainParameters(spring_masses=n_spring), 157.08, Frictionless()
    )
    n = model.n
    rng = np.random.default_rng(3)
    for t in (0.0005, 0.012, 0.014, 0.02):  # base circle, flank, nose, closing
        s, s1, _ = CAM.scalar_derivatives(157.08 * t)
        y = np.zeros(2 * n + 2)
        y[0], y[n] = s - 2e-6, 157.08 * s1 + 0.003  # contact compressed, sliding in
        y[1] = s - 3e-6 if s > 0 else 0.0  # tappet–valve compressed
        y[n + 1] = 157.08 * s1
        y[2:n] = rng.normal(0, 1e-5, n_spring)
        y[n + 2 : 2 * n] = rng.normal(0, 1e-2, n_spring)
        J = model.jacobian(t, y)
        Jn = np.empty((2 * n + 2, 2 * n))
        for k in range(2 * n):
            h = 1e-10 if k < n else 1e-7
            e = np.zeros_like(y)
            e[k] = h
            Jn[:, k] = (model.rhs(t, y + e) - model.rhs(t, y - e)) / (2 * h)
        block = slice(0, 2 * n)
        np.testing.assert_allclose(
            J[block, block], Jn[block], rtol=0, atol=1e-7 * np.abs(Jn[block]).max()
        )


# -- spring surge ------------------------------------------------------------------------
def _surge_matrices(model):
    """(M, K) of the coil masses with the valve held fixed (fixed–fixed spring)."""
    k = model.kseg  # segment j joins coils j − 1 and j (−1 and N: the fixed ends)
    K = np.diag(k[:-1] + k[1:]) - np.diag(k[1:-1], 1) - np.diag(k[1:-1], -1)
    return np.eye(model.N) * model.m_node, K


@pytest.mark.parametrize("n_spring", [8, 12])
def test_surge_frequency(n_spring):
    p = ValvetrainParameters(spring_masses=n_spring, spring_damping_ratio=0.0)
    f_ref = 0.5 * math.sqrt(p.spring_rate / p.spring_mass)
    model = ValvetrainModel(CAM, p, 1e-3, Frictionless())  # cam ~ still: base circle
    M, K = _surge_matrices(model)
    f_eig = math.sqrt(eigh(K, M, eigvals_only=True)[0]) / (2 * math.pi)
    assert f_eig == pytest.approx(f_ref, rel=0.02)
    # Free vibration of the spring on the seated valve, from the full equations of motion.
    y0 = model.static_state()
    i = np.arange(1, n_spring + 1)
    y0[2 : model.n] = 1e-4 * np.sin(np.pi * i / (n_spring + 1))
    sol = solve_ivp(
        model.rhs,
        (0.0, 0.02),
        y0,
        method="LSODA",
        jac=model.jacobian,
        rtol=1e-8,
        atol=1e-12,
        max_step=2e-5,
        dense_output=True,
    )
    t = np.linspace(0.0, 0.02, 20001)
    x = sol.sol(t)[2 + n_spring // 2]
    z = np.nonzero(np.diff(np.sign(x)))[0]
    tz = t[z] - x[z] * (t[z + 1] - t[z]) / (x[z + 1] - x[z])
    f_sim = (tz.size - 1) / 2.0 / (tz[-1] - tz[0])
    assert f_sim == pytest.approx(f_ref, rel=0.02)


# -- jump ------------------------------------------------------------------------------
def quasi_static_jump_rpm(p):
    th = np.linspace(0, 2 * np.pi, 72000, endpoint=False)
    s, s1, s2 = CAM.derivatives(th)
    m = p.valve_mass + p.tappet_mass + p.spring_mass / 3
    closing = (s2 < 0) & (s1 < 0)
    w = np.sqrt(np.min((p.spring_preload + p.spring_rate * s[closing]) / (m * -s2[closing])))
    return w * 60.0 / math.pi  # engine rpm = 2 × cam rpm


def test_jump_onset_single_lumped_mass():
    # One lumped mass: massless spring (m_s/3 on the valve), valve rigidly on the tappet.
    p = ValvetrainParameters(spring_masses=0, tappet_valve_stiffness=1e9)
    n_qs = quasi_static_jump_rpm(p)
    # Onset within ±5 %: no contact loss at 0.95 n_qs, contact loss at 1.05 n_qs.
    lo, hi = jump_speed(
        CAM,
        p,
        low=0.95 * n_qs,
        high=1.05 * n_qs,
        tolerance=0.1 * n_qs,
        tribology=None,
        output_step=0.5,
    )
    assert 0.95 * n_qs <= lo < hi <= 1.05 * n_qs


def test_jump_onset_multi_mass_spring_not_above_quasi_static():
    p = ValvetrainParameters(spring_masses=8)
    n_qs = quasi_static_jump_rpm(p)
    r = simulate_valvetrain(CAM, p, engine_speed=n_qs, tribology=None)
    assert r.converged and r.jump
    on = (r.contact_force == 0.0) & (r.cam_lift > r.jump_lift_threshold)
    assert on.any()
    # Every zero-force sample in the event lies inside a reported jump interval.
    inside = np.zeros_like(on)
    for a, b in r.jumps:
        inside |= (r.crank_angle >= a - 0.25) & (r.crank_angle <= b + 0.25)
    assert np.all(inside[on])
    below = simulate_valvetrain(CAM, p, engine_speed=3000.0, tribology=None)
    assert not below.jump and not below.valve_bounce


def test_valve_bounce_and_seating_velocity_at_overspeed(explicit_3000):
    r = explicit_3000
    assert 0.0 < r.seating_velocity < r.cam_speed * CAM.ramp_velocity
    fast = simulate_valvetrain(CAM, P0, engine_speed=9500.0, tribology=None)
    assert fast.converged and fast.jump and fast.valve_bounce
    for a, b, h in fast.bounces:
        assert b > a and h > 0.0
        k = (fast.crank_angle > a + 0.5) & (fast.crank_angle < b - 0.5)
        assert np.all(fast.seat_force[k] == 0.0)
    assert fast.seating_velocity > 5 * r.seating_velocity


# -- implicit hook ------------------------------------------------------------------------
def test_film_in_series_gives_series_stiffness():
    k, c = 2e8, -5e-9  # film stiffness 1/|c| = 2e8
    k_series = 1.0 / (1.0 / k - c)
    p = ValvetrainParameters(contact_stiffness=k)
    film = FilmTableTribology(Frictionless(), [0.0], 1e-6, c, 0.0)
    model = ValvetrainModel(CAM, p, 100.0, film)
    for dk in (0.5e-6, 2e-6, 4e-6):
        P, dP, h = model.elastic_contact(0.0, dk)
        assert dP == pytest.approx(k_series, rel=1e-9)
        assert P == pytest.approx(k_series * (dk + 1e-6), rel=1e-9)
        assert P / k == pytest.approx(dk + h, rel=1e-9)  # δ_el = δ_kin + h
    assert model.elastic_contact(0.0, -1.5e-6)[0] == 0.0  # film gap open: no force
    # In the dynamics: interference s − x_t versus elastic force has slope 1/k_series.
    r = simulate_valvetrain(CAM, p, engine_speed=1000.0, tribology=film)
    assert r.converged, r.message
    assert_follows_the_cam(r)
    on = r.elastic_contact_force > 50.0
    dk = r.cam_lift - r.tappet_displacement
    slope, icpt = np.polyfit(r.elastic_contact_force[on], dk[on], 1)
    assert slope == pytest.approx(1.0 / k_series, rel=1e-3)
    assert icpt == pytest.approx(-1e-6, rel=1e-3)
    # Palmgren contact: tangent stiffness in series with the film as well.
    pm = ValvetrainModel(CAM, P0, 100.0, film)
    p_dry = ValvetrainModel(CAM, P0, 100.0, Frictionless())
    P, dP, h = pm.elastic_contact(0.0, 2e-6)
    k_dry = p_dry.elastic_contact(0.0, 2e-6 + h)[1]
    assert dP == pytest.approx(1.0 / (1.0 / k_dry - c), rel=1e-9)


def test_film_law_where_the_film_cancels_the_interference():
    """A state met in the implicit coupling near disengagement: h(0) = h_k − c F_k nearly
    cancels δ_kin while h_k and c F_k are µm-sized; the round-off of φ then exceeds a
    tolerance relative to δ_kin + h(0) (a regression: the coupling used to stop there)."""
    time = [0.0, 0.00022222222222222088]
    film = FilmTableTribology(
        Frictionless(),
        time,
        [-3.9822552500934464e-06, -2.8770965324298964e-06],
        [-7.678925280599316e-09, -8.06267147478184e-08],
        [119.92766550360953, 27.507175099051093],
        period=0.04,
    )
    model = ValvetrainModel(CAM, P0, 157.07963267948966, film)
    t, dk = 0.00019301284856435008, 2.0592842553665916e-07
    P, dP, h = model.elastic_contact(t, dk)
    assert P > 0.0 and dP > 0.0
    # Palmgren δ_el(P) = C P^0.9 equals δ_kin + h(P) at the returned force
    assert model.contact_C * P**0.9 == pytest.approx(dk + h, abs=1e-18)
    assert h == pytest.approx(film.film(t, P, 0.0, 0.0)[0], abs=1e-18)


def test_zero_film_table_reproduces_explicit(frictionless_3000):
    film = FilmTableTribology(Frictionless(), [0.0], 0.0, 0.0, 0.0)
    r = simulate_valvetrain(CAM, P0, engine_speed=3000.0, tribology=film)
    assert_follows_the_cam(r)
    d = compare_results(frictionless_3000, r)
    assert d["contact_force"]["max_abs_difference"] < 1.0
    assert d["tappet_velocity"]["relative_to_range"] < 1e-3


# -- other inputs ------------------------------------------------------------------------
def test_tabulated_cam_runs_like_the_analytic_one(explicit_3000):
    tab = TabulatedCam(*CAM.table(1440), 0.015)
    r = simulate_valvetrain(tab, P0, engine_speed=3000.0)
    assert r.converged
    assert_follows_the_cam(r)
    assert r.contact_force.max() == pytest.approx(explicit_3000.contact_force.max(), rel=0.01)
    assert np.max(np.abs(r.tappet_velocity - explicit_3000.tappet_velocity)) < 0.01


def test_speed_sweep_reports_peak_min_and_onset():
    sw = speed_sweep(CAM, [6000.0, 2000.0, 9500.0], P0, tribology=None, output_step=0.5)
    np.testing.assert_array_equal(sw.engine_speed, [2000.0, 6000.0, 9500.0])
    assert np.all(sw.converged)
    assert sw.min_contact_force[0] > sw.min_contact_force[1] > 0.0
    assert list(sw.jump) == [False, False, True]
    assert sw.jump_onset_speed == 9500.0
    assert sw.min_contact_force[2] == 0.0


@pytest.mark.parametrize(
    "kw, match",
    [
        (dict(valve_mass=-0.07), "valve_mass"),
        (dict(spring_rate=0.0), "spring_rate"),
        (dict(spring_masses=-1), "spring_masses"),
        (dict(contact_stiffness=-1e8), "contact_stiffness"),
        (dict(bore_friction_coefficient=-0.1), "bore_friction_coefficient"),
        (dict(spring_damping_ratio=1.5), "spring_damping_ratio"),
    ],
)
def test_bad_parameters_are_rejected(kw, match):
    with pytest.raises(InputError, match=match):
        ValvetrainParameters(**kw)


def test_bad_simulation_arguments_are_rejected():
    with pytest.raises(InputError, match="engine_speed"):
        simulate_valvetrain(CAM, P0, engine_speed=-3000.0)
    with pytest.raises(InputError, match="tappet radius"):
        simulate_valvetrain(CAM, P0.replace(tappet_radius=0.012))
    with pytest.raises(InputError, match="cycles"):
        simulate_valvetrain(CAM, P0, cycles=0)
    with pytest.raises(InputError, match="base circle"):
        simulate_valvetrain(CAM, P0, start_angle=math.pi)
    with pytest.raises(InputError, match="tribology"):
        simulate_valvetrain(CAM, P0, tribology="magic")


class _BrokenFilm(TribologyModel):
    has_film = True
    name = "broken"

    def friction(self, t, force, entrainment_speed, sliding_speed, radius):
        return np.zeros(np.broadcast(t, force).shape)

    def film(self, t, force, entrainment_speed, radius):
        return (float("nan") if t > 0.01 else 0.0), 0.0


def test_solver_failure_is_reported_not_hidden():
    r = simulate_valvetrain(CAM, P0, engine_speed=3000.0, tribology=_BrokenFilm())
    assert not r.converged
    assert "film law" in r.message
    assert r.contact_force.size == 0  # no NaN-filled arrays
    assert r.summary() == {"converged": False, "message": r.message}


def test_time_dependent_friction_respects_start_angle():
    """A friction law that depends on time (not only on the cam angle) must see the
    simulation time also when the run starts at θ₀ ≠ 0: the cam work integrated with the
    motion equals ∫ torque·ω dt for any start angle."""
    import math

    from tribodyn.valvetrain import (
        AccelerationCam,
        ValvetrainParameters,
        simulate_valvetrain,
    )
    from tribodyn.valvetrain.tribology import TribologyModel

    class Pulsing(TribologyModel):
        periodic_in_cam_angle = True
        name = "pulsing"

        def __init__(self, w):
            self.w = w

        def friction(self, t, force, ue, us, R):
            return 0.05 * (1.0 + np.sin(self.w * np.asarray(t))) * np.maximum(force, 0.0)

    cam = AccelerationCam()
    w = 2 * math.pi * 1500 / 60
    for theta0 in (0.0, math.radians(60)):
        r = simulate_valvetrain(
            cam,
            ValvetrainParameters(),
            engine_speed=3000.0,
            tribology=Pulsing(w),
            start_angle=theta0,
        )
        assert r.converged, r.message
        work_from_torque = np.trapezoid(r.cam_torque * w, r.time)
        work_integrated = r.cam_work[-1] - r.cam_work[0]
        assert work_integrated == pytest.approx(work_from_torque, rel=0.02)

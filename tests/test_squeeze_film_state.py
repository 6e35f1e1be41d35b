"""The film as a state of the dynamics (FilmStateTribology): its laws against closed
forms integrated by hand, its Jacobian, and the film off the lobe in a dynamics run."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.physics.film_state_laws import entraining_film_load, limited_growth
from tribodyn.physics.lubricant import Lubricant
from tribodyn.physics.materials import reduced_modulus
from tribodyn.physics.regimes import hamrock_groups, moes_central
from tribodyn.valvetrain.compiled import _cam, compiled_model
from tribodyn.valvetrain.dynamics import simulate_valvetrain
from tribodyn.valvetrain.kinematics import rpm_to_cam_speed
from tribodyn.valvetrain.system import system_class
from tribodyn.valvetrain.tribology import FilmStateTribology, Frictionless

ETA, R, L, E = 0.05, 0.015, 0.012, 2.3e11
ISO = Lubricant(viscosity=ETA, pressure_viscosity=0.0)


def _film(lub=ISO, hs=10e-6, **kw):
    return FilmStateTribology(
        Frictionless(), width=L, lubricant=lub, e_prime=E, supply_film=hs, **kw
    )


def _integrate(model, h0, force, ue, t_end):
    def f(t, y):
        return [model.film_rate(t, float(y[0]), force, ue, R)[0]]

    def jac(t, y):
        return [[model.film_rate(t, float(y[0]), force, ue, R)[1]]]

    t = np.linspace(0.0, t_end, 21)
    sol = solve_ivp(f, (0.0, t_end), [h0], method="Radau", jac=jac, t_eval=t, rtol=1e-9, atol=1e-15)
    assert sol.success
    return t, sol.y[0]


def test_squeeze_under_a_step_load_follows_the_closed_form():
    # u_e = 0: no entraining film, only the squeeze w' = 3√2π η V R^(3/2)/h^(3/2). Its
    # integral under constant load: h(t) = (h_i^(−1/2) + k t/2)^(−2), k = w'/(3√2π η R^1.5)
    F, h0 = 200.0, 5e-6
    t, h = _integrate(_film(), h0, F, 0.0, 2e-3)
    k = F / L / (3.0 * math.sqrt(2.0) * math.pi * ETA * R**1.5)
    exact = (h0**-0.5 + 0.5 * k * t) ** -2
    assert h[-1] < 0.2 * h0  # the film is squeezed substantially
    np.testing.assert_allclose(h, exact, rtol=1e-6)


def test_unloaded_film_recovers_towards_the_supply_in_closed_form():
    # F = 0, isoviscous (α = 0: the piezoviscous load is 0), rigid: Martin's load of the
    # starved film, w' = 4.894 η u R (h_s − h)/(h h_s), against the squeeze gives
    # ẋ = c (1 − x²)/(2√h_s), x = √(h/h_s), c = 4.894 u/(3√2π√R), so
    # h(t) = h_s tanh²(artanh √(h_0/h_s) + c t/(2√h_s))
    hs, h0, u = 10e-6, 1e-6, 1.5
    t, h = _integrate(_film(hs=hs), h0, 0.0, u, 3e-3)
    c = 4.894 * u / (3.0 * math.sqrt(2.0) * math.pi * math.sqrt(R))
    exact = hs * np.tanh(math.atanh(math.sqrt(h0 / hs)) + c * t / (2.0 * math.sqrt(hs))) ** 2
    assert h[-1] > 0.9 * hs and np.all(np.diff(h) > 0.0)
    np.testing.assert_allclose(h, exact, rtol=1e-6)


def test_steady_film_carries_the_force_by_the_entraining_law():
    # the compiled bisection against the Python law it inverts: L w'_ent(h) = F to the
    # bisection's resolution, h_s where F ≤ 0 or u_e = 0, and the input's shape kept
    lub = Lubricant(viscosity=0.055, pressure_viscosity=1.05e-8)
    hs = 10e-6
    m = _film(lub=lub, hs=hs)
    rng = np.random.default_rng(3)
    F = 10.0 ** rng.uniform(0.0, 3.5, 60)
    u = rng.uniform(-6.0, 6.0, 60)
    radius = 10.0 ** rng.uniform(-3.0, -1.0, 60)
    r = np.exp(rng.uniform(-0.6, 0.6, 60))
    h = m.steady_film(0.0, F, u, radius, correction=r)
    args = (lub.viscosity, lub.pressure_viscosity, E, hs)
    for k in range(F.size):
        w, _ = entraining_film_load(h[k], u[k], radius[k], *args, r[k])
        assert L * w == pytest.approx(F[k], rel=1e-12)
    assert m.steady_film(0.0, 0.0, 1.0, R) == hs and m.steady_film(0.0, 50.0, 0.0, R) == hs
    grid = m.steady_film(0.0, F[:6].reshape(2, 3), u[:6].reshape(2, 3), R)
    assert grid.shape == (2, 3)
    assert np.array_equal(grid.ravel(), m.steady_film(0.0, F[:6], u[:6], R))
    assert isinstance(m.steady_film(0.0, F[0], u[0], R), float)


def test_steady_film_inverts_to_the_moes_film_in_the_elastic_piezoviscous_regime():
    # flooded (h_s → ∞), paper-like oil and load: within 7 % of Moes (1992); at light
    # load Martin's rigid film, 1/1.2247 of Moes' rigid asymptote (3/M vs 4.894/W·U)
    lub = Lubricant(viscosity=0.055, pressure_viscosity=1.05e-8)
    m = _film(lub=lub, hs=1.0)
    for F, u, tol in ((600.0, 1.5, 0.07), (1500.0, 5.0, 0.07)):
        W, U, G = hamrock_groups(F / L, R, u, lub.viscosity, lub.pressure_viscosity, E)
        assert m.steady_film(0.0, F, u, R) == pytest.approx(moes_central(W, U, G, R), rel=tol)
    W, U, G = hamrock_groups(1.0 / L, R, 1.5, lub.viscosity, lub.pressure_viscosity, E)
    ratio = m.steady_film(0.0, 1.0, 1.5, R) / moes_central(W, U, G, R)
    assert ratio == pytest.approx(4.894 / 6.0, rel=2e-3)


def test_limited_growth_is_a_smooth_minimum():
    # H = x where the film thins; → x_t far above it; its derivatives by differences
    assert limited_growth(-2.0, 1.0) == (-2.0, 1.0, 0.0)
    assert limited_growth(0.25, 1.0)[0] == pytest.approx(0.25, rel=1e-3)
    assert limited_growth(1e3, 1.0)[0] == pytest.approx(1.0, rel=1e-9)
    for x, xt in ((0.3, 1.0), (1.0, 1.0), (5.0, 0.7)):
        H, dx, dxt = limited_growth(x, xt)
        e = 1e-7
        assert dx == pytest.approx(
            (limited_growth(x + e, xt)[0] - limited_growth(x - e, xt)[0]) / (2 * e),
            rel=1e-6,
            abs=1e-9,
        )
        assert dxt == pytest.approx(
            (limited_growth(x, xt + e)[0] - limited_growth(x, xt - e)[0]) / (2 * e),
            rel=1e-6,
            abs=1e-9,
        )


def test_film_growth_is_limited_by_the_oil_supply_in_closed_form():
    # a thin film under a fast, piezoviscous entrainment (a ramp-less cam's step: u_e
    # 22 m/s, R 87 mm, film 0.7 µm, unloaded): its free rate exceeds the transport limit
    # by orders of magnitude, so ḣ = x_t = u √((h_s − h)/(2R)), whose integral is
    # √(h_s − h) = √(h_s − h_0) − u t/(2√(2R)); compared while the free rate stays 50×
    # above x_t, where the smooth minimum differs from x_t by 1e-7
    lub = Lubricant(viscosity=0.01, pressure_viscosity=1.5e-8)
    m = _film(lub=lub)
    u, Rs, hs, h0 = 22.0, 0.087, 10e-6, 0.7e-6

    def rate(h):
        x = m.film_rate(0.0, h, 0.0, u, Rs)[0]
        xt = m.growth_limit(h, u, Rs)[0]
        return x, xt

    x0, xt0 = rate(h0)
    assert x0 > 1e3 * xt0 and xt0 == pytest.approx(u * math.sqrt((hs - h0) / (2 * Rs)))
    sol = solve_ivp(
        lambda t, y: [limited_growth(*rate(float(y[0])))[0]],
        (0.0, 4e-6),
        [h0],
        method="LSODA",
        t_eval=np.linspace(0.0, 4e-6, 41),
        rtol=1e-10,
        atol=1e-16,
    )
    assert sol.success
    h = sol.y[0]
    keep = np.array([rate(v)[0] > 50.0 * rate(v)[1] for v in h])
    assert keep.sum() > 10 and h[keep][-1] > h0 + 0.2e-6  # the film grows markedly
    exact = hs - (math.sqrt(hs - h0) - u * sol.t / (2.0 * math.sqrt(2.0 * Rs))) ** 2
    np.testing.assert_allclose(h[keep], exact[keep], rtol=1e-6)
    # without the limit the film's rate is its free rate
    free = _film(lub=lub, growth_limited=False)
    assert free.growth_limit(h0, u, Rs) == (math.inf, 0.0)
    assert free.film_rate(0.0, h0, 0.0, u, Rs)[0] > 1e3 * xt0


@pytest.mark.parametrize(
    "name, film, regime",
    [
        (None, 1.5e-6, "free"),
        (None, 0.5e-6, "transition"),
        (None, 0.2e-6, "limited"),
        ("andreou2023_flexible", 1.5e-6, "free"),
        ("andreou2023_flexible", 0.53e-6, "transition"),
        ("andreou2023_flexible", 0.2e-6, "limited"),
    ],
)
def test_film_state_jacobian_matches_finite_differences(name, film, regime, monkeypatch):
    case = load_case(name)
    built = build(case)
    s = built.surface_sets[0]
    ft = FilmStateTribology(
        Frictionless(),
        width=case.width,
        lubricant=built.lubricant,
        e_prime=reduced_modulus(s.bodies),
    )
    w = rpm_to_cam_speed(case.engine.speed_rpm)
    m = system_class(built.valvetrain)(built.cam, built.valvetrain, w, ft)
    assert m.film_state
    cm = compiled_model(m) if m.compilable else None  # the lumped model's compiled form
    n, t = m.n, math.radians(100.0) / w  # on the opening flank
    y = m.static_state()
    y[0] = built.cam.scalar_derivatives(m.lobe_angle(t, y))[0] - 20e-6
    y[n], y[-1] = 0.3, film
    J = m.jacobian(t, y)
    k = 2 * n + 2
    f = m.evaluate(t, y)
    assert f["Fc"] > 100.0
    c = m.cam_contact(t, m.lobe_angle(t, y), w, y[0], y[n], film)
    xt = ft.growth_limit(film, c.ue, c.R)[0]
    # the film thins freely, grows where the smooth minimum bends, or at its transport
    # limit (the three branches of the law)
    ratio = c.hdot / xt
    assert {"free": ratio < 0.5, "transition": 0.5 < ratio < 0.99, "limited": ratio > 0.999}[
        regime
    ], ratio
    for j in (0, n, k):
        e = 1e-12 if j != n else 1e-7
        yp, ym = y.copy(), y.copy()
        yp[j] += e
        ym[j] -= e
        col = (m.rhs(t, yp) - m.rhs(t, ym)) / (2 * e)
        np.testing.assert_allclose(J[:, j][[0 + n, k]], col[[0 + n, k]], rtol=1e-5, atol=1e-6)
    if cm is not None:
        # the compiled kernels on the same cam values (their cam table in the model's
        # place): the same branch of the law, the same rates and Jacobian to round-off
        table = cm.cam_table
        monkeypatch.setattr(m.cam, "scalar_derivatives", lambda th: _cam(th, m.theta0, *table))
        np.testing.assert_allclose(cm.rhs(t, y), m.rhs(t, y), rtol=1e-12, atol=1e-300)
        np.testing.assert_allclose(cm.jac(t, y), m.jacobian(t, y), rtol=1e-12, atol=1e-300)


@pytest.fixture(scope="module")
def paper_film_run():
    case = load_case().updated({"engine.speed_rpm": 4000.0, "numerics.output_step_deg": 0.5})
    built = build(case)
    s = built.surface_sets[0]
    trib = built.analytic_tribology(s.name)
    ft = FilmStateTribology(
        trib, width=case.width, lubricant=built.lubricant, e_prime=reduced_modulus(s.bodies)
    )
    r = simulate_valvetrain(built.cam, built.valvetrain, tribology=ft, **built.dynamics_options)
    assert r.converged, r.message
    return case, ft, r


def test_film_state_closes_the_energy_balance(paper_film_run):
    _, _, r = paper_film_run
    assert abs(r.energy["relative_residual"]) < 1e-5


def test_off_lobe_the_tappet_rides_on_the_film_within_the_squeeze_bound(paper_film_run):
    """Off the lobe after seating the tappet rides on the film with a light load (the
    film separates the surfaces from metal contact, the zero-lash datum): the film never
    thins faster than the pure squeeze allows from any earlier instant,
    h(t)^(−1/2) − h(t₀)^(−1/2) ≤ ∫F dt / (2·3√2π η R^(3/2) L), and it settles (the
    entraining film carries the load: within a factor 2 of its median, well below the
    supply film) rather than collapsing or growing to the supply."""
    case, ft, r = paper_film_run
    h = r.tribology_report["film_thickness"]
    off = np.flatnonzero(~r.event_mask() & (r.crank_angle > 1300.0))
    F, t, hh = r.contact_force[off], r.time[off], h[off]
    assert F.min() > 0.0
    c = 3.0 * math.sqrt(2.0) * math.pi * ft.lubricant.viscosity * build(case).cam.base_radius ** 1.5
    impulse = np.concatenate([[0.0], np.cumsum(0.5 * (F[1:] + F[:-1]) * np.diff(t))])
    for k in range(0, off.size, 10):  # every earlier instant t₀ as the start
        bound = (hh[k] ** -0.5 + (impulse[k:] - impulse[k]) / (2.0 * c * ft.width)) ** -2
        assert np.all(hh[k:] >= bound * (1.0 - 1e-3))
    med = np.median(hh)
    assert np.all((hh > 0.5 * med) & (hh < 2.0 * med)) and med < 0.5 * ft.supply_film


def test_load_pickup_squeezes_the_base_circle_film(paper_film_run):
    # the opening ramp picks up the load below the lobe threshold: the film falls from
    # the base-circle film towards the loaded film while the lift is still below 10 µm
    _, ft, r = paper_film_run
    h = r.tribology_report["film_thickness"]
    ramp = (r.cam_lift > 0.0) & (r.cam_lift < r.jump_lift_threshold) & (r.crank_angle < 1080.0)
    assert h[ramp][-1] < 0.8 * h[ramp][0]  # 1.52 → 1.08 µm at 4000 rpm

"""Friction laws, Greenwood chart and film formulas."""

import math

import numpy as np
import pytest

from ehl_cases import PAIR
from tribodyn import Lubricant, Roughness, solve_ehl
from tribodyn.physics.analytic_contact import analytic_contact
from tribodyn.physics.friction import couette_shear_stress, limit_shear_stress
from tribodyn.physics.regimes import (
    greenwood_chart_groups,
    hamrock_groups,
    lubrication_regime,
    moes_central,
    moes_groups,
)

E_PRIME = 210e9 / 0.91


def test_shear_laws():
    mu, u, h = 0.05, 2.0, 1e-6
    newt = couette_shear_stress(mu, u, h, "newtonian")
    assert newt == pytest.approx(1e5)
    # Eyring: τ_E asinh(τ_N/τ_E) → Newtonian at low stress, below it at high stress
    assert couette_shear_stress(mu, u, h, "eyring", eyring_stress=1e9) == pytest.approx(
        newt, rel=1e-8
    )
    ey = couette_shear_stress(1e3, u, h, "eyring", eyring_stress=2e6)
    assert ey == pytest.approx(2e6 * math.asinh(2e9 / 2e6))
    assert couette_shear_stress(mu, -u, h, "eyring") < 0  # sign follows sliding
    assert limit_shear_stress(-5e7, 1e8, 0.08) == pytest.approx(-8e6)
    assert limit_shear_stress(1e5, -1e8, 0.08) == 0.0
    # Bair–Winer intercept: τ_L = τ_L0 + Λp
    assert limit_shear_stress(-5e7, 1e8, 0.08, 2e6) == pytest.approx(-1e7)
    assert limit_shear_stress(1e5, -1e8, 0.08, 2e6) == pytest.approx(1e5)
    assert limit_shear_stress(3e6, 0.0, 0.08, 2e6) == pytest.approx(2e6)


def test_viscous_friction_rigid_isoviscous_newtonian():
    """Couette friction of a rigid cylinder, no cap: F = μ u_s √(2R/h₀)[atan(x/√(2Rh₀))]."""
    R, w, mu, u, us = 0.01, 1e3, 0.05, 1.0, 0.7
    oil = Lubricant(mu, 0.0, compressible=False)
    r = solve_ehl(
        w,
        R,
        u,
        us,
        PAIR,
        oil,
        elastic=False,
        viscous_model="newtonian",
        limiting_shear=False,
        n=2048,
        inlet=12,
    )
    h0 = r.min_film
    s = math.sqrt(2 * R * h0)
    exact = mu * us * math.sqrt(2 * R / h0) * (math.atan(r.x[-1] / s) - math.atan(r.x[0] / s))
    assert r.viscous_friction == pytest.approx(exact, rel=5e-3)
    assert r.boundary_friction == 0.0
    assert r.friction_coefficient == pytest.approx(r.viscous_friction / w)


def test_limiting_shear_caps_ehl_friction():
    # heavy EHL at high sliding: the Newtonian shear in the Hertz zone exceeds Λp
    R, G = 0.01, 5000.0
    U = (10 / G) ** 4 / 2
    W = 50 * math.sqrt(2 * U)
    w, u = W * E_PRIME * R, U * E_PRIME * R / 0.04
    oil = Lubricant(0.04, G / E_PRIME)
    capped = solve_ehl(w, R, u, 5.0, PAIR, oil, viscous_model="newtonian")
    eyring = solve_ehl(w, R, u, 5.0, PAIR, oil, viscous_model="eyring", limiting_shear=False)
    free = solve_ehl(w, R, u, 5.0, PAIR, oil, viscous_model="newtonian", limiting_shear=False)
    lam = oil.limiting_shear_coefficient
    assert capped.viscous_friction <= lam * w * (1 + 1e-9)
    assert capped.viscous_friction > 0.9 * lam * w  # the cap is active almost everywhere
    assert free.viscous_friction > 10 * capped.viscous_friction
    assert eyring.viscous_friction < free.viscous_friction
    assert np.all(np.abs(capped.shear_stress) <= lam * capped.pressure + 1e-9)
    # an intercept τ_L0 raises the cap by τ_L0 wherever it is active
    tl0 = 5e6
    oil_i = Lubricant(0.04, G / E_PRIME, limiting_shear_stress=tl0)
    inter = solve_ehl(w, R, u, 5.0, PAIR, oil_i, viscous_model="newtonian")
    assert np.all(np.abs(inter.shear_stress) <= tl0 + lam * inter.pressure + 1e-9)
    b = math.sqrt(8 * w * R / (math.pi * E_PRIME))
    assert inter.viscous_friction > capped.viscous_friction + 0.5 * tl0 * 2 * b
    assert inter.viscous_friction < free.viscous_friction


def test_boundary_friction_is_integral_of_local_law():
    R, w, u = 0.01, 2e4, 0.5
    oil = Lubricant(0.055, 1.05e-8)
    rough = Roughness(asperity_density=5e10, rms=0.5e-6, summit_radius=2e-6)
    r = solve_ehl(
        w,
        R,
        u,
        1.0,
        PAIR,
        oil,
        rough,
        boundary_shear_coefficient=0.185,
        boundary_shear_strength=2e6,
    )
    assert r.converged, r.message
    e_s = E_PRIME
    ebs = 5e10 * 2e-6 * 0.5e-6
    # independent recomputation of Eq. 6 and Eq. 17–18 on the returned film
    from tribodyn import greenwood_tripp

    lam = r.film / 0.5e-6
    pa = (
        8
        * math.sqrt(2)
        / 15
        * math.pi
        * ebs**2
        * math.sqrt(0.5 / 2.0)
        * e_s
        * greenwood_tripp(2.5, lam)
    )
    area = math.pi**2 * ebs**2 * greenwood_tripp(2.0, lam)
    dx = r.x[1] - r.x[0]
    assert np.allclose(r.asperity_pressure, pa, rtol=1e-10, atol=1e-6)
    assert r.boundary_friction == pytest.approx(np.sum(2e6 * area + 0.185 * pa) * dx, rel=1e-10)
    assert r.asperity_load == pytest.approx(np.sum(pa) * dx, rel=1e-10)
    tot = r.totals(0.012)
    assert tot["friction"] == pytest.approx((r.viscous_friction + r.boundary_friction) * 0.012)


def test_chart_groups_from_the_dimensional_inputs():
    """Johnson's groups written from the physical inputs (Johnson, Proc. IMechE 184 (1970);
    Contact Mechanics, 1985, §13.6): g_V = α w^(3/2)/(R √(μ₀u)), g_E = w/√(μ₀ u E' R)."""
    w, R, u, mu0, alpha, e = 4e4, 0.01, 2.0, 0.055, 1.05e-8, 2.3e11
    W, U, G = hamrock_groups(w, R, u, mu0, alpha, e)
    gV, gE = greenwood_chart_groups(W, U, G)
    assert gV == pytest.approx(alpha * w**1.5 / (R * math.sqrt(mu0 * u)), rel=1e-12)
    assert gE == pytest.approx(w / math.sqrt(mu0 * u * e * R), rel=1e-12)
    M, L = moes_groups(W, U, G)
    # Moes: M = w/(E'R) (2U)^(−1/2), L = αE' (2U)^(1/4)
    assert M == pytest.approx(w / (e * R) / math.sqrt(2 * mu0 * u / (e * R)), rel=1e-12)
    assert L == pytest.approx(alpha * e * (2 * mu0 * u / (e * R)) ** 0.25, rel=1e-12)


@pytest.mark.parametrize(
    "gV, gE, regime",
    [
        (1.0, 1.80, "IR"),
        (1.0, 1.90, "IE"),
        (5.0, 0.1, "IR"),
        (5.2, 0.1, "PR"),
        (1e4, 1e2, "PE"),
        (1e3, 0.5, "PR"),
        (0.1, 50.0, "IE"),
        # either side of the boundaries where Johnson's asymptotes meet: IR Ĥ = 4.9 = IE
        # 3.01 g_E^0.8 at g_E = (4.9/3.01)^1.25 = 1.838; IR 4.9 = PR 1.66 g_V^(2/3) at
        # g_V = (4.9/1.66)^1.5 = 5.07
        (1.0, 1.70, "IR"),
        (1.0, 2.00, "IE"),
        (4.8, 0.5, "IR"),
        (5.4, 0.5, "PR"),
        (1e5, 1e2, "PE"),
        (1e3, 2e4, "IE"),
    ],
)
def test_greenwood_chart_regimes(gV, gE, regime):
    """Regimes of Johnson's chart (Johnson 1970), inside each and at its asymptotes'
    boundaries."""
    assert lubrication_regime(gV, gE) == regime


def test_moes_formula_tends_to_its_asymptotes():
    """Far into each regime Moes' interpolation tends to its published asymptotes
    (Moes 1992; Venner & Lubrecht 2000): H_RI = 3/M, H_EI = 2.621 M^(−1/5),
    H_RP = 1.287 L^(2/3), H_EP = 1.311 M^(−1/8) L^(3/4), H = (h/R)(2U)^(−1/2)."""
    R, U = 0.01, 1e-11

    def H(M, L):
        W = M * math.sqrt(2 * U)
        G = L / (2 * U) ** 0.25
        return float(moes_central(W, U, G, R)) / R / math.sqrt(2 * U)

    assert H(0.01, 0.0) == pytest.approx(3 / 0.01, rel=1e-3)  # rigid–isoviscous
    assert H(1e4, 0.0) == pytest.approx(2.621 * 1e4**-0.2, rel=2e-2)  # elastic–isoviscous
    assert H(0.05, 1e4) == pytest.approx(1.287 * 1e4 ** (2 / 3), rel=2e-2)  # rigid–piezoviscous
    assert H(1e5, 30.0) == pytest.approx(1.311 * 1e5**-0.125 * 30**0.75, rel=2e-2)


def test_analytic_contact_is_finite_everywhere_including_zero_entrainment():
    oil = Lubricant(0.055, 1.05e-8)
    rough = Roughness(8.3e9, 0.408e-6, 0.669e-6)
    w = np.array([1.0, 2e4, 4e4, 4e4])
    ue = np.array([5.0, 5.0, 0.0, -1.4])
    r = analytic_contact(w, 0.01, ue, 3.0, PAIR, oil, rough)
    for v in (r.central_film, r.min_film, r.viscous_friction, r.boundary_friction, r.asperity_load):
        assert np.all(np.isfinite(v)) and np.all(v >= 0)
    assert np.all(r.asperity_load <= w)
    assert np.all(r.min_film <= r.central_film)
    assert set(np.atleast_1d(r.regime)) <= {"IR", "PR", "IE", "PE"}

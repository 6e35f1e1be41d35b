"""The analytic tribology of the dynamics (physics/analytic_contact.py) against closed forms
and quadratures written here, and against the numerical EHL where both apply."""

import math

import numpy as np
import pytest
from scipy.integrate import quad

from ehl_cases import ALPHA, E_PRIME, MU0, PAIR, R, conditions
from tribodyn import Lubricant, Roughness, solve_ehl
from tribodyn.physics.analytic_contact import analytic_contact

W_LOAD, UE, US = 5e4, 3.0, 2.0


def gt(n, lam):
    """Greenwood–Tripp F_n(λ) = (2π)^(−1/2) ∫_λ^∞ (s − λ)^n e^(−s²/2) ds by quadrature."""
    return quad(lambda s: (s - lam) ** n * math.exp(-s * s / 2), lam, np.inf)[0] / math.sqrt(
        2 * math.pi
    )


def test_hertz_and_isoviscous_newtonian_friction_closed_form():
    """α = 0, Newtonian, no cap: τ = μ₀u_s/h_c over the Hertz width gives 2bμ₀u_s/h_c."""
    oil = Lubricant(MU0, 0.0)
    a = analytic_contact(
        W_LOAD, R, UE, US, PAIR, oil, viscous_model="newtonian", limiting_shear=False
    )
    b = math.sqrt(8 * W_LOAD * R / (math.pi * E_PRIME))
    ph = math.sqrt(W_LOAD * E_PRIME / (2 * math.pi * R))
    assert float(a.half_width) == pytest.approx(b, rel=1e-12)
    assert float(a.max_pressure) == pytest.approx(ph, rel=1e-12)
    hc = float(a.central_film)
    assert float(a.viscous_friction) == pytest.approx(2 * b * MU0 * US / hc, rel=1e-10)


def test_barus_newtonian_friction_against_quadrature():
    """μ = μ₀e^(αp) on the Hertz pressure: ∫ μ(p(x)) u_s/h_c dx by adaptive quadrature."""
    oil = Lubricant(MU0, ALPHA, viscosity_model="barus")
    a = analytic_contact(
        W_LOAD, R, UE, US, PAIR, oil, viscous_model="newtonian", limiting_shear=False
    )
    b, ph, hc = float(a.half_width), float(a.max_pressure), float(a.central_film)
    ref = quad(
        lambda x: MU0 * math.exp(ALPHA * ph * math.sqrt(1 - (x / b) ** 2)) * US / hc,
        -b,
        b,
        limit=200,
    )[0]
    assert float(a.viscous_friction) == pytest.approx(ref, rel=1e-6)


def test_asperity_load_and_boundary_friction_against_greenwood_tripp():
    """W_a = 2b (8√2/15)π(ηβσ)²√(σ/β)E' F_5/2(h_c/σ); F_b = 2b τ₀ π²(ηβσ)² F₂ + ς W_a."""
    oil = Lubricant(MU0, ALPHA)
    probe = analytic_contact(W_LOAD, R, UE, US, PAIR, oil)
    sigma = float(probe.central_film) / 1.2  # λ = 1.2 at the centre
    eta, beta = 5e10, 2e-6
    rough = Roughness(asperity_density=eta, rms=sigma, summit_radius=beta)
    tau0, s_b = 2e6, 0.3
    a = analytic_contact(
        W_LOAD,
        R,
        UE,
        US,
        PAIR,
        oil,
        rough,
        boundary_shear_coefficient=s_b,
        boundary_shear_strength=tau0,
    )
    b, lam = float(a.half_width), float(a.central_film) / sigma
    ebs = eta * beta * sigma
    wa = (
        2
        * b
        * (8 * math.sqrt(2) / 15)
        * math.pi
        * ebs**2
        * math.sqrt(sigma / beta)
        * E_PRIME
        * gt(2.5, lam)
    )
    area = 2 * b * math.pi**2 * ebs**2 * gt(2.0, lam)
    assert float(a.asperity_load) == pytest.approx(wa, rel=1e-6)
    assert float(a.boundary_friction) == pytest.approx(tau0 * area + s_b * wa, rel=1e-6)
    assert 0 < float(a.asperity_load) < W_LOAD


@pytest.mark.parametrize("M, L", [(20, 10), (100, 10)])
@pytest.mark.parametrize("law", ["newtonian", "eyring"])
def test_agrees_with_the_numerical_ehl_where_both_apply(M, L, law):
    """In the elastic regime (parallel central film over the Hertz width) with Barus and
    an incompressible oil, Moes' formula is within 5 % of the numerical film, and the
    capped viscous friction of the Hertz-pressure approximation within 5 % of the
    numerical one."""
    w, u, _, _ = conditions(M, L)
    oil = Lubricant(MU0, ALPHA, viscosity_model="barus", compressible=False)
    r = solve_ehl(w, R, u, 2.0, PAIR, oil, viscous_model=law)
    a = analytic_contact(w, R, u, 2.0, PAIR, oil, viscous_model=law)
    assert r.converged
    assert float(a.central_film) == pytest.approx(r.central_film, rel=0.05)
    assert float(a.viscous_friction) == pytest.approx(r.viscous_friction, rel=0.05)

"""Mixed and coated EHL against quantitative references.

* Load sharing in mixed EHL against the load-sharing model of Johnson, Greenwood & Poon,
  "A simple theory of asperity contact in elastohydrodynamic lubrication", Wear 19 (1972)
  91–108, in the form of Gelinck & Schipper, "Calculation of Stribeck curves for line
  contacts", Tribol. Int. 33 (2000) 175–181: the fluid carries W/γ₁ with a film from the
  smooth-EHL formula at load W/γ₁ and modulus E'/γ₁; the asperities carry W/γ₂ =
  2b p_a(h_c) over the Hertz width; 1/γ₁ + 1/γ₂ = 1. Implemented here independently
  (Moes' film formula, Greenwood–Tripp F_5/2 by quadrature).
* The asperity load recomputed from the returned film; the film equation and steady mass
  flux recomputed from the returned pressure (tests/independent.py).
* A coating many contact half-widths thick behaves as the coating material throughout.
"""

import math

import numpy as np
import pytest
from scipy.integrate import quad
from scipy.optimize import brentq

from ehl_cases import ALPHA, E_PRIME, MU0, PAIR, STEEL, G, R, conditions
from independent import mass_flux_deviation
from tribodyn import Body, Coating, Lubricant, Material, Roughness, solve_ehl
from tribodyn.physics.regimes import hamrock_groups, moes_central

OIL = Lubricant(MU0, ALPHA, viscosity_model="barus", compressible=False)  # Moes' oil
BETA, ETA_BETA_SIGMA = 2e-6, 0.04


def f52(lam):
    return quad(lambda s: (s - lam) ** 2.5 * math.exp(-s * s / 2), lam, np.inf)[0] / math.sqrt(
        2 * math.pi
    )


def rough_for(sigma):
    return Roughness(
        asperity_density=ETA_BETA_SIGMA / (sigma * BETA), rms=sigma, summit_radius=BETA
    )


def pressure_scale(rough, e_prime):
    s, b, eta = rough.rms, rough.summit_radius, rough.asperity_density
    return (8 * math.sqrt(2) / 15) * math.pi * (eta * b * s) ** 2 * math.sqrt(s / b) * e_prime


def jgp_load_share(w, u, rough):
    """(h_c, W_a/W) of the Johnson–Greenwood–Poon load-sharing model (module docstring)."""
    b = math.sqrt(8 * w * R / (math.pi * E_PRIME))
    k = pressure_scale(rough, E_PRIME)

    def hc(g1):
        W, U, Gg = hamrock_groups(w / g1, R, u, MU0, ALPHA, E_PRIME / g1)
        return float(moes_central(W, U, Gg, R))

    g1 = brentq(lambda g: w - w / g - 2 * b * k * f52(hc(g) / rough.rms), 1 + 1e-12, 1e6)
    return hc(g1), 1 - 1 / g1


@pytest.mark.parametrize("M", [20, 100])
@pytest.mark.parametrize("lam", [1.0, 0.7, 0.5])
def test_load_sharing_against_johnson_greenwood_poon(M, lam):
    """Asperity load share within 15 % of the load-sharing model. Both use Greenwood–Tripp
    asperities; the model takes the film flat at h_c over the Hertz width and the fluid
    film from Moes' fit (itself within ~4 % of this solver), the solver resolves h(x):
    measured differences are 0–10 % for M = 20–100, λ = 0.5–1."""
    w, u, W, U = conditions(M, 10)
    sigma = float(moes_central(W, U, G, R)) / lam  # λ of the smooth Moes film
    rough = rough_for(sigma)
    r = solve_ehl(w, R, u, 0.0, PAIR, OIL, rough)
    assert r.converged, r.message
    _, share = jgp_load_share(w, u, rough)
    assert r.asperity_load / w == pytest.approx(share, rel=0.15)
    assert r.hydrodynamic_load + r.asperity_load == pytest.approx(w, rel=1e-9)


def test_smooth_film_limit_of_greenwood_tripp():
    """At λ ≈ 4 the asperities carry < 1e-5 of the load and the film is the smooth one."""
    w, u, W, U = conditions(50, 10)
    smooth = solve_ehl(w, R, u, 0.0, PAIR, OIL)
    r = solve_ehl(w, R, u, 0.0, PAIR, OIL, rough_for(smooth.central_film / 4))
    assert r.asperity_load / w < 1e-5
    assert r.central_film == pytest.approx(smooth.central_film, rel=1e-4)
    _, share = jgp_load_share(w, u, rough_for(smooth.central_film / 4))
    assert share < 1e-5
    # both solutions satisfy the steady Reynolds equation (constant mass flux), which a
    # solver returning its starting state does not
    for sol in (smooth, r):
        dev_max, dev_95 = mass_flux_deviation(sol.x, sol.pressure, sol.film, u, OIL)
        assert dev_max < 0.25 and dev_95 < 0.01


@pytest.mark.parametrize("lam", [1.0, 0.5])
def test_asperity_pressure_and_flux_recomputed_from_the_solution(lam):
    """p_a(x) = K F_5/2(h(x)/σ) from the returned film, by quadrature, and the steady mass
    flux of the fluid pressure; a solver returning its starting state fails both."""
    w, u, W, U = conditions(20, 10)
    rough = rough_for(float(moes_central(W, U, G, R)) / lam)
    r = solve_ehl(w, R, u, 0.0, PAIR, OIL, rough)
    k = pressure_scale(rough, E_PRIME)
    idx = np.linspace(0, r.x.size - 1, 40).astype(int)
    ref = np.array([k * f52(r.film[i] / rough.rms) for i in idx])
    assert np.allclose(r.asperity_pressure[idx], ref, rtol=1e-5, atol=1e-9 * ref.max())
    dev_max, dev_95 = mass_flux_deviation(r.x, r.pressure, r.film, u, OIL)
    assert dev_max < 0.25 and dev_95 < 0.01


@pytest.mark.parametrize("Ec", [70e9, 420e9])
def test_thick_coating_is_the_coating_material_throughout(Ec):
    """A layer 40 Hertz half-widths thick: the contact sees only the coating material."""
    w, u, _, _ = conditions(50, 10)
    b = math.sqrt(8 * w * R / (math.pi * E_PRIME))
    coat = Material(Ec, 0.25)
    layered = (Body(STEEL), Body(STEEL, Coating(Ec, 0.25, 40 * b)))
    solid = (Body(STEEL), Body(coat))
    oil = Lubricant(MU0, ALPHA)
    a = solve_ehl(w, R, u, 0.0, layered, oil)
    s = solve_ehl(w, R, u, 0.0, solid, oil, n=a.x.size)
    assert a.converged and s.converged
    assert a.central_film == pytest.approx(s.central_film, rel=0.01)
    assert a.min_film == pytest.approx(s.min_film, rel=0.01)
    assert a.pressure.max() == pytest.approx(s.pressure.max(), rel=0.02)

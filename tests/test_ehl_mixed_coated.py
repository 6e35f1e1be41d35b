"""Mixed lubrication (Greenwood–Tripp load sharing), coatings, flow direction."""

import math

import numpy as np
import pytest

from ehl_cases import E_PRIME, OIL, PAIR, STEEL, R, conditions
from independent import mass_flux_deviation
from tribodyn import Body, Coating, Roughness, solve_ehl

W_LOAD, U_E, _, _ = conditions(20, 10)


@pytest.fixture(scope="module")
def smooth():
    return solve_ehl(W_LOAD, R, U_E, 0.3, PAIR, OIL)


def assert_reynolds(r):
    """Steady mass flux constant over the pressurised zone (see test_ehl_formulas)."""
    dev_max, dev_95 = mass_flux_deviation(r.x, r.pressure, r.film, r.entrainment_speed, OIL)
    assert dev_max < 0.25 and dev_95 < 0.01, (dev_max, dev_95)


@pytest.mark.parametrize("sigma", [1e-10, 1e-9])
def test_vanishing_roughness_recovers_smooth_solution(smooth, sigma):
    r = solve_ehl(W_LOAD, R, U_E, 0.3, PAIR, OIL, Roughness(5e10, sigma, 2e-6))
    assert r.converged, r.message
    assert_reynolds(r)
    assert r.asperity_load < 1e-12 * W_LOAD
    assert r.boundary_friction < 1e-12 * W_LOAD
    assert r.central_film == pytest.approx(smooth.central_film, rel=1e-9)
    assert np.allclose(r.pressure, smooth.pressure, rtol=0, atol=1e-9 * smooth.pressure.max())


def test_asperities_carry_most_of_the_load_when_film_is_below_sigma(smooth):
    rough = Roughness(asperity_density=5e10, rms=1e-6, summit_radius=2e-6)
    r = solve_ehl(W_LOAD, R, U_E, 0.3, PAIR, OIL, rough)
    assert r.converged, r.message
    assert r.central_film < rough.rms
    assert r.asperity_load > 0.9 * W_LOAD
    assert r.hydrodynamic_load + r.asperity_load == pytest.approx(W_LOAD, rel=1e-9)
    assert r.boundary_friction > r.viscous_friction  # boundary-dominated regime
    # load sharing: the asperities lift the surfaces apart compared with the smooth film
    assert r.central_film > smooth.central_film


def test_intermediate_roughness_shares_load_and_is_monotone(smooth):
    shares = []
    for sigma in (0.2e-6, 0.5e-6, 1e-6):
        r = solve_ehl(W_LOAD, R, U_E, 0.3, PAIR, OIL, Roughness(5e10, sigma, 2e-6))
        assert r.converged, r.message
        shares.append(r.asperity_load / W_LOAD)
    assert 0 < shares[0] < shares[1] < shares[2] < 1


def test_identical_coating_reproduces_uncoated(smooth):
    coated = (Body(STEEL), Body(STEEL, Coating(210e9, 0.3, 4e-6)))
    r = solve_ehl(W_LOAD, R, U_E, 0.3, coated, OIL)
    assert_reynolds(r)
    assert r.central_film == pytest.approx(smooth.central_film, rel=1e-10)
    assert np.allclose(r.pressure, smooth.pressure, rtol=0, atol=1e-9 * smooth.pressure.max())


def test_soft_coating_widens_contact_and_thickens_film(smooth):
    # a thick soft layer (≫ b) behaves like the soft material: lower E' ⇒ wider contact,
    # lower pressure, slightly thicker film (h ∝ E'^(−0.1…0.2) at fixed load and speed)
    b = math.sqrt(8 * W_LOAD * R / (math.pi * E_PRIME))
    soft = (Body(STEEL), Body(STEEL, Coating(70e9, 0.3, 20 * b)))
    r = solve_ehl(W_LOAD, R, U_E, 0.3, soft, OIL)
    assert r.converged, r.message
    assert r.pressure.max() < 0.8 * smooth.pressure.max()
    assert r.central_film > smooth.central_film


def test_negative_entrainment_is_the_mirror_image(smooth):
    m = solve_ehl(W_LOAD, R, -U_E, 0.3, PAIR, OIL)
    assert m.converged, m.message
    assert_reynolds(m)
    assert m.central_film == pytest.approx(smooth.central_film, rel=1e-10)
    assert m.min_film_position == pytest.approx(-smooth.min_film_position, rel=1e-10)
    p_mirror = np.interp(-smooth.x, m.x, m.pressure)
    assert np.allclose(p_mirror, smooth.pressure, rtol=0, atol=1e-9 * smooth.pressure.max())

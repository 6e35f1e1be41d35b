"""Smooth EHL line contact against film-thickness formulas; grid convergence."""

import math

import pytest

from ehl_cases import ALPHA, E_PRIME, MU0, PAIR, G, R, conditions
from independent import film_equation_residual, mass_flux_deviation
from tribodyn import Lubricant, solve_ehl
from tribodyn.physics.regimes import moes_central, pan_hamrock


def assert_solves_reynolds(r, oil):
    """The solution satisfies steady Reynolds (constant mass flux across the pressurised
    zone, up to the difference between the solver's upwind scheme and the central
    differences used here, largest at the pressure spike) and the film equation with the
    analytic log kernel. The solver's starting state (Hertz-like pressure, Moes film)
    misses the flux check by a factor of > 100."""
    dev_max, dev_95 = mass_flux_deviation(r.x, r.pressure, r.film, r.entrainment_speed, oil)
    assert dev_max < 0.25 and dev_95 < 0.01, (dev_max, dev_95)
    assert film_equation_residual(r.x, r.film, r.pressure + r.asperity_pressure, R, E_PRIME) < 1e-6


# Pan & Hamrock fitted Roelands + Dowson–Higginson solutions; their h_c fit drifts above
# ~L = 10 (exponents differ from the asymptotic EHL scaling), so the cases stay where the
# fit was made.
@pytest.mark.parametrize("M, L", [(5, 5), (20, 5), (50, 5), (100, 5), (10, 7.5), (5, 10)])
def test_pan_hamrock_roelands_dowson_higginson(M, L):
    w, u, W, U = conditions(M, L)
    oil = Lubricant(MU0, ALPHA)
    r = solve_ehl(w, R, u, 0.0, PAIR, oil)
    assert r.converged, r.message
    assert_solves_reynolds(r, oil)
    hc, hm = pan_hamrock(W, U, G, R)
    assert r.central_film == pytest.approx(hc, rel=0.05)
    assert r.min_film == pytest.approx(hm, rel=0.05)


# Moes' formula interpolates multigrid solutions for Barus viscosity and an
# incompressible lubricant: compare like with like.
@pytest.mark.parametrize("M, L", [(5, 5), (10, 10), (20, 15), (50, 10), (100, 5), (100, 15)])
def test_moes_barus_incompressible(M, L):
    w, u, W, U = conditions(M, L)
    oil = Lubricant(MU0, ALPHA, viscosity_model="barus", compressible=False)
    r = solve_ehl(w, R, u, 0.0, PAIR, oil)
    assert r.converged, r.message
    assert_solves_reynolds(r, oil)
    assert r.central_film == pytest.approx(float(moes_central(W, U, G, R)), rel=0.10)


@pytest.mark.parametrize("M, L", [(20, 10), (100, 10)])
def test_grid_convergence_from_default(M, L):
    w, u, _, _ = conditions(M, L)
    oil = Lubricant(MU0, ALPHA)
    a = solve_ehl(w, R, u, 0.0, PAIR, oil)  # default (automatic) grid
    b = solve_ehl(w, R, u, 0.0, PAIR, oil, n=2 * a.x.size)  # twice as many nodes
    assert a.converged and b.converged
    assert_solves_reynolds(a, oil)
    assert_solves_reynolds(b, oil)
    assert a.central_film == pytest.approx(b.central_film, rel=0.005)
    assert a.min_film == pytest.approx(b.min_film, rel=0.005)
    # positions of the minimum film agree to within two grid spacings
    assert abs(a.min_film_position - b.min_film_position) < 2 * (a.x[1] - a.x[0])


def test_ehl_solution_structure():
    """Classic EHL features: flat central film, exit constriction, pressure close to Hertz."""
    w, u, W, U = conditions(20, 10)
    r = solve_ehl(w, R, u, 0.0, PAIR, Lubricant(MU0, ALPHA))
    b = math.sqrt(8 * w * R / (math.pi * E_PRIME))
    ph = math.sqrt(w * E_PRIME / (2 * math.pi * R))
    assert r.min_film < r.central_film
    assert 0.5 * b < r.min_film_position < 1.2 * b  # constriction near the exit
    assert r.hydrodynamic_load == pytest.approx(w, rel=1e-9)
    mid = abs(r.x) < 0.5 * b
    assert r.pressure[mid].max() == pytest.approx(ph, rel=0.1)
    assert r.film[mid].max() / r.film[mid].min() < 1.1  # parallel central film


def test_two_grid_preconditioned_solution_equals_dense_solution(monkeypatch):
    """Grids above 1024 nodes are solved by GMRES with a coarse-grid LU preconditioner;
    the converged discrete solution must not depend on the linear solver."""
    import tribodyn.contact.ehl.steady as steady

    w, u, _, _ = conditions(50, 10)
    oil = Lubricant(MU0, ALPHA)
    fast = solve_ehl(w, R, u, 0.0, PAIR, oil, n=2048)
    monkeypatch.setattr(steady, "_N_DENSE", 4096)  # force dense LU on every level
    dense = solve_ehl(w, R, u, 0.0, PAIR, oil, n=2048)
    assert fast.converged and dense.converged
    assert_solves_reynolds(dense, oil)
    assert fast.central_film == pytest.approx(dense.central_film, rel=1e-8)
    assert fast.min_film == pytest.approx(dense.min_film, rel=1e-8)
    assert abs(fast.pressure - dense.pressure).max() < 1e-7 * dense.pressure.max()

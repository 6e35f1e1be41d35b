"""Dry line-contact solver against Hertz and the coated limits."""

import math

import numpy as np
import pytest

from tribodyn import (
    Body,
    Coating,
    InputError,
    Material,
    reduced_modulus,
    solve_dry_contact,
)
from tribodyn.physics.hertz import hertz_line_contact

STEEL = Material(210e9, 0.3)
W, R = 1.0e5, 0.01


def _pair(coating=None):
    return (Body(STEEL), Body(STEEL, coating))


def _flat(x):
    """A starting pressure that is not the answer: uniform over the middle third."""
    return (np.abs(x) < x[-1] / 3).astype(float)


def _assert_complementarity(r, e_prime):
    """Gap recomputed with the analytic log kernel (valid for homogeneous pairs): zero
    where loaded, non-negative elsewhere, to 1e-4 of the Hertz approach scale b²/R."""
    from independent import log_kernel_displacement

    g = r.x**2 / (2 * R) + log_kernel_displacement(r.x, r.pressure, e_prime)
    loaded = r.pressure > 0
    g -= g[loaded].mean()
    scale = r.half_width**2 / R
    assert np.abs(g[loaded]).max() < 1e-4 * scale
    assert g[~loaded].min() > -1e-4 * scale


def test_hertz_at_default_grid():
    r = solve_dry_contact(W, R, _pair(), initial_pressure=_flat)
    # Hertz computed here from the closed form, independent of the solver
    e = 210e9 / 0.91
    b = np.sqrt(8 * W * R / (np.pi * e))
    ph = np.sqrt(W * e / (2 * np.pi * R))
    assert r.converged, r.message
    assert r.half_width == pytest.approx(b, rel=5e-3)
    assert r.max_pressure == pytest.approx(ph, rel=5e-3)
    p_ref = ph * np.sqrt(np.clip(1 - (r.x / b) ** 2, 0, None))
    assert np.sqrt(np.mean((r.pressure - p_ref) ** 2)) < 0.01 * ph
    assert r.load == pytest.approx(W, rel=1e-12)
    # complementarity: non-negative pressure and gap, zero gap under load
    assert r.pressure.min() >= 0
    assert r.gap.min() > -1e-9 * b**2 / R
    assert np.all(np.abs(r.gap[r.pressure > 0]) < 1e-6 * b**2 / R)


@pytest.mark.parametrize("thickness", [1e-8, 1e-6, 1e-4, 1e-2])
def test_identical_coating_is_hertz_for_any_thickness(thickness):
    plain = solve_dry_contact(W, R, _pair(), initial_pressure=_flat)
    r = solve_dry_contact(W, R, _pair(Coating(210e9, 0.3, thickness)), initial_pressure=_flat)
    hz = hertz_line_contact(W, R, reduced_modulus(_pair()))
    assert r.converged
    _assert_complementarity(r, 210e9 / 0.91)
    assert r.half_width == pytest.approx(hz.half_width, rel=1e-2)
    assert r.max_pressure == pytest.approx(hz.max_pressure, rel=1e-2)
    assert np.allclose(r.pressure, plain.pressure, rtol=0, atol=1e-9 * hz.max_pressure)


@pytest.mark.parametrize("Ec, nuc", [(52.5e9, 0.25), (840e9, 0.2)])
def test_thin_coating_gives_substrate_hertz(Ec, nuc):
    r = solve_dry_contact(W, R, _pair(Coating(Ec, nuc, 1e-8)), initial_pressure=_flat)
    hz = hertz_line_contact(W, R, reduced_modulus(_pair()))
    assert r.converged
    _assert_complementarity(r, 210e9 / 0.91)  # a 10 nm layer: the steel pair
    assert r.half_width == pytest.approx(hz.half_width, rel=1e-2)
    assert r.max_pressure == pytest.approx(hz.max_pressure, rel=1e-2)


@pytest.mark.parametrize("Ec, nuc", [(52.5e9, 0.25), (840e9, 0.2)])
def test_thick_coating_gives_coating_material_hertz(Ec, nuc):
    e_coat = 2.0 / (STEEL.compliance + Material(Ec, nuc).compliance)
    hz = hertz_line_contact(W, R, e_coat)
    r = solve_dry_contact(W, R, _pair(Coating(Ec, nuc, 50 * hz.half_width)), initial_pressure=_flat)
    assert r.converged
    assert r.half_width == pytest.approx(hz.half_width, rel=1e-2)
    assert r.max_pressure == pytest.approx(hz.max_pressure, rel=1e-2)


def test_intermediate_coating_is_between_the_limits():
    # a soft 5 µm coating on a ~76 µm contact: wider than steel Hertz, narrower than coating Hertz
    soft = Coating(52.5e9, 0.3, 5e-6)
    r = solve_dry_contact(633 / 0.012, R, _pair(soft))
    b_steel = hertz_line_contact(633 / 0.012, R, reduced_modulus(_pair())).half_width
    b_coat = hertz_line_contact(633 / 0.012, R, 2 / (STEEL.compliance + soft.compliance)).half_width
    assert b_steel * 1.01 < r.half_width < 0.9 * b_coat


def test_grid_convergence():
    soft = _pair(Coating(60e9, 0.3, 10e-6))
    coarse = solve_dry_contact(W, R, soft, n=1024, initial_pressure=_flat)
    fine = solve_dry_contact(W, R, soft, n=4096, initial_pressure=_flat)
    assert coarse.converged and fine.converged
    # the soft layer makes the contact wider than the (starting-state-free) steel Hertz
    b_steel = hertz_line_contact(W, R, reduced_modulus(_pair())).half_width
    assert fine.half_width > 1.02 * b_steel
    assert coarse.max_pressure == pytest.approx(fine.max_pressure, rel=2e-3)
    assert coarse.half_width == pytest.approx(fine.half_width, rel=2e-3)


def test_nonconvergence_is_reported():
    r = solve_dry_contact(W, R, _pair(), max_iter=3)
    assert not r.converged and "not converged" in r.message
    assert np.all(np.isfinite(r.pressure))


def test_contact_at_domain_edge_is_reported():
    r = solve_dry_contact(W, R, _pair(), domain=1.0005, max_domain_growth=0, n=256)
    assert not r.converged and "domain edge" in r.message


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(load=-1.0, radius=R), "load"),
        (dict(load=0.0, radius=R), "load"),
        (dict(load=float("nan"), radius=R), "load"),
        (dict(load=W, radius=0.0), "radius"),
        (dict(load=W, radius=-0.01), "radius"),
    ],
)
def test_bad_input_names_argument(kwargs, name):
    with pytest.raises(InputError, match=rf"^{name} must"):
        solve_dry_contact(bodies=_pair(), **kwargs)


def test_bad_grid_and_bodies():
    with pytest.raises(InputError, match="^n must"):
        solve_dry_contact(W, R, _pair(), n=8)
    with pytest.raises(InputError, match="bodies"):
        solve_dry_contact(W, R, (Body(STEEL),))


def test_hertz_pressure_profile_closed_form():
    """p(x) = p_h √(1 − x²/b²) inside the contact, 0 outside; ∫p dx = π b p_h / 2 = w and
    b = √(8wR/(πE')), p_h = √(wE'/(2πR)) (Johnson, Contact Mechanics, 1985, §4.3)."""
    w, R, E = 5e4, 0.01, 2.3e11
    hz = hertz_line_contact(w, R, E)
    b = math.sqrt(8 * w * R / (math.pi * E))
    ph = math.sqrt(w * E / (2 * math.pi * R))
    assert hz.half_width == pytest.approx(b, rel=1e-12)
    assert hz.max_pressure == pytest.approx(ph, rel=1e-12)
    x = np.array([-2 * b, -b, -0.5 * b, 0.0, 0.3 * b, b, 1.5 * b])
    ref = ph * np.sqrt(np.clip(1 - (x / b) ** 2, 0, None))
    assert np.allclose(hz.pressure(x), ref, rtol=1e-12, atol=0.0)
    xs = np.linspace(-1.2 * b, 1.2 * b, 200001)
    assert float(np.sum(hz.pressure(xs)) * (xs[1] - xs[0])) == pytest.approx(w, rel=1e-5)

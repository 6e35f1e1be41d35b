"""Physics core: materials, reduced modulus, Roelands and Dowson–Higginson."""

import math

import numpy as np
import pytest

from tribodyn import Body, Coating, InputError, Lubricant, Material, reduced_modulus


def test_reduced_modulus_convention():
    # 1/E' = ½[(1−ν₁²)/E₁ + (1−ν₂²)/E₂]: steel on steel → E/(1−ν²)
    s = Material(210e9, 0.3)
    assert reduced_modulus((Body(s), Body(s))) == pytest.approx(210e9 / 0.91, rel=1e-14)
    d = Material(185e9, 0.25)
    expected = 2.0 / (0.91 / 210e9 + (1 - 0.0625) / 185e9)
    assert reduced_modulus((Body(s), Body(d))) == pytest.approx(expected, rel=1e-14)
    # surface=True uses the coating
    coated = Body(s, Coating(185e9, 0.25, 4e-6))
    assert reduced_modulus((Body(s), coated)) == pytest.approx(210e9 / 0.91)
    assert reduced_modulus((Body(s), coated), surface=True) == pytest.approx(expected)


# Hand-calculated (independent of the implementation): μ₀ = 0.055 Pa·s, α = 1.05e-8 1/Pa,
# ln μ₀ + 9.67 = 6.7695779, Z = α/(5.1e-9·6.7695779) = 0.3041288.
@pytest.mark.parametrize(
    "p, mu", [(0.0, 0.055), (0.1e9, 0.13581011), (1e9, 7.868253), (3e9, 468.99509)]
)
def test_roelands_spot_values(p, mu):
    oil = Lubricant(viscosity=0.055, pressure_viscosity=1.05e-8)
    assert oil.roelands_z == pytest.approx(0.3041288, rel=1e-6)
    assert oil.viscosity_at(p) == pytest.approx(mu, rel=1e-6)


def test_roelands_slope_at_zero_is_alpha():
    oil = Lubricant(viscosity=0.055, pressure_viscosity=1.05e-8)
    assert oil.dlog_viscosity_dp(0.0) == pytest.approx(1.05e-8, rel=1e-12)
    p = np.linspace(0, 2e9, 11)
    dp = 1e3
    fd = (oil.log_viscosity_ratio(p + dp) - oil.log_viscosity_ratio(np.maximum(p - dp, 0))) / (
        np.where(p > 0, 2 * dp, dp)
    )
    assert np.allclose(oil.dlog_viscosity_dp(p)[1:], fd[1:], rtol=1e-6)


def test_barus_option():
    oil = Lubricant(viscosity=0.055, pressure_viscosity=1.05e-8, viscosity_model="barus")
    assert oil.viscosity_at(1e9) == pytest.approx(0.055 * math.exp(10.5), rel=1e-12)


@pytest.mark.parametrize(
    "p_gpa, ratio", [(0.5, 1 + 0.3 / 1.85), (1.0, 1 + 0.6 / 2.7), (2.0, 1 + 1.2 / 4.4)]
)
def test_dowson_higginson_spot_values(p_gpa, ratio):
    oil = Lubricant(viscosity=0.055, pressure_viscosity=1.05e-8, density=850.0)
    assert oil.density_at(p_gpa * 1e9) == pytest.approx(850.0 * ratio, rel=1e-12)
    h = 1e3
    fd = (oil.density_at(p_gpa * 1e9 + h) - oil.density_at(p_gpa * 1e9 - h)) / (2 * h)
    assert oil.ddensity_dp(p_gpa * 1e9) == pytest.approx(fd, rel=1e-6)


@pytest.mark.parametrize("mu0, alpha", [(0.055, 1.05e-8), (0.01, 2.5e-8), (0.5, 1.5e-8)])
def test_rheology_monotone_and_finite_to_5_gpa(mu0, alpha):
    oil = Lubricant(viscosity=mu0, pressure_viscosity=alpha)
    p = np.linspace(0.0, 5e9, 2001)
    mu, rho = oil.viscosity_at(p), oil.density_at(p)
    assert np.all(np.isfinite(mu)) and np.all(np.isfinite(rho))
    assert np.all(np.diff(mu) > 0) and np.all(np.diff(rho) > 0)
    # the D–H asymptote: ρ/ρ₀ < 1 + 0.6/1.7
    assert rho.max() < 850 * (1 + 0.6 / 1.7)


def test_negative_pressure_is_held_at_ambient():
    oil = Lubricant(viscosity=0.055, pressure_viscosity=1.05e-8)
    assert oil.viscosity_at(-1e8) == pytest.approx(0.055)
    assert oil.density_at(-1e9) == pytest.approx(850.0)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(E=-210e9, nu=0.3), "E"),
        (dict(E=0.0, nu=0.3), "E"),
        (dict(E=float("nan"), nu=0.3), "E"),
        (dict(E=210e9, nu=0.5), "nu"),
        (dict(E=210e9, nu=-1.0), "nu"),
        (dict(E=210e9, nu=float("nan")), "nu"),
    ],
)
def test_bad_material_input_names_the_argument(kwargs, name):
    with pytest.raises(InputError, match=rf"^{name} must"):
        Material(**kwargs)


@pytest.mark.parametrize("t", [0.0, -1e-6, float("nan"), float("inf")])
def test_bad_coating_thickness(t):
    with pytest.raises(InputError, match="^thickness must"):
        Coating(E=175e9, nu=0.3, thickness=t)


def test_bad_lubricant_input():
    with pytest.raises(InputError, match="^viscosity must"):
        Lubricant(viscosity=-1.0, pressure_viscosity=1e-8)
    with pytest.raises(InputError, match="^viscosity must be >"):
        Lubricant(viscosity=1e-5, pressure_viscosity=1e-8)  # below Roelands' 6.31e-5
    with pytest.raises(InputError, match="^pressure_viscosity must"):
        Lubricant(viscosity=0.05, pressure_viscosity=-1e-8)
    with pytest.raises(InputError, match="^density must"):
        Lubricant(viscosity=0.05, pressure_viscosity=1e-8, density=0.0)


def test_body_rejects_wrong_types():
    with pytest.raises(InputError, match="material"):
        Body("steel")
    with pytest.raises(InputError, match="coating"):
        Body(Material(210e9, 0.3), coating=Material(175e9, 0.3))

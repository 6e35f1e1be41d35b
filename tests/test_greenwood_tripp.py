"""Greenwood–Tripp statistical functions and asperity pressure/area."""

import math

import numpy as np
import pytest
from scipy import integrate

from conftest import asperity_pressure_derivative
from tribodyn import InputError, Roughness, greenwood_tripp
from tribodyn.physics.asperity import greenwood_tripp_derivative


@pytest.mark.parametrize(
    "n, lam, ref",
    [(2.5, 0.0, 0.616634), (2.5, 1.0, 0.0805623), (2.0, 1.0, 0.0753398), (2.0, 2.0, 5.76873e-3)],
)
def test_exact_reference_values(n, lam, ref):
    assert greenwood_tripp(n, lam) == pytest.approx(ref, rel=1e-6)


def _quad_fn(n, lam):
    def f(s):
        return (s - lam) ** n * math.exp(-0.5 * s * s) / math.sqrt(2 * math.pi)

    # split at 0 so that the quadrature sees the Gaussian's mass when λ ≪ 0
    pieces = [(lam, 0.0), (0.0, math.inf)] if lam < 0 else [(lam, math.inf)]
    return sum(integrate.quad(f, a, b, epsabs=0, epsrel=1e-12, limit=200)[0] for a, b in pieces)


@pytest.mark.parametrize("n", [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.7])
@pytest.mark.parametrize("lam", [-40.0, -15.0, -5.0, -1.3, 0.0, 0.7, 2.5, 4.0, 8.0])
def test_exact_matches_definition(n, lam):
    assert greenwood_tripp(n, lam) == pytest.approx(_quad_fn(n, lam), rel=1e-9)


def test_finite_positive_decreasing_over_range():
    lam = np.linspace(-5, 30, 3501)
    for n in (2.0, 2.5):
        f = greenwood_tripp(n, lam)
        assert np.all(np.isfinite(f)) and np.all(f > 0)
        assert np.all(np.diff(f) < 0)
    # F_n(−λ) for large negative λ: polynomial moments, e.g. F₂(−5) = 25 + 1 (mean of (s+5)²)
    assert greenwood_tripp(2.0, -5.0) == pytest.approx(26.0, rel=1e-6)


@pytest.mark.parametrize("n", [0.0, 1.0, 2.0, 2.5, 3.7])
def test_derivative_identity(n):
    """dF_n/dλ against central differences of F_n (which is checked against its defining
    integral above), also on the series branch below λ = −12."""
    lam = np.concatenate([np.linspace(-3, 6, 37), [-30.0, -14.0]])
    h = 1e-6 * np.maximum(1.0, np.abs(lam))
    fd = (greenwood_tripp(n, lam + h) - greenwood_tripp(n, lam - h)) / (2 * h)
    assert np.allclose(greenwood_tripp_derivative(n, lam), fd, rtol=1e-6, atol=1e-12)


@pytest.mark.parametrize("n", [2.0, 2.5])
def test_paper_fit_derivative_is_the_fit_slope(n):
    """The paper's polynomial option: its derivative is the slope of the clipped fit (zero
    where the fit is clipped)."""
    lam = np.linspace(0.05, 3.95, 40)
    h = 1e-6
    f = greenwood_tripp(n, lam + h, method="paper")
    g = greenwood_tripp(n, lam - h, method="paper")
    fd = (f - g) / (2 * h)
    d = greenwood_tripp_derivative(n, lam, method="paper")
    smooth = (f > 0) & (g > 0)  # away from the clipping point
    assert np.allclose(d[smooth], fd[smooth], rtol=1e-6, atol=1e-10)
    assert np.all(d[greenwood_tripp(n, lam, method="paper") == 0.0] == 0.0)
    assert np.all(d[smooth] < 0)


def test_paper_polynomials_are_clipped_and_documented_inaccurate():
    lam = np.linspace(0, 4, 401)
    f2 = greenwood_tripp(2.0, lam, method="paper")
    assert np.all(f2 >= 0)
    # the raw F₂ fit goes negative beyond λ ≈ 1.90 → clipped to 0 there
    assert greenwood_tripp(2.0, 2.2, method="paper") == 0.0
    # F_5/2 fit is ~59 % off the exact value at λ = 2.5
    fit = np.polyval((0.000421, -0.008538, 0.07162, -0.3193, 0.802, -1.082, 0.6166), 2.5)
    assert abs(fit / greenwood_tripp(2.5, 2.5) - 1) == pytest.approx(0.59, abs=0.02)
    with pytest.raises(InputError):
        greenwood_tripp(1.5, 1.0, method="paper")


def test_bad_inputs():
    with pytest.raises(InputError, match="n must be >= 0"):
        greenwood_tripp(-1, 1.0)
    with pytest.raises(InputError, match="lam"):
        greenwood_tripp(2.5, float("nan"))
    with pytest.raises(InputError, match="method"):
        greenwood_tripp(2.5, 1.0, method="bogus")
    with pytest.raises(InputError, match="^rms must"):
        Roughness(asperity_density=1e10, rms=0.0, summit_radius=1e-6)


def test_asperity_pressure_and_area_formulae():
    # Table 4, uncoated: η = 8.3e9 m⁻², σ = 0.408 µm, β = 0.669 µm; E' = 230.77 GPa
    r = Roughness(asperity_density=8.3e9, rms=0.408e-6, summit_radius=0.669e-6)
    e = 210e9 / 0.91
    ebs = 8.3e9 * 0.669e-6 * 0.408e-6
    k = 8 * math.sqrt(2) / 15 * math.pi * ebs**2 * math.sqrt(0.408 / 0.669) * e
    h = 0.408e-6  # λ = 1
    assert r.asperity_pressure(h, e) == pytest.approx(k * 0.0805623, rel=1e-6)
    assert r.contact_area_fraction(h) == pytest.approx(math.pi**2 * ebs**2 * 0.0753398, rel=1e-6)
    # derivative
    d = 1e-12
    fd = (r.asperity_pressure(h + d, e) - r.asperity_pressure(h - d, e)) / (2 * d)
    assert asperity_pressure_derivative(r, h, e) == pytest.approx(fd, rel=1e-5)


def test_interpolation_table_used_by_the_solvers():
    from tribodyn.physics.asperity import greenwood_tripp_table

    lam = np.linspace(-15.0, 36.9, 20001)
    for n in (2.5, 2.0):
        f, df = greenwood_tripp_table(n, lam)
        assert np.max(np.abs(f / greenwood_tripp(n, lam) - 1)) < 1e-8
        assert np.max(np.abs(df / greenwood_tripp_derivative(n, lam) - 1)) < 1e-6
    f, df = greenwood_tripp_table(2.5, np.array([37.5, 1e3]))
    assert np.all(f == 0) and np.all(df == 0)
    # the EHL post-processing's contact-area fraction reads the F₂ table
    r = Roughness(asperity_density=8.3e9, rms=0.408e-6, summit_radius=0.669e-6)
    gap = np.linspace(-1.0, 6.0, 701) * r.rms
    direct = r.contact_area_fraction(gap)
    np.testing.assert_allclose(r.contact_area_fraction(gap, tabulated=True), direct, rtol=1e-8)

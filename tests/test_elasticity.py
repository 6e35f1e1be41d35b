"""Compliance FRFs, influence coefficients and the DC-FFT deformation operator."""

import math

import numpy as np
import pytest
from scipy import integrate, linalg

from tribodyn import Body, Coating, DeformationOperator, Material
from tribodyn.physics.elasticity import influence_coefficients

STEEL = Material(210e9, 0.3)


def half_plane_frf(m, material: Material) -> np.ndarray:
    """Surface FRF of a homogeneous half-plane (paper Eq. 12): g̃(m) = 2(1 − ν²)/(E m)
    [m/Pa per rad/m]."""
    return 2.0 * material.compliance / np.abs(m)


def coated_half_plane_frf(m, coating: Coating, substrate: Material) -> np.ndarray:
    """Surface FRF of a coated half-plane (paper Eqs. 13–14, Liu et al., Tribol. Lett. 18
    (2005) 505), written as printed: g̃ = (1 − ν_c)/(μ_c m)·[1 + 4mhκθ − λκθ²]/
    [1 − (λ + κ + 4κm²h²)θ + λκθ²], θ = e^{−2mh}."""
    m = np.abs(np.asarray(m, dtype=float))
    t = m * coating.thickness
    zeta = coating.shear_modulus / substrate.shear_modulus
    lam = 1.0 - 4.0 * (1.0 - coating.nu) / (1.0 + zeta * (3.0 - 4.0 * substrate.nu))
    kap = (zeta - 1.0) / (zeta + 3.0 - 4.0 * coating.nu)
    th = np.exp(-2.0 * t)
    num = 1.0 + 4.0 * t * kap * th - lam * kap * th**2
    den = 1.0 - (lam + kap + 4.0 * kap * t**2) * th + lam * kap * th**2
    return (1.0 - coating.nu) / (coating.shear_modulus * m) * num / den


def pair_frf(m, bodies) -> np.ndarray:
    """Total FRF of a body pair: the sum of the two bodies' surface FRFs."""
    return sum(
        half_plane_frf(m, b.material)
        if b.coating is None
        else coated_half_plane_frf(m, b.coating, b.material)
        for b in bodies
    )


def log_kernel_influence(dx: float, n: int) -> np.ndarray:
    """Element integrals of (1/π) ln|x|: L_k = (1/π)∫_{kΔ−Δ/2}^{kΔ+Δ/2} ln|s| ds, from the
    antiderivative s ln|s| − s."""
    edges = (np.arange(n + 1) - 0.5) * dx
    return np.diff(edges * np.log(np.abs(edges)) - edges) / math.pi


def dense_deformation(coefficients, p) -> np.ndarray:
    """Reference O(N²) deformation u = T p with the symmetric Toeplitz matrix T_ij = D_|i−j|."""
    return linalg.toeplitz(np.asarray(coefficients)) @ np.asarray(p, dtype=float)


def log_kernel_identity(X) -> np.ndarray:
    """Right-hand side of the log-kernel identity (P = √(1−X²), |X| ≤ 1):
    (1/π) ∫_{−1}^{1} ln|X − s| √(1 − s²) ds = X²/2 − (1/4 + ln 2 / 2)."""
    X = np.asarray(X, dtype=float)
    return 0.5 * X**2 - (0.25 + 0.5 * math.log(2.0))


def test_coated_frf_reduces_to_half_plane_for_identical_materials():
    m = np.logspace(-2, 8, 41)
    g = coated_half_plane_frf(m, Coating(210e9, 0.3, 4e-6), STEEL)
    assert np.allclose(g, 2 * (1 - 0.09) / (210e9 * m), rtol=1e-13)


@pytest.mark.parametrize("Ec, nuc", [(52.5e9, 0.25), (175e9, 0.3), (840e9, 0.2)])
def test_coated_frf_limits(Ec, nuc):
    h = 5e-6
    coat = Coating(Ec, nuc, h)
    # long waves see the substrate, short waves the coating
    g_lo = coated_half_plane_frf(1e-2 / h, coat, STEEL)
    g_hi = coated_half_plane_frf(1e3 / h, coat, STEEL)
    assert g_lo == pytest.approx(float(half_plane_frf(1e-2 / h, STEEL)), rel=2e-2)
    assert g_hi == pytest.approx(float(half_plane_frf(1e3 / h, Material(Ec, nuc))), rel=1e-6)
    # the regular remainder g − C_s/m is finite at m → 0 (no singularity)
    m = np.array([1e-7, 1e-6, 1e-5, 1e-4]) / h
    rem = coated_half_plane_frf(m, coat, STEEL) - half_plane_frf(m, STEEL)
    assert np.all(np.isfinite(rem)) and np.ptp(rem) < 1e-2 * abs(rem[0])


@pytest.mark.parametrize("coated", [False, True])
def test_dcfft_equals_dense_sum(coated, rng):
    bodies = (Body(STEEL), Body(STEEL, Coating(60e9, 0.25, 3e-6) if coated else None))
    n = 777
    op = DeformationOperator(bodies, 0.37e-6, n)
    p = rng.random(n) * 1e9
    u_fft, u_dense = op(p), dense_deformation(op.coefficients, p)
    assert np.max(np.abs(u_fft - u_dense)) < 1e-10 * np.max(np.abs(u_dense))
    # batched use
    P = rng.random((3, n))
    assert np.allclose(op(P)[1], dense_deformation(op.coefficients, P[1]), rtol=1e-10, atol=0)


def test_log_kernel_identity():
    # (1/π)∫ ln|X−s| √(1−s²) ds = X²/2 − (1/4 + ln2/2) for |X| ≤ 1
    n = 4001
    x = np.linspace(-1.0, 1.0, n)
    dx = x[1] - x[0]
    # element-averaged √(1−s²) (exact cell averages, so the test checks the kernel only)
    edges = np.clip(np.concatenate([x - dx / 2, [x[-1] + dx / 2]]), -1, 1)

    def prim(s):
        return 0.5 * (s * np.sqrt(1 - s * s) + np.arcsin(s))

    pav = np.diff(prim(edges)) / dx
    op = DeformationOperator.from_coefficients(log_kernel_influence(dx, n))
    lhs = op(pav)
    assert np.max(np.abs(lhs - log_kernel_identity(x))) < 1e-4


def _displacement_by_fourier_quadrature(bodies, x, s):
    """u(x) − u(0) for the Gaussian pressure exp(−x²/2s²) straight from the pair FRF."""

    def integrand(m, xx):
        return (
            pair_frf(m, bodies)
            * s
            * math.sqrt(2 * math.pi)
            * math.exp(-0.5 * (m * s) ** 2)
            * (math.cos(m * xx) - 1.0)
            / math.pi
        )

    out = []
    for xx in x:
        val = 0.0
        edges = [0.0, 0.1 / s, 1 / s, 3 / s, 6 / s, 12 / s]
        for a, b in zip(edges[:-1], edges[1:]):
            val += integrate.quad(integrand, a, b, args=(xx,), limit=400, epsabs=0, epsrel=1e-11)[0]
        out.append(val)
    return np.array(out)


@pytest.mark.parametrize(
    "Ec, nuc, h_over_s", [(52.5e9, 0.25, 0.3), (840e9, 0.2, 1.0), (175e9, 0.3, 3.0)]
)
def test_influence_coefficients_reproduce_the_frf(Ec, nuc, h_over_s):
    """Independent check of the kernel split (analytic log + analytic layer + tabulated Q₂)."""
    s = 10e-6
    bodies = (Body(STEEL), Body(STEEL, Coating(Ec, nuc, h_over_s * s)))
    n = 4001
    x = np.linspace(-12 * s, 12 * s, n)
    dx = x[1] - x[0]
    p = np.exp(-0.5 * (x / s) ** 2)
    u = DeformationOperator(bodies, dx, n)(p)
    i0 = n // 2
    probe = np.array([0.3, 1.0, 2.0, 4.0]) * s
    idx = i0 + np.round(probe / dx).astype(int)
    u_num = u[idx] - u[i0]
    u_ref = _displacement_by_fourier_quadrature(bodies, x[idx], s)
    assert np.allclose(u_num, u_ref, rtol=2e-4, atol=0)


def test_influence_coefficients_symmetric_pair_order():
    a = (Body(STEEL), Body(STEEL, Coating(100e9, 0.3, 2e-6)))
    b = (a[1], a[0])
    assert np.allclose(
        influence_coefficients(a, 1e-6, 64), influence_coefficients(b, 1e-6, 64), rtol=1e-14
    )

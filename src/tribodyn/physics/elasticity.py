"""Surface compliance of (coated) elastic half-planes and the DC-FFT deformation operator.

Frequency response functions (FRF) of the normal surface displacement to a normal
pressure, m = |ω| the angular wavenumber [rad/m], ``~`` the Fourier transform in x:

* homogeneous half-plane (paper Eq. 12, per body)::

      g̃(m) = C/m,   C = 2(1 − ν²)/E                  (two bodies: Σ = 4/(E'm))

* coated half-plane, coating (E_c, ν_c, thickness h) on substrate (E_s, ν_s)
  (paper Eqs. 13–14, after Liu, Peyronnel, Wang & Keer, Tribol. Lett. 18 (2005) 505)::

      g̃(m) = (1 − ν_c)/(μ_c m) · [1 + 4mhκθ − λκθ²] / [1 − (λ + κ + 4κm²h²)θ + λκθ²]
      θ = e^{−2mh},  λ = 1 − 4(1 − ν_c)/(1 + ζ(3 − 4ν_s)),
      κ = (ζ − 1)/(ζ + 3 − 4ν_c),  ζ = μ_c/μ_s = E_c(1 + ν_s)/(E_s(1 + ν_c))

  which reduces to 2(1 − ν²)/(E m) for coating = substrate.

Space-domain kernel without the m = 0 singularity (docs/conventions.md): write the coated FRF as
C_s/m + r(m) with the regular remainder r(m) = G(mh)/m, G(0) = 0 (finite r at m = 0),
G(∞) = C_c − C_s. Split G = (C_c − C_s)(1 − e^{−2t}) + G₂(t), t = mh. Then

* C_s/m (and the other steel body):  kernel −(C/π) ln|x|                    (analytic)
* (C_c − C_s)(1 − e^{−2mh})/m:       kernel (C_c − C_s)/(2π) ln(1 + 4h²/x²) (analytic)
* G₂(mh)/m, exponentially decaying:  antiderivative h Q₂(x/h) with
  Q₂(ξ) = (1/π) ∫₀^∞ G₂(t) sin(tξ)/t² dt, tabulated once per material pair (a universal
  function of x/h) by adaptive quadrature.

Influence coefficients of piecewise-constant pressure on elements of width Δ centred on a
uniform grid are differences of the kernel's antiderivative A(x):
D_k = A(kΔ + Δ/2) − A(kΔ − Δ/2), displacement u_i = Σ_j D_|i−j| p_j. The convolution is
evaluated by DC-FFT (Liu, Wang & Liu, Wear 243 (2000) 101): kernel zero-padded to 2N in
wrap-around order. The displacement in 2-D is defined up to a constant (here: lengths in
metres inside the logarithm); the rigid approach / h₀ absorbs it.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from scipy import integrate, interpolate

from .._validation import InputError, check_positive
from .materials import BodyPair, Material, as_bodies

__all__ = ["influence_coefficients", "DeformationOperator"]


# ------------------------------------------------------------- tabulated remainder Q₂
_XI_LO, _XI_HI, _PER_DECADE = 1e-4, 2e2, 40
_T_MAX = 40.0  # G₂ ~ t² e^{−2t}: negligible beyond t = 40


def _remainder_integrand(coating: Material, substrate: Material):
    """f(t) = [G(t) + g∞ expm1(−2t)]/t for scalar t > 0 (math-module floats: quadrature
    calls it ~10⁵ times per table), G(t) = m g̃_coated(m) − C_s at t = m h.

    G is evaluated without cancellation near t = 0: with θ = 1 + e₁ (e₁ = expm1(−2t)) the
    constant terms of numerator − (C_s/C_c)·denominator cancel identically; what remains
    is O(t) and computed to full relative precision."""
    zeta = coating.shear_modulus / substrate.shear_modulus
    lam = 1.0 - 4.0 * (1.0 - coating.nu) / (1.0 + zeta * (3.0 - 4.0 * substrate.nu))
    kap = (zeta - 1.0) / (zeta + 3.0 - 4.0 * coating.nu)
    cc, cs = 2.0 * coating.compliance, 2.0 * substrate.compliance
    r = cs / cc
    g_inf = 2.0 * (coating.compliance - substrate.compliance)
    const = (1.0 - lam * kap) - r * (1.0 - lam) * (1.0 - kap)
    a1, lk = (1.0 - lam) * (1.0 - kap), lam * kap

    def f(t):
        e1 = math.expm1(-2.0 * t)
        th = 1.0 + e1
        q = 2.0 * e1 + e1 * e1
        den = a1 - (lam + kap) * e1 - 4.0 * kap * t * t * th + lk * q
        num = (
            const
            + 4.0 * t * kap * th
            - lk * q
            - r * (-(lam + kap) * e1 - 4.0 * kap * t * t * th + lk * q)
        )
        return (cc * num / den + g_inf * e1) / t

    return f


class _RemainderTable:
    """Q₂(ξ) = (1/π)∫₀^∞ G₂(t) sin(tξ)/t² dt for one coating/substrate pair.

    With f(t) = G₂(t)/t (smooth, f(0) = G₂'(0)): tabulated by adaptive quadrature for
    1e-4 ≤ ξ ≤ 200; Q₂ ≈ s ξ below; above, the asymptotic series of a Fourier sine
    integral of a smooth function, Q₂ ≈ f(0)/2 + c₁/ξ + c₃/ξ³, with c₁, c₃ matched to
    the table's top end.
    """

    def __init__(self, coating: Material, substrate: Material):
        g_inf = 2.0 * (coating.compliance - substrate.compliance)
        f = _remainder_integrand(coating, substrate)

        self.q_inf = 0.5 * float(f(1e-8))  # Q₂(ξ → ∞) = f(0)/2
        xi = np.logspace(
            np.log10(_XI_LO),
            np.log10(_XI_HI),
            int(round(_PER_DECADE * np.log10(_XI_HI / _XI_LO))) + 1,
        )
        vals = np.empty_like(xi)
        for i, x in enumerate(xi):
            # ∫₀^T f(t) sin(xt)/t dt; first piece (one half-period) has a regular integrand.
            ta = min(_T_MAX, math.pi / x)
            # quad samples inside (0, ta): sin(xt)/t needs no t = 0 limit
            a, _ = integrate.quad(
                lambda t: f(t) * math.sin(x * t) / t, 0.0, ta, limit=200, epsabs=0.0, epsrel=1e-12
            )
            b = 0.0
            if ta < _T_MAX:
                b, _ = integrate.quad(
                    lambda t: f(t) / t,
                    ta,
                    _T_MAX,
                    weight="sin",
                    wvar=x,
                    limit=500,
                    epsabs=1e-14 * abs(g_inf) + 1e-30,
                    epsrel=1e-11,
                )
            vals[i] = (a + b) / math.pi
        # Interpolate the bounded, smooth Q₂(ξ)(1 + ξ)/ξ (→ s at 0, → Q∞ at ∞) in ln ξ.
        self.spline = interpolate.CubicSpline(np.log(xi), vals * (1.0 + xi) / xi)
        self.lo_slope = vals[0] / xi[0]
        # Match Q∞ + c₁/ξ + c₃/ξ³ at the two top table points.
        x1, x2 = xi[-1], xi[-1 - _PER_DECADE // 4]
        rhs = np.array([vals[-1] - self.q_inf, vals[-1 - _PER_DECADE // 4] - self.q_inf])
        mat = np.array([[1.0 / x1, x1**-3], [1.0 / x2, x2**-3]])
        self.c1, self.c3 = np.linalg.solve(mat, rhs)

    def __call__(self, xi) -> np.ndarray:
        xi = np.asarray(xi, dtype=float)
        s = np.sign(xi)
        a = np.abs(xi)
        out = np.empty_like(a)
        lo = a < _XI_LO
        hi = a > _XI_HI
        mid = ~(lo | hi)
        out[lo] = self.lo_slope * a[lo]
        out[hi] = self.q_inf + self.c1 / a[hi] + self.c3 / a[hi] ** 3
        am = a[mid]
        out[mid] = self.spline(np.log(am)) * am / (1.0 + am)
        return s * out


@lru_cache(maxsize=64)
def _remainder_table(Ec, nuc, Es, nus) -> _RemainderTable:
    return _RemainderTable(Material(Ec, nuc), Material(Es, nus))


# -------------------------------------------------------------- influence coefficients
def _xlogx_minus_x(x):
    a = np.abs(x)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = np.where(a > 0.0, x * np.log(np.where(a > 0.0, a, 1.0)) - x, 0.0)
    return out


def _q1(xi):
    """(1/(2))[ξ ln(1 + 4/ξ²) + 4 atan(ξ/2)]·(1/π) without the (C_c − C_s) factor."""
    xi = np.asarray(xi, dtype=float)
    a = np.abs(xi)
    with np.errstate(divide="ignore", invalid="ignore"):
        lg = np.where(
            a > 0.0, xi * (np.log(xi * xi + 4.0) - 2.0 * np.log(np.where(a > 0, a, 1.0))), 0.0
        )
    return (lg + 4.0 * np.arctan(0.5 * xi)) / (2.0 * math.pi)


def _antiderivative(x, bodies) -> np.ndarray:
    """A(x) = ∫₀^x K(s) ds of the pair's surface-displacement kernel K [m/Pa·m]."""
    c_log = 0.0
    out = np.zeros_like(np.asarray(x, dtype=float))
    for b in bodies:
        c_log += 2.0 * b.material.compliance
        if b.coating is not None:
            c, s, h = b.coating, b.material, b.coating.thickness
            xi = x / h
            g_inf = 2.0 * (c.compliance - s.compliance)
            out = out + h * g_inf * _q1(xi)
            out = out + h * _remainder_table(c.E, c.nu, s.E, s.nu)(xi)
    return out - (c_log / math.pi) * _xlogx_minus_x(x)


def influence_coefficients(bodies, dx: float, n: int) -> np.ndarray:
    """Influence coefficients D_k, k = 0…n−1 [m/Pa] of a body pair.

    Displacement at node i from unit pressure on the element of width ``dx`` centred
    on node j is D_|i−j|; the sum of both bodies' normal displacements (positive =
    surfaces move apart).
    """
    bodies = as_bodies(bodies)
    dx = check_positive("dx", dx, "m")
    if int(n) < 1:
        raise InputError(f"n must be >= 1 (got {n})")
    edges = (np.arange(int(n) + 1) - 0.5) * dx
    a = _antiderivative(edges, bodies)
    return np.diff(a)


class DeformationOperator:
    """O(N log N) surface deformation of a body pair on a uniform grid (DC-FFT).

    Parameters
    ----------
    bodies : pair of :class:`Body` (either or both may be coated).
    dx : grid spacing [m].
    n : number of nodes.

    ``op(p)`` returns the total normal displacement [m] at the nodes for nodal pressures
    ``p`` [Pa] (last axis of length n; leading axes are batched).
    """

    def __init__(self, bodies: BodyPair, dx: float, n: int):
        self._use(influence_coefficients(bodies, dx, n))

    @classmethod
    def from_coefficients(cls, coefficients) -> DeformationOperator:
        """The operator of given influence coefficients D_k (k = 0…n−1)."""
        obj = cls.__new__(cls)
        obj._use(np.asarray(coefficients, dtype=float))
        return obj

    def _use(self, c: np.ndarray) -> None:
        """Keep the coefficients and the spectrum of their wrap-around kernel (2n long)."""
        n = self.n = c.size
        self.coefficients = c
        k = np.zeros(2 * n)
        k[:n] = c
        k[n + 1 :] = c[:0:-1]
        self._kernel_hat = np.fft.rfft(k)

    def __call__(self, p) -> np.ndarray:
        p = np.asarray(p, dtype=float)
        if p.shape[-1] != self.n:
            raise InputError(f"pressure must have {self.n} nodes on its last axis (got {p.shape})")
        ph = np.fft.rfft(p, 2 * self.n, axis=-1)
        return np.fft.irfft(ph * self._kernel_hat, 2 * self.n, axis=-1)[..., : self.n]

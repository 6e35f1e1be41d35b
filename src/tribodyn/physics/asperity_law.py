"""Tabulated asperity load–separation law: the asperity pressure and real-contact area of
a surface pair as functions of λ = h/σ, from a deterministic contact calculation of a
measured or synthetic surface (:mod:`tribodyn.physics.rough_contact`).

It plugs into :class:`~tribodyn.Roughness` (``law=``) in place of Greenwood–Tripp's
F_5/2 and F_2: the solvers read p_a = E' Φ(h/σ) and A_a/A = α(h/σ) through
:meth:`Roughness.load_function` and :meth:`Roughness.contact_area_fraction`, one code path
for both models. E' is the paper's reduced modulus (E' = 2E*).

Interpolation: monotone cubic (PCHIP) in ln Φ and ln α between the computed points,
evaluated by the compiled :func:`log_curve_at` (the EHL solver reads Φ's curve,
:attr:`LoadSeparationLaw.pressure_curve`, node by node).
Beyond the largest computed separation ln Φ continues linearly (p_a ∝ exp(−h/h₀), the
exponential tail Persson's theory gives for randomly rough surfaces: Persson, PRL 99
(2007) 125502); below the smallest, ln Φ continues linearly up to the cap Φ ≤ H/E' (every
point flowing at the hardness H) and α ≤ 1.

Scaling with the modulus: p_a = E' Φ is exact for elastic contact; with plastic flow the
cap H scales with E' as well, so the table should be computed at the surface pair's own
E' and H (the case builder does).
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit
from scipy.interpolate import PchipInterpolator

from .._validation import InputError

__all__ = ["LoadSeparationLaw", "log_curve_at"]


@njit(cache=True, nogil=True)
def _piecewise_at(x, c, t):
    """A piecewise polynomial (breakpoints x, coefficients c[k, i] of (t − x_i)^(K−1−k)
    on interval i, as scipy's PPoly) at t; NaN outside [x₀, x_last]."""
    m = x.size
    if not x[0] <= t <= x[m - 1]:
        return np.nan
    i = min(np.searchsorted(x, t, side="right") - 1, m - 2)
    s = t - x[i]
    k = c.shape[0]
    res, z = 0.0, 1.0
    for kp in range(k):
        res += c[k - 1 - kp, i] * z
        z *= s
    return res


@njit(cache=True, nogil=True)
def log_curve_at(lam, curve):
    """(y, dy/dλ) of a :class:`_LogCurve` at one λ from its ``params``: ln y by the
    PCHIP interpolant inside the computed points, linear outside, capped at ln y_max
    (slope 0 there); y = exp(max(ln y, −745)). NaN for NaN."""
    x, c, dc, lo, hi, y_lo, y_hi, s_lo, s_hi, ln_max = curve
    if lam < lo:
        val, der = y_lo + s_lo * (lam - lo), s_lo
    elif lam > hi:
        val, der = y_hi + s_hi * (lam - hi), s_hi
    else:
        val, der = _piecewise_at(x, c, lam), _piecewise_at(x, dc, lam)
    if val >= ln_max:
        val, der = ln_max, 0.0
    y = math.exp(val if val >= -745.0 or val != val else -745.0)
    return y, y * der


@njit(cache=True, nogil=True)
def _log_curve(lam, curve):
    """:func:`log_curve_at` at every entry of the 1-D array ``lam``."""
    y = np.empty(lam.size)
    dy = np.empty(lam.size)
    for i in range(lam.size):
        y[i], dy[i] = log_curve_at(lam[i], curve)
    return y, dy


class _LogCurve:
    """ln y(λ) by PCHIP through positive points, linear outside, capped at ln y_max.
    ``params``: the curve as :func:`log_curve_at` reads it."""

    def __init__(self, lam: np.ndarray, y: np.ndarray, y_max: float):
        keep = y > 0.0
        lam, y = lam[keep], y[keep]
        if lam.size < 3:
            raise InputError(
                "the load–separation law needs at least 3 separations with contact "
                f"(got {lam.size}): compute it over a wider range of h/σ"
            )
        ly = np.log(y)
        self.spline = PchipInterpolator(lam, ly, extrapolate=False)
        self.dspline = self.spline.derivative()
        self.lo, self.hi = float(lam[0]), float(lam[-1])
        self.y_lo, self.y_hi = float(ly[0]), float(ly[-1])
        self.s_lo = float((ly[1] - ly[0]) / (lam[1] - lam[0]))
        self.s_hi = min(float((ly[-1] - ly[-2]) / (lam[-1] - lam[-2])), -1e-3)
        self.ln_max = math.log(y_max)
        self.params = (
            np.ascontiguousarray(self.spline.x, dtype=float),
            np.ascontiguousarray(self.spline.c, dtype=float),
            np.ascontiguousarray(self.dspline.c, dtype=float),
            self.lo,
            self.hi,
            self.y_lo,
            self.y_hi,
            self.s_lo,
            self.s_hi,
            self.ln_max,
        )

    def __call__(self, lam):
        lam = np.asarray(lam, dtype=float)
        y, dy = _log_curve(np.ascontiguousarray(lam).reshape(-1), self.params)
        if not lam.ndim:  # a number gives numbers
            return y[0], dy[0]
        return y.reshape(lam.shape), dy.reshape(lam.shape)


class LoadSeparationLaw:
    """Asperity pressure and area against λ = h/σ of one surface pair.

    Parameters
    ----------
    lam : increasing λ = ū/σ of the computed points (ū: mean-plane separation).
    pressure : mean asperity pressure p̄ [Pa] at those points.
    area_fraction : real-contact area A/A₀ at those points.
    reduced_modulus : E' [Pa] (paper convention, E' = 2E*) the points were computed at.
    hardness : H [Pa] of the pressure cap (``inf``: elastic).
    source : what the law was computed from (for reports).
    """

    def __init__(
        self,
        lam,
        pressure,
        area_fraction,
        reduced_modulus: float,
        hardness: float = math.inf,
        source: str = "",
    ):
        lam = np.asarray(lam, dtype=float)
        p = np.asarray(pressure, dtype=float)
        a = np.asarray(area_fraction, dtype=float)
        if not (lam.ndim == 1 and lam.shape == p.shape == a.shape) or lam.size < 3:
            raise InputError("lam, pressure and area_fraction must be 1-D of equal length ≥ 3")
        if not np.all(np.isfinite(lam)) or np.any(np.diff(lam) <= 0.0):
            raise InputError("lam must be finite and strictly increasing")
        if np.any(~np.isfinite(p)) or np.any(p < 0.0) or np.any(a < 0.0) or np.any(a > 1.0):
            raise InputError("pressure must be ≥ 0 and area_fraction within [0, 1]")
        if not reduced_modulus > 0.0:
            raise InputError(f"reduced_modulus must be > 0 Pa (got {reduced_modulus!r})")
        self.lam, self.pressure, self.area = lam, p, a
        self.reduced_modulus = float(reduced_modulus)
        self.hardness = float(hardness)
        self.source = source
        phi_max = self.hardness / self.reduced_modulus if math.isfinite(hardness) else 1e6
        self._phi = _LogCurve(lam, p / self.reduced_modulus, phi_max)
        self._area = _LogCurve(lam, a, 1.0)

    def __repr__(self) -> str:
        return (
            f"LoadSeparationLaw({self.lam.size} points, λ {self.lam[0]:.3g}–{self.lam[-1]:.3g},"
            f" E' {self.reduced_modulus:.4g} Pa, H {self.hardness:.4g} Pa, {self.source!r})"
        )

    def pressure_ratio(self, lam):
        """(Φ, dΦ/dλ) with p_a = E' Φ(λ)."""
        return self._phi(lam)

    @property
    def pressure_curve(self) -> tuple:
        """Φ(λ) as the compiled :func:`log_curve_at` reads it."""
        return self._phi.params

    def area_fraction(self, lam):
        """A_a/A at λ."""
        return self._area(lam)[0]

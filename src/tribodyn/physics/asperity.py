"""Greenwood–Tripp asperity contact of two rough surfaces.

Statistical functions of a Gaussian summit-height distribution (Greenwood & Tripp 1970)::

    F_n(λ) = (1/√(2π)) ∫_λ^∞ (s − λ)^n exp(−s²/2) ds
           = Γ(n+1) exp(−λ²/4) D_{−n−1}(λ) / √(2π)          (D: parabolic cylinder fn.)
    dF_n/dλ = −n F_{n−1}(λ)                                  (n ≥ 1)

For λ < −12 the Gaussian-moment series E[(s − λ)^n] in powers of 1/λ² is used (the
parabolic-cylinder product overflows there); it agrees with the integral to < 1e-12.

Local asperity pressure and real-area fraction at a gap h (paper Eqs. 6 and 18, applied
pointwise; E' = reduced modulus of the surface materials, 1/E' = ½Σ(1−ν²)/E)::

    p_a(h) = (8√2/15) π (ηβσ)² √(σ/β) E' F_{5/2}(h/σ)        [Pa]
    A_a/A  = π² (ηβσ)² F_2(h/σ)                               [-]

The paper's polynomial fits (Eqs. 7 and 19) are available with ``method="paper"`` for
reproduction only: its F_2 fit is negative beyond λ ≈ 1.90 and its F_{5/2} fit is 59 %
off at λ = 2.5; both are clipped at zero here.
"""

from __future__ import annotations

import copy
import functools
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numba import njit
from scipy import special

from .._typing import ArrayLike
from .._validation import InputError, check_choice, short_repr
from .limits import (
    ASPERITY_DENSITY,
    GREENWOOD_TRIPP_ORDER,
    ROUGHNESS_RMS,
    SUMMIT_RADIUS,
    check_fields,
)

__all__ = [
    "greenwood_tripp",
    "greenwood_tripp_derivative",
    "greenwood_tripp_table",
    "greenwood_tripp_tabulated",
    "Roughness",
]

_SQRT_2PI = math.sqrt(2.0 * math.pi)

# Paper Eq. 7 (F_5/2, λ ≤ 2.5) and Eq. 19 (F_2, λ ≤ 3); highest power first.
_PAPER_F52 = (0.000421, -0.008538, 0.07162, -0.3193, 0.802, -1.082, 0.6166)
_PAPER_F2 = (-0.002, 0.028, -0.173, 0.526, -0.804, 0.5)
#: The paper's fits by order n: (coefficients, λ above which the fit is 0).
_PAPER_FITS = {2.5: (_PAPER_F52, 2.5), 2.0: (_PAPER_F2, 3.0)}


_LAM_NEG = -12.0  # below: asymptotic series (exp(−λ²/4)·D_{−n−1}(λ) is 0·∞ for λ ≲ −38)
_LAM_POS = 37.0  # above: F_n < φ(λ)/λ ≈ 1e-300, i.e. 0 in double precision


@njit(cache=True, nogil=True)
def _series_at(n, lam):
    """F_n(λ) for λ ≪ 0: E[(s + |λ|)^n] = |λ|^n Σ_k C(n, 2k) (2k−1)!! |λ|^(−2k)
    (Gaussian moments; the part of the integral below s = λ is < φ(λ) ~ e^(−72))."""
    a = abs(lam)
    total = 1.0
    coef, dfact = 1.0, 1.0
    for k in range(1, 12):
        coef *= (n - 2 * k + 2) * (n - 2 * k + 1) / ((2 * k - 1) * (2 * k))
        dfact *= 2 * k - 1
        total = total + coef * dfact * a ** (-2.0 * k)
    return a**n * total


@njit(cache=True, nogil=True)
def _negative_series(n, lam):
    """:func:`_series_at` at every entry of the 1-D array ``lam``."""
    out = np.empty(lam.size)
    for i in range(lam.size):
        out[i] = _series_at(n, lam[i])
    return out


def _exact(n: float, lam: np.ndarray) -> np.ndarray:
    if n == 0.0:
        return 0.5 * special.erfc(lam / math.sqrt(2.0))
    lam = np.asarray(lam, dtype=float)
    neg = lam < _LAM_NEG
    mid = ~neg & (lam <= _LAM_POS)
    out = np.zeros_like(lam)  # λ > 37: F_n underflows to 0
    lm = lam[mid]
    d, _ = special.pbdv(-n - 1.0, lm)
    out[mid] = math.gamma(n + 1.0) * np.exp(-0.25 * lm * lm) * d / _SQRT_2PI
    if np.any(neg):  # the series only where it applies (it is singular at λ = 0)
        out[neg] = _negative_series(float(n), lam[neg])
    return out


def _lambda_array(lam) -> np.ndarray:
    """λ as a float array: real numbers only (no strings, bools, NaN or ±inf)."""
    try:
        a = np.asarray(lam)
    except (TypeError, ValueError):
        a = np.asarray([None])
    if a.dtype.kind not in "iuf" or a.size == 0:
        raise InputError(
            f"lam must be a real number or an array of real numbers (got {short_repr(lam)})"
        )
    try:
        a = a.astype(float)
    except OverflowError:
        a = np.asarray([np.inf])
    if not np.all(np.isfinite(a)):
        raise InputError("lam must be finite (found NaN or inf)")
    return a


def greenwood_tripp(n: float, lam: ArrayLike, method: str = "exact") -> np.ndarray | float:
    """Greenwood–Tripp statistical function F_n(λ) (dimensionless).

    Parameters
    ----------
    n : order, 0 ≤ n ≤ 10 (2 and 5/2 are the ones used for area and load).
    lam : λ = h/σ, finite real scalar or array. The exact form is finite for all real λ.
    method : ``"exact"`` (default) or ``"paper"`` (Eqs. 7/19, n ∈ {2, 2.5} only,
        clipped at 0; inaccurate, for reproducing the paper).
    """
    n = GREENWOOD_TRIPP_ORDER.check("n", n)
    lam_arr = _lambda_array(lam)
    check_choice("method", method, ("exact", "paper"))
    if method == "exact":
        out = _exact(n, lam_arr)
    elif n not in _PAPER_FITS:
        raise InputError(f"method='paper' has fits for n = 2 and 2.5 only (got n = {n:g})")
    else:
        coeffs, lam_max = _PAPER_FITS[n]
        out = np.where(lam_arr <= lam_max, np.polyval(coeffs, lam_arr), 0.0)
        out = np.maximum(out, 0.0)
    return out if out.ndim else float(out)


def greenwood_tripp_derivative(n, lam, method: str = "exact"):
    """dF_n/dλ: −n F_{n−1}(λ) exactly; derivative of the clipped fit for ``"paper"``."""
    n = GREENWOOD_TRIPP_ORDER.check("n", n)
    lam_arr = _lambda_array(lam)
    check_choice("method", method, ("exact", "paper"))
    if method == "paper" and n not in _PAPER_FITS:
        raise InputError(f"method='paper' has fits for n = 2 and 2.5 only (got n = {n:g})")
    if method == "exact":
        if n == 0.0:
            out = -np.exp(-0.5 * lam_arr**2) / _SQRT_2PI
        elif n < 1.0:
            raise InputError("the exact derivative needs n = 0 or n >= 1")
        else:
            out = -n * _exact(n - 1.0, lam_arr)
    else:  # "paper"
        coeffs, lam_max = _PAPER_FITS[n]
        val = np.polyval(coeffs, lam_arr)
        out = np.where(
            (lam_arr <= lam_max) & (val > 0.0), np.polyval(np.polyder(coeffs), lam_arr), 0.0
        )
    return out if out.ndim else float(out)


class _LogTable:
    """Fast F_n(λ) and dF_n/dλ for the solvers: cubic Hermite interpolation of ln F_n on
    −12 ≤ λ ≤ 37 (step 0.002) with the exact slope d ln F_n/dλ = −n F_{n−1}/F_n; the
    exact asymptotic series below, 0 above. Relative error < 1e-8 in F_n and < 1e-6 in
    dF_n/dλ, limited by scipy's parabolic-cylinder function (checked in tests).
    ``params`` = (ln F_n at the nodes, their slopes · step, first λ, step, n): the table
    as :func:`greenwood_tripp_tabulated` reads it."""

    def __init__(self, n: float):
        self.n = n
        lam = np.linspace(_LAM_NEG, _LAM_POS, int(round((_LAM_POS - _LAM_NEG) / 0.002)) + 1)
        f = _exact(n, lam)
        if n < 1.0:
            raise ValueError(f"the tabulated F_n needs n >= 1 (got n = {n:g})")
        slope = -n * _exact(n - 1.0, lam) / f
        self.params = (
            np.log(f),
            slope * float(lam[1] - lam[0]),
            float(lam[0]),
            float(lam[1] - lam[0]),
            float(n),
        )

    def __call__(self, lam):
        lam = np.asarray(lam, dtype=float)
        f, df = _tabulated(np.ascontiguousarray(lam).reshape(-1), self.params)
        if not lam.ndim:  # a number gives numbers
            return f[0], df[0]
        return f.reshape(lam.shape), df.reshape(lam.shape)

    def values(self, lam) -> np.ndarray:
        """F_n(λ) alone (the same numbers as :meth:`__call__`'s first) on an array."""
        lam = np.asarray(lam, dtype=float)
        return _tabulated_values(np.ascontiguousarray(lam).reshape(-1), self.params).reshape(
            lam.shape
        )


@njit(cache=True, nogil=True)
def _hermite_at(lm, y, dy, lam0, step):
    """Cubic Hermite interpolant on a uniform grid (values y, slopes·step dy) and its
    derivative at λ = ``lm``: ln F = y₀ + d₀t + bt² + at³, a = 2(y₀ − y₁) + d₀ + d₁,
    b = 3(y₁ − y₀) − 2d₀ − d₁, t ∈ [0, 1] within the interval; NaN outside the table."""
    top = y.size - 2
    u = (lm - lam0) / step
    if not 0.0 <= u <= top + 1.0:  # outside the table (callers keep λ inside)
        return np.nan, np.nan
    k = min(int(u), top)
    t = u - k
    y0, y1, d0, d1 = y[k], y[k + 1], dy[k], dy[k + 1]
    a = 2.0 * (y0 - y1) + d0 + d1
    b = 3.0 * (y1 - y0) - 2.0 * d0 - d1
    return y0 + t * (d0 + t * (b + t * a)), (d0 + t * (2.0 * b + 3.0 * a * t)) / step


@njit(cache=True, nogil=True)
def greenwood_tripp_tabulated(lam, table):
    """(F_n(λ), dF_n/dλ) at one λ from a table's ``params`` (:class:`_LogTable`): the
    Hermite interpolant of ln F_n on −12 ≤ λ ≤ 37, the asymptotic series below
    (dF_n/dλ = −n F_{n−1}), 0 above (and for NaN)."""
    y, dy, lam0, step, n = table
    if lam < _LAM_NEG:
        return _series_at(n, lam), -n * _series_at(n - 1.0, lam)
    if lam <= _LAM_POS:
        val, der = _hermite_at(lam, y, dy, lam0, step)
        f = math.exp(val)
        return f, f * der
    return 0.0, 0.0


@njit(cache=True, nogil=True)
def _tabulated(lam, table):
    """:func:`greenwood_tripp_tabulated` at every entry of the 1-D array ``lam``."""
    f = np.empty(lam.size)
    df = np.empty(lam.size)
    for i in range(lam.size):
        f[i], df[i] = greenwood_tripp_tabulated(lam[i], table)
    return f, df


@njit(cache=True, nogil=True)
def _tabulated_values(lam, table):
    """The F_n of :func:`greenwood_tripp_tabulated` at every entry of the 1-D array
    ``lam`` (its derivative is not formed)."""
    f = np.empty(lam.size)
    for i in range(lam.size):
        f[i] = greenwood_tripp_tabulated(lam[i], table)[0]
    return f


@functools.cache
def _table(n: float) -> _LogTable:
    return _LogTable(float(n))


def greenwood_tripp_table(n: float, lam):
    """(F_n(λ), dF_n/dλ) from a cached interpolation table (n ≥ 1); for solvers."""
    return _table(n)(lam)


@dataclass(frozen=True)
class Roughness:
    """Composite Greenwood–Tripp roughness of a surface pair (paper Table 4).

    Parameters
    ----------
    asperity_density : η, summit density per unit area [1/m²] (the paper's "ζ"), ≤ 1e18.
    rms : σ, composite RMS roughness of the pair [m], < 1e-4.
    summit_radius : β, mean summit radius of curvature [m], < 1e-2.
    method : "exact" F_n (default) or the paper's polynomial fits ("paper").
    law : a :class:`~tribodyn.physics.asperity_law.LoadSeparationLaw` (the load and area
        against h/σ of a measured surface) that replaces Greenwood–Tripp's F_5/2 and F_2;
        None (default): Greenwood–Tripp. η and β then only describe the summits (used by
        the Greenwood–Tripp comparisons); σ must be the RMS the law was computed with.
    """

    asperity_density: float
    rms: float
    summit_radius: float
    method: str = "exact"
    law: Any = None

    def __post_init__(self):
        check_fields(  # the case file's roughness is checked here (physics.limits)
            self,
            {
                "asperity_density": ASPERITY_DENSITY,
                "rms": ROUGHNESS_RMS,
                "summit_radius": SUMMIT_RADIUS,
            },
        )
        check_choice("method", self.method, ("exact", "paper"))
        self._check_law()

    def _check_law(self) -> None:
        if self.law is not None and not hasattr(self.law, "pressure_ratio"):
            raise InputError(
                f"law must be a LoadSeparationLaw or None (got {type(self.law).__name__})"
            )

    def with_law(self, law, rms: float | None = None) -> Roughness:
        """This roughness with the load–separation ``law`` (and the σ ``rms`` [m] of the
        map it was computed from); only these are checked again."""
        new = copy.copy(self)
        object.__setattr__(new, "law", law)
        if rms is not None:
            object.__setattr__(new, "rms", rms)
        check_fields(new, {"rms": ROUGHNESS_RMS} if rms is not None else {})
        new._check_law()
        return new

    @property
    def asperity_model(self) -> str:
        """``"greenwood_tripp"`` or ``"measured"`` (a tabulated load–separation law)."""
        return "greenwood_tripp" if self.law is None else "measured"

    def load_function(self, lam) -> tuple[np.ndarray, np.ndarray]:
        """(F(λ), dF/dλ) with p_a = :meth:`pressure_scale` · F(h/σ): F_5/2 (solvers'
        table for ``"exact"``) or the law's Φ = p_a/E'."""
        lam = np.asarray(lam, dtype=float)
        if self.law is not None:
            return self.law.pressure_ratio(lam)
        if self.method == "exact":
            return greenwood_tripp_table(2.5, lam)
        return (
            np.asarray(greenwood_tripp(2.5, lam, self.method), float),
            np.asarray(greenwood_tripp_derivative(2.5, lam, self.method), float),
        )

    def load_table(self) -> tuple | None:
        """The table of :meth:`load_function` for compiled solvers: the ``params`` of the
        F_5/2 table (:func:`greenwood_tripp_tabulated`) for the exact Greenwood–Tripp
        model, None for a load–separation law or the paper's fits."""
        if self.law is not None or self.method != "exact":
            return None
        return _table(2.5).params

    @property
    def implied_rms_slope(self) -> float:
        """RMS profile slope √m₂ that η, β and σ imply for an isotropic Gaussian surface
        by Nayak's and McCool's relations (McCool, Wear 107 (1986) 37: η = m₄/(6π√3 m₂),
        β = (3/8)√(π/m₄), σ = √m₀), eliminating m₄: m₂ = 3 (σ/β)/(128 √3 ηβσ)."""
        return math.sqrt(
            3.0
            * (self.rms / self.summit_radius)
            / (128.0 * math.sqrt(3.0) * self.roughness_parameter)
        )

    @property
    def roughness_parameter(self) -> float:
        """ηβσ, the dimensionless roughness parameter."""
        return self.asperity_density * self.summit_radius * self.rms

    def pressure_scale(self, reduced_modulus: float) -> float:
        """K = (8√2/15) π (ηβσ)² √(σ/β) E'  [Pa], so that p_a = K F_{5/2}(h/σ);
        K = E' with a load–separation law (p_a = E' Φ(h/σ))."""
        if self.law is not None:
            return float(reduced_modulus)
        return (
            8.0
            * math.sqrt(2.0)
            / 15.0
            * math.pi
            * self.roughness_parameter**2
            * math.sqrt(self.rms / self.summit_radius)
            * reduced_modulus
        )

    def asperity_pressure(self, gap: ArrayLike, reduced_modulus: float) -> np.ndarray | float:
        """Local asperity pressure p_a(h) [Pa] at gap h [m] (Eq. 6 per unit area)."""
        lam = np.asarray(gap, dtype=float) / self.rms
        if self.law is not None:
            out = reduced_modulus * self.law.pressure_ratio(lam)[0]
            return out if out.ndim else float(out)
        return self.pressure_scale(reduced_modulus) * greenwood_tripp(2.5, lam, self.method)

    def contact_area_fraction(self, gap: ArrayLike, tabulated: bool = False) -> np.ndarray | float:
        """Real-contact-area fraction A_a/A = π²(ηβσ)² F₂(h/σ) (Eq. 18 per unit area), or
        the law's A/A₀(h/σ).

        ``tabulated``: the exact F₂ read from the solvers' interpolation table (relative
        error < 1e-8, several times faster on arrays); the paper's polynomial is direct."""
        lam = np.asarray(gap, dtype=float) / self.rms
        if self.law is not None:
            out = self.law.area_fraction(lam)
            return out if out.ndim else float(out)
        f2: np.ndarray | float
        if tabulated and self.method == "exact":
            f2 = _table(2.0).values(lam)
        else:
            f2 = greenwood_tripp(2.0, lam, self.method)
        return math.pi**2 * self.roughness_parameter**2 * f2

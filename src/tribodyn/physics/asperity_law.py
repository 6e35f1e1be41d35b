"""Tabulated asperity load–separation law: the asperity pressure and real-contact area of
a surface pair as functions of λ = h/σ, from a deterministic contact calculation of a
measured or synthetic surface (:mod:`tribodyn.physics.rough_contact`).

It plugs into :class:`~tribodyn.Roughness` (``law=``) in place of Greenwood–Tripp's
F_5/2 and F_2: the solvers read p_a = E' Φ(h/σ) and A_a/A = α(h/σ) through
:meth:`Roughness.load_function` and :meth:`Roughness.contact_area_fraction`, one code path
for both models. E' is the paper's reduced modulus (E' = 2E*).

Interpolation: monotone cubic (PCHIP) in ln Φ and ln α between the computed points.
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
from scipy.interpolate import PchipInterpolator

from .._validation import InputError

__all__ = ["LoadSeparationLaw"]


class _LogCurve:
    """ln y(λ) by PCHIP through positive points, linear outside, capped at ln y_max."""

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

    def __call__(self, lam):
        lam = np.asarray(lam, dtype=float)
        val = np.empty_like(lam)
        der = np.empty_like(lam)
        lo, hi = lam < self.lo, lam > self.hi
        mid = ~lo & ~hi
        val[mid] = self.spline(lam[mid])
        der[mid] = self.dspline(lam[mid])
        val[lo] = self.y_lo + self.s_lo * (lam[lo] - self.lo)
        der[lo] = self.s_lo
        val[hi] = self.y_hi + self.s_hi * (lam[hi] - self.hi)
        der[hi] = self.s_hi
        cap = val >= self.ln_max
        val = np.where(cap, self.ln_max, val)
        der = np.where(cap, 0.0, der)
        y = np.exp(np.maximum(val, -745.0))
        return y, y * der


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

    def area_fraction(self, lam):
        """A_a/A at λ."""
        return self._area(lam)[0]

"""Lubricant rheology: Roelands piezo-viscosity and Dowson–Higginson density.

Roelands (paper Eq. 3)::

    μ(p) = μ₀ exp{(ln μ₀ + 9.67) [−1 + (1 + 5.1e-9 p)^Z]},
    Z    = α / (5.1e-9 (ln μ₀ + 9.67))            (μ₀ in Pa·s, p in Pa)

so that d ln μ/dp = α at p = 0. Dowson–Higginson (Eq. 2), p in GPa::

    ρ(p)/ρ₀ = 1 + 0.6 p / (1 + 1.7 p)

Barus, μ = μ₀ exp(αp), is available (``viscosity_model="barus"``) for comparison with
classical solutions (Moes, rigid-piezoviscous asymptotes), as is an incompressible
lubricant (``compressible=False``).

Negative (sub-ambient) pressures do not occur in the cavitation model; both laws are
evaluated at max(p, 0) so they stay finite and monotone for any input.

The laws are written once, as compiled elementwise functions of one pressure
(:func:`density_terms`, :func:`viscosity_terms`) with the lubricant's constants as a tuple
(:attr:`Lubricant.rheology_law`): the methods of :class:`Lubricant` apply them to arrays,
and compiled solvers call them node by node. The thermal oil
(:mod:`tribodyn.physics.thermal_oil`) applies the same functions with its ambient
viscosity μ₀(T) at each node (:func:`rheology_at`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numba import njit

from .._validation import check_bool, check_choice
from . import typical
from .limits import (
    DENSITY,
    EYRING_STRESS,
    LIMITING_SHEAR_COEFFICIENT,
    LIMITING_SHEAR_STRESS,
    PRESSURE_VISCOSITY,
    ROELANDS_LN_MU_INF,
    ROELANDS_MU_INF,
    VISCOSITY,
    check_fields,
)

__all__ = [
    "Lubricant",
    "ROELANDS_P0",
    "ROELANDS_MU_INF",
    "TYPICAL_OIL",
    "roelands_log_factor",
    "roelands_index",
    "roelands_alpha",
    "rheology_at",
    "density_terms",
    "viscosity_terms",
]

#: The range of each number of a :class:`Lubricant` (physics.limits).
LIMITS = {
    "viscosity": VISCOSITY,
    "pressure_viscosity": PRESSURE_VISCOSITY,
    "density": DENSITY,
    "eyring_stress": EYRING_STRESS,
    "limiting_shear_coefficient": LIMITING_SHEAR_COEFFICIENT,
    "limiting_shear_stress": LIMITING_SHEAR_STRESS,
}

#: Roelands pressure coefficient 5.1e-9 1/Pa (Eq. 3) and its pressure p₀ = 0.196 GPa.
_ROELANDS_C = 5.1e-9
ROELANDS_P0 = 1.0 / _ROELANDS_C


def roelands_log_factor(mu0):
    """a = ln μ₀ − ln μ∞ = ln μ₀ + 9.67 (μ₀ [Pa·s], a number or an array)."""
    return np.log(mu0) - ROELANDS_LN_MU_INF


def roelands_index(alpha: float, mu0: float) -> float:
    """Roelands' index Z = α/(5.1e-9 (ln μ₀ + 9.67)) of d ln μ/dp = α at p = 0 (Eq. 3)."""
    return float(alpha / (_ROELANDS_C * roelands_log_factor(mu0)))


def roelands_alpha(z: float, mu0: float) -> float:
    """α = 5.1e-9 Z (ln μ₀ + 9.67) [1/Pa], the inverse of :func:`roelands_index`."""
    return float(_ROELANDS_C * z * roelands_log_factor(mu0))


_JIT = dict(cache=True, nogil=True)

# The rheology law of a lubricant, ``law`` = (compressible, barus, α [1/Pa],
# a = ln μ₀ + 9.67 (:func:`roelands_log_factor`), Z) (:attr:`Lubricant.rheology_law`);
# p in Pa. Each function holds
# the law at max(p, 0) (NaN stays NaN); the derivatives are 0 for p < 0.


@njit(**_JIT)
def density_terms(p, law):
    """(ρ/ρ₀, (1/ρ₀) dρ/dp [1/Pa]) = (1 + 0.6 p_GPa/(1 + 1.7 p_GPa), 0.6e-9/(1 + 1.7 p_GPa)²)
    (Dowson–Higginson, Eq. 2); (1, 0) if incompressible."""
    if not law[0]:
        return 1.0, 0.0
    pg = (0.0 if p < 0.0 else p) * 1e-9
    d = 1.0 + 1.7 * pg
    return 1.0 + 0.6 * pg / d, (0.6e-9 / (d * d) if p >= 0.0 else 0.0)


@njit(**_JIT)
def viscosity_terms(p, law):
    """(ln μ/μ₀, d ln μ/dp [1/Pa]): Roelands (Eq. 3) a[(1 + p/p₀)^Z − 1] and
    (a Z/p₀)(1 + p/p₀)^(Z−1), or Barus α p and α."""
    pp = 0.0 if p < 0.0 else p
    slope = p >= 0.0
    if law[1]:
        return law[2] * pp, (law[2] if slope else 0.0)
    lg = math.log1p(pp / ROELANDS_P0)
    d = law[3] * law[4] / ROELANDS_P0 * math.exp((law[4] - 1.0) * lg) if slope else 0.0
    return law[3] * math.expm1(law[4] * lg), d


@njit(**_JIT)
def _each(p, a, law, which):
    """ρ/ρ₀, (1/ρ₀) dρ/dp, ln(μ/μ₀) or d ln μ/dp (``which`` = 0…3) at every entry of the
    1-D array ``p``, with the law's ln μ₀ + 9.67 replaced by ``a[i]`` (``a[0]`` at every
    entry if ``a`` has one)."""
    out = np.empty(p.size)
    for i in range(p.size):
        at = (law[0], law[1], law[2], a[i if a.size > 1 else 0], law[4])
        terms = density_terms(p[i], at) if which < 2 else viscosity_terms(p[i], at)
        out[i] = terms[which % 2]
    return out


def rheology_at(law, which: int, p, a=None):
    """:func:`_each` on an array or a number of any shape (a number gives a number);
    ``a``: ln μ₀ + 9.67 at each p (broadcast with it; None: the law's own)."""
    p = np.asarray(p, dtype=float)
    if a is not None:
        p, a = np.broadcast_arrays(p, np.asarray(a, dtype=float))
    a = np.ascontiguousarray(law[3] if a is None else a, dtype=float).reshape(-1)
    out = _each(np.ascontiguousarray(p).reshape(-1), a, law, which).reshape(p.shape)
    return out if out.ndim else out[()]


@dataclass(frozen=True)
class Lubricant:
    """Newtonian base properties of a lubricant at the inlet temperature.

    Parameters
    ----------
    viscosity : μ₀, dynamic viscosity at ambient pressure [Pa·s], > 6.31e-5 (Roelands), ≤ 100.
    pressure_viscosity : α, pressure–viscosity coefficient [1/Pa], 0 … 1e-6 (0: isoviscous).
    density : ρ₀ at ambient pressure [kg/m³] (paper: not given, 850 assumed).
    eyring_stress : τ_E, Eyring stress of the non-Newtonian shear law [Pa] (typical 5 MPa,
        :mod:`tribodyn.physics.typical`; the paper's 2 MPa is set by its case).
    limiting_shear_coefficient : Λ, pressure slope of the limiting shear stress [-]
        (typical 0.08).
    compressible : use Dowson–Higginson (True) or constant density (False); a bool.
    (Ranges of all numbers: ``physics.limits``, the same as the case file's.)
    viscosity_model : "roelands" (default, paper Eq. 3) or "barus".
    limiting_shear_stress : τ_L0, intercept of the limiting shear stress
        τ_L = τ_L0 + Λ p [Pa] (Bair & Winer's linear form; the paper uses Λ p only, τ_L0 = 0).
    """

    viscosity: float
    pressure_viscosity: float
    density: float = typical.DENSITY.value
    eyring_stress: float = typical.EYRING_STRESS.value
    limiting_shear_coefficient: float = typical.LIMITING_SHEAR_COEFFICIENT.value
    compressible: bool = True
    viscosity_model: str = "roelands"
    limiting_shear_stress: float = typical.LIMITING_SHEAR_STRESS.value

    def __post_init__(self):
        check_fields(self, LIMITS)  # the case file's [lubricant] is checked here
        object.__setattr__(self, "compressible", check_bool("compressible", self.compressible))
        check_choice("viscosity_model", self.viscosity_model, ("roelands", "barus"))

    # -- Roelands -----------------------------------------------------------------
    @property
    def roelands_z(self) -> float:
        """Roelands index Z (:func:`roelands_index`, paper Eq. 3)."""
        return roelands_index(self.pressure_viscosity, self.viscosity)

    @cached_property
    def rheology_law(self) -> tuple[bool, bool, float, float, float]:
        """The constants of the compiled rheology functions of this module:
        (compressible, Barus, α [1/Pa], ln μ₀ + 9.67, Z)."""
        return (
            bool(self.compressible),
            self.viscosity_model == "barus",
            float(self.pressure_viscosity),
            float(roelands_log_factor(self.viscosity)),
            float(self.roelands_z),
        )

    def viscosity_at(self, p) -> np.ndarray:
        """Viscosity μ(p) [Pa·s] for pressure p [Pa] (Roelands or Barus)."""
        return self.viscosity_from_log_ratio(self.log_viscosity_ratio(p))

    def viscosity_from_log_ratio(self, log_ratio) -> np.ndarray:
        """μ = μ₀ exp(ln μ/μ₀) [Pa·s] from ln μ/μ₀ (:meth:`log_viscosity_ratio`, or
        a solver's evaluation of :func:`viscosity_terms`)."""
        return self.viscosity * np.exp(log_ratio)

    def log_viscosity_ratio(self, p) -> np.ndarray:
        """ln(μ/μ₀) = (ln μ₀ + 9.67)[(1 + p/p₀)^Z − 1] (:func:`viscosity_terms`)."""
        return rheology_at(self.rheology_law, 2, p)

    def dlog_viscosity_dp(self, p) -> np.ndarray:
        """d ln μ / dp [1/Pa] (= α at p = 0; 0 for p < 0 where μ is held at μ₀)."""
        return rheology_at(self.rheology_law, 3, p)

    # -- Dowson–Higginson --------------------------------------------------------------
    def density_at(self, p) -> np.ndarray:
        """Dowson–Higginson density ρ(p) [kg/m³] (Eq. 2, :func:`density_terms`)."""
        return self.density * rheology_at(self.rheology_law, 0, p)

    def ddensity_dp(self, p) -> np.ndarray:
        """dρ/dp [kg/(m³ Pa)] (:func:`density_terms`)."""
        return self.density * rheology_at(self.rheology_law, 1, p)


#: A typical engine oil in a warm engine: the typical μ₀, α, ρ₀ and rheology of
#: :mod:`tribodyn.physics.typical` (the paper's SAE 5W-20 is stated in its case file).
TYPICAL_OIL = Lubricant(
    viscosity=typical.VISCOSITY.value, pressure_viscosity=typical.PRESSURE_VISCOSITY.value
)

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
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validation import check_bool, check_choice
from . import typical
from .limits import (
    DENSITY,
    EYRING_STRESS,
    LIMITING_SHEAR_COEFFICIENT,
    LIMITING_SHEAR_STRESS,
    PRESSURE_VISCOSITY,
    ROELANDS_MU_INF,
    VISCOSITY,
    check_fields,
)

__all__ = ["Lubricant", "ROELANDS_P0", "ROELANDS_MU_INF", "TYPICAL_OIL"]

#: Roelands pressure constant 1/5.1e-9 Pa = 0.196 GPa.
ROELANDS_P0 = 1.0 / 5.1e-9


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
        check_fields(  # the case file's [lubricant] is checked here (physics.limits)
            self,
            {
                "viscosity": VISCOSITY,
                "pressure_viscosity": PRESSURE_VISCOSITY,
                "density": DENSITY,
                "eyring_stress": EYRING_STRESS,
                "limiting_shear_coefficient": LIMITING_SHEAR_COEFFICIENT,
                "limiting_shear_stress": LIMITING_SHEAR_STRESS,
            },
        )
        object.__setattr__(self, "compressible", check_bool("compressible", self.compressible))
        check_choice("viscosity_model", self.viscosity_model, ("roelands", "barus"))

    # -- Roelands -----------------------------------------------------------------
    @property
    def roelands_z(self) -> float:
        """Roelands index Z = α/(5.1e-9 (ln μ₀ + 9.67)) (paper Eq. 3)."""
        return self.pressure_viscosity / (5.1e-9 * (np.log(self.viscosity) + 9.67))

    def viscosity_at(self, p) -> np.ndarray:
        """Viscosity μ(p) [Pa·s] for pressure p [Pa] (Roelands or Barus)."""
        return self.viscosity * np.exp(self.log_viscosity_ratio(p))

    def log_viscosity_ratio(self, p) -> np.ndarray:
        """ln(μ/μ₀) = (ln μ₀ + 9.67)[(1 + p/p₀)^Z − 1]."""
        pp = np.maximum(np.asarray(p, dtype=float), 0.0)
        if self.viscosity_model == "barus":
            return self.pressure_viscosity * pp
        a = np.log(self.viscosity) + 9.67
        return a * np.expm1(self.roelands_z * np.log1p(pp / ROELANDS_P0))

    def dlog_viscosity_dp(self, p) -> np.ndarray:
        """d ln μ / dp [1/Pa] (= α at p = 0; 0 for p < 0 where μ is held at μ₀)."""
        p = np.asarray(p, dtype=float)
        if self.viscosity_model == "barus":
            return np.where(p >= 0.0, self.pressure_viscosity, 0.0)
        pp = np.maximum(p, 0.0)
        a = np.log(self.viscosity) + 9.67
        z = self.roelands_z
        d = a * z / ROELANDS_P0 * np.exp((z - 1.0) * np.log1p(pp / ROELANDS_P0))
        return np.where(p >= 0.0, d, 0.0)

    # -- Dowson–Higginson --------------------------------------------------------------
    def density_at(self, p) -> np.ndarray:
        """Dowson–Higginson density ρ(p) [kg/m³] (Eq. 2, p converted to GPa)."""
        pg = np.maximum(np.asarray(p, dtype=float), 0.0) * 1e-9
        if not self.compressible:
            return np.full_like(pg, self.density)
        return self.density * (1.0 + 0.6 * pg / (1.0 + 1.7 * pg))

    def ddensity_dp(self, p) -> np.ndarray:
        """dρ/dp [kg/(m³ Pa)]: ρ₀ 0.6e-9 / (1 + 1.7 p_GPa)²."""
        p = np.asarray(p, dtype=float)
        if not self.compressible:
            return np.zeros_like(p)
        pg = np.maximum(p, 0.0) * 1e-9
        d = self.density * 0.6e-9 / (1.0 + 1.7 * pg) ** 2
        return np.where(p >= 0.0, d, 0.0)


#: A typical engine oil in a warm engine: the typical μ₀, α, ρ₀ and rheology of
#: :mod:`tribodyn.physics.typical` (the paper's SAE 5W-20 is stated in its case file).
TYPICAL_OIL = Lubricant(
    viscosity=typical.VISCOSITY.value,
    pressure_viscosity=typical.PRESSURE_VISCOSITY.value,
)

"""Asperity parameters from spectral moments (McCool 1986), pure functions.

Spectral moments of a profile of an isotropic surface (Nayak 1971)::

    m0 = ⟨h²⟩ = σ²  [m²],   m2 = ⟨(dh/dx)²⟩  [-],   m4 = ⟨(d²h/dx²)²⟩  [1/m²]

From the areal moments M_n = (2π)⁻² ∫ |q|ⁿ C²ᴰ(q) d²q of the 2-D power spectrum (as
returned by SurfaceTopography's ``moment_power_spectrum``), averaging the profile over all
in-plane directions (⟨cos²θ⟩ = 1/2, ⟨cos⁴θ⟩ = 3/8) gives

    m0 = M0,   m2 = M2/2,   m4 = 3 M4/8.

For an isotropic Gaussian surface (Nayak 1971, exact; McCool 1986, Eqs. for the
Greenwood–Williamson inputs)::

    η  = m4 / (6π√3 m2)                 summit density            [1/m²]
    κ̄  = (8/3) √(m4/π),  β = 1/κ̄ = 0.375 √(π/m4)
                                         mean summit curvature / radius [1/m], [m]
    α  = m0 m4 / m2²                     bandwidth parameter (≥ 1.5 when isotropic)
    σ_s = σ √(1 − 0.8968/α)              std of summit heights     [m]
    y_s = 4σ / √(πα)                     mean summit height above the mean plane [m]

(σ_s and y_s are McCool's large-α approximations; κ̄ is averaged over all summits and,
like η, does not depend on α.) Hence ηβσ = 0.375/(6√(3π)) √α ≈ 0.0204 √α ≥ 0.025 for
any isotropic Gaussian surface. For comparison, the paper's Table 4 gives
ηβσ ≈ 2.3e-3 (steel), 4.5e-4 (DLC) and 2.0e-4 (WC-C); read through these formulas they
would need α < 1, which no surface has, so those values cannot come from an isotropic
Gaussian surface with a single consistent σ, η, β.

Sources: P. R. Nayak, "Random process model of rough surfaces", J. Lubr. Technol. 93
(1971) 398–407; J. I. McCool, "Comparison of models for the contact of rough surfaces",
Wear 107 (1986) 37–60.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .._validation import InputError, check_positive
from .records import record_dict

__all__ = [
    "SpectralMoments",
    "McCoolParameters",
    "isotropic_profile_moments",
    "mccool_parameters",
    "MIN_ALPHA_ISOTROPIC",
]

#: Smallest bandwidth parameter of an isotropic surface (profile moments).
MIN_ALPHA_ISOTROPIC = 1.5


@dataclass(frozen=True)
class SpectralMoments:
    """Profile spectral moments m0 [m²], m2 [-], m4 [1/m²] (direction-averaged)."""

    m0: float
    m2: float
    m4: float

    UNITS = {"m0": "m²", "m2": "-", "m4": "1/m²", "alpha": "-"}

    @property
    def alpha(self) -> float:
        """Bandwidth parameter α = m0 m4 / m2² [-]."""
        return self.m0 * self.m4 / self.m2**2

    def __add__(self, other: SpectralMoments) -> SpectralMoments:
        """Moments of the sum of two independent surfaces (spectra add)."""
        return SpectralMoments(self.m0 + other.m0, self.m2 + other.m2, self.m4 + other.m4)

    def to_dict(self) -> dict:
        return record_dict(self, "alpha")


@dataclass(frozen=True)
class McCoolParameters:
    """Greenwood–Williamson parameters from spectral moments (McCool 1986). SI units."""

    asperity_density: float
    summit_radius: float
    rms: float
    alpha: float
    summit_height_std: float
    summit_height_mean: float

    UNITS = {
        "asperity_density": "1/m²",
        "summit_radius": "m",
        "rms": "m",
        "alpha": "-",
        "summit_height_std": "m",
        "summit_height_mean": "m",
    }


def isotropic_profile_moments(areal_m0: float, areal_m2: float, areal_m4: float) -> SpectralMoments:
    """Direction-averaged profile moments from areal moments M0 [m²], M2 [-], M4 [1/m²]:
    m0 = M0, m2 = M2/2, m4 = 3M4/8."""
    return SpectralMoments(
        check_positive("M0", areal_m0, "m²"),
        0.5 * check_positive("M2", areal_m2),
        0.375 * check_positive("M4", areal_m4, "1/m²"),
    )


def mccool_parameters(moments: SpectralMoments) -> McCoolParameters:
    """η, β, σ, α, σ_s and y_s from profile moments (module docstring; McCool 1986)."""
    m0 = check_positive("m0", moments.m0, "m²")
    m2 = check_positive("m2", moments.m2)
    m4 = check_positive("m4", moments.m4, "1/m²")
    alpha = m0 * m4 / m2**2
    if alpha < 1.0:
        raise InputError(
            f"bandwidth parameter α = m0 m4/m2² must be >= 1 (got {alpha:.6g}); "
            "the moments are inconsistent"
        )
    sigma = math.sqrt(m0)
    return McCoolParameters(
        asperity_density=m4 / (6.0 * math.pi * math.sqrt(3.0) * m2),
        summit_radius=0.375 * math.sqrt(math.pi / m4),
        rms=sigma,
        alpha=alpha,
        summit_height_std=sigma * math.sqrt(max(1.0 - 0.8968 / alpha, 0.0)),
        summit_height_mean=4.0 * sigma / math.sqrt(math.pi * alpha),
    )

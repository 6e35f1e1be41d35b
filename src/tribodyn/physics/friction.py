"""Viscous and boundary friction laws (paper Section 2.5, Eqs. 16–18).

Viscous (Couette) shear stress on the surfaces for sliding speed u_s, local viscosity μ
and film h:

* ``"newtonian"`` (Eq. 16 as printed): τ = μ u_s / h
* ``"eyring"``: τ = τ_E asinh(μ u_s / (τ_E h))         (τ_E: Eyring stress)

both capped by the limiting shear stress τ_L = τ_L0 + Λ p unless disabled (paper: Λ = 0.08,
τ_L0 = 0; the intercept τ_L0 of Bair & Winer's linear law keeps a finite cap where the
pressure vanishes). The
Poiseuille part ±(h/2) dp/dx of Eq. 16 has opposite signs on the two surfaces; solvers
report it separately as the rolling friction.

Boundary friction (Eqs. 17–18, applied locally): the asperity shear strength
τ = τ₀ + ς p_a acts on the real contact area, so per unit nominal area
τ_b = τ₀ (A_a/A) + ς p_a,   ς = pressure coefficient of boundary shear strength of the
surface pair (paper: τ₀ = 2 MPa with AFM values steel 0.185, DLC 0.44, WC-C 0.54, Table 6).

Defaults are the typical values of :mod:`tribodyn.physics.typical` (τ_E = 5 MPa; τ₀ = 0,
so that ς is a measured boundary friction coefficient); the paper's values are in
:mod:`tribodyn.paper` and its case files.
"""

from __future__ import annotations

import numpy as np

from .._validation import InputError
from . import typical

__all__ = [
    "VISCOUS_MODELS",
    "couette_shear_stress",
    "limit_shear_stress",
    "boundary_shear_stress",
    "BOUNDARY_SHEAR_STRENGTH",
]

VISCOUS_MODELS = ("newtonian", "eyring")
#: τ₀ of Eq. 17 [Pa], typical (0: ς is then the measured boundary friction coefficient).
BOUNDARY_SHEAR_STRENGTH = typical.BOUNDARY_SHEAR_STRENGTH.value


def couette_shear_stress(
    viscosity,
    sliding_speed,
    film,
    model: str = "eyring",
    eyring_stress: float = typical.EYRING_STRESS.value,
) -> np.ndarray:
    """Couette shear stress [Pa], signed like the sliding speed."""
    if model not in VISCOUS_MODELS:
        raise InputError(f"viscous model must be one of {VISCOUS_MODELS} (got {model!r})")
    rate_stress = (
        np.asarray(viscosity, dtype=float)
        * np.asarray(sliding_speed, dtype=float)
        / np.asarray(film, dtype=float)
    )
    if model == "newtonian":
        return rate_stress
    return eyring_stress * np.arcsinh(rate_stress / eyring_stress)


def limit_shear_stress(tau, pressure, coefficient: float, intercept: float = 0.0) -> np.ndarray:
    """Cap |τ| at the limiting shear stress τ_L0 + Λ·max(p, 0), keeping the sign of τ.

    ``coefficient`` is Λ [-], ``intercept`` τ_L0 [Pa].
    """
    cap = intercept + coefficient * np.maximum(np.asarray(pressure, dtype=float), 0.0)
    tau = np.asarray(tau, dtype=float)
    return np.sign(tau) * np.minimum(np.abs(tau), cap)


def boundary_shear_stress(
    asperity_pressure,
    area_fraction,
    coefficient: float,
    shear_strength: float = BOUNDARY_SHEAR_STRENGTH,
):
    """Boundary shear per unit nominal area τ_b = τ₀ A_a/A + ς p_a [Pa]."""
    return shear_strength * np.asarray(area_fraction, dtype=float) + coefficient * np.asarray(
        asperity_pressure, dtype=float
    )

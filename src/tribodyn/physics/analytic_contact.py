"""Analytic (quasi-static) tribology of a lubricated line contact.

The "simple analytical tribology" used inside the valvetrain dynamics (paper Section 2.1,
the explicit model): no Reynolds solution, only

* Hertz half-width b and pressure p(x) = p_h √(1 − x²/b²) with the bulk reduced modulus,
* central film h_c from a film formula (Moes by default: valid in all four regimes;
  Pan–Hamrock or Dowson–Toyoda on request) and h_min = h_c × (Pan–Hamrock h_min/h_c),
  capped at h_c (h_min = h_c for an isoviscous lubricant, where that fit does not apply),
* Greenwood–Tripp asperity pressure and area at h_c, uniform over the Hertz width
  (asperity load capped at the total load),
* viscous friction ∫_{−b}^{b} τ(x) dx with the local Roelands viscosity μ(p(x)), the
  Couette law of :mod:`tribodyn.physics.friction` at h_c, capped by the limiting shear
  stress τ_L0 + Λp(x),
* boundary friction 2b (τ₀ A_a/A + ς p_a).

All inputs may be arrays (broadcast together); loads and forces are per unit length.
Steady formulas have no squeeze term, so at u_e → 0 they predict a vanishing film: that
is the physics the transient EHL solver adds. |u_e| is floored at 1 mm/s to keep the
formulas finite.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from . import typical
from .asperity import Roughness
from .friction import BOUNDARY_SHEAR_STRENGTH, couette_shear_stress, limit_shear_stress
from .lubricant import Lubricant
from .materials import reduced_modulus
from .regimes import (
    dowson_toyoda_central,
    greenwood_chart_groups,
    hamrock_groups,
    lubrication_regime,
    moes_central,
    pan_hamrock,
)

__all__ = ["AnalyticContact", "analytic_contact", "FILM_FORMULAS"]

FILM_FORMULAS = ("moes", "pan_hamrock", "dowson_toyoda")
_U_FLOOR = 1e-3
_GL_X, _GL_W = np.polynomial.legendre.leggauss(32)


@dataclass
class AnalyticContact:
    """Per-unit-length analytic contact state (arrays broadcast from the inputs)."""

    central_film: np.ndarray
    min_film: np.ndarray
    half_width: np.ndarray
    max_pressure: np.ndarray
    asperity_load: np.ndarray
    viscous_friction: np.ndarray  #: magnitude [N/m]
    boundary_friction: np.ndarray  #: magnitude [N/m]
    gV: np.ndarray
    gE: np.ndarray
    regime: np.ndarray

    @property
    def friction(self) -> np.ndarray:
        return self.viscous_friction + self.boundary_friction


def analytic_contact(
    load,
    radius,
    entrainment_speed,
    sliding_speed,
    bodies,
    lubricant: Lubricant,
    roughness: Roughness | None = None,
    *,
    boundary_shear_coefficient: float = typical.boundary_friction("steel").value,
    boundary_shear_strength: float = BOUNDARY_SHEAR_STRENGTH,
    viscous_model: str = "eyring",
    limiting_shear: bool = True,
    film_formula: str = "moes",
) -> AnalyticContact:
    """Analytic film, asperity load and friction (see module docstring)."""
    if film_formula not in FILM_FORMULAS:
        raise ValueError(f"film_formula must be one of {FILM_FORMULAS} (got {film_formula!r})")
    w, R, ue, us = np.broadcast_arrays(
        *(np.asarray(a, dtype=float) for a in (load, radius, entrainment_speed, sliding_speed))
    )
    w = np.maximum(w, 1e-12)
    e = reduced_modulus(bodies)
    ue_eff = np.maximum(np.abs(ue), _U_FLOOR)
    W, U, G = hamrock_groups(w, R, ue_eff, lubricant.viscosity, lubricant.pressure_viscosity, e)
    hc_ph, hm_ph = pan_hamrock(W, U, G, R)
    central = {"moes": moes_central, "dowson_toyoda": dowson_toyoda_central}
    hc = hc_ph if film_formula == "pan_hamrock" else central[film_formula](W, U, G, R)
    # Pan–Hamrock's h_min/h_c is a piezoviscous-elastic fit (∝ G^0.098 → 0 as α → 0); for
    # an isoviscous lubricant (G = 0) the film is taken flat, h_min = h_c (rigid limit)
    with np.errstate(invalid="ignore", divide="ignore"):
        ratio = np.where(hc_ph > 0.0, hm_ph / hc_ph, 1.0)
    hmin = hc * np.minimum(ratio, 1.0)

    b = np.sqrt(8.0 * w * R / (np.pi * e))
    ph = np.sqrt(w * e / (2.0 * np.pi * R))

    # Viscous friction over the Hertz zone, x = b sin θ (smooth integrand).
    theta = 0.5 * np.pi * _GL_X
    wts = 0.5 * np.pi * _GL_W * np.cos(theta)  # dx/b = cos θ dθ
    p = ph[..., None] * np.cos(theta)  # p_h √(1 − sin²θ)
    mu = lubricant.viscosity_at(p)
    tau = np.abs(
        couette_shear_stress(
            mu, us[..., None], hc[..., None], viscous_model, lubricant.eyring_stress
        )
    )
    if limiting_shear:
        tau = np.abs(
            limit_shear_stress(
                tau, p, lubricant.limiting_shear_coefficient, lubricant.limiting_shear_stress
            )
        )
    f_visc = b * np.sum(tau * wts, axis=-1)

    if roughness is not None:
        e_s = reduced_modulus(bodies, surface=True)
        pa = roughness.asperity_pressure(hc, e_s)
        wa = np.minimum(2.0 * b * pa, w)
        area = 2.0 * b * roughness.contact_area_fraction(hc)
        f_bound = boundary_shear_strength * area + boundary_shear_coefficient * wa
    else:
        wa = np.zeros_like(w)
        f_bound = np.zeros_like(w)

    gV, gE = greenwood_chart_groups(W, U, G)
    return AnalyticContact(
        central_film=hc,
        min_film=hmin,
        half_width=b,
        max_pressure=ph,
        asperity_load=wa,
        viscous_friction=f_visc,
        boundary_friction=f_bound,
        gV=gV,
        gE=gE,
        regime=lubrication_regime(gV, gE),
    )

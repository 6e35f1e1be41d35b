"""ESTIMATE of the asperity-scale stresses in mixed lubrication: one Hertzian micro-contact
at the mean micro-contact pressure of the Greenwood–Tripp model.

The EHL-scale stresses (:mod:`.stress`) load the surface with the *mean* asperity
pressure p_a, smeared over the nominal area. The real contact is carried by the summits
on the fraction A_a/A of the area, at the mean micro-contact pressure (total asperity
load over real contact area)::

    p_m = p_a / (A_a/A) = (8√2 / 15π) √(σ/β) E' F_{5/2}(λ) / F_2(λ),   λ = h/σ

(paper Eqs. 6 and 18, :mod:`.asperity`; F_{5/2}/F_2 falls monotonically with λ, so p_m
is largest at the smallest gap). A summit is a sphere of radius β (Greenwood &
Williamson, Proc. R. Soc. A 295 (1966) 300) pressed on a flat with the Hertz mean
pressure p_m (Johnson, *Contact Mechanics*, 1985, §4.2, with
E* = E'/2 in this project's convention)::

    p0 = 3 p_m / 2,   a = 3π β p_m / (4 E*)

Its stresses on the axis (Johnson §3.4; compression negative, ζ = z/a)::

    σ_z/p0 = −1/(1 + ζ²)
    σ_r/p0 = σ_θ/p0 = −(1 + ν)(1 − ζ arctan(1/ζ)) + 1/(2(1 + ζ²))

so the von Mises stress on the axis is |σ_r − σ_z| (two equal principal stresses); its
maximum (≈ 0.62 p0 at ≈ 0.48a for ν = 0.3, twice the maximum shear 0.31 p0 quoted in the
literature) is found numerically. The largest tensile stress is the radial stress at
the edge of the contact circle, σ_r = (1 − 2ν) p0/3 (Johnson §3.4).

What this is and is not:

* an ESTIMATE of the typical micro-contact, not of the most loaded one (the highest
  summits carry more than the mean pressure);
* elastic and frictionless: the local boundary traction (τ_b per real area, ratio
  τ_b/p_a to the pressure) is not included. On the axis the traction's own σ_xx, σ_yy,
  σ_zz vanish (they are odd in x) and it adds only σ_xz, so the subsurface von Mises
  maximum changes by O((τ_b/p_a)²) while small; the tension at the trailing edge grows
  in proportion to it and is underestimated here;
* homogeneous: valid for a coating when the micro-contact is small against its thickness
  (a ≪ h); the ratio a/h is reported;
* Hertz theory needs a ≪ β: the ratio a/β is reported. At a/β ≳ 0.3 (sharp summits,
  σ/β near 1) the estimate is outside small-strain theory and only says that the
  summits are loaded far beyond yield (Greenwood & Williamson's plasticity index
  (E*/H)√(σ/β) makes the same statement). A safety factor below 1 means the summits
  deform plastically (running-in), not that the coating fails.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import optimize

from .._validation import InputError, check_positive
from .asperity import Roughness, greenwood_tripp
from .limits import POISSON_RATIO

__all__ = [
    "MicroContactEstimate",
    "hertz_sphere_axis_stress",
    "hertz_sphere_peak_von_mises",
    "mean_micro_contact_pressure",
    "micro_contact_estimate",
]


def hertz_sphere_axis_stress(zeta, nu: float) -> tuple[np.ndarray, np.ndarray]:
    """σ_z/p0 and σ_r/p0 (= σ_θ/p0) on the axis of a Hertzian circular contact at depths
    ζ = z/a ≥ 0 (Johnson §3.4; compression negative)."""
    nu = POISSON_RATIO.check("nu", nu)
    z = np.asarray(zeta, dtype=float)
    if np.any(~np.isfinite(z)) or np.any(z < 0.0):
        raise InputError("zeta must be finite and >= 0")
    q = 1.0 / (1.0 + z * z)
    # ζ arctan(1/ζ) → 0 as ζ → 0 (arctan2 keeps it finite at ζ = 0)
    sr = -(1.0 + nu) * (1.0 - z * np.arctan2(1.0, z)) + 0.5 * q
    return -q, sr


def hertz_sphere_peak_von_mises(nu: float) -> tuple[float, float]:
    """Maximum von Mises stress / p0 under a frictionless Hertzian circular contact and its
    depth / a (on the axis, where σ_r = σ_θ: σ_vM = |σ_r − σ_z|)."""

    def neg(z):
        sz, sr = hertz_sphere_axis_stress(z, nu)
        return -abs(float(sr) - float(sz))

    r = optimize.minimize_scalar(neg, bounds=(0.05, 2.0), method="bounded", options={"xatol": 1e-8})
    return -float(r.fun), float(r.x)


def mean_micro_contact_pressure(roughness: Roughness, gap, reduced_modulus: float):
    """Mean pressure on the real contact area p_m = p_a/(A_a/A) [Pa] at gap h [m]
    (module docstring), with the model's own p_a and A_a/A (paper Eqs. 6, 18)."""
    e = check_positive("reduced_modulus", reduced_modulus, "Pa")
    lam = np.asarray(gap, dtype=float) / roughness.rms
    f52 = np.asarray(greenwood_tripp(2.5, lam, roughness.method), dtype=float)
    f2 = np.asarray(greenwood_tripp(2.0, lam, roughness.method), dtype=float)
    scale = (
        8.0 * math.sqrt(2.0) / (15.0 * math.pi) * math.sqrt(roughness.rms / roughness.summit_radius)
    )
    touching = f2 > 0.0  # F_2 underflows to 0 where no summit touches
    return np.where(touching, scale * e * f52 / np.where(touching, f2, 1.0), np.nan)


@dataclass(frozen=True)
class MicroContactEstimate:
    """Hertzian micro-contact at the mean micro-contact pressure (module docstring; an
    ESTIMATE). Stresses in Pa, lengths in m."""

    gap_ratio: float  #: λ = h/σ where it was evaluated
    mean_pressure: float  #: p_m = p_a/(A_a/A)
    peak_pressure: float  #: p0 = 1.5 p_m
    radius: float  #: a = 3πβ p_m/(4E*)
    max_von_mises: float  #: on the axis
    depth: float  #: z of the von Mises maximum
    edge_tension: float  #: (1 − 2ν) p0/3, radial, at r = a on the surface
    radius_over_summit: float  #: a/β (Hertz needs ≪ 1)


def micro_contact_estimate(
    roughness: Roughness, gap: float, reduced_modulus: float, nu: float
) -> MicroContactEstimate:
    """The micro-contact estimate at gap h [m] for the surface material of Poisson's ratio
    ``nu`` (``reduced_modulus``: E' of the two surface materials, 1/E' = ½Σ(1−ν²)/E).
    Its stresses and radius are NaN where no summit touches (F_2 = 0 in double precision,
    h/σ ≳ 37)."""
    e = check_positive("reduced_modulus", reduced_modulus, "Pa")
    nu = POISSON_RATIO.check("nu", nu)
    pm = float(mean_micro_contact_pressure(roughness, gap, e))
    p0 = 1.5 * pm
    a = 3.0 * math.pi * roughness.summit_radius * pm / (4.0 * 0.5 * e)
    vm, zeta = hertz_sphere_peak_von_mises(nu)
    return MicroContactEstimate(
        gap_ratio=float(gap) / roughness.rms,
        mean_pressure=pm,
        peak_pressure=p0,
        radius=a,
        max_von_mises=vm * p0,
        depth=zeta * a,
        edge_tension=(1.0 - 2.0 * nu) / 3.0 * p0,
        radius_over_summit=a / roughness.summit_radius,
    )

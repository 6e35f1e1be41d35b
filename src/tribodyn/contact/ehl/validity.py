"""Checks of an EHL solution against the assumptions of the model.

Run at the end of every post-processing (steady solves and transient steps).

Not a solution (``converged=False``, whatever Newton said):

* a film that is not finite or not positive somewhere, h(x) ≤ 0. The gap h is the
  separation of the mean planes of the rough surfaces; h ≤ 0 means they interpenetrate,
  where neither the Reynolds equation (flow ∝ h³) nor Greenwood–Tripp's asperity model
  (asperities much smaller than the gap to the other mean plane) holds. It happens when the
  load is far beyond what the surfaces can carry elastically (e.g. 1e9 N/m on steel).

Outside the model's validity (the result stays as computed and gets a warning, in
``EHLResult.warnings`` and appended to ``message`` as ``"; warning: …"``):

* **thin film** — Reynolds' equation is the leading order of the Navier–Stokes equations
  in the film aspect ratio ε = h/ℓ, with corrections of order ε² (Szeri, *Fluid Film
  Lubrication*, 2nd ed., 2011, §2.1–2.3). The film varies over ℓ = max(b, √(2R h_c))
  (Hertz half-width in elastic contacts, rigid inlet length otherwise), so ε = h_c/ℓ; the
  warning is given at ε > 0.1 (corrections > 1 %). For the rigid cylinder ε² = h_c/(2R):
  films above 2 % of R are flagged.
* **contact size** — Hertz's half-space idealisation needs a contact much smaller than R
  (Johnson, *Contact Mechanics*, 1985, §4.1): flagged where the Hertz half-width b
  exceeds 0.1 R. The parabolic gap x²/(2R) falls short of the circle by x²/(4R²)
  relative: flagged where that reaches 1 % (as the thin-film check's ε²) at the edge of
  the zone carrying 98 % of the load, i.e. beyond |x| = 0.2 R. At light load and thick
  film that zone is the long hydrodynamic inlet, while b ≪ R.
* **fluid inertia** — the modified Reynolds number Re* = ρ₀|u_e| h_c²/(μ₀ ℓ) measures
  inertia against viscous forces in the film (Szeri 2011, §2.3; Hamrock, Schmid & Jacobson,
  *Fundamentals of Fluid Film Lubrication*, 2004, §7.2); inertia changes the pressure by
  O(Re*), flagged at Re* > 0.1.
* **pressure** — a peak contact pressure above 4 GPa lies beyond the first yield of
  hardened steel (p₀ ≈ 1.67 Y for line contact, Johnson 1985 §6.2, Y ≈ 2 GPa) and far
  beyond the measurements behind the Roelands and Dowson–Higginson laws (≲ 1–2 GPa): the
  elastic, isothermal model does not describe it.
"""

from __future__ import annotations

import math

import numpy as np

from ...physics.hertz import hertz_half_width
from .options import ContactModel, EHLResult
from .post_kernels import validity_stats

__all__ = [
    "check_solution",
    "MAX_ASPECT_RATIO",
    "MAX_HALF_WIDTH_TO_RADIUS",
    "MAX_GAP_ERROR",
    "MAX_MODIFIED_REYNOLDS",
    "MAX_PRESSURE",
]

#: film aspect ratio h_c/ℓ above which Reynolds' thin-film approximation is flagged
MAX_ASPECT_RATIO = 0.1
#: Hertz half-width relative to R above which half-space elasticity is flagged
MAX_HALF_WIDTH_TO_RADIUS = 0.1
#: relative error of the parabolic gap, (x/R)²/4 at the edge of the load-carrying zone,
#: above which it is flagged
MAX_GAP_ERROR = 0.01
#: modified Reynolds number above which fluid inertia is flagged
MAX_MODIFIED_REYNOLDS = 0.1
#: peak contact pressure [Pa] above which the elastic, isothermal model is flagged
MAX_PRESSURE = 4e9


#: the load-carrying zone holds the central 98 % of ∫(p + p_a) dx
_ZONE_SHARES = (0.01, 0.99)


def _array(a) -> np.ndarray:
    return np.ascontiguousarray(a, dtype=float)


def check_solution(res: EHLResult, model: ContactModel) -> EHLResult:
    """Flag ``res`` (in place, and returned): non-positive or non-finite film →
    ``converged=False``; outside the model's validity → a warning (module docstring)."""
    finite, h_min, zone, p_max = validity_stats(
        _array(res.x),
        _array(res.film),
        _array(res.pressure),
        _array(res.asperity_pressure),
        *_ZONE_SHARES,
    )
    if not finite:
        if res.converged:
            res.message = "non-finite film: " + res.message
        res.converged = False
        return res
    if h_min <= 0.0:
        res.converged = False
        res.message = (
            f"non-physical film: h_min = {h_min:.3g} m ≤ 0 (the mean planes of "
            "the surfaces interpenetrate; the load is beyond what the lubricated "
            f"contact model describes) [Newton: {res.message}]"
        )
        return res
    R, w, hc = res.radius, res.load, res.central_film
    lub = model.lubricant
    b = hertz_half_width(w, R, model.e_bulk)  # checked upstream
    ell = max(b, math.sqrt(2.0 * R * max(hc, 0.0)))
    found = []
    eps = hc / ell if ell > 0 else math.inf
    if eps > MAX_ASPECT_RATIO:
        found.append(
            f"film h_c = {hc:.3g} m is {hc / R:.3g} R and {eps:.2g} of the length "
            f"over which it varies (ℓ = {ell:.3g} m): Reynolds' thin-film "
            f"approximation needs h/ℓ ≪ 1 (flagged above {MAX_ASPECT_RATIO:g})"
        )
    if b > MAX_HALF_WIDTH_TO_RADIUS * R:
        found.append(
            f"the Hertz half-width b = {b / R:.3g} R: half-space elasticity needs a contact "
            f"much smaller than R (flagged above {MAX_HALF_WIDTH_TO_RADIUS:g} R)"
        )
    gap_error = 0.25 * (zone / R) ** 2
    if gap_error > MAX_GAP_ERROR:
        found.append(
            f"the load-carrying zone reaches {zone / R:.3g} R (Hertz b = {b / R:.3g} R), "
            f"where the parabolic gap x²/(2R) falls short of the circle by "
            f"{100 * gap_error:.2g} % (flagged above {100 * MAX_GAP_ERROR:g} %)"
        )
    re_star = lub.density * abs(res.entrainment_speed) * hc**2 / (lub.viscosity * ell)
    if re_star > MAX_MODIFIED_REYNOLDS:
        found.append(
            f"modified Reynolds number ρu_e h_c²/(μ₀ℓ) = {re_star:.3g}: fluid "
            "inertia, neglected by the Reynolds equation, is not negligible "
            f"(flagged above {MAX_MODIFIED_REYNOLDS:g})"
        )
    if p_max > MAX_PRESSURE:
        found.append(
            f"peak contact pressure {p_max / 1e9:.3g} GPa exceeds "
            f"{MAX_PRESSURE / 1e9:g} GPa: beyond the elastic limit of hardened steel "
            "and the measured range of the Roelands and Dowson–Higginson laws"
        )
    for text in found:
        res.warnings.append(text)
        res.message += f"; warning: {text}"
    return res

"""The reduced film laws of the film state (valvetrain ``FilmStateTribology``): the load a
steady entraining film of thickness h carries, limited by an oil supply layer, and the
limit on how fast the film can grow. Pure functions of floats and arrays; units SI."""

from __future__ import annotations

import math

__all__ = [
    "SUPPLY_FILM",
    "GROWTH_SHARPNESS",
    "FILM_FLOOR",
    "entraining_film_load",
    "limited_growth",
    "film_rate",
    "squeeze_compliance_slope",
    "growth_limit",
]

#: Oil supply layer h_s [m] bounding the film of the film state (valvetrain
#: ``FilmStateTribology``; assumed, see there): about the flooded EHL film of the paper
#: case under the 5–10 N contacts of the tappet on the base circle.
SUPPLY_FILM = 10e-6
#: Martin's rigid isoviscous line contact, central film (Reynolds exit): h w' = 4.894 η u R.
_MARTIN = 4.894
#: smallest film the film state's laws are evaluated at [m] (the state itself is free)
FILM_FLOOR = 1e-10
#: sharpness p of the smooth minimum of the film's free growth rate and its transport
#: limit (:func:`limited_growth`)
GROWTH_SHARPNESS = 4.0


def limited_growth(x: float, xt: float) -> tuple[float, float, float]:
    """The film's rate ḣ = H(x) from its free rate x = a − F_c/D [m/s] (squeeze-limited)
    and the transport limit x_t ≥ 0 [m/s] of its growth (valvetrain
    ``FilmStateTribology.growth_limit``): H = x where the film thins (x ≤ 0), else the
    smooth minimum

        H = x / (1 + (x/x_t)^p)^(1/p),  p = GROWTH_SHARPNESS,

    which is x within 0.1 % for x < x_t/4 and tends to x_t for x ≫ x_t. Returns
    (H, ∂H/∂x, ∂H/∂x_t)."""
    if x <= 0.0:
        return x, 1.0, 0.0
    if xt <= 0.0:
        return 0.0, 0.0, 1.0
    if xt == math.inf:
        return x, 1.0, 0.0
    p = GROWTH_SHARPNESS
    q = (x / xt) ** p
    f = (1.0 + q) ** (-1.0 / p)
    # ∂H/∂x = f − x f q/(x(1 + q)) = f/(1 + q); ∂H/∂x_t = f q x/(x_t(1 + q))
    return x * f, f / (1.0 + q), f * q * x / (xt * (1.0 + q))


def entraining_film_load(h, ue, R, eta, alpha, e_prime, supply, r):
    """(w' [N/m], dw'/dh [N/m²]): the load per unit length that a steady entraining film
    of thickness h [m] carries between a cylinder of radius R [m] and a plane at
    entrainment speed u_e [m/s] (floats), the inverse of a steady film formula, limited by
    the oil supply h_s = ``supply`` [m]. With U = η₀|u_e|/(E'R), G = αE' (viscosity η₀
    [Pa·s], pressure–viscosity coefficient α [1/Pa], E' [Pa]):

    - *starvation*: the film is the series (harmonic) combination of the flooded film h_f
      and the supply layer h_s, 1/h = 1/h_f + 1/h_s, i.e. h_f = h h_s/(h_s − h), and no
      load for h ≥ h_s. It is the γ = 1 member of the family h/h_f = ρ/(1 + ρ^γ)^(1/γ),
      ρ = h_s/h_f, that Chevalier, Lubrecht, Cann, Colin & Dalmaz (ASME J. Tribol. 120
      (1998) 126) fitted to starved EHL films (measured γ ≈ 2–3: sharper than here). It
      has the flooded film for h_f ≪ h_s, the supply layer as h_f → ∞ (no load) and a
      finite stiffness there; near h_s the film recovers with the time constant
      2.72 √(R h_s)/|u_e| (the inlet length √(R h_s) swept at u_e, with the squeeze
      film of :func:`~tribodyn.valvetrain.tribology.squeeze_film_load`);
    - *flooded*: the loads that the rigid-isoviscous (Martin 1916, central film,
      Reynolds exit) and the elastic-piezoviscous (Moes 1992 asymptote H_EP) films of
      thickness h_e = h_f/r carry, added:

          w' = 4.894 η₀ |u_e| R / h_e + E'R (1.311 G^(3/4) (2U)^(3/4) R / h_e)^8

      Its inverse agrees with the Moes central film (:func:`~tribodyn.physics.regimes.
      moes_central`) within 7 % in the elastic-piezoviscous regime and gives Martin's
      film (Moes' rigid asymptote is 22 % higher) at light loads; in the isoviscous-
      elastic regime (low speed, high load) it is up to 27 % thinner. ``r`` scales the
      flooded film (the implicit coupling sets it from the transient EHL).

    w' → 0 as u_e → 0 (only squeeze then); w' = 0 for h ≥ h_s."""
    if h >= supply or ue == 0.0:
        return 0.0, 0.0
    h = max(h, FILM_FLOOR)
    d = supply - h
    he = h * supply / d / r  # flooded-equivalent film, corrected
    dhe = supply * supply / (d * d) / r
    au = abs(ue)
    w_ri = _MARTIN * eta * au * R / he
    u2 = 2.0 * eta * au / (e_prime * R)
    x = 1.311 * (alpha * e_prime * u2) ** 0.75 * R / he
    x2 = x * x
    x4 = x2 * x2
    w_ep = e_prime * R * x4 * x4
    return w_ri + w_ep, -(w_ri + 8.0 * w_ep) / he * dhe


def film_rate(h, force, ue, R, eta, alpha, e_prime, supply, r, width, sq):
    """(ḣ [m/s], ∂ḣ/∂h [1/s], ∂ḣ/∂F_c [m/(N s)]) of a film h [m] of width L = ``width``
    [m] carrying F_c = ``force`` [N] (floats): ḣ = (L w'_ent(h) − F_c)/D with
    D = 3√2 π η₀ R^(3/2) L/h^(3/2) = ``sq`` R^(3/2)/h^(3/2) (``sq`` = 3√2 π η₀ L), w'_ent
    of :func:`entraining_film_load` (arguments as there); h held at :data:`FILM_FLOOR`
    below it in D, R at 1e-9 m (a flat face's radius is positive)."""
    R = max(R, 1e-9)
    w, dw = entraining_film_load(h, ue, R, eta, alpha, e_prime, supply, r)
    hh = max(h, FILM_FLOOR)
    inv_d = hh**1.5 / (sq * R**1.5)
    rate = (width * w - force) * inv_d
    return rate, width * dw * inv_d + 1.5 * rate / hh, -inv_d


def squeeze_compliance_slope(h, R, sq):
    """∂(1/D)/∂h [1/(N s)] of the squeeze film's 1/D = h^(3/2)/(``sq`` R^(3/2)) of
    :func:`film_rate` at h [m]: 1.5/(D h), with h and R held at their floors as there."""
    hh = max(h, FILM_FLOOR)
    return 1.5 * hh**0.5 / (sq * max(R, 1e-9) ** 1.5)


def growth_limit(h, ue, R, supply, limited):
    """(x_t [m/s], ∂x_t/∂h [1/s]): the fastest the film can thicken. A thicker film
    needs oil from the supply layer h_s, carried at u_e from the inlet meniscus, where
    the gap h + x²/2R opens to h_s, x_m = √(2R(h_s − h)), to the contact; over that
    transit x_m/|u_e| the film can grow by at most h_s − h:

        x_t = |u_e| (h_s − h)/x_m = |u_e| √((h_s − h)/(2R))

    (0 for h ≥ h_s = ``supply`` or u_e = 0; infinite unless ``limited``). The film's
    free rate (entraining load against the squeeze film) exceeds it only where u_e
    or R step (a ramp-less cam's step of acceleration: 413 m/s against 0.16 m/s at
    6000 rpm, 9 mm / 140° cam); elsewhere it is far slower (an unloaded
    rigid-isoviscous film recovers at c√h (1 − h/h_s) ≤ 0.26 x_t, where the smooth
    minimum slows it by at most 0.11 %; a piezoviscous film near u_e = 0 reaches
    0.45 x_t in the paper case, slowed by at most 1 %, 0.5 N of force). x_m is far
    longer than the Hertz width, so x_t errs on the slow side; it scales with
    √(h_s − h), with the assumed supply."""
    if not limited:
        return math.inf, 0.0
    gap = supply - h
    if gap <= 0.0 or ue == 0.0:
        return 0.0, 0.0
    R = max(R, 1e-9)
    xt = abs(ue) * math.sqrt(gap / (2.0 * R))
    return xt, -0.5 * xt / max(gap, 1e-6 * supply)

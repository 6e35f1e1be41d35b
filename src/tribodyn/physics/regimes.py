"""Dimensionless groups, lubrication regimes (Greenwood chart) and line-contact film formulas.

Conventions (docs/conventions.md): E' with 1/E' = ½Σ(1−ν²)/E, u_e = mean entraining speed.

* Hamrock groups   W' = w/(E'R),  U = μ₀|u_e|/(E'R),  G = αE'
* Moes groups      M = W'(2U)^(−1/2),  L = G(2U)^(1/4)
* Greenwood chart  g_V = G W'^(3/2) U^(−1/2),  g_E = W' U^(−1/2)   (paper Fig. 12)
  with the film parameter Ĥ = h w/(μ₀ u_e R) and the regime asymptotes (Johnson 1970)::

      IR  Ĥ = 4.9          PR  Ĥ = 1.66 g_V^(2/3)
      IE  Ĥ = 3.01 g_E^0.8 PE  Ĥ = 1.65 g_V^(3/4) g_E^(−1/4)

  Elasticity thickens an isoviscous film (H_I = max(IR, IE)) but relieves a rigid
  piezoviscous one (H_P = min(PR, PE); the PE asymptote is invalid as g_E → 0). The
  regime is the active asymptote of the larger of H_I and H_P, so the boundaries are
  where asymptotes are equal: IR/IE at g_E ≈ 1.84, IR/PR at g_V ≈ 5.07, PR/PE and IE/PE
  where PE meets PR or IE.

Film formulas return dimensional film thickness [m]; all accept numpy arrays.
"""

from __future__ import annotations

import numpy as np

__all__ = [
    "hamrock_groups",
    "moes_groups",
    "greenwood_chart_groups",
    "regime_asymptotes",
    "lubrication_regime",
    "film_parameter",
    "pan_hamrock",
    "dowson_toyoda_central",
    "moes_central",
    "REGIMES",
]

REGIMES = ("IR", "PR", "IE", "PE")


def hamrock_groups(load, radius, entrainment_speed, viscosity, pressure_viscosity, reduced_modulus):
    """(W', U, G): W' = w/(E'R), U = μ₀|u_e|/(E'R), G = αE'."""
    er = reduced_modulus * np.asarray(radius, dtype=float)
    w_ = np.asarray(load, dtype=float) / er
    u_ = viscosity * np.abs(np.asarray(entrainment_speed, dtype=float)) / er
    g_ = pressure_viscosity * reduced_modulus
    return w_, u_, g_


def moes_groups(W, U, G):
    """(M, L) = (W'(2U)^(−1/2), G(2U)^(1/4))."""
    U = np.asarray(U, dtype=float)
    return np.asarray(W) * (2.0 * U) ** -0.5, np.asarray(G) * (2.0 * U) ** 0.25


def greenwood_chart_groups(W, U, G):
    """(g_V, g_E) = (G W'^(3/2) U^(−1/2), W' U^(−1/2))."""
    W = np.asarray(W, dtype=float)
    U = np.asarray(U, dtype=float)
    return G * W**1.5 / np.sqrt(U), W / np.sqrt(U)


def regime_asymptotes(gV, gE) -> dict:
    """Film parameter Ĥ = h w/(μ₀u_eR) of the four regime asymptotes."""
    gV = np.asarray(gV, dtype=float)
    gE = np.asarray(gE, dtype=float)
    return {
        "IR": np.full(np.broadcast(gV, gE).shape, 4.9),
        "PR": 1.66 * gV ** (2.0 / 3.0) + 0.0 * gE,
        "IE": 3.01 * gE**0.8 + 0.0 * gV,
        "PE": 1.65 * gV**0.75 * gE**-0.25,
    }


def film_parameter(gV, gE):
    """Chart estimate of Ĥ = h w/(μ₀u_eR): max(max(IR, IE), min(PR, PE))."""
    a = regime_asymptotes(gV, gE)
    return np.maximum(np.maximum(a["IR"], a["IE"]), np.minimum(a["PR"], a["PE"]))


def lubrication_regime(gV, gE):
    """Regime label(s) 'IR', 'PR', 'IE' or 'PE' from (g_V, g_E) (see module docstring)."""
    a = regime_asymptotes(gV, gE)
    h_iso = np.maximum(a["IR"], a["IE"])
    h_piezo = np.minimum(a["PR"], a["PE"])
    iso_label = np.where(a["IR"] >= a["IE"], "IR", "IE")
    piezo_label = np.where(a["PR"] <= a["PE"], "PR", "PE")
    labels = np.where(h_piezo > h_iso, piezo_label, iso_label)
    return labels if labels.ndim else str(labels)


def pan_hamrock(W, U, G, radius):
    """Pan & Hamrock (1989), Roelands + Dowson–Higginson, line contact.

    H_min = 1.714 W'^−0.128 U^0.694 G^0.568,  H_c = 2.922 W'^−0.166 U^0.692 G^0.470,
    h = H R. Returns (h_c, h_min) [m].
    """
    hc = 2.922 * np.asarray(W) ** -0.166 * np.asarray(U) ** 0.692 * G**0.470
    hm = 1.714 * np.asarray(W) ** -0.128 * np.asarray(U) ** 0.694 * G**0.568
    return hc * radius, hm * radius


def dowson_toyoda_central(W, U, G, radius):
    """Dowson & Toyoda (1979) central film, line contact: H_c = 3.06 U^0.69 G^0.56 W'^−0.10."""
    return 3.06 * np.asarray(U) ** 0.69 * G**0.56 * np.asarray(W) ** -0.10 * radius


def moes_central(W, U, G, radius):
    """Moes (1992) central film of a line contact, valid in all four regimes.

    With H = (h/R)(2U)^(−1/2) and the asymptotes H_RI = 3/M, H_EI = 2.621 M^(−1/5),
    H_RP = 1.287 L^(2/3), H_EP = 1.311 M^(−1/8) L^(3/4)::

        H = [(H_RI^(7/3) + H_EI^(7/3))^(3s/7) + (H_RP^(−7/2) + H_EP^(−7/2))^(−2s/7)]^(1/s)
        s = (7 + 8 exp(−2 H_EI/H_RI)) / 5

    (Venner & Lubrecht, *Multilevel Methods in Lubrication*, 2000, ch. 7.)

    Note: in these groups the rigid asymptotes are √1.5 above the exact rigid solutions —
    3/M gives h = 6 μ₀u_eR/w against Martin's 4.894 μ₀u_eR/w (central film, Reynolds exit)
    — so in the rigid regimes this fit over-predicts the film by ~22 %; it is meant for
    the elastic regimes, where tribodyn's numerical EHL agrees with it within ~4 %.
    """
    W = np.asarray(W, dtype=float)
    U = np.asarray(U, dtype=float)
    M, L = moes_groups(W, U, G)
    h_ri = 3.0 / M
    h_ei = 2.621 * M**-0.2
    h_rp = 1.287 * L ** (2.0 / 3.0)
    h_ep = 1.311 * M**-0.125 * L**0.75
    s = 0.2 * (7.0 + 8.0 * np.exp(-2.0 * h_ei / h_ri))
    iso = (h_ri ** (7.0 / 3.0) + h_ei ** (7.0 / 3.0)) ** (3.0 * s / 7.0)
    if np.all(np.asarray(G) == 0):
        piezo = 0.0
    else:
        piezo = (h_rp**-3.5 + h_ep**-3.5) ** (-2.0 * s / 7.0)
    H = (iso + piezo) ** (1.0 / s)
    return H * np.sqrt(2.0 * U) * radius

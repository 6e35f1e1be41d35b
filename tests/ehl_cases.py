"""Shared smooth-EHL test conditions: steel on steel, R = 10 mm, μ₀ = 0.04 Pa·s, G = 5000,
with load and speed chosen from the Moes groups (M, L)."""

import math

from tribodyn import Body, Lubricant, Material

STEEL = Material(210e9, 0.3)
PAIR = (Body(STEEL), Body(STEEL))
E_PRIME = 210e9 / 0.91
R, MU0, G = 0.01, 0.04, 5000.0
ALPHA = G / E_PRIME
OIL = Lubricant(MU0, ALPHA)


def conditions(M, L):
    """(w [N/m], u_e [m/s], W', U) for Moes M, L: U = (L/G)⁴/2, W' = M √(2U)."""
    U = (L / G) ** 4 / 2
    W = M * math.sqrt(2 * U)
    return W * E_PRIME * R, U * E_PRIME * R / MU0, W, U

"""Shared smooth-EHL test conditions: steel on steel, R = 10 mm, μ₀ = 0.04 Pa·s, G = 5000,
with load and speed chosen from the Moes groups (M, L)."""

import math

from tribodyn import Body, Lubricant, Material, Roughness

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


#: the oil and composite roughness of the bad-input and validity tests (μ₀ = 0.055 Pa·s,
#: α = 1.05e-8 1/Pa; η = 2.7e9 1/m², σ = 0.347 µm, β = 0.217 µm)
OIL_055 = Lubricant(0.055, 1.05e-8)
ROUGH = Roughness(2.7e9, 0.347e-6, 0.217e-6)

"""Shared smooth-EHL test conditions: steel on steel, R = 10 mm, μ₀ = 0.04 Pa·s, G = 5000,
with load and speed chosen from the Moes groups (M, L); the bad-input oil and roughness,
the thermal inlet analyses' fluid and a counter of transient solves, which the benchmarks
use too."""

import contextlib
import math

from tribodyn import Body, Lubricant, Material, Roughness
from tribodyn.contact.ehl import transient
from tribodyn.physics.thermal_oil import ThermalLubricant

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


def murch_wilson_oil(sheet):
    """The fluid of the thermal inlet analyses (Murch & Wilson 1975) with the inlet
    properties of the datasheet oil ``sheet`` (a ThermalLubricant): Newtonian, Barus,
    incompressible, no thermal expansion; μᵢ, α and β = −d ln μ/dT of ``sheet`` at its
    inlet temperature, k at p = 0 (the caller makes k independent of pressure through
    ``thermal_oil.CONDUCTIVITY_PRESSURE``).

    Returns (oil, fluid): fluid = dict(mu0 [Pa s], alpha [1/Pa], beta [1/K], k [W/(m K)],
    rho_c [J/(m³ K)]), the fluid's arguments of ``independent_inlet.grubin_inlet``."""
    beta = sheet.temperature_viscosity_coefficient()
    k0 = float(sheet.conductivity(0.0, sheet.inlet_temperature))
    oil = ThermalLubricant(
        sheet.inlet_temperature,
        viscosity=sheet.inlet_viscosity,
        viscosity_temperature_coefficient=beta,
        pressure_viscosity=sheet.inlet_pressure_viscosity,
        thermal_conductivity=k0,
        thermal_expansion=0.0,
        viscosity_model="barus",
        compressible=False,
    )
    fluid = dict(
        mu0=oil.inlet_viscosity,
        alpha=oil.inlet_pressure_viscosity,
        beta=beta,
        k=k0,
        rho_c=float(oil.volumetric_heat_capacity(0.0, oil.inlet_temperature)),
    )
    return oil, fluid


@contextlib.contextmanager
def counted_advances():
    """Count the transient solves (sub-step attempts) while the block runs: yields a list
    that gets, per call of ``TransientEHL._advance``, whether it converged. The method is
    restored on leaving the block."""
    calls = []
    orig = transient.TransientEHL._advance

    def counted(self, dt, cond):
        res = orig(self, dt, cond)
        calls.append(res.converged)
        return res

    transient.TransientEHL._advance = counted
    try:
        yield calls
    finally:
        transient.TransientEHL._advance = orig

"""The paper's numbers, in one place.

P. Andreou, P. Soleimanian, M. Mohammadpour, S. R. Bewsher, G. Offner. Effects of
Diamond-like Carbon and Tungsten-Carbide Carbon Coatings on Tribological Performance of
Cam–Tappet Conjunction. *Applied Sciences* 13 (2023) 7815. doi:10.3390/app13137815.

Everything the paper states (its Tables 4–7, Eq. 17, the conditions of its Figs. 5 and 6,
its headline claims) is defined here. Only the paper's comparison add-on imports it: the
claims table, the coating study with its Figs. 5 and 6, and the single-contact command
(``tests/test_layout.py`` lists them); the paper's case files state the same values. No
default of the physics objects, the case-file schema or the valvetrain is the paper's:
those are typical values (:mod:`tribodyn.physics.typical`,
:mod:`~tribodyn.physics.typical_engine`). Values the paper does not give but its case
needs are *assumptions*; those that other modules share are here too, named ``ASSUMED_*``. The errata of the paper that
these values correct are listed in ``docs/conventions.md``. Pure data: no imports from the
package, so every layer may use it. SI units throughout.
"""

from __future__ import annotations

from typing import TypedDict


class MaterialRow(TypedDict):
    """One material of Table 6: E [Pa], ν, ς, display label."""

    E: float
    nu: float
    boundary_shear_coefficient: float
    label: str


__all__ = [
    "STEEL",
    "DLC",
    "WCC",
    "MATERIALS",
    "COATING_THICKNESS",
    "ROUGHNESS",
    "LUBRICANT",
    "BOUNDARY_SHEAR_STRENGTH",
    "ENGINE_SPEED_RPM",
    "CAM_BASE_RADIUS",
    "CAM_MAX_LIFT",
    "CAM_WIDTH",
    "VALVE_MASS",
    "SPRING_MASS",
    "SPRING_RATE",
    "FIG5",
    "CLAIMS",
    "TOPOGRAPHY_BAND",
    "ASSUMED_DENSITY",
    "ASSUMED_FIG5_RADIUS",
]

# ----------------------------------------------------------------------------- Table 6
# Moduli printed as "MPa" in the paper: they are GPa (erratum). ς is the pressure
# coefficient of boundary shear strength (Eq. 17, from AFM measurements).
#: Steel (cam and tappet substrate): E [Pa], ν, ς.
STEEL: MaterialRow = {"E": 210e9, "nu": 0.3, "boundary_shear_coefficient": 0.185, "label": "steel"}
#: Diamond-like carbon coating ("Diamolith-DLC").
DLC: MaterialRow = {"E": 185e9, "nu": 0.3, "boundary_shear_coefficient": 0.44, "label": "DLC"}
#: Tungsten-carbide carbon coating ("Nitron-MC").
WCC: MaterialRow = {"E": 175e9, "nu": 0.3, "boundary_shear_coefficient": 0.54, "label": "WC-C"}
#: Table 6 by the material keys of the bundled case.
MATERIALS = {"steel": STEEL, "dlc": DLC, "wcc": WCC}
#: Coating layer thickness [m] (Table 6).
COATING_THICKNESS = 4e-6

# ----------------------------------------------------------------------------- Table 4
# "ζ" of Table 4 is the summit density η [1/m²] (erratum); σ the composite RMS roughness
# [m], β the mean summit radius [m]. One set per coating type.
ROUGHNESS = {
    "uncoated": {"asperity_density": 8.3e9, "rms": 0.408e-6, "summit_radius": 0.669e-6},
    "dlc": {"asperity_density": 3.8e9, "rms": 0.358e-6, "summit_radius": 0.332e-6},
    "wcc": {"asperity_density": 2.7e9, "rms": 0.347e-6, "summit_radius": 0.217e-6},
}

# ----------------------------------------------------------------------------- Table 5
#: SAE 5W-20: μ₀ [Pa·s], α [1/Pa], Eyring stress τ_E [Pa], limiting-shear slope Λ.
LUBRICANT = {
    "viscosity": 0.055,
    "pressure_viscosity": 1.05e-8,
    "eyring_stress": 2e6,
    "limiting_shear_coefficient": 0.08,
}
#: ρ₀ [kg/m³]: not given in the paper (assumed).
ASSUMED_DENSITY = 850.0

# ----------------------------------------------------------------------------- Eq. 17
#: τ₀ of the boundary shear law τ = τ₀ + ς p_a [Pa].
BOUNDARY_SHEAR_STRENGTH = 2e6

# ----------------------------------------------------------------------------- Table 7
ENGINE_SPEED_RPM = 3000.0
CAM_BASE_RADIUS = 0.015  #: [m]
CAM_MAX_LIFT = 9.3e-3  #: [m]
CAM_WIDTH = 0.012  #: "cam length", the axial contact length [m]
VALVE_MASS = 0.07  #: [kg]
SPRING_MASS = 0.036  #: [kg]
SPRING_RATE = 33750.0  #: [N/m]

# ----------------------------------------------------------------------------- Figs. 5, 6
#: R of Figs. 5/6 is not given in the paper (assumed, stated on the figures).
ASSUMED_FIG5_RADIUS = 0.010
#: Conditions of Figs. 5 and 6: load over the cam width [N], coating 5 µm, modulus ratios
#: E_c/E_s, entraining speed of Fig. 6 [m/s].
FIG5 = {
    "load_total": 633.0,
    "width": CAM_WIDTH,
    "radius": ASSUMED_FIG5_RADIUS,
    "thickness": 5e-6,
    "ratios": (0.25, 0.5, 1.0, 2.0, 4.0),
    "entrainment_speed": 15.31,
}

# ----------------------------------------------------------------------------- claims
#: The paper's headline claims (abstract, Section 3, conclusions).
CLAIMS = {
    "film_gain_pct": 41.0,  # coatings raise the film by up to 41 %
    "wcc_boundary_reduction_pct": 95.0,  # WC-C cuts boundary friction by > 95 % vs steel
    "wcc_vs_dlc_boundary_pct": 70.0,  # … and is ~70 % below DLC
    "wcc_boundary_gain_N": 0.44,  # boundary friction falls by up to 0.44 N (WC-C)
    "wcc_viscous_loss_N": 0.43,  # viscous friction rises by up to 0.43 N (WC-C)
}

# ----------------------------------------------------------------------------- Section 2.2
#: Band-pass filter of the measured topographies: wavelengths 0.25–250 µm [m].
TOPOGRAPHY_BAND = (0.25e-6, 250e-6)

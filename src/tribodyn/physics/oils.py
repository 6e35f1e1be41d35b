"""Bundled engine oils and the thermal properties of the contact materials.

**Oils** (``OILS``): fully formulated passenger-car engine oils of four SAE grades, as
typical datasheet values — kinematic viscosity at 40 and 100 °C (ASTM D445) and density at
15 °C (ASTM D4052) — of the kind printed in the "typical properties" table of
manufacturers' product data sheets for the grade. They describe a representative oil of
the grade, not one brand's certified batch: for a particular oil, enter its own data
sheet. Checks (tests): ν₁₀₀ lies inside the SAE J300 (2015) window of the grade
(20: 6.9–9.3, 30: 9.3–12.5, 40: 12.5–16.3 mm²/s), the ASTM D341 slope is that of an
engine oil and the So–Klaus α is in the usual range. Thermal conductivity and heat
capacity are not on data sheets; they default to Cragoe's estimates (see
:mod:`.thermal_oil`), α to the So & Klaus correlation.

**Materials** (``THERMAL_MATERIALS``): thermal conductivity k [W/(m K)], density ρ
[kg/m³] and specific heat c [J/(kg K)] of the tappet/cam steel and the coatings, from
the literature:

* steel (AISI 52100 bearing steel; the values of thermal EHL studies, e.g. Habchi 2018,
  *Finite Element Modeling of Elastohydrodynamic Lubrication Problems*, Wiley): k = 46,
  ρ = 7850, c = 470;
* DLC (hydrogenated amorphous carbon a-C:H, the Diamolith type): k = 1.0 (measured
  0.2–3.5 W/(m K) depending on sp³ and hydrogen content: Shamsa et al. 2006, Appl. Phys.
  Lett. 89:161921; Bullen et al. 2000, J. Appl. Phys. 88:6317), ρ = 1900 (a-C:H
  1.2–2.2 g/cm³: Robertson 2002, Mater. Sci. Eng. R 37:129), c = 700 (amorphous carbon
  near room temperature);
* WC-C (WC/a-C:H nanocomposite, the Nitron-MC / BALINIT C type): an amorphous-carbon
  matrix with tungsten-carbide grains; no direct measurement was found, so k = 2.0 is an
  estimate between a-C:H (≈ 1) and the range reported for W-containing carbon
  coatings (a few W/(m K)), ρ = 8000 (≈ 50 % WC by volume: WC 15.6 g/cm³, a-C:H ≈ 2),
  c = 300 (rule of mixtures, WC 200 J/(kg K)). Treat these as ASSUMED.

The effusivity e = √(kρc) decides how a surface heats under a short heat pulse: steel
≈ 13 000, DLC ≈ 1 150, WC-C ≈ 2 200 W s^½/(m² K): both coatings are thermal insulators on
steel.
"""

from __future__ import annotations

__all__ = ["OILS", "THERMAL_MATERIALS"]

#: name → datasheet keys of :class:`~tribodyn.physics.thermal_oil.ThermalLubricant`
#: (SI: m²/s, kg/m³) and a description.
OILS = {
    "0W-20": {
        "kinematic_viscosity_40": 44.0e-6,
        "kinematic_viscosity_100": 8.5e-6,
        "density": 845.0,
        "description": "SAE 0W-20 synthetic passenger-car oil (API SP / ILSAC GF-6), "
        "typical datasheet values",
    },
    "5W-20": {
        "kinematic_viscosity_40": 48.0e-6,
        "kinematic_viscosity_100": 8.6e-6,
        "density": 850.0,
        "description": "SAE 5W-20 passenger-car oil (the grade of Andreou et al. 2023), "
        "typical datasheet values",
    },
    "5W-30": {
        "kinematic_viscosity_40": 64.0e-6,
        "kinematic_viscosity_100": 11.0e-6,
        "density": 852.0,
        "description": "SAE 5W-30 synthetic passenger-car oil, typical datasheet values",
    },
    "10W-40": {
        "kinematic_viscosity_40": 100.0e-6,
        "kinematic_viscosity_100": 14.8e-6,
        "density": 868.0,
        "description": "SAE 10W-40 semi-synthetic passenger-car oil, typical datasheet values",
    },
}

#: name → (k [W/(m K)], ρ [kg/m³], c [J/(kg K)]), keyed like the bundled case's materials.
THERMAL_MATERIALS = {
    "steel": {"conductivity": 46.0, "density": 7850.0, "specific_heat": 470.0},
    "dlc": {"conductivity": 1.0, "density": 1900.0, "specific_heat": 700.0},
    "wcc": {"conductivity": 2.0, "density": 8000.0, "specific_heat": 300.0},
}

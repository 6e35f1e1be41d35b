"""Strength of the tappet's materials, safety factors of the contact stresses, and
Archard wear.

The values below are TYPICAL orders of magnitude, for first estimates only; a design
needs the measured properties of the actual coating and heat treatment. Each value is
marked "sourced" (checked against the source named) or "assumed" (no published value
was found for it; an engineering guess to be replaced by a measurement).

* Hardness-based yield (Tabor, *The Hardness of Metals*, 1951): Y ≈ H/3 for fully plastic
  indentation of metals. For hard coatings (high Y/E) the indentation is not fully plastic
  and H/Y is nearer 1.5–2.5 (Johnson, *Contact Mechanics*, 1985, §6.3), so H/3 is a
  conservative (low) yield estimate for DLC and WC-C.
* Steel tappet, through-hardened 100Cr6 (AISI 52100) or case-hardened, 58–62 HRC:
  653–746 HV (ASTM E140 conversion table), H = 7 GPa [sourced: 697 HV at 60 HRC ×
  9.807 MPa]. Ultimate tensile strength 2.0 GPa [sourced: ≈ 2.05 GPa at 58 HRC and
  2.17 GPa at 60 HRC in the approximate E140/SAE J417 conversion; 2.3–2.4 GPa for
  100Cr6 oil-quenched and tempered at 150–200 °C, 62–63 HRC, Lucefin technical card
  100Cr6 to EN ISO 683-17]; the lower end is taken.
* a-C:H (DLC): H = 20 GPa [sourced: 2000–2500 HV ≈ 20–25 GPa, Certess DCC a-C:H
  datasheet (IHI Hauzer); 27 GPa, E = 259 GPa for an a-C:H in Ayestarán Latorre et al.,
  Nat. Commun. 12 (2021), doi:10.1038/s41467-021-24766-6, Table 1; 12.8–22.2 GPa universal hardness of PACVD
  a-C:H, Dorner et al., Wear 249 (2001) 489].
* WC/a-C:H (WC-C): H = 12 GPa [sourced range, conservative end: 16–23 GPa for
  nanocomposite WC/a-C films, El Mrabet, Abad & Sánchez-López, Surf. Coat. Technol. 206
  (2011) 1913; metal-doped DLC 1000–2000 HV ≈ 10–20 GPa in suppliers' data].
* Coating tensile (cracking) strength: 1.8 GPa (DLC), 1.7 GPa (WC-C) [assumed: a
  crack-onset strain of ≈ 1 % times E; no published tensile strength of these films
  was found. Published data are fracture toughness instead, e.g. K_c ≈ 10 MPa√m for
  DLC on Si, Nastasi et al., J. Mater. Res. 14 (1999) 2173].
* Interface adhesion strength, shear and tension: 0.5 GPa [assumed: scratch tests give
  critical loads, not strengths (Bull, Surf. Coat. Technol. 50 (1991) 25; Bull, Tribol.
  Int. 30 (1997) 491); converting them needs a stress analysis of the scratch (e.g.
  Cemin, Boeira & Figueroa, Tribol. Int., doi:10.1016/j.triboint.2015.09.044); no
  value for a Cr-bonded a-C:H or WC/C on steel was found].
* Archard wear coefficients (dimensional, k = V/(F s)) in lubricated boundary sliding:
  steel 1e-7, a-C:H 1e-8, WC/C 3e-8 mm³/(N m) [assumed: orders of magnitude only; no
  source with these conditions was found. Podgornik et al., Surf. Coat. Technol.
  177–178 (2004) 558, report WC/C wear under starved, boundary and EHD lubrication
  without a k for these conditions; a WC/a-C:H roller survived 1.7 GPa contact pressure
  in boundary-lubricated rolling without measurable wear (PCS Instruments MPR study)].
  Use the coefficient measured on one's own tribometer. 1 mm³/(N m) = 1e-9 m³/(N m).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._typing import ArrayLike
from .._validation import InputError, check_array, check_nonnegative, check_positive

__all__ = [
    "Strength",
    "TYPICAL_STRENGTH",
    "TYPICAL_WEAR_COEFFICIENT",
    "WEAR_COEFFICIENT_SPREAD",
    "safety_factors",
    "archard_wear_depth_per_cycle",
    "hours_to_wear_through",
]


@dataclass(frozen=True)
class Strength:
    """Strength of a material [Pa].

    tensile_strength : stress at which the material cracks in tension.
    hardness : indentation hardness H.
    yield_strength : tensile yield Y; None: Tabor's Y = H/3.
    adhesion_shear, adhesion_tensile : strength of the coating–substrate interface
        (coatings only; None for a substrate).
    source : where the numbers come from (free text).
    """

    tensile_strength: float
    hardness: float
    yield_strength: float | None = None
    adhesion_shear: float | None = None
    adhesion_tensile: float | None = None
    source: str = ""

    def __post_init__(self):
        check_positive("tensile_strength", self.tensile_strength, "Pa")
        check_positive("hardness", self.hardness, "Pa")
        for name in ("yield_strength", "adhesion_shear", "adhesion_tensile"):
            v = getattr(self, name)
            if v is not None:
                check_positive(name, v, "Pa")

    @property
    def yield_stress(self) -> float:
        """Y [Pa]: the given yield strength, else Tabor's H/3."""
        return self.yield_strength if self.yield_strength is not None else self.hardness / 3.0


#: TYPICAL values (module docstring): replace by measured ones for a design.
TYPICAL_STRENGTH = {
    "steel": Strength(
        tensile_strength=2.0e9,
        hardness=7.0e9,
        source="100Cr6/case-hardened 58-62 HRC: H sourced (ASTM E140), UTS sourced (EN ISO "
        "683-17 tempering table, lower end); Y = H/3 (Tabor)",
    ),
    "dlc": Strength(
        tensile_strength=1.8e9,
        hardness=20e9,
        adhesion_shear=0.5e9,
        adhesion_tensile=0.5e9,
        source="a-C:H: H sourced (Certess DCC 2000-2500 HV; Ayestaran Latorre 2021); "
        "tensile strength assumed (~1 % crack-onset strain x E); adhesion assumed",
    ),
    "wcc": Strength(
        tensile_strength=1.7e9,
        hardness=12e9,
        adhesion_shear=0.5e9,
        adhesion_tensile=0.5e9,
        source="WC/a-C:H: H sourced, conservative end (El Mrabet 2011: 16-23 GPa; Me-DLC "
        "1000-2000 HV); tensile strength assumed (~1 % strain x E); adhesion assumed",
    ),
}

#: ASSUMED dimensional Archard coefficients k [m³/(N m) = 1/Pa], lubricated boundary
#: sliding (module docstring: no source found); the wear functions take k from the user.
TYPICAL_WEAR_COEFFICIENT = {"steel": 1e-16, "dlc": 1e-17, "wcc": 3e-17}
#: Factor either way around an assumed :data:`TYPICAL_WEAR_COEFFICIENT` that its range
#: spans: the values are orders of magnitude only (module docstring), so the wear
#: depth and the hours to wear through are given over k/10 … 10 k.
WEAR_COEFFICIENT_SPREAD = 10.0


def _factor(strength: float | None, stress: float) -> float:
    """strength / stress; inf where the stress does not load the mode (≤ 0), NaN where
    either is undefined."""
    if strength is None or not math.isfinite(stress):
        return math.nan
    return strength / stress if stress > 0.0 else math.inf


def safety_factors(stress, substrate: Strength, coating: Strength | None = None) -> dict:
    """Safety factors (strength / peak stress; > 1 survives) of a
    :class:`~tribodyn.physics.stress.SubsurfaceStress`, or of a mapping {peak name:
    value [Pa]} (e.g. cycle maxima):

    * ``coating_tension``: tensile strength / largest tensile principal stress in the
      coating (surface included);
    * ``coating_yield``: Y_c / von Mises in the coating;
    * ``interface_shear``, ``interface_tension``: adhesion / max |σ_xz|, max tensile σ_zz
      at z = h;
    * ``substrate_yield``: Y_s / von Mises in the substrate;
    * ``surface_tension``: tensile strength of the surface material / largest tensile
      principal stress on the surface.
    """
    if isinstance(stress, dict):
        v = {k: float(val) for k, val in stress.items()}
    else:
        v = {k: pk.value for k, pk in stress.peaks().items()}
    surface = coating if coating is not None else substrate
    out = {
        "substrate_yield": _factor(substrate.yield_stress, v["max_von_mises_substrate"]),
        "surface_tension": _factor(surface.tensile_strength, v["max_tension_surface"]),
    }
    if coating is not None:
        out.update(
            coating_tension=_factor(coating.tensile_strength, v["max_tension_coating"]),
            coating_yield=_factor(coating.yield_stress, v["max_von_mises_coating"]),
            interface_shear=_factor(coating.adhesion_shear, v["max_interface_shear"]),
            interface_tension=_factor(coating.adhesion_tensile, v["max_interface_tension"]),
        )
    return out


def archard_wear_depth_per_cycle(
    time: ArrayLike,
    asperity_load: ArrayLike,
    sliding_speed: ArrayLike,
    wear_coefficient: float,
    swept_length: float,
) -> float:
    """Mean wear depth per cycle [m] (Archard, J. Appl. Phys. 24 (1953) 981):

        Δh = k ∫ w_a |u_s| dt / L

    with w_a the asperity load per unit width [N/m] (the fluid-borne load causes no
    wear), u_s the sliding speed [m/s], k the dimensional wear coefficient [m³/(N m)],
    and L [m] the length of surface over which the wear is spread (the band of the
    tappet face swept by the contact, or the cam's perimeter section). Samples where w_a
    is NaN (unloaded) count as zero."""
    t = check_array("time", time, min_size=2)
    w = check_array("asperity_load", asperity_load, finite=False)
    us = check_array("sliding_speed", sliding_speed)
    if w.shape != t.shape or us.shape != t.shape:
        raise InputError("time, asperity_load and sliding_speed must have the same shape")
    k = check_nonnegative("wear_coefficient", wear_coefficient, "m^3/(N m)")
    length = check_positive("swept_length", swept_length, "m")
    rate = np.where(np.isfinite(w), np.maximum(w, 0.0), 0.0) * np.abs(us)
    return float(k * np.sum(0.5 * (rate[1:] + rate[:-1]) * np.diff(t)) / length)


def hours_to_wear_through(thickness: float, depth_per_cycle: float, cycles_per_hour: float):
    """Hours until a coating of ``thickness`` [m] is worn through at ``depth_per_cycle``
    [m] and ``cycles_per_hour`` cam revolutions per hour (inf without wear)."""
    h = check_positive("thickness", thickness, "m")
    d = check_nonnegative("depth_per_cycle", depth_per_cycle, "m")
    n = check_positive("cycles_per_hour", cycles_per_hour, "1/h")
    return math.inf if d == 0.0 else h / (d * n)

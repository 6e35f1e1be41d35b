"""Coating-modulus studies of a single line contact (paper Figs. 5 and 6).

The paper's conditions (:data:`tribodyn.paper.FIG5`): coating 5 µm, w = 633 N over the
12 mm cam width, u = 15.31 m/s (EHL); coating/steel modulus ratios 0.25 … 4. The paper does
not give the radius of curvature: R = 10 mm is assumed here and stated on every figure.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .. import paper
from ..config.build import as_built
from ..contact.dry import DryContactResult, solve_dry_contact
from ..contact.ehl import EHLResult, solve_ehl
from ..physics.hertz import hertz_line_contact
from ..physics.lubricant import Lubricant
from ..physics.materials import STEEL, Body, Coating, Material

__all__ = [
    "DryCoatingCase",
    "ModulusCase",
    "PairCase",
    "EHLCoatingStudy",
    "dry_coating_study",
    "dry_grid",
    "HertzReference",
    "dry_hertz_reference",
    "ehl_coating_study",
    "SAE_5W20",
    "DRY_CONDITIONS",
]

#: The paper's Table 5 lubricant (SAE 5W-20), with the paper case's assumed ρ₀.
SAE_5W20 = Lubricant(
    viscosity=paper.LUBRICANT["viscosity"],
    pressure_viscosity=paper.LUBRICANT["pressure_viscosity"],
    density=paper.ASSUMED_DENSITY,
    eyring_stress=paper.LUBRICANT["eyring_stress"],
    limiting_shear_coefficient=paper.LUBRICANT["limiting_shear_coefficient"],
)

_FIG5 = paper.FIG5
#: Conditions of the dry study of Fig. 5 (the defaults of :func:`dry_coating_study`).
DRY_CONDITIONS = {k: v for k, v in _FIG5.items() if k != "ratios"}


@dataclass
class DryCoatingCase:
    """One dry contact of Fig. 5: label, modulus ratio E_c/E_s, result."""

    label: str
    ratio: float | None
    result: DryContactResult


@dataclass
class ModulusCase:
    """One smooth EHL contact of Fig. 6 with a coating of modulus ratio E_c/E_s."""

    label: str
    ratio: float
    result: EHLResult


@dataclass
class PairCase:
    """One smooth EHL contact of Fig. 6 with a real pair; ``material`` is the coating's
    key in the case's ``[materials]`` (None: uncoated steel)."""

    label: str
    material: str | None
    result: EHLResult


@dataclass
class EHLCoatingStudy:
    """Fig. 6: smooth EHL for modulus ratios and for the real pairs, with the conditions."""

    conditions: dict
    ratios: list[ModulusCase] = field(default_factory=list)
    pairs: list[PairCase] = field(default_factory=list)

    @property
    def results(self) -> list[EHLResult]:
        return [c.result for c in self.ratios] + [c.result for c in self.pairs]


def dry_coating_study(
    ratios=_FIG5["ratios"],
    *,
    thickness=_FIG5["thickness"],
    load_total=_FIG5["load_total"],
    width=_FIG5["width"],
    radius=_FIG5["radius"],
    substrate: Material = STEEL,
    coating_nu: float = 0.3,
    n: int = 1024,
) -> list[DryCoatingCase]:
    """Dry pressure for a steel cam on a coated steel tappet, one case per modulus ratio."""
    w = load_total / width
    cases = []
    for ratio in ratios:
        coat = Coating(E=substrate.E * ratio, nu=coating_nu, thickness=thickness)
        res = solve_dry_contact(w, radius, (Body(substrate), Body(substrate, coat)), n=n)
        cases.append(DryCoatingCase(f"E_c/E_s = {ratio:g}", ratio, res))
    return cases


#: the dry study's profiles reach ± this many times the largest half-width
DRY_SPAN = 1.3


def dry_grid(cases: list[DryCoatingCase], n: int = 401) -> np.ndarray:
    """``n`` positions x [m] spanning the dry study ``cases``: ±DRY_SPAN times their
    largest half-width."""
    half = max(DRY_SPAN * c.result.half_width for c in cases)
    return np.linspace(-half, half, n)


@dataclass(frozen=True)
class HertzReference:
    """The Hertz line contact of uncoated steel beside the dry study: pressure [Pa] at
    x [m], half-width b and maximum pressure p_h."""

    x: np.ndarray
    pressure: np.ndarray
    half_width: float
    max_pressure: float


def dry_hertz_reference(
    cases: list[DryCoatingCase],
    conditions: dict = DRY_CONDITIONS,
    substrate: Material = STEEL,
    n: int = 801,
) -> HertzReference | None:
    """Hertz (:func:`~tribodyn.physics.hertz.hertz_line_contact`) of a steel pair,
    E' = E/(1 − ν²), at the dry study's load per width and radius (``conditions``), on
    :func:`dry_grid` of ``n`` points; None without dry cases."""
    if not cases:
        return None
    w = conditions["load_total"] / conditions["width"]
    h = hertz_line_contact(w, conditions["radius"], substrate.E / (1.0 - substrate.nu**2))
    x = dry_grid(cases, n)
    return HertzReference(x, np.asarray(h.pressure(x), float), h.half_width, h.max_pressure)


def ehl_coating_study(
    lubricant: Lubricant = SAE_5W20,
    case=None,
    *,
    ratios=_FIG5["ratios"],
    thickness=_FIG5["thickness"],
    load_total=_FIG5["load_total"],
    width=_FIG5["width"],
    radius=_FIG5["radius"],
    entrainment_speed=_FIG5["entrainment_speed"],
    pair_thickness: float = paper.COATING_THICKNESS,
) -> EHLCoatingStudy:
    """Smooth EHL line contacts of the paper's Fig. 6 conditions.

    ``ratios``: coating/steel modulus ratios with a ``thickness`` coating; ``pairs``: steel
    and the coatings of the case's ``[materials]`` (the paper's DLC 185 GPa and WC-C 175 GPa
    without a case), ``pair_thickness`` thick. Pure rolling (u_s = 0): the pressure and
    film do not depend on sliding in this isothermal model.
    """
    w = load_total / width
    out = EHLCoatingStudy(
        conditions=dict(
            load_total=load_total,
            width=width,
            radius=radius,
            thickness=thickness,
            entrainment_speed=entrainment_speed,
            pair_thickness=pair_thickness,
        )
    )
    steel = Body(STEEL)
    for ratio in ratios:
        coat = Coating(E=STEEL.E * ratio, nu=STEEL.nu, thickness=thickness)
        r = solve_ehl(w, radius, entrainment_speed, 0.0, (steel, Body(STEEL, coat)), lubricant)
        out.ratios.append(ModulusCase(f"E_c/E_s = {ratio:g}", ratio, r))
    if case is not None:  # a Case or BuiltCase
        built = as_built(case)
        coatings = [
            (m.label or k, k, built.materials[k])
            for k, m in built.case.materials.items()
            if k != "steel"
        ]
    else:
        coatings = [
            (v["label"], k, Material(v["E"], v["nu"]))
            for k, v in paper.MATERIALS.items()
            if k != "steel"
        ]
    r = solve_ehl(w, radius, entrainment_speed, 0.0, (steel, steel), lubricant)
    out.pairs.append(PairCase("steel (uncoated)", None, r))
    for label, key, mat in coatings:
        tappet = Body(STEEL, Coating(E=mat.E, nu=mat.nu, thickness=pair_thickness))
        r = solve_ehl(w, radius, entrainment_speed, 0.0, (steel, tappet), lubricant)
        out.pairs.append(PairCase(f"{label} {pair_thickness * 1e6:g} µm", key, r))
    return out

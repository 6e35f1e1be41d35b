"""Coating-modulus studies of a single line contact (paper Figs. 5 and 6).

The paper's conditions (:data:`tribodyn.paper.FIG5`): coating 5 µm, w = 633 N over the
12 mm cam width, u = 15.31 m/s (EHL); coating/steel modulus ratios 0.25 … 4. The paper does
not give the radius of curvature: R = 10 mm is assumed here and stated on every figure.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

import numpy as np

from .. import paper
from ..config.build import as_built
from ..contact.dry import solve_dry_contact
from ..contact.ehl import EHLResult, solve_ehl
from ..physics.hertz import hertz_line_contact
from ..physics.lubricant import Lubricant
from ..physics.materials import STEEL, Body, Coating

__all__ = [
    "CoatingCase",
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

_FIG5: dict[str, Any] = paper.FIG5
#: Conditions of the dry study of Fig. 5 (:func:`dry_coating_study`).
DRY_CONDITIONS = {k: v for k, v in _FIG5.items() if k != "ratios"}


@dataclass
class CoatingCase:
    """One contact of Fig. 5 (dry) or Fig. 6 (smooth EHL): label, modulus ratio E_c/E_s
    (None: a real pair or uncoated steel) and result."""

    label: str
    ratio: float | None
    result: Any  #: DryContactResult or EHLResult


@dataclass
class EHLCoatingStudy:
    """Fig. 6: smooth EHL for modulus ratios and for the real pairs, with the conditions."""

    conditions: dict
    ratios: list[CoatingCase] = field(default_factory=list)
    pairs: list[CoatingCase] = field(default_factory=list)

    @property
    def results(self) -> list[EHLResult]:
        return [c.result for c in self.ratios] + [c.result for c in self.pairs]


def dry_coating_study() -> list[CoatingCase]:
    """Dry pressure for a steel cam on a steel tappet with a coating of ν = 0.3 at the
    paper's conditions (:data:`DRY_CONDITIONS`; 1024 grid points), one case per modulus
    ratio of Fig. 5."""
    c = DRY_CONDITIONS
    w, steel = c["load_total"] / c["width"], Body(STEEL)
    cases = []
    for ratio in _FIG5["ratios"]:
        coat = Coating(E=STEEL.E * ratio, nu=0.3, thickness=c["thickness"])
        res = solve_dry_contact(w, c["radius"], (steel, Body(STEEL, coat)), n=1024)
        cases.append(CoatingCase(f"E_c/E_s = {ratio:g}", ratio, res))
    return cases


#: the dry study's profiles reach ± this many times the largest half-width
DRY_SPAN = 1.3


def dry_grid(cases: list[CoatingCase], n: int = 401) -> np.ndarray:
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


def dry_hertz_reference(cases: list[CoatingCase], n: int = 801) -> HertzReference | None:
    """Hertz (:func:`~tribodyn.physics.hertz.hertz_line_contact`) of a steel pair,
    E' = E/(1 − ν²), at the dry study's load per width and radius
    (:data:`DRY_CONDITIONS`), on :func:`dry_grid` of ``n`` points; None without dry
    cases."""
    if not cases:
        return None
    c = DRY_CONDITIONS
    h = hertz_line_contact(c["load_total"] / c["width"], c["radius"], STEEL.E / (1.0 - STEEL.nu**2))
    x = dry_grid(cases, n)
    return HertzReference(x, np.asarray(h.pressure(x), float), h.half_width, h.max_pressure)


def ehl_coating_study(lubricant: Lubricant, case) -> EHLCoatingStudy:
    """Smooth EHL line contacts at the paper's Fig. 6 conditions in ``lubricant``.

    ``ratios``: coating/steel modulus ratios with the Fig. 6 coating thickness; ``pairs``:
    steel and the coatings of the ``[materials]`` of ``case`` (a Case or BuiltCase),
    :data:`tribodyn.paper.COATING_THICKNESS` thick. Pure rolling (u_s = 0): the pressure
    and film do not depend on sliding in this isothermal model.
    """
    c = {k: _FIG5[k] for k in ("load_total", "width", "radius", "thickness", "entrainment_speed")}
    out = EHLCoatingStudy(conditions={**c, "pair_thickness": paper.COATING_THICKNESS})
    w, steel = c["load_total"] / c["width"], Body(STEEL)

    def solve(tappet: Body) -> EHLResult:
        return solve_ehl(w, c["radius"], c["entrainment_speed"], 0.0, (steel, tappet), lubricant)

    for ratio in _FIG5["ratios"]:
        coat = Coating(E=STEEL.E * ratio, nu=STEEL.nu, thickness=c["thickness"])
        out.ratios.append(CoatingCase(f"E_c/E_s = {ratio:g}", ratio, solve(Body(STEEL, coat))))
    built = as_built(case)
    out.pairs.append(CoatingCase("steel (uncoated)", None, solve(steel)))
    h = paper.COATING_THICKNESS
    for key, m in built.case.materials.items():
        if key != "steel":
            mat = built.materials[key]
            coat = Coating(E=mat.E, nu=mat.nu, thickness=h)
            out.pairs.append(
                CoatingCase(f"{m.label or key} {h * 1e6:g} µm", None, solve(Body(STEEL, coat)))
            )
    return out

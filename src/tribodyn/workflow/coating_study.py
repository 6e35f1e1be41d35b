"""Coating-modulus studies of a single line contact (paper Figs. 5 and 6).

The paper's conditions: coating 5 µm, w = 633 N over the 12 mm cam width, u = 15.31 m/s
(EHL); coating/steel modulus ratios 0.25 … 4. The paper does not give the radius of
curvature: R = 10 mm is assumed here and stated on every figure.
"""

from __future__ import annotations

from dataclasses import dataclass

from ..contact.dry import DryContactResult, solve_dry_contact
from ..contact.ehl import solve_ehl
from ..physics.lubricant import SAE_5W20, Lubricant
from ..physics.materials import DLC, STEEL, WCC, Body, Coating, Material

__all__ = ["PAPER_FIG5", "DryCoatingCase", "dry_coating_study", "ehl_coating_study"]

#: Conditions of the paper's Figs. 5/6 (radius assumed).
PAPER_FIG5 = dict(load_total=633.0, width=0.012, radius=0.010, thickness=5e-6,
                  ratios=(0.25, 0.5, 1.0, 2.0, 4.0), entrainment_speed=15.31)


@dataclass
class DryCoatingCase:
    label: str
    ratio: float | None
    result: DryContactResult


def dry_coating_study(ratios=PAPER_FIG5["ratios"], *, thickness=PAPER_FIG5["thickness"],
                      load_total=PAPER_FIG5["load_total"], width=PAPER_FIG5["width"],
                      radius=PAPER_FIG5["radius"], substrate: Material = STEEL,
                      coating_nu: float = 0.3, n: int = 1024) -> list[DryCoatingCase]:
    """Dry pressure for a steel cam on a coated steel tappet, one case per modulus ratio."""
    w = load_total / width
    cases = []
    for ratio in ratios:
        coat = Coating(E=substrate.E * ratio, nu=coating_nu, thickness=thickness)
        res = solve_dry_contact(w, radius, (Body(substrate), Body(substrate, coat)), n=n)
        cases.append(DryCoatingCase(f"E_c/E_s = {ratio:g}", ratio, res))
    return cases


def ehl_coating_study(lubricant: Lubricant = SAE_5W20, case=None, *,
                      ratios=PAPER_FIG5["ratios"], thickness=PAPER_FIG5["thickness"],
                      load_total=PAPER_FIG5["load_total"], width=PAPER_FIG5["width"],
                      radius=PAPER_FIG5["radius"],
                      entrainment_speed=PAPER_FIG5["entrainment_speed"],
                      pair_thickness: float = 4e-6) -> dict:
    """Smooth EHL line contacts of the paper's Fig. 6 conditions.

    ``"ratios"``: coating/steel modulus ratios with a ``thickness`` coating;
    ``"pairs"``: the paper's real pairs (steel; DLC 185 GPa and WC-C 175 GPa,
    ``pair_thickness``; materials from the case when given). Pure rolling (u_s = 0): the
    pressure and film do not depend on sliding in this isothermal model.
    """
    w = load_total / width
    out = {"ratios": [], "pairs": [], "conditions": dict(
        load_total=load_total, width=width, radius=radius, thickness=thickness,
        entrainment_speed=entrainment_speed, pair_thickness=pair_thickness)}
    for ratio in ratios:
        coat = Coating(E=STEEL.E * ratio, nu=0.3, thickness=thickness)
        r = solve_ehl(w, radius, entrainment_speed, 0.0, (Body(STEEL), Body(STEEL, coat)),
                      lubricant)
        out["ratios"].append((f"E_c/E_s = {ratio:g}", ratio, r))
    mats = [("steel (uncoated)", None), ("DLC", DLC), ("WC-C", WCC)]
    if case is not None:
        m = case.materials
        mats = [("steel (uncoated)", None)] + [
            (m[k].label or k, case.material(k)) for k in m if k not in ("steel",)]
    for label, mat in mats:
        tappet = Body(STEEL) if mat is None else Body(
            STEEL, Coating(E=mat.E, nu=mat.nu, thickness=pair_thickness))
        if mat is not None:
            label = f"{label} {pair_thickness * 1e6:g} µm"
        r = solve_ehl(w, radius, entrainment_speed, 0.0, (Body(STEEL), tappet), lubricant)
        out["pairs"].append((label, r))
    return out

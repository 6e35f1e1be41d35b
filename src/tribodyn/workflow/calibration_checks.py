"""Checks of a friction calibration (:mod:`tribodyn.workflow.calibration`) against input
mistakes that a least-squares fit does not see by itself.

**Repeated rows.** A row copied twice (the same u_e, u_s, w, μ and R) is not a second
measurement: it would shrink the uncertainty s²(JᵀJ)⁻¹ by √2 as if it were.
:func:`distinct_points` keeps the first of exactly equal points and says which were
dropped. Repeated measurements at the same conditions differ in μ and are all kept: their
scatter is what the uncertainty is made of.

**Inputs in the wrong unit.** A viscosity given in mPa·s (or cP) as Pa·s is 1000× too high,
the Moes film about 1000^0.7 ≈ 125× too thick, and the fit makes up for the missing
asperity contact with a boundary coefficient ς several times too large, and may still
meet its tolerances. A tribologist sees it from the Stribeck curve: the measured friction
keeps rising towards low speed where the inputs put the contact in full film (λ = h_c/σ ≫ 3),
so the model cannot follow the curve's shape and the fitted values leave the range
known for oils and surfaces. :func:`fit_problems` flags

* a fit that does not follow the data: an RMS residual above :data:`LACK_OF_FIT` of the
  mean measured μ while the model explains less than 90 % of its variance (R² < 0.9);
* fitted values outside :data:`PLAUSIBLE`, ranges 3–5× wider than the published ones of
  :mod:`tribodyn.physics.typical`, which no real oil or surface pair reaches;

and :func:`units_hint` then refits with the viscosity 1000× lower and higher (the
mPa·s/Pa·s slip) and names it when the data fit far better (a quarter of the squared
residual or less) with plausible values; else it lists the inputs and units to check with
the film parameters the inputs give.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import fields, replace
from typing import Any

import numpy as np

from .._validation import InputError
from ..physics import typical

__all__ = ["PLAUSIBLE", "LACK_OF_FIT", "distinct_points", "fit_problems", "units_hint"]

#: RMS residual, as a share of the mean measured friction coefficient, above which a fit
#: that explains less than 90 % of the variance of μ does not describe the data.
LACK_OF_FIT = 0.1

_BOUNDARY_LOW = min(v.low for v in typical.BOUNDARY_FRICTION.values())
_BOUNDARY_HIGH = max(v.high for v in typical.BOUNDARY_FRICTION.values())

#: Fitted values a real oil or surface pair can have: the published ranges of
#: :mod:`tribodyn.physics.typical` widened 3× (boundary friction, Λ above) to 5× (τ_E,
#: Λ below). name → (low, high, what it is).
PLAUSIBLE: dict[str, tuple[float, float, str]] = {
    "boundary_shear_coefficient": (
        _BOUNDARY_LOW / 3.0,
        _BOUNDARY_HIGH * 3.0,
        "boundary friction coefficients of lubricated pairs",
    ),
    "eyring_stress": (
        typical.EYRING_STRESS.low / 5.0,
        typical.EYRING_STRESS.high * 5.0,
        "Eyring stresses of oils",
    ),
    "limiting_shear_coefficient": (
        typical.LIMITING_SHEAR_COEFFICIENT.low / 5.0,
        typical.LIMITING_SHEAR_COEFFICIENT.high * 3.0,
        "limiting-shear pressure coefficients of oils",
    ),
}

#: Factors tried on the viscosity: mPa·s (cP) given as Pa·s, and the reverse.
VISCOSITY_FACTORS = (1e-3, 1e3)


def distinct_points(data):
    """``(data without exact repeats, 1-based numbers of the dropped points)``: of points
    equal in every column (u_e, u_s, w, μ and R if given) the first is kept."""
    arrays = {f.name: getattr(data, f.name) for f in fields(data)}
    table = np.column_stack([v for v in arrays.values() if v is not None])
    _, first = np.unique(table, axis=0, return_index=True)
    keep = np.sort(first)
    if keep.size == table.shape[0]:
        return data, []
    dropped = sorted(set(range(table.shape[0])) - set(keep.tolist()))
    if keep.size < 3:
        raise InputError(
            f"only {keep.size} distinct measured points ({len(dropped)} rows repeat "
            "another exactly); at least 3 are needed"
        )
    kept = {k: None if v is None else v[keep] for k, v in arrays.items()}
    return replace(data, **kept), [i + 1 for i in dropped]


def repeated_message(dropped: list[int]) -> str:
    """Warning for the points :func:`distinct_points` dropped."""
    shown = ", ".join(map(str, dropped[:10])) + (", …" if len(dropped) > 10 else "")
    return (
        f"{len(dropped)} measured point(s) repeat an earlier one exactly (points {shown}, "
        "counted from 1 in the order given): each is counted once, since a copied row is "
        "not a new measurement and would shrink the ± values (repeated measurements differ "
        "in μ and are all kept)"
    )


def implausible(values: dict[str, float]) -> list[str]:
    """Fitted parameters outside :data:`PLAUSIBLE`, as message parts."""
    out = []
    for name, v in values.items():
        if name in PLAUSIBLE:
            low, high, what = PLAUSIBLE[name]
            if not low <= v <= high:
                out.append(f"{name} = {v:.3g} lies outside the {what} ({low:.3g} to {high:.3g})")
    return out


def fit_problems(measured: np.ndarray, residuals: np.ndarray, values: dict[str, float]) -> list:
    """Signs that a converged fit does not describe the data (module docstring)."""
    out = []
    mean = float(np.mean(measured))
    rms = float(np.sqrt(np.mean(residuals**2)))
    ss_tot = float(np.sum((measured - mean) ** 2))
    r2 = 1.0 - float(residuals @ residuals) / ss_tot if ss_tot > 0.0 else float("nan")
    if mean > 0.0 and rms > LACK_OF_FIT * mean and not r2 >= 0.9:
        out.append(
            f"the model does not follow the measured friction: RMS residual {rms:.3g} is "
            f"{100.0 * rms / mean:.0f} % of the mean measured μ {mean:.3g} (R² = {r2:.2f})"
        )
    return out + implausible(values)


def units_hint(
    setup,
    cost: float,
    refit: Callable[[Any], tuple[float, dict[str, float], bool]],
    film_parameter: np.ndarray | None,
) -> str:
    """What to check when :func:`fit_problems` found something (module docstring).

    refit(setup) → (cost, fitted values, any value at its bound) of the same fit with
    another setup; film_parameter: λ = h_c/σ of the points at the given inputs (None:
    smooth surfaces)."""
    mu0 = setup.lubricant.viscosity
    for factor in VISCOSITY_FACTORS:
        try:
            other = replace(setup, lubricant=replace(setup.lubricant, viscosity=mu0 * factor))
        except InputError:  # outside the viscosity's allowed range
            continue
        c, values, at_bound = refit(other)
        if c <= 0.25 * cost and not at_bound and not implausible(values):
            way = "high" if factor < 1.0 else "low"
            ratio = 1.0 / factor if factor < 1.0 else factor
            unit = "mPa·s or cP given as Pa·s" if factor < 1.0 else "Pa·s given as mPa·s"
            return (
                f"the given viscosity {mu0:.4g} Pa·s is probably {ratio:g}× "
                f"too {way} ({unit}?): with {mu0 * factor:.4g} Pa·s the data fit with "
                f"{100.0 * (c / cost) ** 0.5:.0f} % of the RMS residual and plausible values "
                f"({', '.join(f'{k} = {v:.3g}' for k, v in values.items())}); give the "
                "viscosity in Pa·s (1 mPa·s = 1 cP = 0.001 Pa·s)"
            )
    lam = ""
    if film_parameter is not None and film_parameter.size:
        lam = (
            f"; at these inputs the film parameter λ = h_c/σ of the points spans "
            f"{float(np.min(film_parameter)):.2g} to {float(np.max(film_parameter)):.2g} "
            "(boundary friction needs λ ≲ 1; full film λ ≳ 3)"
        )
    return (
        "check the units of the inputs: viscosity [Pa·s], pressure-viscosity coefficient "
        "[1/Pa], load per unit length [N/m], radius [m], RMS roughness [m] and the "
        f"measured speeds [m/s]{lam}"
    )

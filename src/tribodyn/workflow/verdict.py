"""The coating verdict: does a surface set lower the friction energy per cycle against the
reference set, by how much, and over what range of the uncertain friction inputs.

The range is computed after the EHL solve, from the stored traces, without solving
again:

* **Boundary friction.** Eq. 17, τ_b = τ₀ A_a/A + ς p_a, integrates to
  F_b = τ₀ A_a + ς W_a with W_a the asperity load. The EHL solution does not depend on
  ς, so F_b(ς') = F_b + (ς' − ς) W_a exactly, sample by sample.
* **Viscous friction.** F_v = ∫ min(τ_E asinh(μ u_s/(τ_E h)), Λ p) dx (Eyring, capped
  by the limiting shear stress). For τ_E' = r_τ τ_E, τ asinh(a/τ) lies between
  min(1, r_τ) and max(1, r_τ) times its value (asinh is concave), and Λ' = r_Λ Λ
  scales the cap by r_Λ; so F_v(τ_E', Λ') lies within k_lo F_v … k_hi F_v with
  k_lo = min(1, r_τ,lo, r_Λ,lo) and k_hi = max(1, r_τ,hi, r_Λ,hi). The range uses
  these bounds (a conservative envelope, not a new solve); the film is that of the
  inputs in use.
* **Energy.** E = Σ (F_v + F_b) |u_s| Δt over the loaded samples, as the summary's
  ``friction_energy_per_cycle_J``.

The published ranges are those of :mod:`tribodyn.physics.typical`: ς of each pair
(:func:`~tribodyn.physics.typical.boundary_friction_range`), τ_E
(:data:`~tribodyn.physics.typical.EYRING_STRESS`) and Λ
(:data:`~tribodyn.physics.typical.LIMITING_SHEAR_COEFFICIENT`). ``range_pct`` moves ς of
both pairs to the same end of their ranges together (one oil moves both) and the
viscous factor of both sets together (one oil); ``range_independent_pct`` lets each
pair's ς take either end independently (the widest reading). The
surface's spectrum (H, λ_s) is not in the range: it changes the film and needs new EHL
runs (benchmarks/default_surface_law.py gives its effect on the bundled rig).
"""

from __future__ import annotations

import itertools
import math
from typing import Any

import numpy as np

from ..config.build import as_built, build
from ..physics import typical

__all__ = [
    "ENGINE_METHOD",
    "METHOD",
    "boundary_ranges",
    "coating_verdicts",
    "set_energy_function",
    "verdict_sentence",
    "verdicts_from_energies",
    "viscous_factor_bounds",
]

#: How the verdict's range is computed (``coating_verdict.method``).
METHOD = (
    "Change of the friction energy per cycle against the reference set. Range: "
    "recomputed from the stored traces without a new EHL solve, boundary friction "
    "exactly (F_b + (ς' − ς) W_a), viscous friction within the bounds k·F_v that the "
    "published ranges of τ_E and Λ allow (Eyring law, limiting shear stress Λp); ς of "
    "both pairs at the same end of their published ranges together, the viscous factor "
    "of both sets together (one oil; range_independent_pct: each pair's ς "
    "independently). Published ranges: tribodyn.physics.typical. Not in the range: the "
    "surface's spectrum (Hurst exponent, cutoffs) of the surface law, which needs new "
    "EHL runs (benchmarks/default_surface_law.py sensitivity gives its effect on the "
    "bundled rig)."
)


#: How the engine's verdict is computed (``engine.surface_sets.*.coating_verdict``).
ENGINE_METHOD = (
    "Change of the engine's valvetrain friction energy per cycle (and so of its FMEP) "
    "against the reference set. Each lobe kind's cam–tappet energy is scaled by the "
    "ratio E(ς', k)/E(ς, 1) of its single-valve study (recomputed from the stored traces "
    "as for a run: boundary friction exactly, viscous friction within the bounds of the "
    "τ_E and Λ ranges); tappet-bore, valve-guide and journal friction are held at their "
    "values. " + METHOD.split(". Range: ", 1)[1]
)


def _ratio_bounds(value: float, tv: typical.TypicalValue) -> tuple[float, float]:
    """(r_lo, r_hi): the published range of ``tv`` over the value in use."""
    if not (value > 0.0 and math.isfinite(value)):
        return 1.0, 1.0
    return tv.low / value, tv.high / value


def viscous_factor_bounds(case) -> tuple[float, float]:
    """(k_lo, k_hi) of the viscous friction over the published ranges of τ_E and Λ
    (module text); 1 for an input the viscous law of ``case`` (a Case or BuiltCase) does
    not use."""
    built = as_built(case)
    lub = built.lubricant
    n = built.case.numerics
    k_lo = k_hi = 1.0
    if n.viscous_model == "eyring":
        r_lo, r_hi = _ratio_bounds(float(lub.eyring_stress), typical.EYRING_STRESS)
        k_lo, k_hi = min(k_lo, r_lo), max(k_hi, r_hi)
    if n.limiting_shear:
        lam = float(lub.limiting_shear_coefficient)
        l_lo, l_hi = _ratio_bounds(lam, typical.LIMITING_SHEAR_COEFFICIENT)
        k_lo, k_hi = min(k_lo, l_lo), max(k_hi, l_hi)
    return k_lo, k_hi


def set_energy_function(study, name: str):
    """E(ς', k) [J]: the friction energy per cycle of set ``name`` with its ς replaced
    by ς' and its viscous friction scaled by k (module text)."""
    inp = study.inputs
    s = study.set(name)
    dt = np.gradient(inp.time)
    us = np.abs(inp.sliding_speed)
    w = np.where(s.loaded, us * dt, 0.0)
    e_v = float(np.nansum(np.where(s.loaded, s.viscous_friction, 0.0) * w))
    e_b = float(np.nansum(np.where(s.loaded, s.boundary_friction, 0.0) * w))
    e_wa = float(np.nansum(np.where(s.loaded, s.asperity_load, 0.0) * w))
    sigma = float(build(study.case).set(name).surface.boundary_shear_coefficient)

    def energy(sigma_new: float, k: float = 1.0) -> float:
        return k * e_v + e_b + (sigma_new - sigma) * e_wa

    return energy


def _material(case, name: str) -> str:
    cfg = {c.name: c for c in case.surface_set_configs}[name]
    return cfg.coating if cfg.coating is not None else cfg.substrate


def _pct(x: float) -> str:
    """Signed percentage with a true minus sign; one decimal below 10 %."""
    return (f"{x:+.1f}" if abs(x) < 10.0 else f"{x:+.0f}").replace("-", "−")


def verdict_sentence(label: str, ref_label: str, pct: float, lo: float, hi: float) -> str:
    """The engineer's sentence of a verdict (see :func:`coating_verdicts`)."""
    rng = f"{_pct(lo)} … {_pct(hi)} %"
    over = "over the published ranges of ς of both pairs, τ_E and Λ"
    if hi < 0.0 or lo > 0.0:  # the sign is settled: the size of the change
        word, size = ("lowers", -pct) if hi < 0.0 else ("raises", pct)
        return (
            f"{label} {word} friction energy per cycle by {_pct(size)[1:]} % against "
            f"{ref_label} ({rng} {over})."
        )
    return (
        f"{label} changes friction energy per cycle by {_pct(pct)} % against {ref_label}, "
        f"but the sign is not settled: {rng} {over}."
    )


def coating_verdicts(study, reference: str, labels: dict[str, str]) -> dict[str, dict]:
    """``coating_verdict`` of every set of a cycle study other than ``reference`` (see
    :func:`verdicts_from_energies`)."""
    built = build(study.case)
    energies = {s.name: set_energy_function(study, s.name) for s in study.sets}
    return verdicts_from_energies(
        energies, boundary_ranges(built, list(energies)), reference, labels, built, METHOD
    )


def boundary_ranges(case, names) -> dict[str, tuple[float, float, float]]:
    """(ς in use, low, high) of each surface set of ``case`` (a Case or BuiltCase;
    :func:`~tribodyn.physics.typical.boundary_friction_range`)."""
    built = as_built(case)
    out = {}
    for name in names:
        sig = float(built.set(name).surface.boundary_shear_coefficient)
        out[name] = (sig, *typical.boundary_friction_range(_material(built.case, name), sig))
    return out


def verdicts_from_energies(
    energies: dict, sigmas: dict, reference: str, labels: dict[str, str], case, method: str
) -> dict[str, dict]:
    """``coating_verdict`` of every set other than ``reference`` from its energy function
    E(ς', k) (:func:`set_energy_function`): {``friction_energy_change_pct`` (negative:
    less friction), ``range_pct`` [lo, hi], ``range_independent_pct`` [lo, hi],
    ``lowers_friction`` (the change in use is negative), ``sign_settled`` (the range
    does not include 0), ``sentence``, ``method``, ``inputs``} (module text). A set
    whose energies are not finite gets None values and says so. ``case``: a Case or
    BuiltCase."""
    k_lo, k_hi = viscous_factor_bounds(case)
    e_ref = energies[reference]
    sig_ref, ref_lo, ref_hi = sigmas[reference]
    out: dict[str, dict[str, Any]] = {}
    for name, e_set in energies.items():
        if name == reference:
            continue
        sig, lo_s, hi_s = sigmas[name]
        base_ref = e_ref(sig_ref, 1.0)
        pct = 100.0 * (e_set(sig, 1.0) / base_ref - 1.0) if base_ref > 0 else math.nan
        together = [
            100.0 * (e_set(ss, k) / e_ref(sr, k) - 1.0)
            for (ss, sr), k in itertools.product(((lo_s, ref_lo), (hi_s, ref_hi)), (k_lo, k_hi))
        ]
        indep = [
            100.0 * (e_set(ss, k) / e_ref(sr, k) - 1.0)
            for ss, sr, k in itertools.product((lo_s, hi_s), (ref_lo, ref_hi), (k_lo, k_hi))
        ]
        ok = math.isfinite(pct) and all(math.isfinite(v) for v in together + indep)
        if not ok:
            unknown = "friction_energy_change_pct range_pct range_independent_pct lowers_friction"
            out[name] = {
                **dict.fromkeys((*unknown.split(), "sign_settled")),
                "sentence": f"{labels[name]}: no verdict (the friction energy is not known).",
                "method": method,
            }
            continue
        lo, hi = min(together + [pct]), max(together + [pct])
        out[name] = {
            "friction_energy_change_pct": pct,
            "range_pct": [lo, hi],
            "range_independent_pct": [min(indep + [pct]), max(indep + [pct])],
            "lowers_friction": bool(pct < 0.0),
            "sign_settled": bool(hi < 0.0 or lo > 0.0),
            "sentence": verdict_sentence(labels[name], labels[reference], pct, lo, hi),
            "method": method,
            "inputs": {
                "boundary_shear_coefficient": [sig, lo_s, hi_s],
                "reference_boundary_shear_coefficient": [sig_ref, ref_lo, ref_hi],
                "viscous_factor": [1.0, k_lo, k_hi],
            },
        }
    return out

"""The thermal part of a finished cycle study's summary (``numerics.thermal = true``):
per surface set the temperatures and the thermal model's film and friction against the
isothermal one at the same inlet temperature, and the coatings' thermal effect. The
thermal passes themselves are :mod:`tribodyn.cycle.thermal`.
"""

from __future__ import annotations

from typing import Any

import numpy as np

from .conventions import finite

__all__ = ["coating_thermal_effect", "thermal_summary"]


def coating_thermal_effect(thermal: dict, isothermal: dict, reference: str, mask, inputs) -> dict:
    """Per coated set: the change of its viscous-friction energy and of its mean central
    film relative to the reference (uncoated) set, thermal and isothermal, over the
    samples in ``mask`` that converged in all four runs; and the peak tappet surface
    temperature. The thermal effect of a coating is the thermal change minus the
    isothermal one (what an isothermal model misses)."""
    us = np.abs(inputs.sliding_speed)
    ref_t, ref_i = thermal[reference], isothermal[reference]
    res = {}
    for name, th in thermal.items():
        if name == reference:
            continue
        iso = isothermal[name]
        ok = mask & th.loaded & th.converged & iso.converged & ref_t.converged & ref_i.converged
        ok &= np.isfinite(th.viscous_friction) & np.isfinite(ref_t.viscous_friction)
        if not ok.any():
            continue

        def energy(r):
            return inputs.integral(r.viscous_friction * us, ok)

        def film(r):
            return float(np.mean(r.central_film[ok]))

        e = {k: energy(r) for k, r in (("t", th), ("tr", ref_t), ("i", iso), ("ir", ref_i))}
        f = {k: film(r) for k, r in (("t", th), ("tr", ref_t), ("i", iso), ("ir", ref_i))}
        dv_t = 100.0 * (e["t"] / e["tr"] - 1.0) if e["tr"] > 0 else float("nan")
        dv_i = 100.0 * (e["i"] / e["ir"] - 1.0) if e["ir"] > 0 else float("nan")
        dh_t = 100.0 * (f["t"] / f["tr"] - 1.0)
        dh_i = 100.0 * (f["i"] / f["ir"] - 1.0)
        res[name] = {
            "viscous_energy_vs_reference_thermal_pct": dv_t,
            "viscous_energy_vs_reference_isothermal_pct": dv_i,
            "viscous_energy_thermal_effect_pct": dv_t - dv_i,
            "mean_film_vs_reference_thermal_pct": dh_t,
            "mean_film_vs_reference_isothermal_pct": dh_i,
            "film_thermal_effect_pct": dh_t - dh_i,
            "max_tappet_surface_temperature_K": float(
                np.nanmax(np.where(ok, th.surface_temperature_tappet, np.nan))
            ),
            "max_tappet_surface_temperature_reference_K": float(
                np.nanmax(np.where(ok, ref_t.surface_temperature_tappet, np.nan))
            ),
            "samples": int(ok.sum()),
        }
    return res


def thermal_summary(study, an) -> dict:
    """The thermal part of ``summary.json``: per surface set the peak temperatures, the
    film and friction of the thermal model against the isothermal one (same inlet
    temperature), and the coatings' thermal effect (:func:`coating_thermal_effect`)."""
    inp = study.inputs
    us = np.abs(inp.sliding_speed)
    iso = {s.name: s for s in study.isothermal_sets}
    out: dict[str, Any] = {"inlet_temperature_K": None, "surface_sets": {}}
    ev = an.in_event

    for th in study.sets:
        i = iso[th.name]
        out["inlet_temperature_K"] = finite(th.inlet_temperature)
        ok = th.loaded & th.converged & i.converged
        L = ok & ev
        if not L.any():
            out["surface_sets"][th.name] = {"samples": 0}
            continue

        e_t, e_i = (inp.integral(r.viscous_friction * us, ok) for r in (th, i))
        f_t, f_i = (inp.integral(r.friction_power, ok) for r in (th, i))
        out["surface_sets"][th.name] = {
            "max_temperature_K": finite(np.nanmax(th.max_temperature[L])),
            "max_mid_film_temperature_K": finite(np.nanmax(th.mid_film_temperature[L])),
            "max_surface_temperature_cam_K": finite(np.nanmax(th.surface_temperature_cam[L])),
            "max_surface_temperature_tappet_K": finite(np.nanmax(th.surface_temperature_tappet[L])),
            "viscous_friction_energy_thermal_J": finite(e_t),
            "viscous_friction_energy_isothermal_J": finite(e_i),
            "viscous_friction_energy_change_pct": finite(100 * (e_t / e_i - 1))
            if e_i > 0
            else None,
            "friction_energy_thermal_J": finite(f_t),
            "friction_energy_isothermal_J": finite(f_i),
            "mean_central_film_change_pct": finite(
                100 * (np.mean(th.central_film[L]) / np.mean(i.central_film[L]) - 1)
            ),
            "min_film_thermal_m": finite(np.nanmin(th.min_film[L])),
            "min_film_isothermal_m": finite(np.nanmin(i.min_film[L])),
            "samples": int(L.sum()),
        }
    out["coating_thermal_effect"] = coating_thermal_effect(
        {s.name: s for s in study.sets}, iso, an.roles["reference"], ev, inp
    )
    return out

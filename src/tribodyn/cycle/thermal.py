"""Thermal transient mixed-EHL along the cam cycle (``numerics.thermal = true``).

For every surface set the thermal solver (:class:`~tribodyn.contact.ehl.thermal_transient.
ThermalTransientEHL`: generalized Reynolds, film energy equation, conduction in the cam
and in the coated tappet) is marched over the same samples by the same driver as the
isothermal one (:func:`.driver.march_cycle`, with its time-error control), from the
oil's inlet (sump) temperature. Results are :class:`ThermalSetCycleResult` — the fields
of :class:`~.data.SetCycleResult` plus the temperatures along the cycle. The study keeps the isothermal results beside them for the
comparison (film and friction thermal vs isothermal, the coatings' thermal effect).

Body 1 is the cam, body 2 the tappet (the coating's side).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from ..config.build import BuiltCase, as_built, options_for
from ..contact.ehl.options import EHLOptions
from ..contact.ehl.thermal import ThermalOptions, couette_stress
from ..contact.ehl.thermal_transient import ThermalTransientEHL
from ..physics.asperity import Roughness
from ..physics.thermal_oil import ThermalLubricant
from .driver import (
    TIME_TOL,
    CycleInputs,
    CycleMethod,
    Recorder,
    SetCycleResult,
    cycle_for_set,
    march_cycle,
)

__all__ = [
    "ThermalSetCycleResult",
    "ThermalCycle",
    "TemperatureRecorder",
    "thermal_along_cycle",
    "thermal_for_set",
    "thermal_task",
    "coating_thermal_effect",
]

_TEMPS = (
    "max_temperature",
    "mid_film_temperature",
    "surface_temperature_cam",
    "surface_temperature_tappet",
    "mean_film_temperature",
)


def _unset() -> np.ndarray:
    """Default of a per-sample field (the cycle driver always sets it)."""
    return np.empty(0)


@dataclass
class ThermalSetCycleResult(SetCycleResult):
    """:class:`SetCycleResult` of the thermal model, with temperatures [K] per sample:
    the maximum of film and surfaces, the mid-film temperature at the contact centre, the
    maximum surface temperatures of cam and tappet, the film-mean temperature at the
    centre; and the inlet temperature."""

    max_temperature: np.ndarray = field(default_factory=_unset)
    mid_film_temperature: np.ndarray = field(default_factory=_unset)
    surface_temperature_cam: np.ndarray = field(default_factory=_unset)
    surface_temperature_tappet: np.ndarray = field(default_factory=_unset)
    mean_film_temperature: np.ndarray = field(default_factory=_unset)
    inlet_temperature: float = float("nan")
    thermal_iterations: np.ndarray = field(default_factory=_unset)
    thermal: bool = field(default=True)


class TemperatureRecorder:
    """The thermal variant's per-sample outputs: the temperatures of :data:`_TEMPS` [K]
    and the pressure ↔ temperature iterations."""

    def __init__(self, n: int):
        self.out = {k: np.full(n, np.nan) for k in _TEMPS}
        self.thermal_iterations = np.zeros(n, dtype=int)

    def record(self, i, stepper, r):
        out, tf = self.out, stepper.tf
        self.thermal_iterations[i] = r.thermal_iterations
        out["max_temperature"][i] = r.max_temperature
        out["mid_film_temperature"][i] = r.central_mid_film_temperature
        out["surface_temperature_cam"][i] = r.max_surface_temperature[0]
        out["surface_temperature_tappet"][i] = r.max_surface_temperature[1]
        out["mean_film_temperature"][i] = float(np.interp(0.0, tf.x, tf.mean_T()))

    def fields(self) -> dict:
        return {"thermal_iterations": self.thermal_iterations, **self.out}


@dataclass
class ThermalCycle(CycleMethod):
    """The thermal transient EHL (:class:`~tribodyn.contact.ehl.thermal_transient.
    ThermalTransientEHL`) for :func:`~.driver.march_cycle`, from the oil's inlet
    temperature; temperatures recorded by :class:`TemperatureRecorder`."""

    result_type: ClassVar[type[SetCycleResult]] = ThermalSetCycleResult
    bodies: Any
    oil: ThermalLubricant
    thermal_bodies: Any
    roughness: Roughness | None
    options: EHLOptions
    thermal_options: ThermalOptions

    def new_stepper(self) -> ThermalTransientEHL:
        return ThermalTransientEHL(
            self.bodies,
            self.oil,
            self.thermal_bodies,
            self.roughness,
            options=self.options,
            thermal_options=self.thermal_options,
        )

    def law_shear(self, stepper, r) -> Callable[[str], np.ndarray]:
        """Both laws on the same film and temperatures (the thermal Couette stress)."""
        _, _, Tm, fl, flim = stepper.tf.factors(r.x, _cond(r))
        return lambda law: couette_stress(
            r.pressure,
            r.film,
            r.sliding_speed,
            self.oil,
            Tm,
            fl,
            flim,
            law,
            self.options.limiting_shear,
        )

    def recorders(self, n: int) -> list[Recorder]:
        return [TemperatureRecorder(n)]

    def result_fields(self) -> dict:
        return {"inlet_temperature": float(self.oil.inlet_temperature)}

    @classmethod
    def for_set(cls, case, surface_set) -> ThermalCycle:
        """The thermal method of one surface set of a case (Case or BuiltCase)."""
        s, built = surface_set, as_built(case)
        return cls(
            s.bodies,
            built.thermal_oil(),
            built.thermal_bodies_of(s),
            s.roughness,
            options_for(built, s),
            built.thermal_solver_options(),
        )


def thermal_along_cycle(
    inp: CycleInputs,
    name,
    label,
    bodies,
    oil,
    thermal_bodies,
    roughness,
    options,
    thermal_options,
    *,
    min_load=5.0,
    progress=None,
    time_tol: float = TIME_TOL,
) -> ThermalSetCycleResult:
    """March the thermal transient EHL over the cycle for one surface set
    (:func:`~.driver.march_cycle` with :class:`ThermalCycle`: the same samples,
    time-error control, outputs and unloaded-sample convention as the isothermal march)."""
    res = march_cycle(
        inp,
        name,
        label,
        ThermalCycle(bodies, oil, thermal_bodies, roughness, options, thermal_options),
        min_load=min_load,
        progress=progress,
        time_tol=time_tol,
    )
    assert isinstance(res, ThermalSetCycleResult)
    return res


def _cond(r):
    from ..contact.ehl.options import Conditions

    return Conditions(r.load, r.radius, r.entrainment_speed, r.sliding_speed)


def thermal_for_set(case, surface_set, inputs: CycleInputs, progress=None) -> ThermalSetCycleResult:
    """The thermal march of one surface set of a case (Case or BuiltCase;
    :func:`~.driver.cycle_for_set` with the ``"thermal"`` method)."""
    res = cycle_for_set(case, surface_set, inputs, "thermal", progress)
    assert isinstance(res, ThermalSetCycleResult)
    return res


def thermal_task(built: BuiltCase, name, inputs):
    """The thermal cycle of one surface set, as a task of the study's executor."""
    from threadpoolctl import threadpool_limits

    with threadpool_limits(1):
        return thermal_for_set(built, built.set(name).surface, inputs)


def coating_thermal_effect(
    thermal: dict, isothermal: dict, reference: str, mask, time, sliding_speed
) -> dict:
    """Per coated set: the change of its viscous-friction energy and of its mean central
    film relative to the reference (uncoated) set, thermal and isothermal, over the
    samples in ``mask`` that converged in all four runs; and the peak tappet surface
    temperature. The thermal effect of a coating is the thermal change minus the
    isothermal one (what an isothermal model misses)."""
    dt = np.gradient(np.asarray(time, dtype=float))
    us = np.abs(np.asarray(sliding_speed, dtype=float))
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
            return float(np.sum(np.where(ok, r.viscous_friction * us, 0.0) * dt))

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
    dt = np.gradient(inp.time)
    us = np.abs(inp.sliding_speed)
    iso = {s.name: s for s in study.isothermal_sets}
    out: dict[str, Any] = {"inlet_temperature_K": None, "surface_sets": {}}
    ev = an.in_event

    def fin(v):
        v = float(v)
        return v if np.isfinite(v) else None

    for th in study.sets:
        i = iso[th.name]
        out["inlet_temperature_K"] = fin(th.inlet_temperature)
        ok = th.loaded & th.converged & i.converged
        L = ok & ev
        if not L.any():
            out["surface_sets"][th.name] = {"samples": 0}
            continue

        def energy(r, key):
            return float(np.nansum(np.where(ok, getattr(r, key) * us, 0.0) * dt))

        e_t, e_i = energy(th, "viscous_friction"), energy(i, "viscous_friction")
        f_t = float(np.nansum(np.where(ok, th.friction_power, 0.0) * dt))
        f_i = float(np.nansum(np.where(ok, i.friction_power, 0.0) * dt))
        out["surface_sets"][th.name] = {
            "max_temperature_K": fin(np.nanmax(th.max_temperature[L])),
            "max_mid_film_temperature_K": fin(np.nanmax(th.mid_film_temperature[L])),
            "max_surface_temperature_cam_K": fin(np.nanmax(th.surface_temperature_cam[L])),
            "max_surface_temperature_tappet_K": fin(np.nanmax(th.surface_temperature_tappet[L])),
            "viscous_friction_energy_thermal_J": fin(e_t),
            "viscous_friction_energy_isothermal_J": fin(e_i),
            "viscous_friction_energy_change_pct": fin(100 * (e_t / e_i - 1)) if e_i > 0 else None,
            "friction_energy_thermal_J": fin(f_t),
            "friction_energy_isothermal_J": fin(f_i),
            "mean_central_film_change_pct": fin(
                100 * (np.mean(th.central_film[L]) / np.mean(i.central_film[L]) - 1)
            ),
            "min_film_thermal_m": fin(np.nanmin(th.min_film[L])),
            "min_film_isothermal_m": fin(np.nanmin(i.min_film[L])),
            "samples": int(L.sum()),
        }
    out["coating_thermal_effect"] = coating_thermal_effect(
        {s.name: s for s in study.sets}, iso, an.roles["reference"], ev, inp.time, inp.sliding_speed
    )
    return out

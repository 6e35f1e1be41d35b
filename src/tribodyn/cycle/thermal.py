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

from .._threads import single_blas_thread
from ..config.build import BuiltCase, as_built, options_for
from ..contact.ehl.options import Conditions, EHLOptions
from ..contact.ehl.thermal import ThermalOptions, couette_stress
from ..contact.ehl.thermal_transient import ThermalTransientEHL
from ..physics.asperity import Roughness
from ..physics.thermal_oil import ThermalLubricant
from .driver import CycleMethod, Recorder, SetCycleResult, march_for_set

__all__ = [
    "ThermalSetCycleResult",
    "ThermalCycle",
    "TemperatureRecorder",
    "thermal_task",
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
        cond = Conditions(r.load, r.radius, r.entrainment_speed, r.sliding_speed)
        _, _, Tm, fl, flim = stepper.tf.factors(r.x, cond)
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


def thermal_task(built: BuiltCase, name, inputs):
    """The thermal march of one surface set of a built case (:func:`~.driver.march_for_set`
    with :class:`ThermalCycle`), as a task of the study's executor."""
    s = built.set(name).surface
    with single_blas_thread():
        return march_for_set(built, s, inputs, ThermalCycle.for_set(built, s))

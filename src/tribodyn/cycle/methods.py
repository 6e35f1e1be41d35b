"""The EHL methods along the cycle by name: the one place a variant is chosen.

Each entry builds the :class:`~.driver.CycleMethod` of one surface set of a case; the
method carries everything in which the variants differ (its stepper, its Couette stress,
its extra recorders, its result class), so the driver (:func:`~.driver.march_cycle`)
never branches on the variant. A new variant is one :class:`~.driver.CycleMethod`
subclass and one entry here.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from .._validation import InputError
from ..config.build import BuiltCase
from ..physics.thermal_oil import ThermalLubricant
from .data import CycleInputs, SetCycleResult
from .driver import CycleMethod, IsothermalCycle, march_for_set
from .tasks import Task
from .thermal import ThermalCycle, thermal_task

__all__ = ["METHODS", "cycle_for_set", "IsothermalStudy", "ThermalStudy", "study_variant"]

#: The EHL variants by name: ``METHODS[name](case, surface_set)`` is the
#: :class:`~.driver.CycleMethod` of a surface set of a case (Case or BuiltCase).
METHODS: dict[str, Callable[[Any, Any], CycleMethod]] = {
    "isothermal": IsothermalCycle.for_set,
    "thermal": ThermalCycle.for_set,
}


def cycle_for_set(
    case: Any,
    surface_set: Any,
    inputs: CycleInputs,
    method: str = "isothermal",
    progress: Callable[[int, int], None] | None = None,
) -> SetCycleResult:
    """The march of one surface set of a case (Case or BuiltCase) along the cycle with
    the variant ``method`` (a key of :data:`METHODS`) at the case's numerics
    (:func:`~.driver.march_for_set`); an unknown name is an input error."""
    if method not in METHODS:
        raise InputError(f"method must be one of {sorted(METHODS)} (got {method!r})")
    chosen = METHODS[method](case, surface_set)
    return march_for_set(case, surface_set, inputs, chosen, progress)


class IsothermalStudy:
    """The isothermal cycle study: it adds no pass (``kinds``: the kinds of the tasks it
    adds, keys ``"<kind>:<set>"``) and presents the isothermal pass of every set."""

    kinds: tuple[str, ...] = ()

    def tasks(self, built: BuiltCase, inputs: CycleInputs) -> list[Task]:
        return []

    def oil(self, built: BuiltCase) -> ThermalLubricant | None:
        """The thermal oil its passes run with (None: no thermal pass)."""
        return None

    def collect(self, order: list[str], isothermal: dict, own: dict) -> tuple[list, list | None]:
        """(the results the study presents, the isothermal ones kept beside or None) in
        the set ``order``, from the isothermal passes by set name and its ``own`` passes
        by task key."""
        return [isothermal[n] for n in order], None


class ThermalStudy(IsothermalStudy):
    """The thermal cycle study (``numerics.thermal``): the thermal pass of every set
    (:func:`~.thermal.thermal_task`, keys ``"thermal:<set>"``) is presented, the
    isothermal pass at the same inlet temperature kept beside it."""

    kinds = ("thermal",)

    def tasks(self, built: BuiltCase, inputs: CycleInputs) -> list[Task]:
        return [Task(f"thermal:{name}", thermal_task, (built, name, inputs)) for name in built.sets]

    def oil(self, built: BuiltCase) -> ThermalLubricant | None:
        return built.thermal_lubricant

    def collect(self, order: list[str], isothermal: dict, own: dict) -> tuple[list, list | None]:
        return [own[f"thermal:{n}"] for n in order], [isothermal[n] for n in order]


def study_variant(built: BuiltCase) -> IsothermalStudy:
    """The study variant of a built case: chosen here, once, by ``numerics.thermal``."""
    return ThermalStudy() if built.case.numerics.thermal else IsothermalStudy()

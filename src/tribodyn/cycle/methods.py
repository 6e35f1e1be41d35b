"""The EHL variants of a cycle study: the one place a variant is chosen.

A variant is a :class:`~.driver.CycleMethod` (its stepper, its Couette stress, its extra
recorders, its result class), so the driver (:func:`~.driver.march_cycle`) never branches
on it; the study's side of a variant (the passes it adds, the oil they run with, the
results it presents) is a study class here, chosen once by :func:`study_variant`.
"""

from __future__ import annotations

from ..config.build import BuiltCase
from ..physics.thermal_oil import ThermalLubricant
from .data import CycleInputs
from .tasks import Task
from .thermal import thermal_task

__all__ = ["IsothermalStudy", "ThermalStudy", "study_variant"]


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

"""The variables of an engine valvetrain study's Dataset (``tribodyn engine``'s
``results.nc``): the table of :mod:`~tribodyn.workflow.variables`, extracted from an
:class:`~tribodyn.workflow.engine.EngineStudy`. Torques over ``(engine_set, camshaft,
engine_crank)``, each valve's over ``(engine_set, valve, engine_crank)``.
"""

from __future__ import annotations

from operator import attrgetter as _attr  # the study attribute of that name
from string import ascii_lowercase

from .conventions import ENGINE_CRANK_ANGLE
from .variables import Group, var
from .variables_study import SURFACE_SET

__all__ = ["ENGINE", "ALL", "valve_names"]

DIMS = ("engine_set", "camshaft", "engine_crank")


def valve_names(valves) -> list[str]:
    """Unique names of the engine's valves (the ``valve`` coordinate of results.nc):
    kind, cylinder and, where the cylinder has several valves of that kind, a letter:
    ``intake1a``, ``intake1b``, ``exhaust1a``, …; a single valve of its kind on its
    cylinder is ``intake1``."""
    base = [f"{v['kind']}{v['cylinder']}" for v in valves]
    return [
        b if base.count(b) == 1 else f"{b}{ascii_lowercase[base[:i].count(b)]}"  # k-th of its kind
        for i, b in enumerate(base)
    ]


ENGINE = Group(
    (
        var("camshaft_friction_torque", DIMS, "N m",
            "cam–tappet friction torque on the camshaft, all its lobes", _attr("friction_torque")),
        var("camshaft_drive_torque", DIMS, "N m",
            "camshaft drive torque of the cam–tappet contacts", _attr("drive_torque")),
        var("camshaft_friction_power", DIMS, "W",
            "valvetrain friction power of the camshaft (contact + auxiliary)",
            lambda e: (e.friction_torque + e.auxiliary_torque) * e.cam_speed),
        var("tappet_bore_torque", DIMS, "N m",
            "tappet–bore friction torque (side load + Couette)", _attr("bore_torque")),
        var("valve_guide_torque", DIMS, "N m", "valve stem–guide friction torque",
            _attr("guide_torque")),
        var("camshaft_journal_torque", DIMS, "N m", "camshaft journal bearings (short bearing)",
            _attr("journal_torque")),
        var("lobe_friction_torque", ("engine_set", "valve", "engine_crank"), "N m",
            "cam–tappet friction torque of each valve", _attr("lobe_friction_torque")),
        var("engine_set", "engine_set", None, SURFACE_SET.description,
            lambda e: list(e.set_names), coord=True),
        var("camshaft", "camshaft", None, "camshaft", lambda e: list(e.camshafts), coord=True),
        var("engine_crank", "engine_crank", "deg", ENGINE_CRANK_ANGLE,
            _attr("crank_angle"), coord=True),
        var("valve", "valve", None,
            "valve: kind, cylinder and a letter where the cylinder has several valves of "
            "the kind (intake1a, intake1b, …; unique)",
            lambda e: valve_names(e.valves), coord=True),
        var("valve_kind", "valve", None, "lobe kind of the valve (intake, exhaust)",
            lambda e: [v["kind"] for v in e.valves], coord=True),
        var("valve_cylinder", "valve", "1", "cylinder of the valve",
            lambda e: [int(v["cylinder"]) for v in e.valves], coord=True),
        var("valve_camshaft", "valve", None, "camshaft that drives the valve",
            lambda e: [v["camshaft"] for v in e.valves], coord=True),
        var("valve_nose_deg", "valve", "deg",
            f"crank angle of the valve's maximum lift ({ENGINE_CRANK_ANGLE})",
            lambda e: [v["nose_deg"] for v in e.valves], coord=True),
    )
)  # fmt: skip

ALL = tuple(ENGINE)

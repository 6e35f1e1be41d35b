"""The variables of an engine valvetrain study's Dataset (``tribodyn engine``'s
``results.nc``): the table of :mod:`~tribodyn.workflow.variables`, extracted from an
:class:`~tribodyn.workflow.engine.EngineStudy`. Torques over ``(engine_set, camshaft,
engine_crank)``, each valve's over ``(engine_set, valve, engine_crank)``.
"""

from __future__ import annotations

from .variables import Group, var
from .variables_study import SURFACE_SET

__all__ = ["ENGINE", "ALL"]

DIMS = ("engine_set", "camshaft", "engine_crank")


def _attr(k):
    return lambda e: getattr(e, k)


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
        var("engine_crank", "engine_crank", "deg", "crank angle from cylinder 1's firing TDC",
            _attr("crank_angle"), coord=True),
        var("valve", "valve", None, "valve: kind and cylinder number",
            lambda e: [f"{v['kind']}{v['cylinder']}" for v in e.valves], coord=True),
        var("valve_nose_deg", "valve", "deg", "crank angle of the valve's cam nose",
            lambda e: [v["nose_deg"] for v in e.valves], coord=True),
    )
)  # fmt: skip

ALL = tuple(ENGINE)

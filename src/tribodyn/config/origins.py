"""Where each input value of a case comes from: the case file, a typical value of
:mod:`tribodyn.physics.typical` or :mod:`~tribodyn.physics.typical_engine` (with its
source) or an assumed default.

The origin is fixed where a value enters, when the case is validated: a key the case
file (or dict) gave is ``"case"``; a key it left out takes its schema default, whose
origin is listed here next to the default. The run's report lists every valvetrain,
lubricant, material and surface value with this origin ("Inputs as used"), and
:func:`default_warnings` names the values that decide the contact force and that the
case left to typical values.

Why typical values with a warning, not a refusal: the spring rate, the preload and the
masses decide the cam–tappet force, so a case without them is not the user's engine.
Refusing such a case would also refuse ``Case()`` of the Python API and every quick
study of a cam, an oil or a coating whose valvetrain does not matter to its question; a
typical passenger-car valvetrain, named value by value in a warning and in the report,
keeps those running and tells the engineer exactly which numbers to replace.
"""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from ..physics import typical, typical_engine
from ..physics.typical import TypicalValue
from .case_thermal import DATASHEET_KEYS, OIL_LAW_KEYS
from .schema_fields import field_extra
from .schema_surfaces import TYPICAL_MATERIALS, LubricantConfig

if TYPE_CHECKING:
    from .case import Case

__all__ = ["CASE", "Origin", "input_origins", "default_warnings", "typical_origin"]

#: Origin of a value the case gave.
CASE = "case"

#: One input value: dotted key, value, unit, origin ("case", "typical (…)", "assumed …").
Origin = tuple[str, Any, str, str]


def typical_origin(t: TypicalValue) -> str:
    """``"typical (status; source)"`` of a typical value."""
    return f"typical ({t.status}; {t.source})"


_ASSUMED = "assumed (tribodyn default, ValvetrainParameters)"
_NUMERICAL = "assumed (numerical setting)"

#: Origin of the default of each lumped ``[valvetrain]`` key (units in the schema).
_VALVETRAIN = {
    **{k: typical_origin(t) for k, t in typical_engine.VALVETRAIN.items()},
    "spring_masses": _NUMERICAL,
    "spring_damping_ratio": _ASSUMED,
    "contact_stiffness": "assumed (absent: Palmgren steel line-contact law)",
    "contact_modulus": "assumed (E' of typical steel on steel)",
    "contact_damping": _ASSUMED,
    "camshaft_stiffness": "assumed (absent: rigid camshaft)",
    "tappet_valve_stiffness": _ASSUMED,
    "tappet_valve_damping": _ASSUMED,
    "lash": _ASSUMED,
    "seat_stiffness": _ASSUMED,
    "seat_damping": _ASSUMED,
    "spring_seat_stiffness": _ASSUMED,
    "spring_support_stiffness": _ASSUMED,
    "damping_force_ramp": _NUMERICAL,
    "bore_friction_coefficient": _ASSUMED,
    "bore_friction_velocity": _NUMERICAL,
    "tappet_radius": _ASSUMED,
}

_CAM = {
    "base_radius": typical_engine.CAM_BASE_RADIUS,
    "max_lift": typical_engine.CAM_MAX_LIFT,
    "width": typical_engine.CAM_WIDTH,
}
#: The keys of the isothermal oil in file order.
_LUBRICANT_KEYS = tuple(
    k for k in LubricantConfig.model_fields if k in {*DATASHEET_KEYS, *OIL_LAW_KEYS}
)


def _unit(section, key: str) -> str:
    return str(field_extra(type(section).model_fields[key]).get("unit", ""))


def input_origins(case: Case) -> list[Origin]:
    """Every valvetrain, lubricant, material and surface value of ``case`` with its
    origin (module text), in case-file order."""
    given = case.input_given
    out: list[Origin] = []

    def add(key: str, value: Any, unit: str, default_origin: str) -> None:
        out.append((key, value, unit, CASE if key in given else default_origin))

    speed = typical_origin(typical_engine.ENGINE_SPEED)
    add("engine.speed_rpm", case.engine.speed_rpm, "rpm", speed)
    for k, t in _CAM.items():
        value = getattr(case.cam_config, k, None)
        if value is not None:
            add(f"cam.{k}", value, "m", typical_origin(t))
    vt = case.valvetrain
    for k, default in _VALVETRAIN.items():
        if k not in vt.unused_keys:
            add(f"valvetrain.{k}", getattr(vt, k), _unit(vt, k), default)
    lub = case.lubricant_config
    # the datasheet oil as built at validation (absent while the case is being validated)
    built = case._built
    oil = built.lubricant if built is not None else None
    for k in _LUBRICANT_KEYS:
        key = f"lubricant.{k}"
        if lub.datasheet and k in DATASHEET_KEYS and key not in given:
            src = f"oil {lub.oil}" if lub.oil else "kinematic viscosities"
            at = (
                f" at {lub.inlet_temperature_c:g} °C" if lub.inlet_temperature_c is not None else ""
            )
            value = getattr(oil, k) if oil is not None else None
            out.append((key, value, _unit(lub, k), f"datasheet ({src}{at})"))
            continue
        tl = typical.LUBRICANT.get(k)
        default = typical_origin(tl) if tl is not None else "assumed (tribodyn default)"
        add(key, getattr(lub, k), _unit(lub, k), default)
    for name, m in case.materials.items():
        defaults = TYPICAL_MATERIALS.get(name, {})
        for k in ("E", "nu", "boundary_shear_coefficient"):
            if getattr(m, k) is not None:
                tv = defaults.get(k)
                other = typical_origin(tv) if tv is not None else "assumed"
                add(f"materials.{name}.{k}", getattr(m, k), _unit(m, k), other)
    tau0 = typical_origin(typical.BOUNDARY_SHEAR_STRENGTH)
    for s in case.surface_set_configs:
        p = f"surface_sets[{s.name}]"
        for k, v in s.roughness.arguments().items():  # η, β: from σ where absent
            add(f"{p}.roughness.{k}", v, _unit(s.roughness, k), _ROUGHNESS[k])
        add(f"{p}.boundary_shear_strength", s.boundary_shear_strength, "Pa", tau0)
        if s.boundary_shear_coefficient is not None:  # the set's own ς (else its material's)
            add(f"{p}.boundary_shear_coefficient", s.boundary_shear_coefficient, "", CASE)
    return out


_ROUGHNESS = {
    "rms": typical_origin(typical.COMPOSITE_RMS["ground"]),
    "summit_radius": typical_origin(typical.RMS_TO_SUMMIT_RADIUS) + ", β = σ/(σ/β)",
    "asperity_density": typical_origin(typical.ROUGHNESS_PARAMETER) + ", η = ηβσ/(βσ)",
}


def default_warnings(case: Case) -> list[str]:
    """Warnings naming every value that decides the contact force (masses, spring rate,
    preload) or the film (the oil's viscosity and α) which the case left out, and the
    typical value it runs on instead."""
    out = []
    lub = case.lubricant_config
    oil = [k for k in DATASHEET_KEYS[:2] if f"lubricant.{k}" not in case.input_given]
    if oil and not lub.datasheet:
        vals = ", ".join(f"{k} = {getattr(lub, k):g} {typical.LUBRICANT[k].unit}" for k in oil)
        out.append(
            f"lubricant: the case does not give {', '.join(oil)}; the run uses the typical "
            f"values {vals} (tribodyn.physics.typical: an engine oil near 100 °C, not your "
            "oil). The viscosity decides the film and the viscous friction: give the oil in "
            "the case's lubricant section (a datasheet oil at its inlet temperature, or its "
            "viscosity and α; docs/case-files.md)."
        )
    vt = case.valvetrain
    used = [k for k in typical_engine.VALVETRAIN if k not in vt.unused_keys]  # flexible: none
    missing = [k for k in used if f"valvetrain.{k}" not in case.input_given]
    if not missing:
        return out
    vals = ", ".join(
        f"{k} = {getattr(vt, k):g} {typical_engine.VALVETRAIN[k].unit}" for k in missing
    )
    return out + [
        f"valvetrain: the case does not give {', '.join(missing)}; the run uses the typical "
        f"values {vals} (tribodyn.physics.typical_engine: magnitudes of passenger-car "
        "direct-acting valvetrains, not your engine's). They decide the contact force, the "
        "spring surge, the film and the friction: state your engine's values in the "
        "case's valvetrain section (docs/case-files.md)."
    ]


def carried_given(old: Case, new: Case) -> frozenset[str]:
    """The given keys of ``new``, a copy of ``old`` with some keys changed
    (:meth:`~tribodyn.config.Case.updated`, an engine's lobe case): those ``old`` gave,
    and those whose value the change made different."""
    before = {k: v for k, v, _, _ in input_origins(old)}
    changed = {k for k, v, _, _ in input_origins(new) if k not in before or before[k] != v}
    return frozenset(old.input_given | changed)

"""Builders of the thermal model's inputs from a validated case (:class:`~tribodyn.config.case.Case`
inherits them): the temperature- and pressure-dependent oil, the materials' thermal
properties, the thermal bodies of a surface set and the thermal solver's options.
"""

from __future__ import annotations

from types import SimpleNamespace
from typing import TYPE_CHECKING, Any

from .._validation import InputError
from ..contact.ehl.thermal import ThermalOptions
from ..physics import thermal_oil
from ..physics.heat_conduction import LIMITS, ThermalBody, ThermalProperties
from ..physics.limits import Limit, RangeError, check_fields
from ..physics.oils import OILS, THERMAL_MATERIALS
from ..physics.thermal_oil import ThermalLubricant
from .schema_surfaces import OIL_KEYS

if TYPE_CHECKING:
    from ..physics.lubricant import Lubricant
    from .schema import CamConfig, LubricantConfig, MaterialConfig, Numerics, SurfaceSetConfig
    from .surface_set import SurfaceSet


#: ``[lubricant]`` keys of the isothermal oil that a datasheet gives (at its inlet
#: temperature; α by So–Klaus unless given), in this order
DATASHEET_KEYS = ("viscosity", "pressure_viscosity", "density")
#: ``[lubricant]`` keys that the isothermal and the thermal oil take unchanged
OIL_LAW_KEYS = {
    "eyring_stress",
    "limiting_shear_coefficient",
    "limiting_shear_stress",
    "compressible",
    "viscosity_model",
}
#: ``[materials.<name>]`` key of each argument of :class:`ThermalProperties` not named so
MATERIAL_KEYS = {"conductivity": "thermal_conductivity"}
#: ``[numerics]`` key of each argument of :class:`ThermalOptions`
NUMERICS_KEYS = {a: f"thermal_{a}" for a in ("x_nodes", "film_nodes", "solid_nodes")} | {
    "step_iter": "thermal_iterations",
    "tol": "thermal_tol",
}


def _check_given(given: dict[str, Any], limits: dict[str, Limit]) -> None:
    """Check the ranges of the values ``given`` (by argument name; None: absent)."""
    check_fields(SimpleNamespace(**given), {k: limits[k] for k in given}, tuple(given))


def _oil_arguments(c: LubricantConfig) -> dict[str, float]:
    """The ThermalLubricant arguments the keys of :data:`OIL_KEYS` given in ``c`` set."""
    given = {k: getattr(c, k) for k in OIL_KEYS}
    return {OIL_KEYS[k].argument: OIL_KEYS[k].value(v) for k, v in given.items() if v is not None}


def _in_key_units(c: LubricantConfig, exc: RangeError) -> RangeError:
    """``exc`` with each value a key of :data:`OIL_KEYS` set named by that key, in its
    unit and as given."""
    for key, conv in OIL_KEYS.items():
        if getattr(c, key) is not None:
            exc = conv.renamed(exc, key, getattr(c, key))
    return exc


class ThermalBuilders:
    """The thermal oil, thermal bodies and thermal options of a
    :class:`~tribodyn.config.case.Case`."""

    if TYPE_CHECKING:  # the fields and methods of Case these builders use
        lubricant_config: LubricantConfig
        materials: dict[str, MaterialConfig]
        surface_set_configs: list[SurfaceSetConfig]
        cam_config: CamConfig
        numerics: Numerics

    def _new_thermal_lubricant(self, checked: Lubricant | None = None) -> ThermalLubricant:
        """The temperature- and pressure-dependent oil of ``[lubricant]``
        (:class:`~tribodyn.physics.thermal_oil.ThermalLubricant`): a datasheet, or the
        viscosity at ``inlet_temperature_c`` with its ``viscosity_temperature_coefficient``
        (an InputError naming a missing key); ``checked``: the isothermal oil of
        ``[lubricant]`` built already, whose values are not checked again."""
        c = self.lubricant_config
        if c.inlet_temperature_c is None:
            raise InputError(
                "lubricant.inlet_temperature_c: required for the thermal model "
                "(the oil supply temperature, °C)"
            )
        # the thermal oil's own keys (β None with a datasheet) and the laws of both oils
        common = dict(c.model_dump(include=OIL_LAW_KEYS | thermal_oil.LIMITS.keys()))
        sheet = {k: v for k, v in OILS.get(c.oil or "", {}).items() if k != "description"}
        common |= sheet | _oil_arguments(c)  # a datasheet's keys override its oil's values
        given = c.model_fields_set
        try:
            if c.datasheet:
                alpha = c.pressure_viscosity if "pressure_viscosity" in given else None
                name = c.oil or "datasheet oil"
                return ThermalLubricant(**common, pressure_viscosity=alpha, name=name)
            if c.viscosity_temperature_coefficient is None:
                raise InputError(
                    "lubricant.viscosity_temperature_coefficient: required for the "
                    "thermal model with a viscosity (or give a datasheet: oil, "
                    "kinematic_viscosity_40_cst/_100_cst)"
                )
            return ThermalLubricant(
                **common,
                viscosity=c.viscosity,
                density=c.density,
                density_temperature=common["inlet_temperature"],
                pressure_viscosity=c.pressure_viscosity,
                name="lubricant",
                _checked=checked,
            )
        except RangeError as exc:
            raise _in_key_units(c, exc) from None

    def _check_thermal_oil_keys(self) -> None:
        """Check the ranges of the thermal oil's keys given in ``[lubricant]``: of a case
        whose thermal oil is not built (where it is, its constructor checks them)."""
        c, limits = self.lubricant_config, thermal_oil.LIMITS
        given = c.model_dump(include=c.model_fields_set & limits.keys()) | _oil_arguments(c)
        try:
            _check_given(given, limits | {k.argument: k.limit for k in OIL_KEYS.values()})
        except RangeError as exc:
            raise _in_key_units(c, exc) from None

    def _thermal_properties_given(self, name: str) -> dict[str, float]:
        """The thermal properties ``[materials.<name>]`` gives, by argument name."""
        found = {k: getattr(self.materials[name], MATERIAL_KEYS.get(k, k)) for k in LIMITS}
        return {k: v for k, v in found.items() if v is not None}

    def _check_thermal_properties(self, name: str, built: dict | None) -> None:
        """Check the ranges of the thermal properties of ``[materials.<name>]`` once:
        ``built`` (a thermal case) and all three known, by building them into ``built``;
        else the given ones."""
        given = self._thermal_properties_given(name)
        if built is None or {**THERMAL_MATERIALS.get(name, {}), **given}.keys() != LIMITS.keys():
            _check_given(given, LIMITS)
        else:
            built[name] = self._new_thermal_properties(name)

    def _new_thermal_properties(self, name: str) -> ThermalProperties:
        """k, ρ, c of ``[materials.<name>]`` (steel, dlc and wcc default to the literature
        values of :mod:`tribodyn.physics.oils`)."""
        d = {**THERMAL_MATERIALS.get(name, {}), **self._thermal_properties_given(name)}
        missing = [k for k in LIMITS if k not in d]
        if missing:
            raise InputError(
                "; ".join(
                    f"materials.{name}.{MATERIAL_KEYS.get(k, k)}: required for the thermal model"
                    for k in missing
                )
            )
        return ThermalProperties(**d)

    def _new_thermal_bodies(
        self, s: SurfaceSet, built: dict[str, ThermalProperties] | None = None
    ) -> tuple[ThermalBody, ThermalBody]:
        """(cam, tappet) as :class:`~tribodyn.physics.heat_conduction.ThermalBody`; the
        materials' properties are taken from ``built`` (by name) or built and kept there."""
        cfg = next(c for c in self.surface_set_configs if c.name == s.name) if s.name else None
        sub = (
            cfg.substrate
            if cfg is not None
            else ("steel" if "steel" in self.materials else self.cam_config.material)
        )
        coat = s.coating_material if cfg is None else cfg.coating
        built = {} if built is None else built
        for name in (self.cam_config.material, sub, coat):
            if name is not None and name not in built:
                built[name] = self._new_thermal_properties(name)
        cam = ThermalBody(built[self.cam_config.material])
        if coat is None:
            tappet = ThermalBody(built[sub])
        else:
            coating = s.bodies[1].coating
            assert coating is not None  # a coated set's tappet carries its coating
            tappet = ThermalBody(built[sub], built[coat], coating.thickness)
        return cam, tappet

    def _new_thermal_options(self) -> ThermalOptions:
        """:class:`~tribodyn.contact.ehl.thermal.ThermalOptions` from ``[numerics]``."""
        return ThermalOptions(**{a: getattr(self.numerics, k) for a, k in NUMERICS_KEYS.items()})

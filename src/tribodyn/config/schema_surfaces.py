"""Case-file sections of the lubricant and the surfaces: ``[lubricant]``, ``[materials]``
(with strength and stress settings), roughness and ``[[surface_sets]]``, and the typical
(:mod:`tribodyn.physics.typical`) materials and surface sets of a case that leaves them out.
"""

from __future__ import annotations

import math
from typing import Literal

from pydantic import model_validator

from ..physics import limits as L
from ..physics import typical, typical_engine
from ..physics.oils import OILS
from ..physics.strength import TYPICAL_STRENGTH
from ..physics.thermal_oil import ThermalLubricant, kelvin
from ..topography.load_separation import synthetic_load_separation
from .errors import Problems
from .schema_fields import _NAME_PATTERN, Converted, Section, _arg, _lim, _q, defaults_of

#: the defaults of the constructors the sections set: the one source of theirs
_OIL_DEFAULTS = defaults_of(ThermalLubricant)
_SURFACE_LAW_DEFAULTS = defaults_of(synthetic_load_separation)
#: ``[lubricant]`` keys in another unit or name than the ThermalLubricant argument they
#: set (density_15: of a datasheet), checked there
OIL_KEYS = {
    "kinematic_viscosity_40_cst": Converted(
        "kinematic_viscosity_40", L.KINEMATIC_VISCOSITY_40, "mm²/s", 1e-6
    ),
    "kinematic_viscosity_100_cst": Converted(
        "kinematic_viscosity_100", L.KINEMATIC_VISCOSITY_100, "mm²/s", 1e-6
    ),
    "density_15": Converted("density", L.DENSITY, L.DENSITY.unit),
    "inlet_temperature_c": Converted(
        "inlet_temperature", L.OIL_TEMPERATURE, "°C", offset=float(kelvin(0.0))
    ),
}


class LubricantConfig(Section):
    """``[lubricant]``: :class:`~tribodyn.Lubricant` (Roelands + Dowson–Higginson)."""

    viscosity: float = _arg(
        typical.VISCOSITY.value,
        L.VISCOSITY,
        "dynamic viscosity μ₀ at ambient pressure (Roelands needs μ₀ > exp(−9.67))",
    )
    pressure_viscosity: float = _arg(
        typical.PRESSURE_VISCOSITY.value,
        L.PRESSURE_VISCOSITY,
        "pressure–viscosity coefficient α",
    )
    density: float = _arg(typical.DENSITY.value, L.DENSITY, "density ρ₀ at ambient pressure")
    eyring_stress: float = _arg(
        typical.EYRING_STRESS.value, L.EYRING_STRESS, "Eyring stress τ_E (typical)"
    )
    limiting_shear_coefficient: float = _arg(
        typical.LIMITING_SHEAR_COEFFICIENT.value,
        L.LIMITING_SHEAR_COEFFICIENT,
        "pressure slope Λ of the limiting shear stress τ_L = τ_L0 + Λ p",
    )
    limiting_shear_stress: float = _arg(
        typical.LIMITING_SHEAR_STRESS.value,
        L.LIMITING_SHEAR_STRESS,
        "intercept τ_L0 of the limiting shear stress (typical: 0)",
    )
    compressible: bool = _q(True, "", "Dowson–Higginson density (false: constant density)")
    viscosity_model: Literal["roelands", "barus"] = _q("roelands", "", "piezo-viscosity law")
    # -- datasheet form and thermal properties (numerics.thermal)
    oil: Literal[tuple(OILS)] | None = _q(  # type: ignore[valid-type]
        None, "", "bundled oil (datasheet values; the keys below override them)"
    )
    kinematic_viscosity_40_cst: float | None = _arg(
        None,
        OIL_KEYS["kinematic_viscosity_40_cst"].key_limit,
        "kinematic viscosity at 40 °C (datasheet, ASTM D445)",
    )
    kinematic_viscosity_100_cst: float | None = _arg(
        None,
        OIL_KEYS["kinematic_viscosity_100_cst"].key_limit,
        "kinematic viscosity at 100 °C (datasheet)",
    )
    density_15: float | None = _arg(
        None, OIL_KEYS["density_15"].key_limit, "density at 15 °C (datasheet)"
    )
    thermal_expansion: float = _arg(
        _OIL_DEFAULTS["thermal_expansion"],
        L.THERMAL_EXPANSION,
        "thermal expansion of the density ε",
    )
    inlet_temperature_c: float | None = _arg(
        None,
        OIL_KEYS["inlet_temperature_c"].key_limit,
        "oil supply (sump) temperature, also that of the solids far from the "
        "contact; required with a datasheet or numerics.thermal",
    )
    viscosity_temperature_coefficient: float | None = _arg(
        None,
        L.VISCOSITY_TEMPERATURE,
        "β = −d ln μ/dT at the inlet temperature (viscosity form with numerics.thermal)",
    )
    thermal_conductivity: float | None = _arg(
        None,
        L.OIL_CONDUCTIVITY,
        "oil conductivity at the inlet temperature (absent: Cragoe's estimate from the density)",
    )
    specific_heat: float | None = _arg(
        None, L.OIL_SPECIFIC_HEAT, "oil specific heat at the inlet temperature (absent: Cragoe)"
    )
    limiting_shear_temperature_coefficient: float = _arg(
        _OIL_DEFAULTS["limiting_shear_temperature_coefficient"],
        L.LIMITING_SHEAR_TEMPERATURE,
        "c_L: τ_L falls by the factor 1 − c_L (T − T_inlet) (0: temperature independent)",
    )

    @property
    def datasheet(self) -> bool:
        """Given as a datasheet (bundled oil or kinematic viscosities)."""
        return (
            self.oil is not None
            or self.kinematic_viscosity_40_cst is not None
            or self.kinematic_viscosity_100_cst is not None
        )

    @model_validator(mode="after")
    def _forms(self):
        problems: list[tuple[str, str]] = []
        given = self.model_fields_set
        if self.datasheet:
            for k in ("viscosity", "density", "viscosity_temperature_coefficient"):
                if k in given and getattr(self, k) is not None:
                    problems.append(
                        (
                            k,
                            "not with a datasheet oil (oil or kinematic_viscosity_"
                            "*_cst): the viscosity and density follow from it",
                        )
                    )
            if self.oil is None:
                for k in ("kinematic_viscosity_40_cst", "kinematic_viscosity_100_cst"):
                    if getattr(self, k) is None:
                        problems.append((k, "required with the other kinematic viscosity"))
            if self.inlet_temperature_c is None:
                problems.append(
                    (
                        "inlet_temperature_c",
                        "required with a datasheet oil (the temperature it is supplied at)",
                    )
                )
        elif self.density_15 is not None:
            problems.append(("density_15", "only with a datasheet oil; give density"))
        if problems:
            raise Problems(problems)
        return self


class MaterialConfig(Section):
    """``[materials.<name>]``: an isotropic elastic material (substrate or coating)."""

    E: float = _arg(..., L.YOUNGS_MODULUS, "Young's modulus")
    nu: float = _arg(..., L.POISSON_RATIO, "Poisson's ratio")
    boundary_shear_coefficient: float | None = _lim(
        None,
        L.BOUNDARY_SHEAR_COEFFICIENT,
        "pressure coefficient ς of the boundary shear strength of its asperities (paper Eq. 17)",
    )
    label: str | None = _q(None, "", "display name (default: the table key)", min_length=1)
    thermal_conductivity: float | None = _arg(
        None,
        L.SOLID_CONDUCTIVITY,
        "thermal conductivity k (numerics.thermal; steel, dlc, wcc have literature defaults)",
    )
    density: float | None = _arg(None, L.SOLID_DENSITY, "density ρ (numerics.thermal)")
    specific_heat: float | None = _arg(
        None, L.SOLID_SPECIFIC_HEAT, "specific heat c (numerics.thermal)"
    )


class StrengthConfig(Section):
    """``[strength.<material>]``: strength of a material of the case (a key of
    ``[materials]``) for the safety factors and wear of the cycle's stresses
    (:mod:`tribodyn.physics.strength`). Keys not given take the typical values of
    steel, dlc or wcc when the material has that name (assumed or sourced: see the
    module), otherwise the factors that need them are not computed."""

    tensile_strength: float | None = _q(
        None, "Pa", "stress at which the material cracks in tension", gt=1e6, le=1e11
    )
    hardness: float | None = _q(None, "Pa", "indentation hardness H", gt=1e6, le=2e11)
    yield_strength: float | None = _q(
        None, "Pa", "tensile yield strength Y (absent: Tabor's H/3)", gt=1e6, le=1e11
    )
    adhesion_shear: float | None = _q(
        None, "Pa", "shear strength of its interface to the substrate (coatings)", gt=1e5, le=1e11
    )
    adhesion_tensile: float | None = _q(
        None,
        "Pa",
        "tensile strength of its interface to the substrate (coatings)",
        gt=1e5,
        le=1e11,
    )
    wear_coefficient: float | None = _q(
        None,
        "m³/(N m)",
        "dimensional Archard wear coefficient k measured for this surface "
        "(e.g. 1e-17 = 1e-8 mm³/(N m))",
        ge=0.0,
        le=1e-9,
    )


class StressConfig(Section):
    """``[stress]``: subsurface stresses, safety factors and wear along the cycle."""

    enabled: bool = _q(True, "", "compute the stresses of every surface set along the cycle")
    running_hours: float | None = _q(
        None,
        "h",
        "service life to check: wear depth after this many hours of running at the "
        "case's engine speed (needs a wear coefficient)",
        gt=0.0,
        le=1e7,
    )


#: σ of the typical ground cam on a ground tappet [m]
_GROUND_RMS = typical.COMPOSITE_RMS["ground"].value


class RoughnessConfig(Section):
    """``roughness = {…}``: composite roughness of the pair (paper Table 4). σ (``rms``)
    scales every asperity law; η and β are Greenwood–Tripp's (``asperity_model =
    "greenwood_tripp"``, which requires them) and otherwise only describe the summits
    (the asperity-scale stress estimate's β); absent, they follow from σ with the typical
    ratios (:func:`~tribodyn.physics.typical.typical_summits`)."""

    asperity_density: float | None = _arg(
        None,
        L.ASPERITY_DENSITY,
        "summit density η (the paper's ζ); absent: ηβσ/(βσ) with the typical ηβσ "
        "(required with Greenwood–Tripp)",
    )
    rms: float = _arg(..., L.ROUGHNESS_RMS, "composite RMS roughness σ")
    summit_radius: float | None = _arg(
        None,
        L.SUMMIT_RADIUS,
        "mean summit radius β; absent: σ/(σ/β) with the typical σ/β (required with "
        "Greenwood–Tripp)",
    )

    def arguments(self) -> dict[str, float]:
        """The arguments of :class:`~tribodyn.Roughness`: the keys given, and η and β
        from σ with the typical ratios where absent (from the typical ground σ where σ is
        outside its range, so that Roughness reports σ alone)."""
        sigma = self.rms if L.ROUGHNESS_RMS.contains(self.rms) else _GROUND_RMS
        eta, beta = typical.typical_summits(sigma)
        return {
            "asperity_density": eta if self.asperity_density is None else self.asperity_density,
            "rms": self.rms,
            "summit_radius": beta if self.summit_radius is None else self.summit_radius,
        }


#: Length units of ``measured_surface.unit`` (all are SurfaceTopography length units).
MAP_UNITS = ("m", "mm", "µm", "um", "nm", "pm", "Å")


class MeasuredSurfaceConfig(Section):
    """``measured_surface = {…}``: the composite surface whose boundary-element contact
    gives the asperity load–separation law (``asperity_model = "measured"``;
    :mod:`tribodyn.topography.load_separation`). Either a measured map (``topography``)
    or a self-affine spectrum (``hurst``, ``short_cutoff``, ``long_cutoff``) with the
    set's roughness ``rms``."""

    topography: str | None = _q(
        None, "", "measured composite height map (any format `tribodyn topography` reads)"
    )
    unit: Literal[MAP_UNITS] | None = _q(  # type: ignore[valid-type]
        None,
        "",
        "length unit of the map file's numbers (heights and physical_sizes), for files "
        "that store none (.npy, plain text)",
    )
    physical_sizes: list[float] | None = _q(
        None,
        "unit",
        "lateral size [Lx, Ly] of the map in `unit` ([L]: square), for files without "
        "lateral calibration (.npy, plain text)",
        min_length=1,
        max_length=2,
    )
    hurst: float | None = _q(None, "", "Hurst exponent of the spectrum", gt=0.0, le=1.0)
    short_cutoff: float | None = _q(
        None, "m", "shortest wavelength of the spectrum (instrument resolution)", gt=1e-8, lt=1e-3
    )
    long_cutoff: float | None = _q(
        None, "m", "longest wavelength of the self-affine range", gt=1e-8, lt=1e-2
    )
    grid: int = _q(
        _SURFACE_LAW_DEFAULTS["grid"], "", "points per side of the synthetic map", ge=32, le=512
    )
    seed: int = _q(_SURFACE_LAW_DEFAULTS["seed"], "", "seed of the synthetic map", ge=0)
    hardness: float = _q(
        TYPICAL_STRENGTH["steel"].hardness,
        "Pa",
        "hardness of the softer surface, where asperity pressure is capped (default: "
        "hardened steel 60 HRC, 697 HV, ASTM E140; tribodyn.physics.strength)",
        gt=1e8,
        le=1e11,
    )

    @model_validator(mode="after")
    def _one_source(self):
        spectrum = (self.hurst, self.short_cutoff, self.long_cutoff)
        given = [v is not None for v in spectrum]
        if self.topography is not None and any(given):
            raise Problems(
                [("topography", "give either a topography file or hurst/short_cutoff/long_cutoff")]
            )
        if self.topography is None:
            for key in ("unit", "physical_sizes"):
                if getattr(self, key) is not None:
                    raise Problems([(key, "only with a topography file (not with a spectrum)")])
        if self.physical_sizes is not None and not all(
            math.isfinite(v) and v > 0.0 for v in self.physical_sizes
        ):
            raise Problems([("physical_sizes", f"lengths must be > 0 (got {self.physical_sizes})")])
        if self.topography is None and not all(given):
            missing = [n for n, g in zip(("hurst", "short_cutoff", "long_cutoff"), given) if not g]
            raise Problems(
                [
                    (
                        missing[0],
                        "required (a measured_surface needs a topography file or all of "
                        "hurst, short_cutoff and long_cutoff)",
                    )
                ]
            )
        if self.topography is None:
            assert self.short_cutoff is not None and self.long_cutoff is not None
            if not 2.0 * self.short_cutoff <= self.long_cutoff:
                raise Problems([("short_cutoff", "must be at most half of long_cutoff")])
            if self.short_cutoff < 4.0 * (2.0 * self.long_cutoff / self.grid):
                raise Problems(
                    [
                        (
                            "short_cutoff",
                            f"must be ≥ 4 pixels of the map (2·long_cutoff/grid = "
                            f"{2.0 * self.long_cutoff / self.grid:.3g} m); raise grid or "
                            "short_cutoff",
                        )
                    ]
                )
        return self


class SurfaceSetConfig(Section):
    """``[[surface_sets]]``: one tappet surface to study (the cam is uncoated)."""

    name: str = _q(
        ...,
        "",
        "identifier (letters, digits, _ . + -), unique",
        min_length=1,
        max_length=64,
        pattern=_NAME_PATTERN,
    )
    coating: str | None = _q(
        None,
        "",
        "coating material on the tappet (a key of [materials]); absent: uncoated",
        min_length=1,
    )
    coating_thickness: float | None = _arg(
        None, L.COATING_THICKNESS, "coating thickness (required with a coating)"
    )
    substrate: str = _q(
        "steel", "", "tappet substrate material (a key of [materials])", min_length=1
    )
    roughness: RoughnessConfig = _q(..., "", "composite roughness of the cam/tappet pair")
    asperity_model: Literal["surface", "measured", "greenwood_tripp"] = _q(
        "surface",
        "",
        'asperity load and area. "surface" (default): the law of a boundary-element '
        "contact of the set's surface: its measured_surface if given, otherwise a "
        "self-affine surface with the roughness rms and the typical spectrum of "
        'tribodyn.physics.typical (SURFACE_HURST, SURFACE_*_CUTOFF). "measured": the '
        'same law, measured_surface required. "greenwood_tripp": Greenwood–Tripp from '
        "asperity_density, rms and summit_radius",
    )
    measured_surface: MeasuredSurfaceConfig | None = _q(
        None,
        "",
        'the surface of the surface law (asperity_model "surface" or "measured"); '
        "absent: a self-affine surface with the typical spectrum",
    )
    boundary_shear_coefficient: float | None = _arg(
        None,
        L.BOUNDARY_SHEAR_COEFFICIENT,
        "ς of the pair; absent: the coating's (or the substrate's if uncoated)",
    )
    boundary_shear_strength: float = _arg(
        typical.BOUNDARY_SHEAR_STRENGTH.value,  # ς is then a measured boundary μ_b
        L.BOUNDARY_SHEAR_STRENGTH,
        "τ₀ of the boundary shear law τ = τ₀ + ς p_a (Eq. 17)",
    )

    @property
    def materials(self) -> tuple[str, ...]:
        """The keys of ``[materials]`` the tappet is made of (substrate, coating)."""
        return (self.substrate,) if self.coating is None else (self.substrate, self.coating)

    def boundary_friction(self, materials: dict[str, MaterialConfig]) -> tuple[float | None, float]:
        """(ς, τ₀) of the boundary shear law (Eq. 17) of the pair: its own ς, else that of
        its surface material in ``materials`` (the coating, or the substrate if uncoated;
        None if neither gives one)."""
        sigma = self.boundary_shear_coefficient
        if sigma is None:
            sigma = materials[self.coating or self.substrate].boundary_shear_coefficient
        return sigma, self.boundary_shear_strength

    @model_validator(mode="before")
    @classmethod
    def _none_coating(cls, data):
        # ``coating = "none"`` is accepted as "uncoated" (TOML has no null).
        if (
            isinstance(data, dict)
            and isinstance(data.get("coating"), str)
            and data["coating"].strip().lower() in ("none", "")
        ):
            data = {k: v for k, v in data.items() if k != "coating"}
        return data

    @model_validator(mode="after")
    def _asperity_model(self):
        if self.asperity_model == "measured" and self.measured_surface is None:
            raise Problems(
                [
                    (
                        "measured_surface",
                        'required with asperity_model = "measured": give { topography = '
                        '"map.sdf" } or { hurst, short_cutoff, long_cutoff }',
                    )
                ]
            )
        rough = self.roughness
        absent = [k for k in ("asperity_density", "summit_radius") if getattr(rough, k) is None]
        if self.asperity_model == "greenwood_tripp" and absent:
            raise Problems(
                [
                    (
                        f"roughness.{k}",
                        'required with asperity_model = "greenwood_tripp", whose asperity '
                        "load depends on η and β (from a profile: tribodyn topography); or use "
                        "the surface law, which needs only rms",
                    )
                    for k in absent
                ]
            )
        derived = rough.arguments()
        limits = {"asperity_density": L.ASPERITY_DENSITY, "summit_radius": L.SUMMIT_RADIUS}
        checked = L.ROUGHNESS_RMS.contains(rough.rms)  # else Roughness reports σ
        if bad := [k for k in absent if checked and not limits[k].contains(derived[k])]:
            raise Problems(
                [
                    (
                        f"roughness.{k}",
                        f"required for rms = {rough.rms:.3g} m: the typical ratios "
                        f"(ηβσ = {typical.ROUGHNESS_PARAMETER.value:g}, σ/β = "
                        f"{typical.RMS_TO_SUMMIT_RADIUS.value:g}) give {derived[k]:.3g} "
                        f"{limits[k].unit}, outside {limits[k].describe()}; give it",
                    )
                    for k in bad
                ]
            )
        if self.asperity_model == "greenwood_tripp" and self.measured_surface is not None:
            raise Problems(
                [
                    (
                        "asperity_model",
                        'must be "surface" or "measured" when measured_surface is given',
                    )
                ]
            )
        return self

    @model_validator(mode="after")
    def _coating_thickness(self):
        if self.coating is not None and self.coating_thickness is None:
            raise Problems(
                [
                    (
                        "coating_thickness",
                        f"required when a coating is named (coating = {self.coating!r}); "
                        "give the thickness in m, e.g. 4e-6",
                    )
                ]
            )
        if self.coating is None and self.coating_thickness is not None:
            raise Problems(
                [
                    (
                        "coating_thickness",
                        'given but no coating is named; add `coating = "<material>"` or '
                        "remove the thickness",
                    )
                ]
            )
        return self


def typical_materials() -> dict:
    """Default ``[materials]``: typical elastic constants of steel, a-C:H DLC and WC-C
    (:data:`~tribodyn.physics.typical_engine.STEEL_MODULUS`, ``DLC_MODULUS``, ``WCC_MODULUS``)
    with ς = the typical boundary friction coefficient of each surface against steel in a
    ZDDP oil (:data:`tribodyn.physics.typical.BOUNDARY_FRICTION`, used with τ₀ = 0)."""
    return {
        k: MaterialConfig(**{key: v.value for key, v in t.items()}, label=_TYPICAL_LABELS[k])
        for k, t in TYPICAL_MATERIALS.items()
    }


#: The typical value of each key of the default ``[materials]`` (typical_materials).
TYPICAL_MATERIALS = {
    "steel": {
        "E": typical_engine.STEEL_MODULUS,
        "nu": typical_engine.STEEL_POISSON,
        "boundary_shear_coefficient": typical.boundary_friction("steel"),
    },
    "dlc": {
        "E": typical_engine.DLC_MODULUS,
        "nu": typical_engine.COATING_POISSON,
        "boundary_shear_coefficient": typical.boundary_friction("a-C:H"),
    },
    "wcc": {
        "E": typical_engine.WCC_MODULUS,
        "nu": typical_engine.COATING_POISSON,
        "boundary_shear_coefficient": typical.boundary_friction("WC-C"),
    },
}
_TYPICAL_LABELS = {"steel": "steel", "dlc": "DLC", "wcc": "WC-C"}


def typical_surface_sets() -> list:
    """Default surface sets: the paper's five (uncoated; DLC and WC-C at 1 and 4 µm), each
    with the typical composite roughness of a ground cam on a ground tappet: σ from
    :data:`~tribodyn.physics.typical.COMPOSITE_RMS`, β = σ/(σ/β) and η = ηβσ/(βσ)."""
    eta, beta = typical.typical_summits(_GROUND_RMS)
    rough = RoughnessConfig(asperity_density=eta, rms=_GROUND_RMS, summit_radius=beta)
    coated = [
        SurfaceSetConfig(
            name=f"{coat}_{t_um}um", coating=coat, coating_thickness=t_um * 1e-6, roughness=rough
        )
        for coat in ("dlc", "wcc")
        for t_um in (1, 4)
    ]
    return [SurfaceSetConfig(name="uncoated", roughness=rough), *coated]

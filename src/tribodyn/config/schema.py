"""The case-file schema: one pydantic model per TOML section.

Every field records its unit (``json_schema_extra={"unit": …}``), its allowed range and a
one-line description; ``docs/case-files.md`` documents them and the error messages quote
them. Defaults are the paper's case (:mod:`tribodyn.paper`) and tribodyn's numerical
defaults. Sections are strict (no type coercion), frozen, and reject unknown keys.
"""

from __future__ import annotations

import dataclasses
from typing import Annotated, Any, Literal, Optional, Union

from pydantic import BaseModel, ConfigDict, Discriminator, Field, Tag, model_validator

from .. import paper
from ..physics.friction import BOUNDARY_SHEAR_STRENGTH
from ..physics import limits as L
from ..valvetrain.parameters import ValvetrainParameters
from .errors import Problems

__all__ = ["CaseInfo", "Engine", "AccelerationCamConfig", "CircularArcCamConfig",
           "TableCamConfig", "CAM_MODELS", "CamConfig", "Valvetrain", "LubricantConfig",
           "MaterialConfig", "RoughnessConfig", "SurfaceSetConfig", "Numerics",
           "paper_materials", "paper_surface_sets"]

_VT_DEFAULTS = {f.name: f.default for f in dataclasses.fields(ValvetrainParameters)}
_NAME_PATTERN = r"^[A-Za-z0-9][A-Za-z0-9_.+\-]*$"


def _q(default: Any, unit: str, doc: str, **constraints) -> Any:
    """A field with its unit recorded (used in error messages and the docs)."""
    return Field(default, description=doc, json_schema_extra={"unit": unit}, **constraints)


def _lim(default: Any, limit: "L.Limit", doc: str) -> Any:
    """A field whose unit and range are a shared limit of :mod:`tribodyn.physics.limits`
    (the physics constructors check the same range)."""
    return _q(default, limit.unit, doc, **limit.constraints())


class Section(BaseModel):
    """Base of all case sections: unknown keys rejected, no silent type coercion."""

    model_config = ConfigDict(extra="forbid", strict=True, frozen=True, allow_inf_nan=False,
                              validate_default=False)


# ----------------------------------------------------------------------------- sections
class CaseInfo(Section):
    """``[case]``: identification of the study."""

    name: str = _q("case", "", "short name of the case (used in reports and file names)",
                   min_length=1, max_length=64, pattern=_NAME_PATTERN)
    description: str = _q("", "", "free text")


class Engine(Section):
    """``[engine]``: operating point. The cam turns at half the engine speed (4-stroke)."""

    speed_rpm: float = _lim(paper.ENGINE_SPEED_RPM, L.ENGINE_SPEED,
                            "engine (crank) speed; cam speed = speed_rpm/2")


class _CamBase(Section):
    material: str = _q("steel", "", "cam material (a key of [materials]); the cam is uncoated",
                       min_length=1)
    base_radius: float = _q(paper.CAM_BASE_RADIUS, "m", "base-circle radius r_b", gt=0.0, lt=1.0)
    width: float = _lim(paper.CAM_WIDTH, L.LENGTH_BELOW_1M, "cam width (axial contact length)")


class AccelerationCamConfig(_CamBase):
    """``[cam] type = "acceleration"``: :class:`~tribodyn.valvetrain.AccelerationCam`."""

    type: Literal["acceleration"] = "acceleration"
    max_lift: float = _q(paper.CAM_MAX_LIFT, "m", "maximum lift L incl. the ramp", gt=0.0, lt=1.0)
    event_angle_deg: float = _q(171.0, "deg (cam)", "total event incl. both ramps",
                                gt=0.0, lt=360.0)
    nose_radius: float = _q(3e-3, "m", "radius of curvature at the nose", gt=0.0, lt=1.0)
    ramp_height: float = _q(0.2e-3, "m", "opening/closing ramp height (0: no ramp)",
                            ge=0.0, lt=1.0)
    ramp_angle_deg: float = _q(20.0, "deg (cam)", "ramp length (0: no ramp)", ge=0.0, lt=180.0)
    pulse_share: float = _q(0.25, "", "share of the half main event taken by the positive "
                                      "acceleration pulse", gt=0.0, lt=1.0)
    ramp_pulse_share: float = _q(0.5, "", "share of the ramp taken by its acceleration pulse",
                                 gt=0.0, le=1.0)
    nose_angle_deg: float = _q(180.0, "deg (cam)", "cam angle of maximum lift", ge=0.0,
                               lt=360.0)


class CircularArcCamConfig(_CamBase):
    """``[cam] type = "circular_arc"``: :class:`~tribodyn.valvetrain.CircularArcCam`."""

    type: Literal["circular_arc"]
    max_lift: float = _q(paper.CAM_MAX_LIFT, "m", "maximum lift L", gt=0.0, lt=1.0)
    flank_radius: float = _q(0.030, "m", "flank arc radius (> base_radius)", gt=0.0, lt=1.0)
    nose_radius: float = _q(3e-3, "m", "nose arc radius (< base_radius)", gt=0.0, lt=1.0)
    nose_angle_deg: float = _q(180.0, "deg (cam)", "cam angle of maximum lift", ge=0.0,
                               lt=360.0)


class TableCamConfig(_CamBase):
    """``[cam] type = "table"``: :class:`~tribodyn.valvetrain.TabulatedCam` from a CSV file."""

    type: Literal["table"]
    path: str = _q(..., "", "CSV lift table (cam angle, lift), relative to the case file",
                   min_length=1)
    angle_unit: Literal["deg", "rad"] = _q("deg", "", "unit of the angle column")
    lift_unit: Literal["mm", "m", "um", "in"] = _q("mm", "", "unit of the lift column")
    smoothing: float = _q(0.0, "m", "allowed RMS deviation of the smoothing spline "
                                    "(0: interpolate)", ge=0.0, lt=1e-3)
    max_lift: Optional[float] = _q(None, "m", "optional check: the table's maximum lift must "
                                              "agree within 1 %", gt=0.0, lt=1.0)


CAM_MODELS = {"acceleration": AccelerationCamConfig, "circular_arc": CircularArcCamConfig,
              "table": TableCamConfig}


def _cam_tag(v: Any):
    if isinstance(v, dict):
        return v.get("type", "acceleration")
    return getattr(v, "type", None)


CamConfig = Annotated[Union[Annotated[AccelerationCamConfig, Tag("acceleration")],
                            Annotated[CircularArcCamConfig, Tag("circular_arc")],
                            Annotated[TableCamConfig, Tag("table")]],
                      Discriminator(_cam_tag)]


class Valvetrain(Section):
    """``[valvetrain]``: mirrors :class:`~tribodyn.valvetrain.ValvetrainParameters`
    (``cam_width`` comes from ``[cam] width``); defaults are its defaults, ranges its
    ranges (:mod:`tribodyn.physics.limits`)."""

    valve_mass: float = _lim(_VT_DEFAULTS["valve_mass"], L.MASS, "valve + retainer + collets")
    tappet_mass: float = _lim(_VT_DEFAULTS["tappet_mass"], L.MASS, "flat (bucket) tappet")
    spring_mass: float = _lim(_VT_DEFAULTS["spring_mass"], L.MASS, "active valve-spring mass")
    spring_rate: float = _lim(_VT_DEFAULTS["spring_rate"], L.SPRING_RATE, "valve-spring rate")
    spring_preload: float = _lim(_VT_DEFAULTS["spring_preload"], L.SPRING_PRELOAD,
                                 "installed spring load (valve closed)")
    spring_masses: int = _lim(_VT_DEFAULTS["spring_masses"], L.SPRING_MASSES,
                              "lumped coil masses of the spring model (0: massless spring)")
    spring_damping_ratio: float = _lim(_VT_DEFAULTS["spring_damping_ratio"],
                                       L.SPRING_DAMPING_RATIO,
                                       "damping ratio of the first surge mode")
    contact_stiffness: Optional[float] = _lim(None, L.STIFFNESS, "linear cam–tappet contact "
                                              "stiffness (absent: Palmgren line-contact law)")
    contact_modulus: float = _lim(_VT_DEFAULTS["contact_modulus"], L.CONTACT_MODULUS,
                                  "E' of the cam/tappet pair for the Palmgren law")
    contact_damping: float = _lim(_VT_DEFAULTS["contact_damping"], L.DAMPING,
                                  "cam–tappet contact damping")
    camshaft_stiffness: Optional[float] = _lim(None, L.STIFFNESS, "camshaft/bearing support "
                                               "stiffness in series (absent: rigid)")
    tappet_valve_stiffness: float = _lim(_VT_DEFAULTS["tappet_valve_stiffness"], L.STIFFNESS,
                                         "bucket crown + shim + valve tip")
    tappet_valve_damping: float = _lim(_VT_DEFAULTS["tappet_valve_damping"], L.DAMPING,
                                       "tappet–valve damping")
    lash: float = _lim(_VT_DEFAULTS["lash"], L.LASH, "tappet–valve clearance on the base circle")
    seat_stiffness: float = _lim(_VT_DEFAULTS["seat_stiffness"], L.STIFFNESS,
                                 "valve stem + seat insert")
    seat_damping: float = _lim(_VT_DEFAULTS["seat_damping"], L.DAMPING, "valve-seat damping")
    spring_seat_stiffness: float = _lim(_VT_DEFAULTS["spring_seat_stiffness"], L.STIFFNESS,
                                        "retainer–spring seating")
    spring_support_stiffness: float = _lim(_VT_DEFAULTS["spring_support_stiffness"],
                                           L.STIFFNESS, "head–spring seating")
    damping_force_ramp: float = _lim(_VT_DEFAULTS["damping_force_ramp"], L.DAMPING_FORCE_RAMP,
                                     "elastic force over which unilateral damping phases in")
    bore_friction_coefficient: float = _lim(_VT_DEFAULTS["bore_friction_coefficient"],
                                            L.BORE_FRICTION_COEFFICIENT,
                                            "friction coefficient of the tappet in its bore")
    bore_friction_velocity: float = _lim(_VT_DEFAULTS["bore_friction_velocity"],
                                         L.BORE_FRICTION_VELOCITY,
                                         "regularisation velocity of the bore friction")
    tappet_radius: float = _lim(_VT_DEFAULTS["tappet_radius"], L.LENGTH_BELOW_1M,
                                "radius of the tappet face (max contact offset must stay below)")


class LubricantConfig(Section):
    """``[lubricant]``: :class:`~tribodyn.Lubricant` (Roelands + Dowson–Higginson)."""

    viscosity: float = _lim(paper.LUBRICANT["viscosity"], L.VISCOSITY,
                            "dynamic viscosity μ₀ at ambient pressure (Roelands needs "
                            "μ₀ > exp(−9.67))")
    pressure_viscosity: float = _lim(paper.LUBRICANT["pressure_viscosity"],
                                     L.PRESSURE_VISCOSITY, "pressure–viscosity coefficient α")
    density: float = _lim(paper.ASSUMED_DENSITY, L.DENSITY, "density ρ₀ at ambient pressure")
    eyring_stress: float = _lim(paper.LUBRICANT["eyring_stress"], L.EYRING_STRESS,
                                "Eyring stress τ_E")
    limiting_shear_coefficient: float = _lim(paper.LUBRICANT["limiting_shear_coefficient"],
                                             L.LIMITING_SHEAR_COEFFICIENT,
                                             "pressure slope Λ of the limiting shear stress "
                                             "τ_L = τ_L0 + Λ p")
    limiting_shear_stress: float = _lim(0.0, L.LIMITING_SHEAR_STRESS,
                                        "intercept τ_L0 of the limiting shear stress (paper: 0)")
    compressible: bool = _q(True, "", "Dowson–Higginson density (false: constant density)")
    viscosity_model: Literal["roelands", "barus"] = _q("roelands", "", "piezo-viscosity law")


class MaterialConfig(Section):
    """``[materials.<name>]``: an isotropic elastic material (substrate or coating)."""

    E: float = _lim(..., L.YOUNGS_MODULUS, "Young's modulus")
    nu: float = _lim(..., L.POISSON_RATIO, "Poisson's ratio")
    boundary_shear_coefficient: Optional[float] = _lim(
        None, L.BOUNDARY_SHEAR_COEFFICIENT, "pressure coefficient ς of the boundary shear "
                                            "strength of its asperities (paper Eq. 17)")
    label: Optional[str] = _q(None, "", "display name (default: the table key)",
                              min_length=1)


class RoughnessConfig(Section):
    """``roughness = {…}``: composite Greenwood–Tripp roughness of the pair (paper Table 4)."""

    asperity_density: float = _lim(..., L.ASPERITY_DENSITY, "summit density η (the paper's ζ)")
    rms: float = _lim(..., L.ROUGHNESS_RMS, "composite RMS roughness σ")
    summit_radius: float = _lim(..., L.SUMMIT_RADIUS, "mean summit radius β")


class SurfaceSetConfig(Section):
    """``[[surface_sets]]``: one tappet surface to study (the cam is uncoated)."""

    name: str = _q(..., "", "identifier (letters, digits, _ . + -), unique", min_length=1,
                   max_length=64, pattern=_NAME_PATTERN)
    coating: Optional[str] = _q(None, "", "coating material on the tappet (a key of "
                                          "[materials]); absent: uncoated", min_length=1)
    coating_thickness: Optional[float] = _lim(None, L.COATING_THICKNESS, "coating thickness "
                                              "(required with a coating)")
    substrate: str = _q("steel", "", "tappet substrate material (a key of [materials])",
                        min_length=1)
    roughness: RoughnessConfig = _q(..., "", "composite roughness of the cam/tappet pair")
    boundary_shear_coefficient: Optional[float] = _lim(
        None, L.BOUNDARY_SHEAR_COEFFICIENT, "ς of the pair; absent: the coating's (or the "
                                            "substrate's if uncoated)")
    boundary_shear_strength: float = _lim(
        BOUNDARY_SHEAR_STRENGTH, L.BOUNDARY_SHEAR_STRENGTH,
        "τ₀ of the boundary shear law τ = τ₀ + ς p_a (Eq. 17)")

    @model_validator(mode="before")
    @classmethod
    def _none_coating(cls, data):
        # ``coating = "none"`` is accepted as "uncoated" (TOML has no null).
        if isinstance(data, dict) and isinstance(data.get("coating"), str) \
                and data["coating"].strip().lower() in ("none", ""):
            data = {k: v for k, v in data.items() if k != "coating"}
        return data

    @model_validator(mode="after")
    def _coating_thickness(self):
        if self.coating is not None and self.coating_thickness is None:
            raise Problems([("coating_thickness",
                              f"required when a coating is named (coating = {self.coating!r}); "
                              "give the thickness in m, e.g. 4e-6")])
        if self.coating is None and self.coating_thickness is not None:
            raise Problems([("coating_thickness",
                              "given but no coating is named; add `coating = \"<material>\"` or "
                              "remove the thickness")])
        return self


class Numerics(Section):
    """``[numerics]``: solver settings."""

    n: int = _q(0, "", "EHL grid nodes (uniform); 0 = automatic from the contact "
                       "(512…4096; steady solves refine until h_c, h_min change < 0.5 % "
                       "on doubling); at most 4096 (the transient steps factor dense "
                       "matrices)",
                ge=0, le=L.EHL_NODES_TRANSIENT.le)
    min_load: float = _q(5.0, "N", "contact force below which the EHL is not solved "
                                   "(cam on the base circle: no load, no film)",
                         gt=0.0, le=1e4)
    inlet: float = _lim(4.0, L.DOMAIN_HALF_WIDTHS,
                        "EHL domain upstream of the centre, in Hertz half-widths")
    outlet: float = _lim(1.75, L.DOMAIN_HALF_WIDTHS,
                         "EHL domain downstream of the centre, in Hertz half-widths")
    inlet_truncation: float = _lim(0.005, L.INLET_TRUNCATION,
                                   "EHL domain upstream at least as far as the cut-off inlet "
                                   "loses this share of the load (far-field estimate)")
    inlet_rigid: float = _lim(4.0, L.DOMAIN_RIGID_LENGTHS,
                              "EHL domain upstream at least this many rigid inlet lengths "
                              "√(2R h) (squeeze films)")
    outlet_rigid: float = _lim(2.0, L.DOMAIN_RIGID_LENGTHS,
                               "EHL domain downstream, in rigid inlet lengths")
    tol: float = _lim(1e-9, L.NEWTON_TOL, "EHL Newton tolerance (scaled update and residual)")
    max_iter: int = _lim(60, L.NEWTON_MAX_ITER, "EHL Newton iterations per solve")
    time_order: Literal[1, 2] = _q(2, "", "EHL time discretisation: 1 backward Euler, 2 BDF2")
    crank_step_deg: float = _q(1.0, "deg (crank)", "time step of the transient EHL along the "
                                                   "cycle", gt=0.0, le=5.0)
    viscous_model: Literal["eyring", "newtonian"] = _q("eyring", "", "viscous friction law")
    limiting_shear: bool = _q(True, "", "cap viscous shear at Λp")
    greenwood_tripp: Literal["exact", "paper"] = _q(
        "exact", "", "Greenwood–Tripp functions: exact, or the paper's polynomial fits "
                     "(reproduction only)")
    film_formula: Literal["moes", "pan_hamrock", "dowson_toyoda"] = _q(
        "moes", "", "film formula of the explicit (analytic) tribology in the dynamics")
    cycles: int = _q(2, "", "engine cycles simulated (the last is presented)", ge=1, le=50)
    output_step_deg: float = _q(0.25, "deg (crank)", "output step of the valvetrain dynamics",
                                gt=0.0, le=5.0)
    max_step_deg: float = _q(1.0, "deg (crank)", "largest integrator step of the dynamics",
                             gt=0.0, le=10.0)
    dynamics_method: Literal["LSODA", "Radau", "BDF"] = _q("LSODA", "",
                                                           "stiff integrator (solve_ivp)")
    dynamics_rtol: float = _q(1e-6, "", "relative tolerance of the dynamics", gt=0.0, lt=0.1)
    implicit_coupling: bool = _q(True, "", "also run the implicit dynamics (numerical EHL "
                                           "film and friction in the dynamics) for the "
                                           "comparison with the explicit run")
    coupling_iterations: int = _q(6, "", "dynamics ↔ EHL iterations of the implicit coupling",
                                  ge=1, le=100)
    workers: int = _q(0, "", "worker processes for the surface sets (0: one per CPU core)",
                      ge=0, le=4096)



def paper_materials() -> dict:
    """Table 6 as ``[materials]`` (moduli in GPa: the paper prints "MPa")."""
    return {k: MaterialConfig(**v) for k, v in paper.MATERIALS.items()}


def paper_surface_sets() -> list:
    """The bundled case's surface sets: uncoated, DLC and WC-C at 1 and 4 µm, with the
    Table 4 roughness of the coating type (the same for both thicknesses)."""
    sets = [SurfaceSetConfig(name="uncoated",
                             roughness=RoughnessConfig(**paper.ROUGHNESS["uncoated"]))]
    for coat in ("dlc", "wcc"):
        for t_um in (1, 4):
            sets.append(SurfaceSetConfig(name=f"{coat}_{t_um}um", coating=coat,
                                         coating_thickness=t_um * 1e-6,
                                         roughness=RoughnessConfig(**paper.ROUGHNESS[coat])))
    return sets

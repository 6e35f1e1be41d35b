"""Case files: TOML input validated with pydantic, and builders of tribodyn objects.

A case file describes one study: engine speed, cam, valvetrain, lubricant, materials, the
surface sets to compare (uncoated, DLC, WC-C, …) and the numerical settings. Every key is
in SI units unless its name says otherwise (``speed_rpm``, ``*_deg``); see
``docs/case-files.md`` for the full list with units, ranges and defaults. An empty file is
the paper's case (Andreou et al. 2023, bundled as ``cases/andreou2023.toml``)::

    from tribodyn.config import load_case
    case = load_case()                      # the bundled paper case
    case = load_case("my_case.toml")
    cam, params = case.cam(), case.valvetrain_parameters()
    for s in case.surface_sets():           # SurfaceSet(name, bodies, roughness, ς, …)
        r = solve_ehl(w, R, ue, us, s.bodies, case.lubricant(), s.roughness,
                      options=case.ehl_options(s))

Validation errors (unknown keys, values out of range, wrong types, cross-field rules such
as a surface set naming an undefined material) raise :class:`~tribodyn.InputError` with
one line per problem: the dotted key path, the allowed range or choices, and the value
given. The cam profile, lubricant and valvetrain parameters are built once during
validation, so a case that loads can be run; their own error messages are kept.

Models are frozen; change a validated case with :meth:`Case.updated` (validates again)
rather than ``model_copy``.
"""

from __future__ import annotations

import dataclasses
import difflib
import math
import os
import re
import tomllib
from pathlib import Path
from typing import Annotated, Any, Literal, Optional, Union, get_args, get_origin

from pydantic import (BaseModel, ConfigDict, Discriminator, Field, PrivateAttr, Tag,
                      ValidationError, ValidationInfo, model_validator)

from ._validation import InputError
from .contact.ehl import EHLOptions
from .physics.asperity import Roughness
from .physics.friction import BOUNDARY_SHEAR_STRENGTH
from .physics.lubricant import ROELANDS_MU_INF, Lubricant
from .physics.materials import Body, Coating, Material
from .valvetrain.cams import AccelerationCam, CamProfile, CircularArcCam, TabulatedCam
from .valvetrain.kinematics import rpm_to_cam_speed
from .valvetrain.parameters import ValvetrainParameters

__all__ = ["Case", "SurfaceSet", "load_case", "bundled_cases", "DEFAULT_CASE",
           "CASES_DIR", "to_toml"]

#: Folder of the bundled case files.
CASES_DIR = Path(__file__).resolve().parent / "cases"
#: The bundled default case (the paper's).
DEFAULT_CASE = CASES_DIR / "andreou2023.toml"

_VT_DEFAULTS = {f.name: f.default for f in dataclasses.fields(ValvetrainParameters)}
_NAME_PATTERN = r"^[A-Za-z0-9][A-Za-z0-9_.+\-]*$"


def _q(default: Any, unit: str, doc: str, **constraints) -> Any:
    """A field with its unit recorded (used in error messages and the docs)."""
    return Field(default, description=doc, json_schema_extra={"unit": unit}, **constraints)


class _Section(BaseModel):
    """Base of all case sections: unknown keys rejected, no silent type coercion."""

    model_config = ConfigDict(extra="forbid", strict=True, frozen=True, allow_inf_nan=False,
                              validate_default=False)


class _Problems(ValueError):
    """Cross-field problems found by a model validator: (relative key path, message)."""

    def __init__(self, items: list[tuple[str, str]]):
        super().__init__("; ".join(f"{p}: {m}" if p else m for p, m in items))
        self.items = items


class _CamTableError(InputError):
    """A lift-table problem, with the ``[cam]`` key it belongs to."""

    def __init__(self, key: str, message: str):
        super().__init__(message)
        self.key = f"cam.{key}"


# ----------------------------------------------------------------------------- sections
class CaseInfo(_Section):
    """``[case]``: identification of the study."""

    name: str = _q("case", "", "short name of the case (used in reports and file names)",
                   min_length=1, max_length=64, pattern=_NAME_PATTERN)
    description: str = _q("", "", "free text")


class Engine(_Section):
    """``[engine]``: operating point. The cam turns at half the engine speed (4-stroke)."""

    speed_rpm: float = _q(3000.0, "rpm", "engine (crank) speed; cam speed = speed_rpm/2",
                          gt=0.0, le=50000.0)


class _CamBase(_Section):
    material: str = _q("steel", "", "cam material (a key of [materials]); the cam is uncoated",
                       min_length=1)
    base_radius: float = _q(0.015, "m", "base-circle radius r_b", gt=0.0, lt=1.0)
    width: float = _q(0.012, "m", "cam width (axial contact length)", gt=0.0, lt=1.0)


class AccelerationCamConfig(_CamBase):
    """``[cam] type = "acceleration"``: :class:`~tribodyn.valvetrain.AccelerationCam`."""

    type: Literal["acceleration"] = "acceleration"
    max_lift: float = _q(9.3e-3, "m", "maximum lift L incl. the ramp", gt=0.0, lt=1.0)
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
    max_lift: float = _q(9.3e-3, "m", "maximum lift L", gt=0.0, lt=1.0)
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


class Valvetrain(_Section):
    """``[valvetrain]``: mirrors :class:`~tribodyn.valvetrain.ValvetrainParameters`
    (``cam_width`` comes from ``[cam] width``); defaults are its defaults."""

    valve_mass: float = _q(_VT_DEFAULTS["valve_mass"], "kg", "valve + retainer + collets",
                           gt=0.0)
    tappet_mass: float = _q(_VT_DEFAULTS["tappet_mass"], "kg", "flat (bucket) tappet", gt=0.0)
    spring_mass: float = _q(_VT_DEFAULTS["spring_mass"], "kg", "active valve-spring mass",
                            gt=0.0)
    spring_rate: float = _q(_VT_DEFAULTS["spring_rate"], "N/m", "valve-spring rate", gt=0.0)
    spring_preload: float = _q(_VT_DEFAULTS["spring_preload"], "N",
                               "installed spring load (valve closed)", gt=0.0)
    spring_masses: int = _q(_VT_DEFAULTS["spring_masses"], "",
                            "lumped coil masses of the spring model (0: massless spring)",
                            ge=0, le=200)
    spring_damping_ratio: float = _q(_VT_DEFAULTS["spring_damping_ratio"], "",
                                     "damping ratio of the first surge mode", ge=0.0, lt=1.0)
    contact_stiffness: Optional[float] = _q(None, "N/m", "linear cam–tappet contact "
                                            "stiffness (absent: Palmgren line-contact law)",
                                            gt=0.0)
    contact_modulus: float = _q(_VT_DEFAULTS["contact_modulus"], "Pa",
                                "E' of the cam/tappet pair for the Palmgren law", gt=0.0)
    contact_damping: float = _q(_VT_DEFAULTS["contact_damping"], "N·s/m",
                                "cam–tappet contact damping", ge=0.0)
    camshaft_stiffness: Optional[float] = _q(None, "N/m", "camshaft/bearing support "
                                             "stiffness in series (absent: rigid)", gt=0.0)
    tappet_valve_stiffness: float = _q(_VT_DEFAULTS["tappet_valve_stiffness"], "N/m",
                                       "bucket crown + shim + valve tip", gt=0.0)
    tappet_valve_damping: float = _q(_VT_DEFAULTS["tappet_valve_damping"], "N·s/m",
                                     "tappet–valve damping", ge=0.0)
    lash: float = _q(_VT_DEFAULTS["lash"], "m", "tappet–valve clearance on the base circle",
                     ge=0.0, lt=0.01)
    seat_stiffness: float = _q(_VT_DEFAULTS["seat_stiffness"], "N/m",
                               "valve stem + seat insert", gt=0.0)
    seat_damping: float = _q(_VT_DEFAULTS["seat_damping"], "N·s/m", "valve-seat damping",
                             ge=0.0)
    spring_seat_stiffness: float = _q(_VT_DEFAULTS["spring_seat_stiffness"], "N/m",
                                      "retainer–spring seating", gt=0.0)
    spring_support_stiffness: float = _q(_VT_DEFAULTS["spring_support_stiffness"], "N/m",
                                         "head–spring seating", gt=0.0)
    damping_force_ramp: float = _q(_VT_DEFAULTS["damping_force_ramp"], "N",
                                   "elastic force over which unilateral damping phases in",
                                   gt=0.0)
    bore_friction_coefficient: float = _q(_VT_DEFAULTS["bore_friction_coefficient"], "",
                                          "friction coefficient of the tappet in its bore",
                                          ge=0.0, le=2.0)
    bore_friction_velocity: float = _q(_VT_DEFAULTS["bore_friction_velocity"], "m/s",
                                       "regularisation velocity of the bore friction", gt=0.0)
    tappet_radius: float = _q(_VT_DEFAULTS["tappet_radius"], "m",
                              "radius of the tappet face (max contact offset must stay below)",
                              gt=0.0, lt=1.0)


class LubricantConfig(_Section):
    """``[lubricant]``: :class:`~tribodyn.Lubricant` (Roelands + Dowson–Higginson)."""

    viscosity: float = _q(0.055, "Pa·s", "dynamic viscosity μ₀ at ambient pressure "
                                         "(Roelands needs μ₀ > exp(−9.67))",
                          gt=ROELANDS_MU_INF, le=100.0)
    pressure_viscosity: float = _q(1.05e-8, "1/Pa", "pressure–viscosity coefficient α",
                                   ge=0.0, le=1e-6)
    density: float = _q(850.0, "kg/m³", "density ρ₀ at ambient pressure", gt=0.0, le=5000.0)
    eyring_stress: float = _q(2e6, "Pa", "Eyring stress τ_E", gt=0.0)
    limiting_shear_coefficient: float = _q(0.08, "", "pressure slope Λ of the limiting shear "
                                                     "stress τ_L = τ_L0 + Λ p",
                                           ge=0.0, le=1.0)
    limiting_shear_stress: float = _q(0.0, "Pa", "intercept τ_L0 of the limiting shear stress "
                                                 "(paper: 0)", ge=0.0, le=1e9)
    compressible: bool = _q(True, "", "Dowson–Higginson density (false: constant density)")
    viscosity_model: Literal["roelands", "barus"] = _q("roelands", "", "piezo-viscosity law")


class MaterialConfig(_Section):
    """``[materials.<name>]``: an isotropic elastic material (substrate or coating)."""

    E: float = _q(..., "Pa", "Young's modulus", ge=1e6, le=2e12)
    nu: float = _q(..., "", "Poisson's ratio", gt=-1.0, lt=0.5)
    boundary_shear_coefficient: Optional[float] = _q(
        None, "", "pressure coefficient ς of the boundary shear strength of its asperities "
                  "(paper Eq. 17)", ge=0.0, le=2.0)
    label: Optional[str] = _q(None, "", "display name (default: the table key)",
                              min_length=1)


class RoughnessConfig(_Section):
    """``roughness = {…}``: composite Greenwood–Tripp roughness of the pair (paper Table 4)."""

    asperity_density: float = _q(..., "1/m²", "summit density η (the paper's ζ)", gt=0.0)
    rms: float = _q(..., "m", "composite RMS roughness σ", gt=0.0, lt=1e-4)
    summit_radius: float = _q(..., "m", "mean summit radius β", gt=0.0, lt=1e-2)


class SurfaceSetConfig(_Section):
    """``[[surface_sets]]``: one tappet surface to study (the cam is uncoated)."""

    name: str = _q(..., "", "identifier (letters, digits, _ . + -), unique", min_length=1,
                   max_length=64, pattern=_NAME_PATTERN)
    coating: Optional[str] = _q(None, "", "coating material on the tappet (a key of "
                                          "[materials]); absent: uncoated", min_length=1)
    coating_thickness: Optional[float] = _q(None, "m", "coating thickness (required with a "
                                                       "coating)", gt=0.0, le=1e-3)
    substrate: str = _q("steel", "", "tappet substrate material (a key of [materials])",
                        min_length=1)
    roughness: RoughnessConfig = _q(..., "", "composite roughness of the cam/tappet pair")
    boundary_shear_coefficient: Optional[float] = _q(
        None, "", "ς of the pair; absent: the coating's (or the substrate's if uncoated)",
        ge=0.0, le=2.0)
    boundary_shear_strength: float = _q(
        BOUNDARY_SHEAR_STRENGTH, "Pa", "τ₀ of the boundary shear law τ = τ₀ + ς p_a (Eq. 17)",
        ge=0.0, le=1e9)

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
            raise _Problems([("coating_thickness",
                              f"required when a coating is named (coating = {self.coating!r}); "
                              "give the thickness in m, e.g. 4e-6")])
        if self.coating is None and self.coating_thickness is not None:
            raise _Problems([("coating_thickness",
                              "given but no coating is named; add `coating = \"<material>\"` or "
                              "remove the thickness")])
        return self


class Numerics(_Section):
    """``[numerics]``: solver settings."""

    n: int = _q(0, "", "EHL grid nodes (uniform); 0 = automatic from the contact "
                       "(512…4096; steady solves refine until h_c, h_min change < 0.5 % "
                       "on doubling); at most 4096 (the transient steps factor dense "
                       "matrices)",
                ge=0, le=4096)
    min_load: float = _q(5.0, "N", "contact force below which the EHL is not solved "
                                   "(cam on the base circle: no load, no film)",
                         gt=0.0, le=1e4)
    inlet: float = _q(4.0, "", "EHL domain upstream of the centre, in Hertz half-widths",
                      ge=1.0, le=100.0)
    outlet: float = _q(1.75, "", "EHL domain downstream of the centre, in Hertz half-widths",
                       ge=1.0, le=100.0)
    inlet_truncation: float = _q(0.005, "", "EHL domain upstream at least as far as the "
                                            "cut-off inlet loses this share of the load "
                                            "(far-field estimate)", gt=0.0, le=0.1)
    inlet_rigid: float = _q(4.0, "", "EHL domain upstream at least this many rigid inlet "
                                     "lengths √(2R h) (squeeze films)",
                            ge=1.0, le=200.0)
    outlet_rigid: float = _q(2.0, "", "EHL domain downstream, in rigid inlet lengths",
                             ge=1.0, le=200.0)
    tol: float = _q(1e-9, "", "EHL Newton tolerance (scaled update and residual)", gt=0.0,
                    lt=1.0)
    max_iter: int = _q(60, "", "EHL Newton iterations per solve", ge=1, le=10000)
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


# ----------------------------------------------------------------------------- results
@dataclasses.dataclass(frozen=True)
class SurfaceSet:
    """One surface set, ready for the solvers.

    name : identifier from the case.
    bodies : (cam, tappet) — the cam is uncoated, the tappet carries the coating.
    roughness : composite Greenwood–Tripp roughness of the pair.
    boundary_shear_coefficient : ς of Eq. 17 [-].
    coating_label : display label, e.g. ``"DLC 4 µm"`` or ``"uncoated"``.
    boundary_shear_strength : τ₀ of Eq. 17 [Pa].
    """

    name: str
    bodies: tuple[Body, Body]
    roughness: Roughness
    boundary_shear_coefficient: float
    coating_label: str
    boundary_shear_strength: float = BOUNDARY_SHEAR_STRENGTH

    @property
    def cam(self) -> Body:
        return self.bodies[0]

    @property
    def tappet(self) -> Body:
        return self.bodies[1]

    @property
    def coating(self) -> Coating | None:
        return self.bodies[1].coating


def _paper_materials() -> dict:
    # Table 6 (moduli printed as "MPa": they are GPa).
    return {"steel": MaterialConfig(E=210e9, nu=0.3, boundary_shear_coefficient=0.185,
                                    label="steel"),
            "dlc": MaterialConfig(E=185e9, nu=0.3, boundary_shear_coefficient=0.44,
                                  label="DLC"),
            "wcc": MaterialConfig(E=175e9, nu=0.3, boundary_shear_coefficient=0.54,
                                  label="WC-C")}


def _paper_surface_sets() -> list:
    # Table 4 roughness per coating type (the same for both thicknesses).
    rough = {None: dict(asperity_density=8.3e9, rms=0.408e-6, summit_radius=0.669e-6),
             "dlc": dict(asperity_density=3.8e9, rms=0.358e-6, summit_radius=0.332e-6),
             "wcc": dict(asperity_density=2.7e9, rms=0.347e-6, summit_radius=0.217e-6)}
    sets = [SurfaceSetConfig(name="uncoated", roughness=RoughnessConfig(**rough[None]))]
    for coat in ("dlc", "wcc"):
        for t_um in (1, 4):
            sets.append(SurfaceSetConfig(name=f"{coat}_{t_um}um", coating=coat,
                                         coating_thickness=t_um * 1e-6,
                                         roughness=RoughnessConfig(**rough[coat])))
    return sets


# ----------------------------------------------------------------------------- the case
class Case(_Section):
    """A validated case. Build it with :func:`load_case`, :meth:`from_toml_string` or
    :meth:`from_dict`; every section has defaults (the paper's case)."""

    case: CaseInfo = Field(default_factory=CaseInfo)
    engine: Engine = Field(default_factory=Engine)
    cam_config: CamConfig = Field(default_factory=AccelerationCamConfig, alias="cam")
    valvetrain: Valvetrain = Field(default_factory=Valvetrain)
    lubricant_config: LubricantConfig = Field(default_factory=LubricantConfig,
                                              alias="lubricant")
    materials: dict[Annotated[str, Field(min_length=1)], MaterialConfig] = Field(
        default_factory=_paper_materials, min_length=1)
    surface_set_configs: list[SurfaceSetConfig] = Field(default_factory=_paper_surface_sets,
                                                        min_length=1, alias="surface_sets")
    numerics: Numerics = Field(default_factory=Numerics)

    _base_dir: Path = PrivateAttr(default_factory=Path.cwd)
    _source: Optional[Path] = PrivateAttr(default=None)
    _cam: Any = PrivateAttr(default=None)

    # -- validation ---------------------------------------------------------------------
    @model_validator(mode="after")
    def _cross_check(self, info: ValidationInfo):
        ctx = info.context or {}
        self._base_dir = Path(ctx.get("base_dir") or Path.cwd())
        self._source = ctx.get("source")
        problems: list[tuple[str, str]] = []
        known = ", ".join(self.materials)

        def check_material(path, name):
            if name not in self.materials:
                hint = difflib.get_close_matches(name, list(self.materials), n=1)
                more = f"; did you mean {hint[0]!r}?" if hint else ""
                problems.append((path, f"unknown material {name!r} (defined in [materials]: "
                                       f"{known}){more}"))
                return False
            return True

        check_material("cam.material", self.cam_config.material)
        seen: dict[str, int] = {}
        for i, s in enumerate(self.surface_set_configs):
            p = f"surface_sets[{i}]"
            if s.name in seen:
                problems.append((f"{p}.name", f"duplicate surface-set name {s.name!r} (also "
                                              f"surface_sets[{seen[s.name]}])"))
            seen.setdefault(s.name, i)
            ok = check_material(f"{p}.substrate", s.substrate)
            if s.coating is not None:
                ok = check_material(f"{p}.coating", s.coating) and ok
            if ok and s.boundary_shear_coefficient is None:
                mat = s.coating if s.coating is not None else s.substrate
                if self.materials[mat].boundary_shear_coefficient is None:
                    problems.append((f"{p}.boundary_shear_coefficient",
                                     f"required: material {mat!r} has no "
                                     "boundary_shear_coefficient"))
        for path, build in (("lubricant", self.lubricant),
                            ("valvetrain", self.valvetrain_parameters),
                            ("numerics", self.ehl_options)):
            try:
                build()
            except InputError as exc:
                problems.append((path, str(exc)))
        try:
            self._cam = self._build_cam()
        except _CamTableError as exc:
            problems.append((exc.key, str(exc)))
        except InputError as exc:
            problems.append(("cam", str(exc)))
        if problems:
            raise _Problems(problems)
        return self

    # -- construction -------------------------------------------------------------------
    @classmethod
    def from_dict(cls, data: dict, *, base_dir=None, source=None) -> "Case":
        """Validate a (TOML-shaped) dict. Relative paths resolve against ``base_dir``
        (default: the current folder)."""
        if not isinstance(data, dict):
            raise InputError(f"a case must be a table of sections (got {type(data).__name__})")
        ctx = {"base_dir": Path(base_dir) if base_dir is not None else None,
               "source": Path(source) if source is not None else None}
        try:
            return cls.model_validate(data, context=ctx)
        except ValidationError as exc:
            raise InputError(format_validation_error(exc, cls, source)) from None

    @classmethod
    def from_toml_string(cls, text: str, *, base_dir=None, source=None) -> "Case":
        """Parse and validate TOML text (see :meth:`from_dict` for ``base_dir``)."""
        try:
            data = tomllib.loads(text)
        except tomllib.TOMLDecodeError as exc:
            where = f"{source}: " if source is not None else ""
            raise InputError(f"{where}TOML syntax error: {exc}") from None
        return cls.from_dict(data, base_dir=base_dir, source=source)

    @classmethod
    def from_toml(cls, path) -> "Case":
        """Read and validate a case file; relative paths resolve against its folder."""
        p = Path(path)
        try:
            text = p.read_text(encoding="utf-8")
        except OSError as exc:
            raise InputError(f"cannot read case file {str(p)!r}: {exc.strerror}") from None
        return cls.from_toml_string(text, base_dir=p.resolve().parent, source=p)

    def updated(self, changes: dict) -> "Case":
        """A new case with some keys changed and everything validated again.

        ``changes`` maps dotted key paths to values, e.g.
        ``{"engine.speed_rpm": 2000, "surface_sets[1].coating_thickness": 2e-6}``.
        """
        data = self.to_dict()
        for key, value in changes.items():
            _set_dotted(data, key, value)
        new = Case.from_dict(data, base_dir=self._base_dir)
        new._source = self._source
        return new

    def __eq__(self, other) -> bool:
        """Equal keys (and the same resolved cam table file); how the case was read and
        its cached objects do not matter."""
        if not isinstance(other, Case):
            return NotImplemented
        return (self.model_dump() == other.model_dump()
                and self.cam_table_path == other.cam_table_path)

    __hash__ = None  # mutable containers inside: not hashable

    # -- serialisation ------------------------------------------------------------------
    def to_dict(self, *, resolve_paths: bool = False) -> dict:
        """Plain dict of all keys (absent optional keys omitted: TOML has no null).
        ``resolve_paths=True`` makes the cam table path absolute."""
        d = self.model_dump(mode="python", exclude_none=True, by_alias=True)
        d["cam"] = {"type": d["cam"].pop("type"), **d["cam"]}
        if resolve_paths and self.cam_config.type == "table":
            d["cam"]["path"] = str(self.cam_table_path)
        return d

    def to_toml(self, *, resolve_paths: bool = False) -> str:
        """TOML text that reads back to an equal case (all keys written)."""
        head = [f"# tribodyn case {self.case.name!r} (all keys, SI units unless the key "
                "says otherwise)"]
        return to_toml(self.to_dict(resolve_paths=resolve_paths), header=head)

    def write_toml(self, path, *, resolve_paths: bool = True) -> Path:
        """Write :meth:`to_toml` to ``path`` (cam table path made absolute by default, so
        the file works from any folder)."""
        p = Path(path)
        p.write_text(self.to_toml(resolve_paths=resolve_paths), encoding="utf-8")
        return p

    # -- builders -----------------------------------------------------------------------
    @property
    def source(self) -> Optional[Path]:
        """The file the case was read from (None if built in memory)."""
        return self._source

    @property
    def name(self) -> str:
        return self.case.name

    @property
    def engine_speed(self) -> float:
        """Engine speed [rpm]."""
        return self.engine.speed_rpm

    @property
    def cam_speed(self) -> float:
        """Cam angular speed ω [rad/s] = engine speed / 2."""
        return rpm_to_cam_speed(self.engine.speed_rpm)

    @property
    def width(self) -> float:
        """Cam width (contact length) [m]."""
        return self.cam_config.width

    @property
    def cam_table_path(self) -> Optional[Path]:
        """Resolved path of the cam lift table (``type = "table"`` only)."""
        if self.cam_config.type != "table":
            return None
        p = Path(self.cam_config.path).expanduser()
        return p if p.is_absolute() else (self._base_dir / p)

    def lubricant(self) -> Lubricant:
        """The :class:`~tribodyn.Lubricant` of ``[lubricant]``."""
        c = self.lubricant_config
        return Lubricant(viscosity=c.viscosity, pressure_viscosity=c.pressure_viscosity,
                         density=c.density, eyring_stress=c.eyring_stress,
                         limiting_shear_coefficient=c.limiting_shear_coefficient,
                         limiting_shear_stress=c.limiting_shear_stress,
                         compressible=c.compressible, viscosity_model=c.viscosity_model)

    def material(self, name: str) -> Material:
        """The :class:`~tribodyn.Material` of ``[materials.<name>]``."""
        if name not in self.materials:
            raise InputError(f"unknown material {name!r} (defined: {', '.join(self.materials)})")
        m = self.materials[name]
        return Material(E=m.E, nu=m.nu)

    def _build_cam(self) -> CamProfile:
        c = self.cam_config
        tr = self.valvetrain.tappet_radius
        if c.type == "acceleration":
            return AccelerationCam(c.base_radius, c.max_lift,
                                   event_angle=math.radians(c.event_angle_deg),
                                   nose_radius=c.nose_radius, ramp_height=c.ramp_height,
                                   ramp_angle=math.radians(c.ramp_angle_deg),
                                   pulse_share=c.pulse_share,
                                   ramp_pulse_share=c.ramp_pulse_share,
                                   nose_angle=math.radians(c.nose_angle_deg),
                                   tappet_radius=tr)
        if c.type == "circular_arc":
            return CircularArcCam(c.base_radius, c.max_lift, flank_radius=c.flank_radius,
                                  nose_radius=c.nose_radius,
                                  nose_angle=math.radians(c.nose_angle_deg), tappet_radius=tr)
        try:
            cam = TabulatedCam.from_csv(self.cam_table_path, c.base_radius,
                                        smoothing=c.smoothing, angle_unit=c.angle_unit,
                                        lift_unit=c.lift_unit, tappet_radius=tr)
        except InputError as exc:        # the table's own message, filed under cam.path
            msg = str(exc)
            if str(self.cam_table_path) not in msg:
                msg = f"{self.cam_table_path}: {msg}"
            raise _CamTableError("path", msg) from None
        if c.max_lift is not None and abs(cam.max_lift / c.max_lift - 1.0) > 0.01:
            raise _CamTableError("max_lift", f"{c.max_lift:g} m disagrees with the lift "
                                             f"table's maximum {cam.max_lift:g} m by more "
                                             "than 1 %")
        return cam

    def cam(self) -> CamProfile:
        """The cam profile (built and checked during validation)."""
        if self._cam is None:
            self._cam = self._build_cam()
        return self._cam

    def valvetrain_parameters(self) -> ValvetrainParameters:
        """:class:`~tribodyn.valvetrain.ValvetrainParameters` (cam_width = ``[cam] width``)."""
        d = self.valvetrain.model_dump()
        return ValvetrainParameters(**d, cam_width=self.cam_config.width)

    def ehl_options(self, surface_set: "SurfaceSet | str | None" = None) -> EHLOptions:
        """:class:`~tribodyn.EHLOptions` from ``[numerics]``; with a surface set (object or
        name), its ς and τ₀ of the boundary friction law."""
        n = self.numerics
        if 0 < n.n < 32:
            raise InputError(f"numerics.n: must be 0 (automatic) or >= 32 (got {n.n})")
        kw = dict(n=n.n or None, inlet=n.inlet, outlet=n.outlet,
                  inlet_truncation=n.inlet_truncation, inlet_rigid=n.inlet_rigid,
                  outlet_rigid=n.outlet_rigid, tol=n.tol, max_iter=n.max_iter,
                  viscous_model=n.viscous_model, limiting_shear=n.limiting_shear,
                  time_order=n.time_order)
        if surface_set is not None:
            s = self.surface_set(surface_set) if isinstance(surface_set, str) else surface_set
            kw.update(boundary_shear_coefficient=s.boundary_shear_coefficient,
                      boundary_shear_strength=s.boundary_shear_strength)
        return EHLOptions(**kw)

    def surface_sets(self) -> list[SurfaceSet]:
        """All surface sets as :class:`SurfaceSet` objects, in file order."""
        return [self._build_set(s) for s in self.surface_set_configs]

    def surface_set(self, name: str) -> SurfaceSet:
        """One surface set by name."""
        for s in self.surface_set_configs:
            if s.name == name:
                return self._build_set(s)
        names = self.surface_set_names
        hint = difflib.get_close_matches(name, names, n=1)
        more = f"; did you mean {hint[0]!r}?" if hint else ""
        raise InputError(f"unknown surface set {name!r} (defined: {', '.join(names)}){more}")

    @property
    def surface_set_names(self) -> list[str]:
        return [s.name for s in self.surface_set_configs]

    def _build_set(self, s: SurfaceSetConfig) -> SurfaceSet:
        cam = Body(self.material(self.cam_config.material))
        substrate = self.material(s.substrate)
        if s.coating is None:
            tappet = Body(substrate)
            label = "uncoated"
            mat = s.substrate
        else:
            cm = self.materials[s.coating]
            tappet = Body(substrate, Coating(E=cm.E, nu=cm.nu, thickness=s.coating_thickness))
            label = f"{cm.label or s.coating} {s.coating_thickness * 1e6:.3g} µm"
            mat = s.coating
        sigma = (s.boundary_shear_coefficient if s.boundary_shear_coefficient is not None
                 else self.materials[mat].boundary_shear_coefficient)
        r = s.roughness
        rough = Roughness(asperity_density=r.asperity_density, rms=r.rms,
                          summit_radius=r.summit_radius, method=self.numerics.greenwood_tripp)
        return SurfaceSet(name=s.name, bodies=(cam, tappet), roughness=rough,
                          boundary_shear_coefficient=float(sigma), coating_label=label,
                          boundary_shear_strength=s.boundary_shear_strength)

    def dynamics_options(self) -> dict:
        """Keyword arguments of :func:`~tribodyn.valvetrain.simulate_valvetrain` from the
        case (engine speed and ``[numerics]``)."""
        n = self.numerics
        return dict(engine_speed=self.engine.speed_rpm, cycles=n.cycles,
                    output_step=n.output_step_deg, method=n.dynamics_method,
                    rtol=n.dynamics_rtol, max_step=n.max_step_deg)

    def analytic_tribology(self, surface_set: "SurfaceSet | str"):
        """Explicit tribology of the dynamics for one surface set
        (:class:`~tribodyn.valvetrain.AnalyticTribology` over the cam width)."""
        from .valvetrain.tribology import AnalyticTribology
        s = self.surface_set(surface_set) if isinstance(surface_set, str) else surface_set
        n = self.numerics
        model = AnalyticTribology(self.cam_config.width, bodies=s.bodies,
                                  lubricant=self.lubricant(),
                                  roughness=s.roughness,
                                  boundary_shear_coefficient=s.boundary_shear_coefficient,
                                  viscous_model=n.viscous_model, film_formula=n.film_formula,
                                  limiting_shear=n.limiting_shear)
        # τ₀ is not a constructor argument of AnalyticTribology; it is forwarded through
        # the keyword arguments it passes to analytic_contact.
        model.kwargs["boundary_shear_strength"] = s.boundary_shear_strength
        return model


# ----------------------------------------------------------------------------- loading
def bundled_cases() -> dict[str, Path]:
    """Name → path of the case files shipped with tribodyn."""
    return {p.stem: p for p in sorted(CASES_DIR.glob("*.toml"))}


def load_case(path=None) -> Case:
    """Load and validate a case file.

    ``path=None`` loads the bundled paper case; a bare name such as ``"andreou2023"`` or
    ``"example_table_cam"`` that is not an existing file selects a bundled case.
    """
    if path is None:
        return Case.from_toml(DEFAULT_CASE)
    p = Path(path)
    if not p.exists():
        bundled = bundled_cases()
        if p.stem in bundled and p.parent == Path(".") and p.suffix in ("", ".toml"):
            return Case.from_toml(bundled[p.stem])
    return Case.from_toml(p)


# ----------------------------------------------------------------------------- errors
def _unit_of(fi) -> str:
    extra = fi.json_schema_extra if fi is not None else None
    return extra.get("unit", "") if isinstance(extra, dict) else ""


def _bounds_text(fi) -> str | None:
    """'> 0 m', '>= 1e+06 Pa and <= 2e+12 Pa', from the field's constraints."""
    if fi is None:
        return None
    unit = _unit_of(fi)
    u = f" {unit}" if unit and not unit.startswith("deg") else ("°" if unit else "")
    parts = []
    for m in fi.metadata:
        for attr, sym in (("gt", ">"), ("ge", ">="), ("lt", "<"), ("le", "<=")):
            v = getattr(m, attr, None)
            if v is not None:
                parts.append(f"{sym} {_num(v)}{u}")
    return " and ".join(parts) if parts else None


def _num(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    return f"{v:.6g}"


def _given(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        g = f"{v:.6g}"
        return g if any(c in g for c in ".eni") else g + ".0"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, str):
        return repr(v)
    if isinstance(v, dict):
        return "a table"
    if isinstance(v, list):
        return "an array"
    return repr(v)


def _strip_optional(ann):
    if get_origin(ann) is Union:
        args = [a for a in get_args(ann) if a is not type(None)]
        if len(args) == 1:
            return args[0]
    return ann


def _fields_by_key(model) -> dict:
    """Fields of a model keyed as they appear in the file (alias if any)."""
    return {(fi.alias or name): fi for name, fi in model.model_fields.items()}


def _resolve_loc(root, loc) -> tuple[str, Any, Any]:
    """Dotted path of ``loc`` plus the FieldInfo and the model owning the last key."""
    path = ""
    cur: Any = root
    fi = None
    owner = root
    items = list(loc)
    i = 0
    while i < len(items):
        item = items[i]
        if isinstance(cur, type) and issubclass(cur, BaseModel):
            owner = cur
            fi = _fields_by_key(cur).get(item) if isinstance(item, str) else None
            path = f"{path}.{item}" if path else str(item)
            if fi is None:
                cur = None
            elif cur is Case and item == "cam":
                cur = None
                if i + 1 < len(items) and items[i + 1] in CAM_MODELS:
                    cur = CAM_MODELS[items[i + 1]]
                    i += 1
            else:
                cur = _strip_optional(fi.annotation)
        elif get_origin(cur) is list:
            path = f"{path}[{item}]"
            cur = get_args(cur)[0]
            fi = None
        elif get_origin(cur) is dict:
            key = str(item)
            path = f"{path}.{key}" if re.fullmatch(r"[A-Za-z0-9_\-]+", key) else f'{path}."{key}"'
            cur = get_args(cur)[1]
            fi = None
        else:
            path = f"{path}.{item}" if path else str(item)
            fi = None
            cur = None
        i += 1
    return path, fi, owner


def _allowed_keys(model) -> list[str]:
    if isinstance(model, type) and issubclass(model, BaseModel):
        return list(_fields_by_key(model))
    return []


def _error_lines(err: dict, root) -> list[tuple[str, str]]:
    typ, loc, ctx = err["type"], err["loc"], err.get("ctx") or {}
    inp = err.get("input")
    if typ == "value_error" and isinstance(ctx.get("error"), _Problems):
        prefix, _, _ = _resolve_loc(root, loc)
        return [(f"{prefix}.{p}" if prefix and p else (prefix or p), m)
                for p, m in ctx["error"].items]
    path, fi, owner = _resolve_loc(root, loc)
    got = f" (got {_given(inp)})"
    if typ in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        b = _bounds_text(fi) or err["msg"]
        return [(path, f"must be {b}{got}")]
    if typ == "extra_forbidden":
        allowed = _allowed_keys(owner)
        hint = difflib.get_close_matches(str(loc[-1]), allowed, n=1)
        more = f"; did you mean {hint[0]!r}?" if hint else ""
        where = ""
        if owner in CAM_MODELS.values():
            where = f" for cam type {owner.model_fields['type'].annotation.__args__[0]!r}"
        return [(path, f"unknown key{where}{more} (allowed: {', '.join(allowed)})")]
    if typ == "missing":
        return [(path, "required key is missing")]
    if typ == "literal_error":
        return [(path, f"must be {ctx.get('expected')}{got}")]
    if typ == "union_tag_invalid":
        return [(f"{path}.type", f"must be one of {ctx.get('expected_tags')} "
                                 f"(got {ctx.get('tag')!r})")]
    if typ in ("union_tag_not_found", "model_type", "model_attributes_type", "dict_type"):
        return [(path, f"must be a table{got}")]
    if typ == "list_type":
        return [(path, f"must be an array of tables ([[{path}]]){got}")]
    if typ == "too_short":
        return [(path, f"must have at least {ctx.get('min_length')} entr"
                       f"{'y' if ctx.get('min_length') == 1 else 'ies'}")]
    if typ in ("float_type", "float_parsing"):
        return [(path, f"must be a number{_unit_hint(fi)}{got}")]
    if typ in ("int_type", "int_parsing", "int_from_float"):
        return [(path, f"must be an integer{got}")]
    if typ == "bool_type":
        return [(path, f"must be true or false{got}")]
    if typ == "string_type":
        return [(path, f"must be a string{got}")]
    if typ == "finite_number":
        return [(path, f"must be a finite number{got}")]
    if typ == "string_too_short":
        return [(path, f"must not be empty{got}")]
    if typ == "string_too_long":
        return [(path, f"must have at most {ctx.get('max_length')} characters{got}")]
    if typ == "string_pattern_mismatch":
        return [(path, "must start with a letter or digit and contain only letters, digits, "
                       f"'_', '.', '+', '-'{got}")]
    if typ == "value_error":
        return [(path, f"{ctx.get('error', err['msg'])}")]
    return [(path, f"{err['msg']}{got}")]


def _unit_hint(fi) -> str:
    u = _unit_of(fi)
    return f" [{u}]" if u else ""


def format_validation_error(exc: ValidationError, root=None, source=None) -> str:
    """Readable multi-line message: one ``dotted.key: problem (got value)`` per line."""
    root = root or Case
    lines: list[tuple[str, str]] = []
    for err in exc.errors(include_url=False):
        lines.extend(_error_lines(err, root))
    n = len(lines)
    what = "case" if root is Case else root.__name__
    where = f" {source}" if source is not None else ""
    head = f"invalid {what}{where}: {n} problem{'s' if n != 1 else ''}"
    return head + "".join(f"\n  {p or '(top level)'}: {m}" for p, m in lines)


# ----------------------------------------------------------------------------- TOML writer
_BARE_KEY = re.compile(r"^[A-Za-z0-9_\-]+$")


def _key(k: str) -> str:
    return k if _BARE_KEY.match(k) else _string(k)


def _string(s: str) -> str:
    out = ['"']
    for ch in s:
        o = ord(ch)
        if ch == '"':
            out.append('\\"')
        elif ch == "\\":
            out.append("\\\\")
        elif ch == "\n":
            out.append("\\n")
        elif ch == "\t":
            out.append("\\t")
        elif ch == "\r":
            out.append("\\r")
        elif o < 0x20 or o == 0x7F:
            out.append(f"\\u{o:04x}")
        else:
            out.append(ch)
    out.append('"')
    return "".join(out)


def _float(v: float) -> str:
    if math.isnan(v):
        return "nan"
    if math.isinf(v):
        return "inf" if v > 0 else "-inf"
    r = repr(v)
    if "e" not in r and v != 0.0 and (abs(v) >= 1e6 or abs(v) < 1e-4):
        for p in range(17):
            s = f"{v:.{p}e}"
            if float(s) == v:
                return s
    return r


def _value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        return _float(v)
    if isinstance(v, str):
        return _string(v)
    if isinstance(v, os.PathLike):
        return _string(os.fspath(v))
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{_key(k)} = {_value(x)}" for k, x in v.items()
                                if x is not None) + " }"
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_value(x) for x in v) + "]"
    raise TypeError(f"cannot write {type(v).__name__} to TOML")


def _is_table_array(v) -> bool:
    return isinstance(v, list) and len(v) > 0 and all(isinstance(x, dict) for x in v)


def _emit_table(lines: list[str], table: dict, path: tuple[str, ...]) -> None:
    # Key/value pairs first (they belong to the current header), then sub-tables and
    # arrays of tables in their original order, each under its own header.
    for k, v in table.items():
        if v is not None and not isinstance(v, dict) and not _is_table_array(v):
            lines.append(f"{_key(k)} = {_value(v)}")
    for k, v in table.items():
        sub = path + (k,)
        name = ".".join(_key(p) for p in sub)
        if isinstance(v, dict):
            has_pairs = any(x is not None and not isinstance(x, dict) and not _is_table_array(x)
                            for x in v.values())
            if has_pairs or not v:
                if lines:
                    lines.append("")
                lines.append(f"[{name}]")
            _emit_table(lines, v, sub)
        elif _is_table_array(v):
            for item in v:
                if lines:
                    lines.append("")
                lines.append(f"[[{name}]]")
                for kk, vv in item.items():      # nested tables of an element: inline
                    if vv is not None:
                        lines.append(f"{_key(kk)} = {_value(vv)}")


def to_toml(data: dict, *, header: list[str] | None = None) -> str:
    """Minimal TOML writer for case dicts: tables, arrays of tables (their sub-tables
    inline), strings, booleans, ints, floats (shortest exact form) and arrays. ``None``
    values are omitted."""
    lines = [f"# {h.lstrip('# ')}" for h in (header or [])]
    body: list[str] = []
    _emit_table(body, data, ())
    if lines and body:
        lines.append("")
    return "\n".join(lines + body) + "\n"


def _set_dotted(data: dict, key: str, value) -> None:
    tokens = []
    for part in key.split("."):
        m = re.fullmatch(r"([^\[\]]+)((?:\[\d+\])*)", part)
        if not m:
            raise InputError(f"cannot parse key path {key!r}")
        tokens.append(m.group(1))
        tokens.extend(int(i) for i in re.findall(r"\[(\d+)\]", m.group(2)))
    cur: Any = data
    for t in tokens[:-1]:
        try:
            if isinstance(t, int):
                cur = cur[t]
            else:
                cur = cur.setdefault(t, {})
        except (IndexError, KeyError, TypeError, AttributeError):
            raise InputError(f"key path {key!r} does not exist in the case") from None
    last = tokens[-1]
    try:
        cur[last] = value
    except (IndexError, TypeError):
        raise InputError(f"key path {key!r} does not exist in the case") from None

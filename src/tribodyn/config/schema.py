"""The case-file schema: one pydantic model per TOML section.

Every field records its unit (``json_schema_extra={"unit": …}``), its allowed range and a
one-line description; ``docs/case-files.md`` documents them and the error messages quote
them. Friction, rheology and roughness default to typical sourced values
(:mod:`tribodyn.physics.typical`); the engine, cam and valvetrain default to the paper's
engine (:mod:`tribodyn.paper`, no typical values exist for them); the paper's friction
values are stated in its case files. Numerical settings are tribodyn's defaults. Sections are strict (no type coercion), frozen, and reject unknown keys.
"""

from __future__ import annotations

import dataclasses
from typing import Annotated, Any, Literal

from pydantic import BaseModel, ConfigDict, Discriminator, Field, Tag, model_validator

from .. import paper
from ..contact.ehl.options import EHLOptions
from ..physics import limits as L
from ..physics import typical
from ..physics.oils import OILS
from ..valvetrain.parameters import ValvetrainParameters
from .errors import Problems

__all__ = [
    "CaseInfo",
    "Engine",
    "LobeConfig",
    "AuxiliaryFrictionConfig",
    "AccelerationCamConfig",
    "CircularArcCamConfig",
    "TableCamConfig",
    "CAM_MODELS",
    "CamConfig",
    "Valvetrain",
    "ValveConfig",
    "TappetConfig",
    "SpringConfig",
    "CamshaftConfig",
    "LUMPED_ONLY",
    "LubricantConfig",
    "MaterialConfig",
    "RoughnessConfig",
    "SurfaceSetConfig",
    "StrengthConfig",
    "StressConfig",
    "Numerics",
    "paper_materials",
    "paper_surface_sets",
    "typical_materials",
    "typical_surface_sets",
    "TappetRotationConfig",
]

_VT_DEFAULTS = {f.name: f.default for f in dataclasses.fields(ValvetrainParameters)}
#: the EHL solver's defaults (contact layer): the one source of [numerics]' shared defaults
_EHL_DEFAULTS = {f.name: f.default for f in dataclasses.fields(EHLOptions)}
_NAME_PATTERN = r"^[A-Za-z0-9][A-Za-z0-9_.+\-]*$"


def _q(default: Any, unit: str, doc: str, **constraints) -> Any:
    """A field with its unit recorded (used in error messages and the docs)."""
    return Field(default, description=doc, json_schema_extra={"unit": unit}, **constraints)


def _lim(default: Any, limit: L.Limit, doc: str) -> Any:
    """A field whose unit and range are a shared limit of :mod:`tribodyn.physics.limits`
    (the physics constructors check the same range)."""
    return _q(default, limit.unit, doc, **limit.constraints())


class Section(BaseModel):
    """Base of all case sections: unknown keys rejected, no silent type coercion."""

    model_config = ConfigDict(
        extra="forbid", strict=True, frozen=True, allow_inf_nan=False, validate_default=False
    )


# ----------------------------------------------------------------------------- sections
class CaseInfo(Section):
    """``[case]``: identification of the study."""

    name: str = _q(
        "case",
        "",
        "short name of the case (used in reports and file names)",
        min_length=1,
        max_length=64,
        pattern=_NAME_PATTERN,
    )
    description: str = _q("", "", "free text")


class LobeConfig(Section):
    """``[engine.intake]`` / ``[engine.exhaust]``: the lobes of one kind. Their cam,
    spring, masses and surfaces are the case's own with ``changes`` applied (dotted keys
    as in :meth:`~tribodyn.config.Case.updated`, validated as the case is)."""

    valves: int = _q(2, "", "valves of this kind per cylinder", ge=1, le=3)
    centre_angle_deg: float = _q(
        ..., "°", "crank angle of maximum lift after the cylinder's firing TDC", ge=0.0, lt=720.0
    )
    changes: dict[Annotated[str, Field(min_length=1)], float | int | str | bool] = _q(
        {}, "", 'keys of this case changed for these lobes, e.g. {"cam.max_lift" = 0.008}'
    )


class AuxiliaryFrictionConfig(Section):
    """``[engine.auxiliary]``: tappet bore, camshaft journals and valve guides
    (:mod:`tribodyn.physics.valvetrain_friction`). Defaults are ASSUMED typical values of a
    passenger-car direct-acting valvetrain."""

    bore_diameter: float | None = _q(
        None, "m", "tappet bore diameter (absent: 2 × valvetrain.tappet_radius)", gt=0.0, lt=0.2
    )
    bore_guided_length: float = _q(0.018, "m", "guided length of the bucket", gt=0.0, lt=0.2)
    bore_clearance: float = _q(2.5e-5, "m", "radial clearance in the bore", gt=0.0, lt=1e-3)
    bore_edge_offset: float = _q(0.0, "m", "lower bore edge above the face", ge=0.0, lt=0.2)
    bore_friction_coefficient: float | None = _q(
        None, "", "boundary μ at the bore edges (absent: valvetrain's)", ge=0.0, le=1.0
    )
    journal_radius: float = _q(0.0125, "m", "camshaft journal radius", gt=0.0, lt=0.2)
    journal_length: float = _q(0.018, "m", "camshaft journal length", gt=0.0, lt=0.2)
    journal_clearance: float = _q(3e-5, "m", "journal radial clearance", gt=0.0, lt=1e-3)
    guide_stem_diameter: float = _q(0.006, "m", "valve stem diameter", gt=0.0, lt=0.1)
    guide_length: float = _q(0.035, "m", "valve guide length", gt=0.0, lt=0.3)
    guide_clearance: float = _q(2e-5, "m", "stem radial clearance", gt=0.0, lt=1e-3)
    guide_friction_coefficient: float = _q(0.1, "", "boundary μ in the guide", ge=0.0, le=1.0)
    guide_side_load: float = _q(0.0, "N", "side load on the stem", ge=0.0, le=1e4)


class Engine(Section):
    """``[engine]``: operating point. The cam turns at half the engine speed (4-stroke).
    With ``cylinders``: a whole engine's direct-acting valvetrain (``tribodyn engine``)."""

    speed_rpm: float = _lim(
        paper.ENGINE_SPEED_RPM, L.ENGINE_SPEED, "engine (crank) speed; cam speed = speed_rpm/2"
    )
    cylinders: int | None = _q(None, "", "cylinders (absent: one valve)", ge=1, le=16)
    firing_order: list[int] | None = _q(
        None, "", "cylinder numbers 1…n in firing order (absent: 1, 2, …, n)"
    )
    displacement: float | None = _q(None, "m³", "swept volume of the engine", gt=0.0, le=0.1)
    camshafts: int = _q(2, "", "1: intake and exhaust lobes on one shaft; 2: DOHC", ge=1, le=2)
    intake: LobeConfig | None = None
    exhaust: LobeConfig | None = None
    #: absent: the ASSUMED defaults of :class:`AuxiliaryFrictionConfig`
    auxiliary: AuxiliaryFrictionConfig | None = None

    @model_validator(mode="after")
    def _engine_keys(self):
        problems = []
        if self.cylinders is None:
            for k in ("firing_order", "displacement", "intake", "exhaust"):
                if getattr(self, k) is not None:
                    problems.append((k, "needs engine.cylinders"))
        else:
            n = self.cylinders
            for k in ("displacement", "intake", "exhaust"):
                if getattr(self, k) is None:
                    problems.append((k, "required with engine.cylinders"))
            fo = self.firing_order
            if fo is not None and sorted(fo) != list(range(1, n + 1)):
                problems.append(("firing_order", f"must list each cylinder 1…{n} once, got {fo}"))
        if problems:
            raise Problems(problems)
        return self

    def auxiliary_friction(self) -> AuxiliaryFrictionConfig:
        """``[engine.auxiliary]`` (its defaults when absent)."""
        return self.auxiliary or AuxiliaryFrictionConfig()

    def firing_angles(self) -> dict[int, float]:
        """Crank angle [°] of each cylinder's firing TDC (evenly spaced over 720°, in
        firing order; cylinder 1 of the order at 0°)."""
        n = self.cylinders or 1
        order = self.firing_order or list(range(1, n + 1))
        return {c: 720.0 * i / n for i, c in enumerate(order)}


class _CamBase(Section):
    material: str = _q(
        "steel", "", "cam material (a key of [materials]); the cam is uncoated", min_length=1
    )
    base_radius: float = _q(paper.CAM_BASE_RADIUS, "m", "base-circle radius r_b", gt=0.0, lt=1.0)
    width: float = _lim(paper.CAM_WIDTH, L.LENGTH_BELOW_1M, "cam width (axial contact length)")


class AccelerationCamConfig(_CamBase):
    """``[cam] type = "acceleration"``: :class:`~tribodyn.valvetrain.AccelerationCam`."""

    type: Literal["acceleration"] = "acceleration"
    max_lift: float = _q(paper.CAM_MAX_LIFT, "m", "maximum lift L incl. the ramp", gt=0.0, lt=1.0)
    event_angle_deg: float = _q(
        171.0, "deg (cam)", "total event incl. both ramps", gt=0.0, lt=360.0
    )
    nose_radius: float = _q(3e-3, "m", "radius of curvature at the nose", gt=0.0, lt=1.0)
    ramp_height: float = _q(0.2e-3, "m", "opening/closing ramp height (0: no ramp)", ge=0.0, lt=1.0)
    ramp_angle_deg: float = _q(20.0, "deg (cam)", "ramp length (0: no ramp)", ge=0.0, lt=180.0)
    pulse_share: float = _q(
        0.25,
        "",
        "share of the half main event taken by the positive acceleration pulse",
        gt=0.0,
        lt=1.0,
    )
    ramp_pulse_share: float = _q(
        0.5, "", "share of the ramp taken by its acceleration pulse", gt=0.0, le=1.0
    )
    nose_angle_deg: float = _q(180.0, "deg (cam)", "cam angle of maximum lift", ge=0.0, lt=360.0)


class CircularArcCamConfig(_CamBase):
    """``[cam] type = "circular_arc"``: :class:`~tribodyn.valvetrain.CircularArcCam`."""

    type: Literal["circular_arc"]
    max_lift: float = _q(paper.CAM_MAX_LIFT, "m", "maximum lift L", gt=0.0, lt=1.0)
    flank_radius: float = _q(0.030, "m", "flank arc radius (> base_radius)", gt=0.0, lt=1.0)
    nose_radius: float = _q(3e-3, "m", "nose arc radius (< base_radius)", gt=0.0, lt=1.0)
    nose_angle_deg: float = _q(180.0, "deg (cam)", "cam angle of maximum lift", ge=0.0, lt=360.0)


class TableCamConfig(_CamBase):
    """``[cam] type = "table"``: :class:`~tribodyn.valvetrain.TabulatedCam` from a CSV file."""

    type: Literal["table"]
    path: str = _q(
        ..., "", "CSV lift table (cam angle, lift), relative to the case file", min_length=1
    )
    angle_unit: Literal["auto", "deg", "rad", "crank_deg"] = _q(
        "auto", "", "unit of the angle column (auto: from the header, else degrees)"
    )
    lift_unit: Literal["auto", "mm", "m", "um", "in"] = _q(
        "auto", "", "unit of the lift column (auto: from the header, else mm)"
    )
    angle_column: int | str | None = _q(
        None, "", "angle column: 1-based number or header name (needed with > 2 columns)"
    )
    lift_column: int | str | None = _q(
        None, "", "lift column: 1-based number or header name (needed with > 2 columns)"
    )
    smoothing: float | None = _q(
        None,
        "m",
        "precision of the table: allowed RMS deviation "
        "of the fit (absent: estimated from the "
        "table)",
        ge=0.0,
        lt=1e-3,
    )
    max_lift: float | None = _q(
        None, "m", "optional check: the table's maximum lift must agree within 1 %", gt=0.0, lt=1.0
    )


CAM_MODELS = {
    "acceleration": AccelerationCamConfig,
    "circular_arc": CircularArcCamConfig,
    "table": TableCamConfig,
}


def _cam_tag(v: Any):
    if isinstance(v, dict):
        return v.get("type", "acceleration")
    return getattr(v, "type", None)


CamConfig = Annotated[
    Annotated[AccelerationCamConfig, Tag("acceleration")]
    | Annotated[CircularArcCamConfig, Tag("circular_arc")]
    | Annotated[TableCamConfig, Tag("table")],
    Discriminator(_cam_tag),
]


# ------------------------------------------------------- flexible valvetrain bodies
class _BodyModes(Section):
    modes: int | None = _q(
        None,
        "",
        "fixed-interface modes kept (Craig–Bampton); absent: all modes up to `cutoff`",
        ge=0,
        le=400,
    )
    cutoff: float = _q(
        5000.0,
        "Hz",
        "keep the fixed-interface modes up to this frequency (used when `modes` is absent)",
        gt=0.0,
        le=1e7,
    )
    damping_ratio: float = _q(0.02, "", "modal damping ratio ζ of the body's modes", ge=0.0, lt=1.0)


class ValveConfig(_BodyModes):
    """``[valvetrain.valve]`` (model = "flexible"): :class:`~tribodyn.valvetrain.flexible.
    ValveGeometry`. Defaults: an ASSUMED valve of 0.07 kg total (Table 7)."""

    stem_diameter: float = _q(5.5e-3, "m", "valve stem diameter", gt=0.0, lt=0.1)
    stem_length: float = _q(0.105, "m", "stem length from the tip to the head", gt=0.0, lt=1.0)
    retainer_position: float = _q(
        0.006, "m", "distance from the tip to the collet groove", gt=0.0, lt=1.0
    )
    retainer_mass: float = _q(0.0204, "kg", "spring retainer + collets", gt=0.0, lt=10.0)
    head_mass: float = _q(0.030, "kg", "valve head", gt=0.0, lt=10.0)
    head_stiffness: float = _q(5e8, "N/m", "head and fillet between stem end and seat face", gt=0.0)
    seat_stiffness: float = _q(5e8, "N/m", "seat insert + seat contact", gt=0.0)
    E: float = _q(paper.STEEL["E"], "Pa", "Young's modulus of the valve", ge=1e9, le=2e12)
    density: float = _q(7850.0, "kg/m³", "density of the valve", gt=0.0, le=3e4)
    elements: int = _q(12, "", "bar elements of the stem below the groove", ge=2, le=400)


class TappetConfig(_BodyModes):
    """``[valvetrain.tappet]`` (model = "flexible"): :class:`~tribodyn.valvetrain.flexible.
    TappetGeometry`; radius = ``[valvetrain] tappet_radius``."""

    model: Literal["fe", "lumped"] = _q("fe", "", "crown + skirt bars, or one rigid mass")
    mass: float | None = _q(None, "kg", 'tappet mass (model = "lumped" only)', gt=0.0, lt=10.0)
    crown_thickness: float = _q(3.5e-3, "m", "crown (disc) thickness", gt=0.0, lt=0.1)
    skirt_length: float = _q(0.02, "m", "skirt (tube) length below the crown", gt=0.0, lt=0.5)
    skirt_thickness: float = _q(1e-3, "m", "skirt wall thickness", gt=0.0, lt=0.1)
    E: float = _q(paper.STEEL["E"], "Pa", "Young's modulus of the tappet", ge=1e9, le=2e12)
    density: float = _q(7850.0, "kg/m³", "density of the tappet", gt=0.0, le=3e4)
    elements: int = _q(6, "", "bar elements of the skirt", ge=1, le=400)

    @model_validator(mode="after")
    def _mass_rule(self):
        if self.model == "lumped" and self.mass is None:
            raise Problems([("mass", 'required with model = "lumped"')])
        if self.model == "fe" and self.mass is not None:
            raise Problems(
                [
                    (
                        "mass",
                        'only with model = "lumped" (the FE tappet\'s mass '
                        "follows from its geometry)",
                    )
                ]
            )
        return self


class SpringConfig(_BodyModes):
    """``[valvetrain.spring]`` (model = "flexible"): :class:`~tribodyn.valvetrain.spring.
    HelicalSpring`. Defaults: ASSUMED dimensions giving Table 7's rate and mass."""

    wire_diameter: float = _q(3.7874e-3, "m", "wire diameter d", gt=0.0, lt=0.1)
    mean_diameter: float = _q(21.596e-3, "m", "mean coil diameter D", gt=0.0, lt=0.5)
    active_coils: float = _q(6.0, "", "number of active coils n_a", gt=0.0, le=100.0)
    dead_coils: float = _q(1.0, "", "closed end coils at each end", ge=0.0, le=10.0)
    free_length: float = _q(53.007e-3, "m", "free length", gt=0.0, lt=1.0)
    installed_length: float = _q(45.600e-3, "m", "installed length (valve closed)", gt=0.0, lt=1.0)
    pitches: list[float] | None = _q(
        None, "m", "free pitch of each active coil (progressive spring); absent: uniform"
    )
    shear_modulus: float = _q(79.3e9, "Pa", "shear modulus G of the wire", ge=1e9, le=1e12)
    density: float = _q(7850.0, "kg/m³", "density of the wire", gt=0.0, le=3e4)
    elements_per_coil: int = _q(2, "", "bar elements per active coil", ge=1, le=20)
    clash_margin: float = _q(
        1.25,
        "",
        "coils closing below this × the largest static force are resolved exactly",
        ge=1.0,
        le=100.0,
    )
    clash_damping: float = _q(50.0, "N·s/m", "damping of a closed coil contact", ge=0.0, le=1e6)


class CamshaftConfig(Section):
    """``[valvetrain.camshaft]`` (model = "flexible"; absent: rigid camshaft):
    :class:`~tribodyn.valvetrain.camshaft.Camshaft`."""

    diameter: float = _q(..., "m", "shaft diameter", gt=0.0, lt=1.0)
    bearing_span: float = _q(
        ..., "m", "distance between the two bearings next to the lobe", gt=0.0, lt=10.0
    )
    lobe_position: float = _q(
        ..., "m", "lobe distance from the nearer bearing (≤ span/2)", ge=0.0, lt=10.0
    )
    drive_stiffness: float = _q(
        ..., "N·m/rad", "torsional stiffness of the drive (chain/belt, sprocket)", gt=0.0
    )
    drive_length: float = _q(..., "m", "shaft length from the drive to the lobe", gt=0.0, lt=10.0)
    E: float = _q(paper.STEEL["E"], "Pa", "Young's modulus of the shaft", ge=1e9, le=2e12)
    nu: float = _q(0.3, "", "Poisson's ratio of the shaft", gt=-1.0, lt=0.5)
    density: float = _q(7850.0, "kg/m³", "density of the shaft", gt=0.0, le=3e4)
    bearing_stiffness: float | None = _q(
        None, "N/m", "radial stiffness of each bearing (absent: rigid)", gt=0.0
    )
    torsional_damping_ratio: float = _q(
        0.02, "", "damping ratio of the torsion mode", ge=0.0, lt=1.0
    )
    lobe_inertia: float | None = _q(
        None, "kg·m²", "polar inertia of the lobe (absent: from the cam contour)", gt=0.0
    )


#: [valvetrain] keys of the lumped model that the flexible bodies replace.
LUMPED_ONLY = (
    "valve_mass",
    "tappet_mass",
    "spring_mass",
    "spring_rate",
    "spring_preload",
    "spring_masses",
    "spring_damping_ratio",
    "seat_stiffness",
    "camshaft_stiffness",
)


class Valvetrain(Section):
    """``[valvetrain]``: mirrors :class:`~tribodyn.valvetrain.ValvetrainParameters`
    (``cam_width`` comes from ``[cam] width``); defaults are its defaults, ranges its
    ranges (:mod:`tribodyn.physics.limits`). ``model = "flexible"`` adds the bodies
    ``valve``, ``tappet``, ``spring`` and ``camshaft``."""

    model: Literal["lumped", "flexible"] = _q(
        "lumped", "", "valvetrain model: lumped chain or Craig–Bampton bodies"
    )
    valve: ValveConfig | None = _q(None, "", "flexible valve ([valvetrain.valve])")
    tappet: TappetConfig | None = _q(None, "", "flexible tappet ([valvetrain.tappet])")
    spring: SpringConfig | None = _q(None, "", "flexible spring ([valvetrain.spring])")
    camshaft: CamshaftConfig | None = _q(
        None, "", "camshaft compliance ([valvetrain.camshaft]; absent: rigid)"
    )

    valve_mass: float = _lim(_VT_DEFAULTS["valve_mass"], L.MASS, "valve + retainer + collets")
    tappet_mass: float = _lim(_VT_DEFAULTS["tappet_mass"], L.MASS, "flat (bucket) tappet")
    spring_mass: float = _lim(_VT_DEFAULTS["spring_mass"], L.MASS, "active valve-spring mass")
    spring_rate: float = _lim(_VT_DEFAULTS["spring_rate"], L.SPRING_RATE, "valve-spring rate")
    spring_preload: float = _lim(
        _VT_DEFAULTS["spring_preload"], L.SPRING_PRELOAD, "installed spring load (valve closed)"
    )
    spring_masses: int = _lim(
        _VT_DEFAULTS["spring_masses"],
        L.SPRING_MASSES,
        "lumped coil masses of the spring model (0: massless spring)",
    )
    spring_damping_ratio: float = _lim(
        _VT_DEFAULTS["spring_damping_ratio"],
        L.SPRING_DAMPING_RATIO,
        "damping ratio of the first surge mode",
    )
    contact_stiffness: float | None = _lim(
        None, L.STIFFNESS, "linear cam–tappet contact stiffness (absent: Palmgren line-contact law)"
    )
    contact_modulus: float = _lim(
        _VT_DEFAULTS["contact_modulus"],
        L.CONTACT_MODULUS,
        "E' of the cam/tappet pair for the Palmgren law",
    )
    contact_damping: float = _lim(
        _VT_DEFAULTS["contact_damping"], L.DAMPING, "cam–tappet contact damping"
    )
    camshaft_stiffness: float | None = _lim(
        None, L.STIFFNESS, "camshaft/bearing support stiffness in series (absent: rigid)"
    )
    tappet_valve_stiffness: float = _lim(
        _VT_DEFAULTS["tappet_valve_stiffness"], L.STIFFNESS, "bucket crown + shim + valve tip"
    )
    tappet_valve_damping: float = _lim(
        _VT_DEFAULTS["tappet_valve_damping"], L.DAMPING, "tappet–valve damping"
    )
    lash: float = _lim(_VT_DEFAULTS["lash"], L.LASH, "tappet–valve clearance on the base circle")
    seat_stiffness: float = _lim(
        _VT_DEFAULTS["seat_stiffness"], L.STIFFNESS, "valve stem + seat insert"
    )
    seat_damping: float = _lim(_VT_DEFAULTS["seat_damping"], L.DAMPING, "valve-seat damping")
    spring_seat_stiffness: float = _lim(
        _VT_DEFAULTS["spring_seat_stiffness"], L.STIFFNESS, "retainer–spring seating"
    )
    spring_support_stiffness: float = _lim(
        _VT_DEFAULTS["spring_support_stiffness"], L.STIFFNESS, "head–spring seating"
    )
    damping_force_ramp: float = _lim(
        _VT_DEFAULTS["damping_force_ramp"],
        L.DAMPING_FORCE_RAMP,
        "elastic force over which unilateral damping phases in",
    )
    bore_friction_coefficient: float = _lim(
        _VT_DEFAULTS["bore_friction_coefficient"],
        L.BORE_FRICTION_COEFFICIENT,
        "friction coefficient of the tappet in its bore",
    )
    bore_friction_velocity: float = _lim(
        _VT_DEFAULTS["bore_friction_velocity"],
        L.BORE_FRICTION_VELOCITY,
        "regularisation velocity of the bore friction",
    )
    tappet_radius: float = _lim(
        _VT_DEFAULTS["tappet_radius"],
        L.LENGTH_BELOW_1M,
        "radius of the tappet face (max contact offset must stay below)",
    )

    @model_validator(mode="after")
    def _model_rule(self):
        problems = []
        if self.model == "flexible":
            for k in LUMPED_ONLY:
                if k in self.model_fields_set:
                    problems.append(
                        (
                            k,
                            'only with model = "lumped" (the flexible bodies '
                            "give it: see [valvetrain.valve], "
                            "[valvetrain.spring], [valvetrain.camshaft])",
                        )
                    )
        else:
            for k in ("valve", "tappet", "spring", "camshaft"):
                if getattr(self, k) is not None:
                    problems.append((k, 'only with model = "flexible"'))
        if problems:
            raise Problems(problems)
        return self


class LubricantConfig(Section):
    """``[lubricant]``: :class:`~tribodyn.Lubricant` (Roelands + Dowson–Higginson)."""

    viscosity: float = _lim(
        paper.LUBRICANT["viscosity"],
        L.VISCOSITY,
        "dynamic viscosity μ₀ at ambient pressure (Roelands needs μ₀ > exp(−9.67))",
    )
    pressure_viscosity: float = _lim(
        paper.LUBRICANT["pressure_viscosity"],
        L.PRESSURE_VISCOSITY,
        "pressure–viscosity coefficient α",
    )
    density: float = _lim(paper.ASSUMED_DENSITY, L.DENSITY, "density ρ₀ at ambient pressure")
    eyring_stress: float = _lim(
        typical.EYRING_STRESS.value, L.EYRING_STRESS, "Eyring stress τ_E (typical)"
    )
    limiting_shear_coefficient: float = _lim(
        typical.LIMITING_SHEAR_COEFFICIENT.value,
        L.LIMITING_SHEAR_COEFFICIENT,
        "pressure slope Λ of the limiting shear stress τ_L = τ_L0 + Λ p",
    )
    limiting_shear_stress: float = _lim(
        0.0, L.LIMITING_SHEAR_STRESS, "intercept τ_L0 of the limiting shear stress (paper: 0)"
    )
    compressible: bool = _q(True, "", "Dowson–Higginson density (false: constant density)")
    viscosity_model: Literal["roelands", "barus"] = _q("roelands", "", "piezo-viscosity law")
    # -- datasheet form and thermal properties (numerics.thermal)
    oil: Literal[tuple(OILS)] | None = _q(  # type: ignore[valid-type]
        None, "", "bundled oil (datasheet values; the keys below override them)"
    )
    kinematic_viscosity_40_cst: float | None = _q(
        None, "mm²/s", "kinematic viscosity at 40 °C (datasheet, ASTM D445)", gt=1.5, le=1e5
    )
    kinematic_viscosity_100_cst: float | None = _q(
        None, "mm²/s", "kinematic viscosity at 100 °C (datasheet)", ge=1.5, le=1e4
    )
    density_15: float | None = _q(
        None, "kg/m³", "density at 15 °C (datasheet)", gt=500.0, le=2000.0
    )
    thermal_expansion: float = _q(
        6.5e-4, "1/K", "thermal expansion of the density ε", ge=0.0, le=3e-3
    )
    inlet_temperature_c: float | None = _q(
        None,
        "°C",
        "oil supply (sump) temperature, also that of the solids far from the "
        "contact; required with a datasheet or numerics.thermal",
        gt=-40.0,
        le=250.0,
    )
    viscosity_temperature_coefficient: float | None = _q(
        None,
        "1/K",
        "β = −d ln μ/dT at the inlet temperature (viscosity form with numerics.thermal)",
        gt=0.0,
        le=0.5,
    )
    thermal_conductivity: float | None = _q(
        None,
        "W/(m K)",
        "oil conductivity at the inlet temperature (absent: Cragoe's estimate from the density)",
        gt=0.01,
        le=10.0,
    )
    specific_heat: float | None = _q(
        None,
        "J/(kg K)",
        "oil specific heat at the inlet temperature (absent: Cragoe)",
        gt=100.0,
        le=1e4,
    )
    limiting_shear_temperature_coefficient: float = _q(
        0.0,
        "1/K",
        "c_L: τ_L falls by the factor 1 − c_L (T − T_inlet) (0: temperature independent)",
        ge=0.0,
        le=0.05,
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
        problems = []
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

    E: float = _lim(..., L.YOUNGS_MODULUS, "Young's modulus")
    nu: float = _lim(..., L.POISSON_RATIO, "Poisson's ratio")
    boundary_shear_coefficient: float | None = _lim(
        None,
        L.BOUNDARY_SHEAR_COEFFICIENT,
        "pressure coefficient ς of the boundary shear strength of its asperities (paper Eq. 17)",
    )
    label: str | None = _q(None, "", "display name (default: the table key)", min_length=1)
    thermal_conductivity: float | None = _q(
        None,
        "W/(m K)",
        "thermal conductivity k (numerics.thermal; steel, dlc, wcc have literature defaults)",
        ge=1e-3,
        le=1e4,
    )
    density: float | None = _q(None, "kg/m³", "density ρ (numerics.thermal)", ge=10.0, le=1e5)
    specific_heat: float | None = _q(
        None, "J/(kg K)", "specific heat c (numerics.thermal)", ge=10.0, le=1e5
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


class RoughnessConfig(Section):
    """``roughness = {…}``: composite Greenwood–Tripp roughness of the pair (paper Table 4)."""

    asperity_density: float = _lim(..., L.ASPERITY_DENSITY, "summit density η (the paper's ζ)")
    rms: float = _lim(..., L.ROUGHNESS_RMS, "composite RMS roughness σ")
    summit_radius: float = _lim(..., L.SUMMIT_RADIUS, "mean summit radius β")


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
    coating_thickness: float | None = _lim(
        None, L.COATING_THICKNESS, "coating thickness (required with a coating)"
    )
    substrate: str = _q(
        "steel", "", "tappet substrate material (a key of [materials])", min_length=1
    )
    roughness: RoughnessConfig = _q(..., "", "composite roughness of the cam/tappet pair")
    boundary_shear_coefficient: float | None = _lim(
        None,
        L.BOUNDARY_SHEAR_COEFFICIENT,
        "ς of the pair; absent: the coating's (or the substrate's if uncoated)",
    )
    boundary_shear_strength: float = _lim(
        typical.BOUNDARY_SHEAR_STRENGTH.value,  # ς is then a measured boundary μ_b
        L.BOUNDARY_SHEAR_STRENGTH,
        "τ₀ of the boundary shear law τ = τ₀ + ς p_a (Eq. 17)",
    )

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


class Numerics(Section):
    """``[numerics]``: solver settings."""

    n: int = _q(
        0,
        "",
        "EHL grid nodes (uniform); 0 = automatic (384 nodes over the "
        "domain sized from the contact; steady solves double them while "
        "h_c, h_min change > 1 % from half the nodes); at most 4096 (the "
        "transient steps factor dense matrices)",
        ge=0,
        le=L.EHL_NODES_TRANSIENT.le,
    )
    min_load: float = _q(
        5.0,
        "N",
        "contact force below which the EHL is not solved "
        "(cam on the base circle: no load, no film)",
        gt=0.0,
        le=1e4,
    )
    inlet: float = _lim(
        _EHL_DEFAULTS["inlet"],
        L.DOMAIN_HALF_WIDTHS,
        "EHL domain upstream of the centre, in Hertz half-widths",
    )
    outlet: float = _lim(
        _EHL_DEFAULTS["outlet"],
        L.DOMAIN_HALF_WIDTHS,
        "EHL domain downstream of the centre, in Hertz half-widths",
    )
    inlet_truncation: float = _lim(
        _EHL_DEFAULTS["inlet_truncation"],
        L.INLET_TRUNCATION,
        "EHL domain upstream at least as far as the cut-off inlet "
        "loses this share of the load (far-field estimate)",
    )
    inlet_rigid: float = _lim(
        _EHL_DEFAULTS["inlet_rigid"],
        L.DOMAIN_RIGID_LENGTHS,
        "EHL domain upstream at least this many rigid inlet lengths √(2R h) (squeeze films)",
    )
    outlet_rigid: float = _lim(
        _EHL_DEFAULTS["outlet_rigid"],
        L.DOMAIN_RIGID_LENGTHS,
        "EHL domain downstream, in rigid inlet lengths",
    )
    tol: float = _lim(
        _EHL_DEFAULTS["tol"], L.NEWTON_TOL, "EHL Newton tolerance (scaled update and residual)"
    )
    max_iter: int = _lim(
        _EHL_DEFAULTS["max_iter"], L.NEWTON_MAX_ITER, "EHL Newton iterations per solve"
    )
    time_order: Literal[1, 2] = _q(
        _EHL_DEFAULTS["time_order"], "", "EHL time discretisation: 1 backward Euler, 2 BDF2"
    )
    crank_step_deg: float = _q(
        1.0,
        "deg (crank)",
        "sample step of the transient EHL along "
        "the cycle (steps with a large estimated "
        "time error are subdivided)",
        gt=0.0,
        le=5.0,
    )
    viscous_model: Literal["eyring", "newtonian"] = _q(
        _EHL_DEFAULTS["viscous_model"], "", "viscous friction law"
    )
    limiting_shear: bool = _q(_EHL_DEFAULTS["limiting_shear"], "", "cap viscous shear at Λp")
    greenwood_tripp: Literal["exact", "paper"] = _q(
        "exact",
        "",
        "Greenwood–Tripp functions: exact, or the paper's polynomial fits (reproduction only)",
    )
    film_formula: Literal["moes", "pan_hamrock", "dowson_toyoda"] = _q(
        "moes", "", "film formula of the explicit (analytic) tribology in the dynamics"
    )
    cycles: int = _lim(2, L.DYNAMICS_CYCLES, "engine cycles simulated (the last is presented)")
    output_step_deg: float = _lim(0.25, L.OUTPUT_STEP, "output step of the valvetrain dynamics")
    max_step_deg: float = _lim(1.0, L.MAX_STEP, "largest integrator step of the dynamics")
    dynamics_method: Literal["LSODA", "Radau", "BDF"] = _q(
        "LSODA", "", "stiff integrator (LSODA: compiled lumped model; Radau, BDF: solve_ivp)"
    )
    dynamics_rtol: float = _lim(1e-6, L.DYNAMICS_RTOL, "relative tolerance of the dynamics")
    implicit_coupling: bool = _q(
        True,
        "",
        "also run the implicit dynamics (numerical EHL "
        "film and friction in the dynamics) for the "
        "comparison with the explicit run",
    )
    coupling_iterations: int = _q(
        6,
        "",
        "dynamics ↔ EHL iterations of the implicit coupling (Anderson-accelerated)",
        ge=1,
        le=100,
    )
    coupling_n: int = _q(
        192,
        "",
        "EHL grid nodes of the coupling's re-passes along the implicit dynamics (they "
        "give the film law, needed to the coupling tolerance only; the reported EHL "
        "keeps numerics.n); at most numerics.n when that is set; 0 = as numerics.n",
        ge=0,
        le=4096,
    )
    workers: int = _q(
        0,
        "",
        "worker processes for the surface sets, the coupling chain and "
        "the single-contact studies (0: one per CPU core)",
        ge=0,
        le=4096,
    )
    thermal: bool = _q(
        False,
        "",
        "thermal EHL (film energy equation, conduction in the "
        "solids and coatings) along the cycle, beside the "
        "isothermal one",
    )
    thermal_x_nodes: int = _q(96, "", "thermal grid nodes along the contact", ge=16, le=1024)
    thermal_film_nodes: int = _q(7, "", "thermal nodes across the film (odd)", ge=3, le=41)
    thermal_solid_nodes: int = _q(12, "", "thermal depth nodes per solid", ge=6, le=200)
    thermal_iterations: int = _q(
        2, "", "pressure ↔ temperature iterations per transient step (1: staggered)", ge=1, le=50
    )
    thermal_tol: float = _q(
        0.05,
        "K",
        "temperature change at which the thermal fixed-point iteration stops",
        gt=0.0,
        le=10.0,
    )


def paper_materials() -> dict:
    """Table 6 as ``[materials]`` (moduli in GPa: the paper prints "MPa")."""
    return {k: MaterialConfig(**v) for k, v in paper.MATERIALS.items()}


def paper_surface_sets() -> list:
    """The bundled case's surface sets: uncoated, DLC and WC-C at 1 and 4 µm, with the
    Table 4 roughness of the coating type (the same for both thicknesses)."""
    sets = [
        SurfaceSetConfig(name="uncoated", roughness=RoughnessConfig(**paper.ROUGHNESS["uncoated"]))
    ]
    for coat in ("dlc", "wcc"):
        for t_um in (1, 4):
            sets.append(
                SurfaceSetConfig(
                    name=f"{coat}_{t_um}um",
                    coating=coat,
                    coating_thickness=t_um * 1e-6,
                    roughness=RoughnessConfig(**paper.ROUGHNESS[coat]),
                )
            )
    return sets


def typical_materials() -> dict:
    """Default ``[materials]``: the moduli of Table 6 (elastic constants of steel, a-C:H
    DLC and WC-C) with ς = the typical boundary friction coefficient of each surface
    against steel in a ZDDP oil (:data:`tribodyn.physics.typical.BOUNDARY_FRICTION`, used
    with τ₀ = 0)."""
    mu = {"steel": "steel", "dlc": "a-C:H", "wcc": "WC-C"}
    out = {}
    for k, v in paper.MATERIALS.items():
        d: dict[str, Any] = dict(v)
        d["boundary_shear_coefficient"] = typical.boundary_friction(mu[k]).value
        out[k] = MaterialConfig(**d)
    return out


def typical_surface_sets() -> list:
    """Default surface sets: the names of the paper's sets, each with the typical composite
    roughness of a ground cam on a ground tappet: σ from
    :data:`~tribodyn.physics.typical.COMPOSITE_RMS`, β = σ/(σ/β) and η = ηβσ/(βσ)."""
    sigma = typical.COMPOSITE_RMS["ground"].value
    beta = sigma / typical.RMS_TO_SUMMIT_RADIUS.value
    eta = typical.ROUGHNESS_PARAMETER.value / (beta * sigma)
    rough = RoughnessConfig(asperity_density=eta, rms=sigma, summit_radius=beta)
    sets = [SurfaceSetConfig(name="uncoated", roughness=rough)]
    for coat in ("dlc", "wcc"):
        for t_um in (1, 4):
            sets.append(
                SurfaceSetConfig(
                    name=f"{coat}_{t_um}um",
                    coating=coat,
                    coating_thickness=t_um * 1e-6,
                    roughness=rough,
                )
            )
    return sets


class TappetRotationConfig(Section):
    """``[tappet_rotation]``: a bucket tappet turning about its axis
    (:class:`~tribodyn.valvetrain.tappet_rotation.TappetRotation`; docs/case-files.md)."""

    speed_ratio: float = _q(
        0.0,
        "",
        "tappet speed over cam speed ω_t/ω (0: the tappet does not turn; no typical "
        "value was found in the sources)",
        ge=-1.0,
        le=1.0,
    )
    cam_offset: float = _q(
        0.0, "m", "offset e_o of the cam from the tappet axis, along the cam axis", ge=0.0, lt=0.05
    )

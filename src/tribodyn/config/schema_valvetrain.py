"""Case-file sections of the cam and the valvetrain: ``[cam]`` (acceleration, circular-arc
or tabulated lift, :data:`CAM_MODELS`) and ``[valvetrain]`` with its flexible bodies
(valve, tappet, spring, camshaft). Defaults: the typical cam sizes and valvetrain of
:mod:`tribodyn.physics.typical` (masses, spring, preload: a case that leaves them out runs
with a warning naming them, :mod:`tribodyn.config.origins`) and the assumed joints of
:class:`~tribodyn.valvetrain.ValvetrainParameters`.
"""

from __future__ import annotations

import math
from typing import Annotated, Any, Literal

from pydantic import Discriminator, Tag, model_validator

from ..physics import limits as L
from ..physics import typical_engine
from ..valvetrain.cams import AccelerationCam, CircularArcCam
from ..valvetrain.camshaft import Camshaft
from ..valvetrain.fe import ModalBody
from ..valvetrain.flexible import TappetGeometry, ValveGeometry
from ..valvetrain.parameters import ValvetrainParameters
from ..valvetrain.spring import HelicalSpring
from .errors import Problems
from .schema_fields import Section, _arg, _q, defaults_of

#: the defaults of the constructors the sections set: the one source of theirs
_VT_DEFAULTS = defaults_of(ValvetrainParameters)
_ACC = defaults_of(AccelerationCam)
_ARC = defaults_of(CircularArcCam)
_MODES = defaults_of(ModalBody)
_VALVE = defaults_of(ValveGeometry)
_TAPPET = defaults_of(TappetGeometry)
_SPRING = defaults_of(HelicalSpring)
_SHAFT = defaults_of(Camshaft)


class _CamBase(Section):
    material: str = _q(
        "steel", "", "cam material (a key of [materials]); the cam is uncoated", min_length=1
    )
    base_radius: float = _q(
        typical_engine.CAM_BASE_RADIUS.value, "m", "base-circle radius r_b", gt=0.0, lt=1.0
    )
    width: float = _arg(
        typical_engine.CAM_WIDTH.value, L.LENGTH_BELOW_1M, "cam width (axial contact length)"
    )


class AccelerationCamConfig(_CamBase):
    """``[cam] type = "acceleration"``: :class:`~tribodyn.valvetrain.AccelerationCam`."""

    type: Literal["acceleration"] = "acceleration"
    max_lift: float = _q(
        typical_engine.CAM_MAX_LIFT.value, "m", "maximum lift L incl. the ramp", gt=0.0, lt=1.0
    )
    event_angle_deg: float = _q(
        math.degrees(_ACC["event_angle"]),
        "deg (cam)",
        "total event incl. both ramps",
        gt=0.0,
        lt=360.0,
    )
    nose_radius: float = _q(
        _ACC["nose_radius"], "m", "radius of curvature at the nose", gt=0.0, lt=1.0
    )
    ramp_height: float = _q(
        _ACC["ramp_height"], "m", "opening/closing ramp height (0: no ramp)", ge=0.0, lt=1.0
    )
    ramp_angle_deg: float = _q(
        math.degrees(_ACC["ramp_angle"]), "deg (cam)", "ramp length (0: no ramp)", ge=0.0, lt=180.0
    )
    pulse_share: float = _q(
        _ACC["pulse_share"],
        "",
        "share of the half main event taken by the positive acceleration pulse",
        gt=0.0,
        lt=1.0,
    )
    ramp_pulse_share: float = _q(
        _ACC["ramp_pulse_share"],
        "",
        "share of the ramp taken by its acceleration pulse",
        gt=0.0,
        le=1.0,
    )
    nose_angle_deg: float = _q(
        math.degrees(_ACC["nose_angle"]), "deg (cam)", "cam angle of maximum lift", ge=0.0, lt=360.0
    )


class CircularArcCamConfig(_CamBase):
    """``[cam] type = "circular_arc"``: :class:`~tribodyn.valvetrain.CircularArcCam`."""

    type: Literal["circular_arc"]
    max_lift: float = _q(typical_engine.CAM_MAX_LIFT.value, "m", "maximum lift L", gt=0.0, lt=1.0)
    flank_radius: float = _q(
        _ARC["flank_radius"], "m", "flank arc radius (> base_radius)", gt=0.0, lt=1.0
    )
    nose_radius: float = _q(
        _ARC["nose_radius"], "m", "nose arc radius (< base_radius)", gt=0.0, lt=1.0
    )
    nose_angle_deg: float = _q(
        math.degrees(_ARC["nose_angle"]), "deg (cam)", "cam angle of maximum lift", ge=0.0, lt=360.0
    )


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
        _MODES["cutoff"],
        "Hz",
        "keep the fixed-interface modes up to this frequency (used when `modes` is absent)",
        gt=0.0,
        le=1e7,
    )
    damping_ratio: float = _q(
        _MODES["damping_ratio"], "", "modal damping ratio ζ of the body's modes", ge=0.0, lt=1.0
    )


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
    E: float = _q(
        typical_engine.STEEL_MODULUS.value, "Pa", "Young's modulus of the valve", ge=1e9, le=2e12
    )
    density: float = _q(_VALVE["density"], "kg/m³", "density of the valve", gt=0.0, le=3e4)
    elements: int = _q(
        _VALVE["elements"], "", "bar elements of the stem below the groove", ge=2, le=400
    )


class TappetConfig(_BodyModes):
    """``[valvetrain.tappet]`` (model = "flexible"): :class:`~tribodyn.valvetrain.flexible.
    TappetGeometry`; radius = ``[valvetrain] tappet_radius``."""

    model: Literal["fe", "lumped"] = _q("fe", "", "crown + skirt bars, or one rigid mass")
    mass: float | None = _q(None, "kg", 'tappet mass (model = "lumped" only)', gt=0.0, lt=10.0)
    crown_thickness: float = _q(
        _TAPPET["crown_thickness"], "m", "crown (disc) thickness", gt=0.0, lt=0.1
    )
    skirt_length: float = _q(
        _TAPPET["skirt_length"], "m", "skirt (tube) length below the crown", gt=0.0, lt=0.5
    )
    skirt_thickness: float = _q(
        _TAPPET["skirt_thickness"], "m", "skirt wall thickness", gt=0.0, lt=0.1
    )
    E: float = _q(
        typical_engine.STEEL_MODULUS.value, "Pa", "Young's modulus of the tappet", ge=1e9, le=2e12
    )
    density: float = _q(_TAPPET["density"], "kg/m³", "density of the tappet", gt=0.0, le=3e4)
    elements: int = _q(_TAPPET["elements"], "", "bar elements of the skirt", ge=1, le=400)

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
    dead_coils: float = _q(
        _SPRING["dead_coils"], "", "closed end coils at each end", ge=0.0, le=10.0
    )
    free_length: float = _q(53.007e-3, "m", "free length", gt=0.0, lt=1.0)
    installed_length: float = _q(45.600e-3, "m", "installed length (valve closed)", gt=0.0, lt=1.0)
    pitches: list[float] | None = _q(
        None, "m", "free pitch of each active coil (progressive spring); absent: uniform"
    )
    shear_modulus: float = _q(
        _SPRING["shear_modulus"], "Pa", "shear modulus G of the wire", ge=1e9, le=1e12
    )
    density: float = _q(_SPRING["density"], "kg/m³", "density of the wire", gt=0.0, le=3e4)
    elements_per_coil: int = _q(
        _SPRING["elements_per_coil"], "", "bar elements per active coil", ge=1, le=20
    )
    clash_margin: float = _q(
        _SPRING["clash_margin"],
        "",
        "coils closing below this × the largest static force are resolved exactly",
        ge=1.0,
        le=100.0,
    )
    clash_damping: float = _q(
        _SPRING["clash_damping"], "N·s/m", "damping of a closed coil contact", ge=0.0, le=1e6
    )


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
    E: float = _q(
        typical_engine.STEEL_MODULUS.value, "Pa", "Young's modulus of the shaft", ge=1e9, le=2e12
    )
    nu: float = _q(_SHAFT["nu"], "", "Poisson's ratio of the shaft", gt=-1.0, lt=0.5)
    density: float = _q(_SHAFT["density"], "kg/m³", "density of the shaft", gt=0.0, le=3e4)
    bearing_stiffness: float | None = _q(
        None, "N/m", "radial stiffness of each bearing (absent: rigid)", gt=0.0
    )
    torsional_damping_ratio: float = _q(
        _SHAFT["torsional_damping_ratio"], "", "damping ratio of the torsion mode", ge=0.0, lt=1.0
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

    valve_mass: float = _arg(_VT_DEFAULTS["valve_mass"], L.MASS, "valve + retainer + collets")
    tappet_mass: float = _arg(_VT_DEFAULTS["tappet_mass"], L.MASS, "flat (bucket) tappet")
    spring_mass: float = _arg(_VT_DEFAULTS["spring_mass"], L.MASS, "active valve-spring mass")
    spring_rate: float = _arg(_VT_DEFAULTS["spring_rate"], L.SPRING_RATE, "valve-spring rate")
    spring_preload: float = _arg(
        _VT_DEFAULTS["spring_preload"], L.SPRING_PRELOAD, "installed spring load (valve closed)"
    )
    spring_masses: int = _arg(
        _VT_DEFAULTS["spring_masses"],
        L.SPRING_MASSES,
        "lumped coil masses of the spring model (0: massless spring)",
    )
    spring_damping_ratio: float = _arg(
        _VT_DEFAULTS["spring_damping_ratio"],
        L.SPRING_DAMPING_RATIO,
        "damping ratio of the first surge mode",
    )
    contact_stiffness: float | None = _arg(
        None, L.STIFFNESS, "linear cam–tappet contact stiffness (absent: Palmgren line-contact law)"
    )
    contact_modulus: float = _arg(
        _VT_DEFAULTS["contact_modulus"],
        L.CONTACT_MODULUS,
        "E' of the cam/tappet pair for the Palmgren law",
    )
    contact_damping: float = _arg(
        _VT_DEFAULTS["contact_damping"], L.DAMPING, "cam–tappet contact damping"
    )
    camshaft_stiffness: float | None = _arg(
        None, L.STIFFNESS, "camshaft/bearing support stiffness in series (absent: rigid)"
    )
    tappet_valve_stiffness: float = _arg(
        _VT_DEFAULTS["tappet_valve_stiffness"], L.STIFFNESS, "bucket crown + shim + valve tip"
    )
    tappet_valve_damping: float = _arg(
        _VT_DEFAULTS["tappet_valve_damping"], L.DAMPING, "tappet–valve damping"
    )
    lash: float = _arg(_VT_DEFAULTS["lash"], L.LASH, "tappet–valve clearance on the base circle")
    seat_stiffness: float = _arg(
        _VT_DEFAULTS["seat_stiffness"], L.STIFFNESS, "valve stem + seat insert"
    )
    seat_damping: float = _arg(_VT_DEFAULTS["seat_damping"], L.DAMPING, "valve-seat damping")
    spring_seat_stiffness: float = _arg(
        _VT_DEFAULTS["spring_seat_stiffness"], L.STIFFNESS, "retainer–spring seating"
    )
    spring_support_stiffness: float = _arg(
        _VT_DEFAULTS["spring_support_stiffness"], L.STIFFNESS, "head–spring seating"
    )
    damping_force_ramp: float = _arg(
        _VT_DEFAULTS["damping_force_ramp"],
        L.DAMPING_FORCE_RAMP,
        "elastic force over which unilateral damping phases in",
    )
    bore_friction_coefficient: float = _arg(
        _VT_DEFAULTS["bore_friction_coefficient"],
        L.BORE_FRICTION_COEFFICIENT,
        "friction coefficient of the tappet in its bore",
    )
    bore_friction_velocity: float = _arg(
        _VT_DEFAULTS["bore_friction_velocity"],
        L.BORE_FRICTION_VELOCITY,
        "regularisation velocity of the bore friction",
    )
    tappet_radius: float = _arg(
        _VT_DEFAULTS["tappet_radius"],
        L.LENGTH_BELOW_1M,
        "radius of the tappet face (max contact offset must stay below)",
    )

    @property
    def unused_keys(self) -> tuple[str, ...]:
        """The keys its model does not use (flexible: :data:`LUMPED_ONLY`, the bodies give
        them)."""
        return LUMPED_ONLY if self.model == "flexible" else ()

    @model_validator(mode="after")
    def _model_rule(self):
        problems = []
        if self.model == "flexible":
            for k in self.unused_keys:
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

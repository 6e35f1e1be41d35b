"""The case-file schema: one pydantic model per TOML section.

Every field records its unit (``json_schema_extra={"unit": …}``), its allowed range and a
one-line description; ``docs/case-files.md`` documents them and the error messages quote
them. Friction, rheology and roughness default to typical sourced values
(:mod:`tribodyn.physics.typical`); so do the engine speed, the cam's sizes and the
valvetrain's masses, spring and preload (a warning names those a case leaves out); the paper's friction
values are stated in its case files. Numerical settings are tribodyn's defaults. Sections are strict (no type coercion), frozen, and reject unknown keys.

Here: ``[case]``, ``[engine]``, ``[numerics]``, ``[tappet_rotation]``; the cam and
valvetrain sections are in :mod:`.schema_valvetrain`, the lubricant and surfaces in
:mod:`.schema_surfaces`, the section base in :mod:`.schema_fields` (all importable here).
"""

from __future__ import annotations

from typing import Annotated, Literal

from pydantic import Field, model_validator

from .._validation import InputError
from ..contact.ehl.grid import N_AUTO, N_MAX_AUTO
from ..contact.ehl.options import EHLOptions
from ..contact.ehl.thermal_field import ThermalOptions
from ..physics import limits as L
from ..physics import typical_engine
from ..physics.valvetrain_friction import BoreGeometry, GuideGeometry
from ..valvetrain.dynamics import simulate_valvetrain
from ..valvetrain.tappet_rotation import TappetRotation
from ..valvetrain.tribology import SUPPLY_FILM
from .errors import CaseKeyError, Problems
from .schema_fields import _NAME_PATTERN, Section, _arg, _lim, _q, defaults_of
from .schema_surfaces import (
    LubricantConfig,
    MaterialConfig,
    MeasuredSurfaceConfig,
    RoughnessConfig,
    StrengthConfig,
    StressConfig,
    SurfaceSetConfig,
    typical_materials,
    typical_surface_sets,
)
from .schema_valvetrain import (
    CAM_MODELS,
    LUMPED_ONLY,
    AccelerationCamConfig,
    CamConfig,
    CamshaftConfig,
    CircularArcCamConfig,
    SpringConfig,
    TableCamConfig,
    TappetConfig,
    ValveConfig,
    Valvetrain,
)
from .schema_valvetrain import _CamBase as _CamBase  # re-exported (tests)

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
    "MeasuredSurfaceConfig",
    "RoughnessConfig",
    "SurfaceSetConfig",
    "StrengthConfig",
    "StressConfig",
    "Numerics",
    "typical_materials",
    "typical_surface_sets",
    "TappetRotationConfig",
]


#: the defaults of the constructors the sections set: the one source of theirs
_EHL_DEFAULTS = defaults_of(EHLOptions)
_THERMAL_DEFAULTS = defaults_of(ThermalOptions)
_DYNAMICS_DEFAULTS = defaults_of(simulate_valvetrain)
_BORE_DEFAULTS = defaults_of(BoreGeometry)
_GUIDE_DEFAULTS = defaults_of(GuideGeometry)
_ROTATION_DEFAULTS = defaults_of(TappetRotation)


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

    bore_diameter: float | None = _lim(
        None,
        L.TAPPET_BORE_DIAMETER,
        "tappet bore diameter, at least 2 × valvetrain.tappet_radius (absent: that)",
    )
    bore_guided_length: float = _q(0.018, "m", "guided length of the bucket", gt=0.0, lt=0.2)
    bore_clearance: float = _q(2.5e-5, "m", "radial clearance in the bore", gt=0.0, lt=1e-3)
    bore_edge_offset: float = _q(
        _BORE_DEFAULTS["edge_offset"], "m", "lower bore edge above the face", ge=0.0, lt=0.2
    )
    bore_friction_coefficient: float | None = _q(
        None, "", "boundary μ at the bore edges (absent: valvetrain's)", ge=0.0, le=1.0
    )
    journal_radius: float = _q(0.0125, "m", "camshaft journal radius", gt=0.0, lt=0.2)
    journal_length: float = _q(0.018, "m", "camshaft journal length", gt=0.0, lt=0.2)
    journal_clearance: float = _q(3e-5, "m", "journal radial clearance", gt=0.0, lt=1e-3)
    guide_stem_diameter: float = _q(0.006, "m", "valve stem diameter", gt=0.0, lt=0.1)
    guide_length: float = _q(0.035, "m", "valve guide length", gt=0.0, lt=0.3)
    guide_clearance: float = _q(2e-5, "m", "stem radial clearance", gt=0.0, lt=1e-3)
    guide_friction_coefficient: float = _q(
        _GUIDE_DEFAULTS["friction_coefficient"], "", "boundary μ in the guide", ge=0.0, le=1.0
    )
    guide_side_load: float = _q(
        _GUIDE_DEFAULTS["side_load"], "N", "side load on the stem", ge=0.0, le=1e4
    )


class Engine(Section):
    """``[engine]``: operating point. The cam turns at half the engine speed (4-stroke).
    With ``cylinders``: a whole engine's direct-acting valvetrain (``tribodyn engine``)."""

    speed_rpm: float = _lim(
        typical_engine.ENGINE_SPEED.value,
        L.ENGINE_SPEED,
        "engine (crank) speed; cam speed = speed_rpm/2",
    )
    cylinders: int | None = _q(None, "", "cylinders (absent: one valve)", ge=1, le=16)
    firing_order: list[int] | None = _q(
        None, "", "cylinder numbers 1…n in firing order (absent: 1, 2, …, n)"
    )
    displacement: float | None = _lim(None, L.ENGINE_DISPLACEMENT, "swept volume of the engine")
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

    def auxiliary_geometries(self, tappet_radius: float, bore_friction_coefficient: float):
        """(bore, guide, journal) geometries of :mod:`tribodyn.physics.valvetrain_friction`
        from ``[engine.auxiliary]`` with the valvetrain's tappet radius [m] and bore
        friction coefficient (used where the auxiliary's are absent). Raises
        :class:`~tribodyn.config.errors.CaseKeyError` naming the key."""
        from ..physics import valvetrain_friction as vf

        a = self.auxiliary_friction()
        d = a.bore_diameter if a.bore_diameter is not None else 2.0 * tappet_radius
        if d < 2.0 * tappet_radius:
            raise CaseKeyError(
                "engine.auxiliary.bore_diameter",
                f"must be >= 2 × valvetrain.tappet_radius = {2e3 * tappet_radius:.4g} mm "
                f"(got {d * 1e3:.4g} mm): the tappet face slides in its bore",
            )
        # each part's keys are "<part>_<argument>" of its geometry
        keys = a.model_dump() | {"bore_diameter": d}
        if a.bore_friction_coefficient is None:
            keys["bore_friction_coefficient"] = bore_friction_coefficient
        geometries = {
            "bore": vf.BoreGeometry,
            "guide": vf.GuideGeometry,
            "journal": vf.JournalGeometry,
        }
        out = []
        for part, geometry in geometries.items():
            prefix = f"{part}_"
            args = {k.removeprefix(prefix): v for k, v in keys.items() if k.startswith(prefix)}
            try:
                out.append(geometry(**args))
            except InputError as exc:
                raise CaseKeyError(f"engine.auxiliary.{part}_clearance", str(exc)) from None
        return tuple(out)

    def firing_angles(self) -> dict[int, float]:
        """Crank angle [°] of each cylinder's firing TDC (evenly spaced over 720°, in
        firing order; cylinder 1 of the order at 0°)."""
        n = self.cylinders or 1
        order = self.firing_order or list(range(1, n + 1))
        return {c: 720.0 * i / n for i, c in enumerate(order)}


class Numerics(Section):
    """``[numerics]``: solver settings."""

    n: int = _arg(
        0,
        L.EHL_NODES_CYCLE,
        f"EHL grid nodes (uniform); 0 = automatic ({N_AUTO} nodes over the "
        "domain sized from the contact; steady solves double them, up to "
        f"{N_MAX_AUTO}, while h_c, h_min change > 1 % from half the nodes); at most "
        f"{L.EHL_NODES_CYCLE.le} ({L.EHL_NODES_CYCLE.why})",
    )
    min_load: float = _q(
        5.0,
        "N",
        "contact force below which the EHL is not solved "
        "(cam on the base circle: no load, no film)",
        gt=0.0,
        le=1e4,
    )
    inlet: float = _arg(
        _EHL_DEFAULTS["inlet"],
        L.DOMAIN_HALF_WIDTHS,
        "EHL domain upstream of the centre, in Hertz half-widths",
    )
    outlet: float = _arg(
        _EHL_DEFAULTS["outlet"],
        L.DOMAIN_HALF_WIDTHS,
        "EHL domain downstream of the centre, in Hertz half-widths",
    )
    inlet_truncation: float = _arg(
        _EHL_DEFAULTS["inlet_truncation"],
        L.INLET_TRUNCATION,
        "EHL domain upstream at least as far as the cut-off inlet "
        "loses this share of the load (far-field estimate)",
    )
    inlet_rigid: float = _arg(
        _EHL_DEFAULTS["inlet_rigid"],
        L.DOMAIN_RIGID_LENGTHS,
        "EHL domain upstream at least this many rigid inlet lengths √(2R h) (squeeze films)",
    )
    outlet_rigid: float = _arg(
        _EHL_DEFAULTS["outlet_rigid"],
        L.DOMAIN_RIGID_LENGTHS,
        "EHL domain downstream, in rigid inlet lengths",
    )
    tol: float = _arg(
        _EHL_DEFAULTS["tol"], L.NEWTON_TOL, "EHL Newton tolerance (scaled update and residual)"
    )
    max_iter: int = _arg(
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
    cycles: int = _lim(
        _DYNAMICS_DEFAULTS["cycles"],
        L.DYNAMICS_CYCLES,
        "engine cycles simulated (the last is presented)",
    )
    output_step_deg: float = _lim(
        _DYNAMICS_DEFAULTS["output_step"], L.OUTPUT_STEP, "output step of the valvetrain dynamics"
    )
    max_step_deg: float = _lim(
        _DYNAMICS_DEFAULTS["max_step"], L.MAX_STEP, "largest integrator step of the dynamics"
    )
    dynamics_method: Literal["LSODA", "Radau", "BDF"] = _q(
        _DYNAMICS_DEFAULTS["method"],
        "",
        "stiff integrator (LSODA: compiled lumped model; Radau, BDF: solve_ivp)",
    )
    dynamics_rtol: float = _lim(
        _DYNAMICS_DEFAULTS["rtol"], L.DYNAMICS_RTOL, "relative tolerance of the dynamics"
    )
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
    coupling_n: int = _arg(
        192,
        L.EHL_NODES_CYCLE,
        "EHL grid nodes of the coupling's re-passes along the implicit dynamics (they "
        "give the film law, needed to the coupling tolerance only; the reported EHL "
        "keeps numerics.n); at most numerics.n when that is set; 0 = as numerics.n",
    )
    coupling_supply_film: float = _lim(
        SUPPLY_FILM,
        L.SUPPLY_FILM_THICKNESS,
        "oil supply layer that bounds the film of the implicit dynamics (the tappet rides "
        "on it off the cam lobe; assumed)",
    )
    workers: int = _lim(
        0,
        L.WORKERS,
        "worker processes for the surface sets, the coupling chain and "
        "the single-contact studies (0: one per CPU core)",
    )
    thermal: bool = _q(
        False,
        "",
        "thermal EHL (film energy equation, conduction in the "
        "solids and coatings) along the cycle, beside the "
        "isothermal one",
    )
    thermal_x_nodes: int = _arg(
        _THERMAL_DEFAULTS["x_nodes"], L.THERMAL_X_NODES, "thermal grid nodes along the contact"
    )
    thermal_film_nodes: int = _arg(
        _THERMAL_DEFAULTS["film_nodes"], L.THERMAL_FILM_NODES, "thermal nodes across the film (odd)"
    )
    thermal_solid_nodes: int = _arg(
        _THERMAL_DEFAULTS["solid_nodes"], L.THERMAL_SOLID_NODES, "thermal depth nodes per solid"
    )
    thermal_iterations: int = _arg(
        _THERMAL_DEFAULTS["step_iter"],
        L.THERMAL_STEP_ITER,
        "pressure ↔ temperature iterations per transient step (1: staggered)",
    )
    thermal_tol: float = _arg(
        _THERMAL_DEFAULTS["tol"],
        L.THERMAL_TOL,
        "temperature change at which the thermal fixed-point iteration stops",
    )


class TappetRotationConfig(Section):
    """``[tappet_rotation]``: a bucket tappet turning about its axis
    (:class:`~tribodyn.valvetrain.tappet_rotation.TappetRotation`; docs/case-files.md)."""

    speed_ratio: float = _q(
        _ROTATION_DEFAULTS["speed_ratio"],
        "",
        "tappet speed over cam speed ω_t/ω (0: the tappet does not turn; no typical "
        "value was found in the sources)",
        ge=-1.0,
        le=1.0,
    )
    cam_offset: float = _q(
        _ROTATION_DEFAULTS["cam_offset"],
        "m",
        "offset e_o of the cam from the tappet axis, along the cam axis",
        ge=0.0,
        lt=0.05,
    )

"""Building a case: every tribodyn object a validated :class:`~tribodyn.config.Case`
describes, built once.

A :class:`~tribodyn.config.Case` is data (the validated keys of a case file).
:func:`build` turns it into a :class:`BuiltCase`: the cam profile, the lubricant (and the
thermal oil of a thermal or datasheet case), the valvetrain parameters (lumped or
flexible), the EHL, thermal and dynamics options, the tappet rotation and, per surface
set, its bodies, roughness and boundary-friction law (:class:`~tribodyn.config.SurfaceSet`),
its EHL options (ς, τ₀), its thermal bodies and its materials' strengths. The workflow
reads these objects instead of building them again.

Validating a case builds it: the physics constructors check the ranges of the keys they
are given (the schema does not check them again), and :func:`collect` files each
constructor's :class:`~tribodyn.InputError` under the case key it comes from (a
:class:`~tribodyn.physics.limits.RangeError` under the key of each argument out of
range, in the schema's message form). The case keeps the result, so ``build(case)`` of a
loaded case returns the objects built at validation.
"""

from __future__ import annotations

import copy
import functools
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, TypeVar

from pydantic import ValidationError

from .._validation import InputError
from ..contact.ehl.options import EHLOptions
from ..physics.limits import RangeError
from .case_thermal import MATERIAL_KEYS, NUMERICS_KEYS
from .errors import CaseKeyError, Problems, in_file_order, out_of_range, validation_problems
from .paths import did_you_mean
from .schema_surfaces import RoughnessConfig

if TYPE_CHECKING:
    from ..contact.ehl.thermal import ThermalOptions
    from ..physics.heat_conduction import ThermalBody
    from ..physics.lubricant import Lubricant
    from ..physics.materials import Material
    from ..physics.strength import Strength
    from ..physics.thermal_oil import ThermalLubricant
    from ..valvetrain.cams import CamProfile
    from ..valvetrain.flexible import FlexibleValvetrain
    from ..valvetrain.parameters import ValvetrainParameters
    from ..valvetrain.tappet_rotation import TappetRotation
    from ..valvetrain.tribology import AnalyticTribology
    from .case import Case
    from .schema import SurfaceSetConfig
    from .surface_set import SurfaceSet

__all__ = [
    "BuiltCase",
    "BuiltSet",
    "as_built",
    "build",
    "collect",
    "range_problems_beside",
]

T = TypeVar("T")

#: Constructor arguments whose case key is not ``<section>.<argument>``: of the valvetrain
#: and ThermalOptions (absolute keys) and of a surface set's objects (keys within the set).
VALVETRAIN_KEYS = {"cam_width": "cam.width"}
SET_KEYS = {
    "thickness": "coating_thickness",
    **{k: f"roughness.{k}" for k in RoughnessConfig.model_fields},  # Roughness's arguments
}
THERMAL_KEYS = {a: f"numerics.{k}" for a, k in NUMERICS_KEYS.items()}


@dataclass(frozen=True)
class BuiltSet:
    """One surface set, built.

    surface : bodies, roughness, ς, τ₀ and labels (:class:`~tribodyn.config.SurfaceSet`).
    options : :class:`~tribodyn.EHLOptions` of ``[numerics]`` with this set's ς and τ₀.
    thermal_bodies : (cam, tappet) :class:`~tribodyn.ThermalBody` (None unless
        ``numerics.thermal``).
    strengths : ``{"cam": (substrate, None), "tappet": (substrate, coating)}``
        :class:`~tribodyn.physics.strength.Strength` (None where unknown).
    wear_coefficient : Archard k [m³/(N m)] of the tappet's surface material (None:
        unknown), and ``wear_source``, where it comes from
        (the case's ``[strength.<m>]``, or the labelled typical value).
    """

    surface: SurfaceSet
    options: EHLOptions
    thermal_bodies: tuple[ThermalBody, ThermalBody] | None
    strengths: dict
    wear_coefficient: float | None = None
    wear_source: str = ""

    @property
    def name(self) -> str:
        return self.surface.name


@dataclass(frozen=True)
class BuiltCase:
    """Every object of a validated case, built once by :func:`build` (module text).

    ``thermal_lubricant`` is None unless the case is thermal or its oil a datasheet;
    ``thermal_options`` are those of ``[numerics]`` (also of a case that is not thermal:
    its single-contact studies);
    ``dynamics_options`` are the keyword arguments of
    :func:`~tribodyn.valvetrain.simulate_valvetrain` (engine speed and ``[numerics]``);
    ``materials`` the :class:`~tribodyn.Material` (E, ν) and ``material_strengths`` the
    :class:`~tribodyn.physics.strength.Strength` (None where unknown) of each
    ``[materials]`` key.
    """

    case: Case
    cam: CamProfile
    lubricant: Lubricant
    thermal_lubricant: ThermalLubricant | None
    valvetrain: ValvetrainParameters | FlexibleValvetrain
    options: EHLOptions
    thermal_options: ThermalOptions
    tappet_rotation: TappetRotation
    dynamics_options: dict[str, Any]
    sets: dict[str, BuiltSet] = field(default_factory=dict)
    materials: dict[str, Material] = field(default_factory=dict)
    material_strengths: dict[str, Strength | None] = field(default_factory=dict)

    def set(self, name: str) -> BuiltSet:
        """The built surface set ``name`` (an InputError naming the defined sets if none)."""
        if name in self.sets:
            return self.sets[name]
        names = list(self.sets)
        more = did_you_mean(name, names)
        raise InputError(f"unknown surface set {name!r} (defined: {', '.join(names)}){more}")

    @property
    def surface_sets(self) -> list[SurfaceSet]:
        """The surface sets in case order."""
        return [s.surface for s in self.sets.values()]

    @property
    def lumped(self) -> ValvetrainParameters:
        """The lumped valvetrain (a flexible case's lumped equivalent)."""
        return self.valvetrain.lumped_equivalent()

    def analytic_tribology(self, name: str) -> AnalyticTribology:
        """The explicit tribology of the dynamics for surface set ``name`` (a new model
        object over the built bodies, roughness and lubricant)."""
        return self.case._new_analytic_tribology(self.set(name).surface, self.lubricant)

    def thermal_oil(self) -> ThermalLubricant:
        """The thermal oil: :attr:`thermal_lubricant`, or (a case neither thermal nor a
        datasheet) built now from ``[lubricant]``, an InputError naming the missing key."""
        oil = self.thermal_lubricant
        return oil if oil is not None else self.case._new_thermal_lubricant()

    def thermal_solver_options(self) -> ThermalOptions:
        """:attr:`thermal_options`."""
        return self.thermal_options

    def thermal_bodies_of(self, surface: SurfaceSet) -> tuple[ThermalBody, ThermalBody]:
        """(cam, tappet) :class:`~tribodyn.ThermalBody` of ``surface``: the built ones of
        one of the case's sets, else built now from the materials' thermal properties (an
        InputError naming a missing one)."""
        own = self.sets.get(surface.name)
        if own is not None and own.thermal_bodies is not None and own.surface == surface:
            return own.thermal_bodies
        return self.case._new_thermal_bodies(surface)


def as_built(case: Case | BuiltCase) -> BuiltCase:
    """The :class:`BuiltCase` of a Case (:func:`build`), or ``case`` if it is one: the
    argument of a public study function that takes either."""
    return case if isinstance(case, BuiltCase) else build(case)


def build(case: Case) -> BuiltCase:
    """The :class:`BuiltCase` of ``case``: the one built when the case was validated, or
    (a case constructed without validation, or a copy such as ``model_copy(update=…)``
    that kept the original's objects) built now; raises :class:`~tribodyn.InputError`
    listing every problem."""
    built = case._built
    if built is None or built.case is not case:
        built, problems = collect(case)
        if problems or built is None:
            raise Problems(problems)
        case._built = built
    return built


def collect(
    case: Case, *, materials_ok: bool = True, ranges_only: bool = False
) -> tuple[BuiltCase | None, list[tuple[str, str]]]:
    """Build every object of ``case``; each constructor's InputError becomes a
    ``(case key, message)`` problem. Returns the BuiltCase (None if any object failed)
    and the problems in the order of the case file's sections. ``materials_ok=False``
    (a surface set names an undefined material): the surface sets are not built; nor is
    a set whose materials failed. First the objects whose constructors check the keys'
    ranges are built, then (none failed, not ``ranges_only``) the rest: surface laws,
    thermal bodies, strengths, cam."""
    problems: list[tuple[str, str]] = []
    seen: set[tuple[str, str]] = set()

    def attempt(path: str, make: Callable[[], T], keys: dict[str, str] | None = None) -> T | None:
        """``make()``, or None with its problems filed: a RangeError's arguments under
        ``keys[argument]`` or ``path.argument``, other errors under ``path``."""
        found: list[tuple[str, str]]
        try:
            return make()
        except CaseKeyError as exc:  # the key itself (numerics.n, cam.path)
            found = [(exc.key, str(exc))]
        except RangeError as exc:
            found = [
                (
                    (keys or {}).get(name, f"{path}.{name}"),
                    out_of_range(lim.constraints(), lim.unit, v, lim.auto),
                )
                for name, lim, v in exc.items
            ]
        except InputError as exc:
            found = [(path, str(exc))]
        for problem in found:
            if problem not in seen:
                problems.append(problem)
                seen.add(problem)
        return None

    # 1. the objects whose constructors check the ranges of the case's keys
    n = case.numerics
    thermal_lubricant = lubricant = None
    if case.lubricant_config.datasheet:  # the isothermal oil is the datasheet's at its inlet
        thermal_lubricant = attempt("lubricant", case._new_thermal_lubricant)
        lubricant = thermal_lubricant.isothermal() if thermal_lubricant is not None else None
    else:
        lubricant = attempt("lubricant", case._new_lubricant)
    valvetrain = attempt("valvetrain", case._new_valvetrain_parameters, VALVETRAIN_KEYS)
    options = attempt("numerics", case._new_ehl_options)
    thermal_options = attempt("numerics", case._new_thermal_options, THERMAL_KEYS)
    if n.thermal and not case.lubricant_config.datasheet:  # takes the checked μ, α, τ_E, …
        thermal_lubricant = attempt(
            "lubricant", functools.partial(case._new_thermal_lubricant, lubricant)
        )
    if thermal_lubricant is None:  # no thermal oil checked its keys (a failed one: same lines)
        attempt("lubricant", case._check_thermal_oil_keys)
    built_materials = {
        k: attempt(f"materials.{k}", functools.partial(case._new_material, k))
        for k in case.materials
    }
    materials = {k: m for k, m in built_materials.items() if m is not None}
    thermal_properties: dict = {}  # of each material, built once (a thermal case)
    for k in case.materials:
        keys = {a: f"materials.{k}.{key}" for a, key in MATERIAL_KEYS.items()}
        built = thermal_properties if n.thermal else None
        attempt(f"materials.{k}", functools.partial(case._check_thermal_properties, k, built), keys)
    checked: list[tuple[SurfaceSetConfig, SurfaceSet | None, EHLOptions | None]] = []
    for i, cfg in enumerate(case.surface_set_configs if materials_ok else ()):
        where = f"surface_sets[{i}]"
        surface = None
        if all(m is None or m in materials for m in (case.cam_config.material, *cfg.materials)):
            keys = {name: f"{where}.{key}" for name, key in SET_KEYS.items()}
            surface = attempt(where, functools.partial(case._build_set, cfg, materials), keys)
        # the set's friction law with [numerics] (its defaults if [numerics] failed)
        base = options if options is not None else EHLOptions()
        sigma, tau0 = cfg.boundary_friction(case.materials)
        assert sigma is not None  # required by the case cross-check (materials_ok)
        # a material's ς was checked by the schema ([materials]), the set's own is checked here
        by_schema = (
            ("boundary_shear_coefficient",) if cfg.boundary_shear_coefficient is None else ()
        )
        friction = functools.partial(base.with_boundary_friction, sigma, tau0, by_schema)
        set_options = attempt(where, friction)
        checked.append((cfg, surface, set_options))
    if problems or not materials_ok or ranges_only:
        return None, in_file_order(type(case), problems)
    # 2. the rest, built from those: surface laws, thermal bodies, strengths, cam
    lubricant_ok = lubricant is not None and not any(
        p.split(".")[0] == "lubricant" for p, _ in problems
    )
    sets: dict[str, BuiltSet] = {}
    for cfg, surface, set_options in checked:
        assert surface is not None and set_options is not None
        surface = attempt(
            f"surface_sets[{cfg.name}]", functools.partial(case._with_surface_law, cfg, surface)
        )
        if surface is None:
            continue
        bodies = None
        if n.thermal and lubricant_ok:
            bodies = attempt(
                "materials",
                functools.partial(case._new_thermal_bodies, surface, thermal_properties),
            )
        strengths = attempt("strength", functools.partial(case._new_strengths, cfg))
        wear = attempt("strength", functools.partial(case._new_wear_coefficient, cfg))
        sets[cfg.name] = BuiltSet(
            surface=surface,
            options=set_options,
            thermal_bodies=bodies,
            strengths=strengths or {},
            wear_coefficient=wear[0] if wear else None,
            wear_source=wear[1] if wear else "",
        )
    material_strengths = attempt(
        "strength", lambda: {k: case._new_material_strength(k) for k in case.materials}
    )
    cam = attempt("cam", case._build_cam)
    rotation = attempt("tappet_rotation", functools.partial(case._new_tappet_rotation, cam))
    if problems:
        return None, in_file_order(type(case), problems)
    assert cam is not None and lubricant is not None and valvetrain is not None
    assert rotation is not None
    assert options is not None and thermal_options is not None
    assert material_strengths is not None
    return (
        BuiltCase(
            case=case,
            cam=cam,
            lubricant=lubricant,
            thermal_lubricant=thermal_lubricant,
            valvetrain=valvetrain,
            options=options,
            thermal_options=thermal_options,
            tappet_rotation=rotation,
            dynamics_options=case._new_dynamics_options(),
            sets=sets,
            materials=materials,
            material_strengths=material_strengths,
        ),
        problems,
    )


def range_problems_beside(
    root: type[Case], data: dict, exc: ValidationError, context: dict, variants: dict
) -> list[tuple[str, str]]:
    """The out-of-range values the build finds in ``data`` beside the schema's errors
    ``exc`` (so that a file's problems are reported together): ``data`` without the
    values the schema rejected (their defaults apply) is validated again as ``root``
    (with ``context`` and ``"ranges_only"``), and the range problems
    (:func:`~tribodyn.config.errors.out_of_range`) of the keys it kept are returned; a
    value's range does not depend on the other keys. ``variants``: the tagged unions
    (:func:`~tribodyn.config.errors.validation_problems`)."""
    rest = copy.deepcopy(data)
    dropped = [_drop(rest, err["loc"]) for err in exc.errors(include_url=False)]
    if not any(dropped):  # the same data again: nothing new
        return []
    try:
        root.model_validate(rest, context={**context, "ranges_only": True})
    except ValidationError as again:
        rejected = {key for key, _ in validation_problems(exc, root, variants)}
        return [
            (key, msg)
            for key, msg in validation_problems(again, root, variants)
            if key not in rejected and _RANGE_PROBLEM.fullmatch(msg)
        ]
    return []


#: the message of an out-of-range value (errors.out_of_range; units such as W/(m K))
_RANGE_PROBLEM = re.compile(r"must be (?:[^()]|\([^()]*\))* \(got [^()]*\)")


def _drop(data: dict, loc: tuple) -> bool:
    """Remove the value at the location ``loc`` of a validation error from ``data`` (a
    location item that is no key there, the tag of a tagged union, is passed over);
    whether there was one."""
    cur: Any = data
    for item in loc[:-1]:
        if isinstance(cur, dict) and item in cur:
            cur = cur[item]
        elif isinstance(cur, list) and isinstance(item, int) and 0 <= item < len(cur):
            cur = cur[item]
        elif not isinstance(cur, dict):
            return False
    return bool(loc) and isinstance(cur, dict) and cur.pop(loc[-1], _NONE) is not _NONE


_NONE = object()


def options_for(built: BuiltCase, surface: SurfaceSet | str | None) -> EHLOptions:
    """The EHL options of a surface set (object or name) of ``built``: the built ones for
    one of its sets, else ``[numerics]`` with the given set's ς and τ₀."""
    if surface is None:
        return built.options
    if isinstance(surface, str):
        return built.set(surface).options
    own = built.sets.get(surface.name)
    if own is not None and own.surface == surface:
        return own.options
    return built.options.with_boundary_friction(  # the set's ς and τ₀
        surface.boundary_shear_coefficient, surface.boundary_shear_strength
    )

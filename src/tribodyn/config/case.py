"""The validated case: :class:`Case`, its builders of tribodyn objects, and loading.
The builders of the cam and valvetrain, the thermal model and the strengths are
inherited from :mod:`.case_valvetrain`, :mod:`.case_thermal` and :mod:`.case_strength`.

A case file describes one study: engine speed, cam, valvetrain, lubricant, materials, the
surface sets to compare (uncoated, DLC, WC-C, …) and the numerical settings. Every key is
in SI units unless its name says otherwise (``speed_rpm``, ``*_deg``); see
``docs/case-files.md``. An empty file is a typical engine (:mod:`tribodyn.physics.typical`,
:mod:`~tribodyn.physics.typical_engine`), run with a warning naming the valvetrain and oil
values that decide the forces and film (:mod:`tribodyn.config.origins`); the paper's own
case, with every paper value stated, is ``cases/andreou2023.toml``.

Validation errors (unknown keys, values out of range, wrong types, cross-field rules such
as a surface set naming an undefined material) raise :class:`~tribodyn.InputError` with
one line per problem. Every object the case describes is built once, during validation,
so a case that loads can be run; :func:`tribodyn.config.build.build` returns those
objects (the builders below are private: ``build(case).cam``, ``.lubricant``, …). Models are frozen; change a validated case with
:meth:`Case.updated` (validates again).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from pathlib import Path
from typing import Annotated, Any, ClassVar, TypeVar

import numpy as np
import tomli_w
from pydantic import (
    Field,
    PrivateAttr,
    ValidationError,
    ValidationInfo,
    model_validator,
)

from .._typing import PathLike
from .._validation import InputError
from ..contact.ehl import EHLOptions
from ..physics.asperity import Roughness
from ..physics.limits import EHL_NODES_CYCLE, RangeError, unchecked
from ..physics.lubricant import Lubricant
from ..physics.materials import Body, Coating, Material
from ..valvetrain.kinematics import rpm_to_cam_speed
from ..valvetrain.tappet_rotation import TappetRotation
from .build import collect, range_problems_beside
from .case_strength import StrengthBuilders
from .case_thermal import DATASHEET_KEYS, OIL_LAW_KEYS, ThermalBuilders
from .case_valvetrain import CamValvetrainBuilders
from .errors import (
    CaseKeyError,
    Problems,
    format_validation_error,
    problem_text,
)
from .measured_surface import asperity_law_note, measured_map, measured_roughness
from .origins import carried_given
from .paths import FILE_KEYS, Key, did_you_mean, find_paths, parse_path, set_path
from .schema import (
    CAM_MODELS,
    AccelerationCamConfig,
    CamConfig,
    CaseInfo,
    Engine,
    LubricantConfig,
    MaterialConfig,
    Numerics,
    Section,
    StrengthConfig,
    StressConfig,
    SurfaceSetConfig,
    TappetRotationConfig,
    Valvetrain,
    typical_materials,
    typical_surface_sets,
)
from .surface_set import SurfaceSet
from .tomlfile import TomlFile, check_nesting, file_or_bundled

T = TypeVar("T")

__all__ = [
    "Case",
    "SurfaceSet",
    "load_case",
    "bundled_cases",
    "DEFAULT_CASE",
    "CASES_DIR",
    "to_toml",
]

#: Folder of the bundled case files.
CASES_DIR = Path(__file__).resolve().parent.parent / "cases"
#: The bundled default case (the paper's).
DEFAULT_CASE = CASES_DIR / "andreou2023.toml"
#: Sections an engine's ``[engine.<kind>] changes`` may not touch: the lobes share them.
LOBE_SHARED_SECTIONS = ("engine", "case", "numerics")
#: The ``[numerics]`` keys that are EHLOptions fields of the same name, but the grid ``n``.
EHL_OPTION_KEYS = {f.name for f in dataclasses.fields(EHLOptions)} & set(Numerics.model_fields)
EHL_OPTION_KEYS.discard("n")


class Case(CamValvetrainBuilders, ThermalBuilders, StrengthBuilders, Section, TomlFile):
    """A validated case. Build it with :func:`load_case`, :meth:`from_toml_string` or
    :meth:`from_dict`; every section has defaults (module text)."""

    toml_kind: ClassVar[str] = "case"

    case: CaseInfo = Field(default_factory=CaseInfo)
    engine: Engine = Field(default_factory=Engine)
    cam_config: CamConfig = Field(default_factory=AccelerationCamConfig, alias="cam")
    valvetrain: Valvetrain = Field(default_factory=Valvetrain)
    lubricant_config: LubricantConfig = Field(default_factory=LubricantConfig, alias="lubricant")
    materials: dict[Annotated[str, Field(min_length=1)], MaterialConfig] = Field(
        default_factory=typical_materials, min_length=1
    )
    surface_set_configs: list[SurfaceSetConfig] = Field(
        default_factory=typical_surface_sets, min_length=1, alias="surface_sets"
    )
    numerics: Numerics = Field(default_factory=Numerics)
    strength_configs: dict[Annotated[str, Field(min_length=1)], StrengthConfig] = Field(
        default_factory=dict, alias="strength"
    )
    stress: StressConfig = Field(default_factory=StressConfig)
    tappet_rotation_config: TappetRotationConfig = Field(
        default_factory=TappetRotationConfig, alias="tappet_rotation"
    )

    _base_dir: Path = PrivateAttr(default_factory=Path.cwd)
    _source: Path | None = PrivateAttr(default=None)
    #: the objects built at validation (:func:`tribodyn.config.build.build`)
    _built: Any = PrivateAttr(default=None)
    #: dotted keys of the input values the case gave (:mod:`tribodyn.config.origins`)
    _given: frozenset[str] = PrivateAttr(default=frozenset())

    # -- validation ---------------------------------------------------------------------
    @model_validator(mode="after")
    def _cross_check(self, info: ValidationInfo):
        ctx = info.context or {}
        self._base_dir = Path(ctx.get("base_dir") or Path.cwd())
        self._source = ctx.get("source")
        self._given = _given_keys(self)
        problems: list[tuple[str, str]] = []
        known = ", ".join(self.materials)

        def check_material(path, name):
            if name not in self.materials:
                more = did_you_mean(name, self.materials)
                problems.append(
                    (path, f"unknown material {name!r} (defined in [materials]: {known}){more}")
                )
                return False
            return True

        check_material("cam.material", self.cam_config.material)
        for name in self.strength_configs:
            check_material(f"strength.{name}", name)
        seen: dict[str, int] = {}
        for i, s in enumerate(self.surface_set_configs):
            p = f"surface_sets[{i}]"
            if s.name in seen:
                problems.append(
                    (
                        f"{p}.name",
                        f"duplicate surface-set name {s.name!r} (also "
                        f"surface_sets[{seen[s.name]}])",
                    )
                )
            seen.setdefault(s.name, i)
            ok = check_material(f"{p}.substrate", s.substrate)
            if s.coating is not None:
                ok = check_material(f"{p}.coating", s.coating) and ok
            if ok and s.boundary_shear_coefficient is None:
                mat = s.coating if s.coating is not None else s.substrate
                if self.materials[mat].boundary_shear_coefficient is None:
                    problems.append(
                        (
                            f"{p}.boundary_shear_coefficient",
                            f"required: material {mat!r} has no boundary_shear_coefficient",
                        )
                    )
            m = s.measured_surface
            if m is not None and m.topography is not None and not ctx.get("ranges_only"):
                try:  # cheap checks before any computing: the map reads, its σ matches
                    measured_map(s, self.resolve_path)
                except InputError as exc:
                    problems.append((f"{p}.measured_surface.topography", str(exc)))
        # every object built once, its constructor's errors filed under the case keys;
        # the case keeps them (config.build)
        ranges_only = bool(ctx.get("ranges_only"))  # (config.build.range_problems_beside)
        built, build_problems = collect(self, materials_ok=not problems, ranges_only=ranges_only)
        problems += build_problems
        self._built = built
        problems += [] if ranges_only else self._engine_lobe_problems()
        if problems:
            raise Problems(problems)
        return self

    def _engine_lobe_problems(self) -> list[tuple[str, str]]:
        """The engine's auxiliary parts must be built, and each lobe kind's case
        (``[engine.intake]`` changes applied) must validate."""
        out = []
        if self.engine.cylinders is not None:  # the auxiliary parts, before any computing
            try:
                self.engine.auxiliary_geometries(
                    self.valvetrain.tappet_radius, self.valvetrain.bore_friction_coefficient
                )
            except CaseKeyError as exc:
                out.append((exc.key, str(exc)))
        for kind in ("intake", "exhaust"):
            if getattr(self.engine, kind) is None:
                continue
            try:
                self.engine_lobe_case(kind)
            except InputError as exc:
                out.append((f"engine.{kind}.changes", problem_text(exc)))
        return out

    def engine_lobe_case(self, kind: str) -> Case:
        """The single-valve case of the engine's ``kind`` ("intake"/"exhaust") lobes: this
        case without the engine's layout, with ``[engine.<kind>] changes`` applied."""
        lobe = getattr(self.engine, kind)
        data = self.to_dict()
        data["engine"] = {"speed_rpm": self.engine.speed_rpm}
        for key, value in lobe.changes.items():
            tokens = parse_path(key)  # the parsed path: '"engine".x' is engine.x
            first = tokens[0].name if isinstance(tokens[0], Key) else ""
            if first in LOBE_SHARED_SECTIONS:
                raise InputError(
                    f"{key!r}: the lobes share the engine's speed, name and numerics; "
                    "change only cam, valvetrain, lubricant, materials or surface_sets"
                )
            if (
                isinstance(tokens[-1], Key)
                and tokens[-1].name == "name"
                and first == "surface_sets"
            ):
                raise InputError(
                    f"{key!r}: the lobes keep the case's surface sets and their names "
                    f"({', '.join(self.surface_set_names)}); change their other keys only"
                )
            set_path(data, list(tokens), value)
        new = self._changed(data)
        if new.surface_set_names != self.surface_set_names:
            raise InputError(
                f"the lobes must keep the case's surface sets "
                f"({', '.join(self.surface_set_names)}; got {', '.join(new.surface_set_names)})"
            )
        return new

    # -- construction -------------------------------------------------------------------
    @classmethod
    def from_dict(cls, data: dict, *, base_dir=None, source=None) -> Case:
        """Validate a (TOML-shaped) dict. Relative paths resolve against ``base_dir``
        (default: the current folder)."""
        if not isinstance(data, dict):
            raise InputError(f"a case must be a table of sections (got {type(data).__name__})")
        check_nesting(data, source)
        ctx = {
            "base_dir": Path(base_dir) if base_dir is not None else None,
            "source": Path(source) if source is not None else None,
        }
        variants = {"cam": CAM_MODELS}
        try:
            return cls.model_validate(data, context=ctx)
        except ValidationError as exc:
            more = range_problems_beside(cls, data, exc, ctx, variants)
            msg = format_validation_error(exc, cls, source, variants=variants, more=more)
            raise InputError(msg) from None

    def updated(self, changes: dict) -> Case:
        """A new case with some keys changed and everything validated again.

        ``changes`` maps dotted key paths to values, e.g.
        ``{"engine.speed_rpm": 2000, "surface_sets[1].coating_thickness": 2e-6}``.
        """
        data = self.to_dict()
        for key, value in changes.items():
            set_path(data, key, value)
        return self._changed(data)

    def _changed(self, data: dict) -> Case:
        """The case of ``data``, this case's dict with some keys changed: validated, read
        from the same file and folder, its given keys carried over."""
        new = Case.from_dict(data, base_dir=self._base_dir)
        new._source = self._source
        new._given = carried_given(self, new)
        return new

    def __eq__(self, other) -> bool:
        """Equal keys (and the same resolved cam table file); how the case was read and
        its cached objects do not matter."""
        if not isinstance(other, Case):
            return NotImplemented
        return (
            self.model_dump() == other.model_dump() and self.cam_table_path == other.cam_table_path
        )

    __hash__ = None  # type: ignore[assignment]  # mutable containers inside: not hashable

    # -- serialisation ------------------------------------------------------------------
    def to_dict(self, *, resolve_paths: bool = False) -> dict:
        """Plain dict of all keys (absent optional keys omitted: TOML has no null).
        ``resolve_paths=True`` makes the cam table path and measured maps absolute."""
        d = self.model_dump(mode="python", exclude_none=True, by_alias=True)
        d["cam"] = {"type": d["cam"].pop("type"), **d["cam"]}
        for k in self.valvetrain.unused_keys:  # a flexible model's bodies give these
            d["valvetrain"].pop(k, None)
        lub = self.lubricant_config
        if lub.datasheet:  # follow from the datasheet (α: So–Klaus unless given)
            for k in DATASHEET_KEYS:
                if k not in lub.model_fields_set:
                    d["lubricant"].pop(k, None)
        if resolve_paths:  # the files the case names (cam table, measured maps), absolute
            for key in FILE_KEYS:
                for where, name in find_paths(d, key):
                    set_path(d, where, str(self.resolve_path(name)))
        return d

    def to_toml(self, *, resolve_paths: bool = False) -> str:
        """TOML text that reads back to an equal case (all keys written)."""
        head = [
            f"# tribodyn case {self.case.name!r} (all keys, SI units unless the key says otherwise)"
        ]
        return to_toml(self.to_dict(resolve_paths=resolve_paths), header=head)

    def write_toml(self, path, *, resolve_paths: bool = True) -> Path:
        """Write :meth:`to_toml` to ``path`` (cam table path made absolute by default, so
        the file works from any folder)."""
        from .._safe_write import atomic_write

        return atomic_write(Path(path), self.to_toml(resolve_paths=resolve_paths))

    # -- properties and builders -------------------------------------------------------
    @property
    def source(self) -> Path | None:
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
    def cam_table_path(self) -> Path | None:
        """Resolved path of the cam lift table (``type = "table"`` only)."""
        if self.cam_config.type != "table":
            return None
        return self.resolve_path(self.cam_config.path)

    def resolve_path(self, path: PathLike) -> Path:
        """A file named in the case: absolute, relative paths from the case's folder."""
        p = Path(path).expanduser()
        return p if p.is_absolute() else (self._base_dir / p)

    @property
    def input_given(self) -> frozenset[str]:
        """Dotted keys (``valvetrain.spring_rate``, ``surface_sets[dlc].roughness.rms``)
        of the valvetrain, lubricant, material and surface values the case gave; the
        others are defaults (:func:`tribodyn.config.origins.input_origins`)."""
        return self._given

    def _new_tappet_rotation(self, cam=None) -> TappetRotation:
        """``[tappet_rotation]`` as a :class:`TappetRotation` (speed ratio 0: none); with
        the ``cam``, checked to fit it and the tappet
        (:meth:`~tribodyn.valvetrain.tappet_rotation.TappetRotation.check_fit`)."""
        c = self.tappet_rotation_config
        rot = TappetRotation(c.speed_ratio, c.cam_offset)
        if cam is not None and rot.cam_offset > 0.0:
            th = np.linspace(0.0, 2.0 * np.pi, 7201)
            e_max = float(np.max(np.abs(cam.derivatives(th)[1])))
            try:
                rot.check_fit(self.valvetrain.tappet_radius, self.width, e_max, cam.base_radius)
            except InputError as exc:
                key = str(exc).split(" ", 1)[0]
                raise CaseKeyError(f"tappet_rotation.{key}", str(exc)) from None
        return rot

    def _new_lubricant(self) -> Lubricant:
        """The :class:`~tribodyn.Lubricant` of ``[lubricant]`` (a datasheet oil at its
        inlet temperature)."""
        c = self.lubricant_config
        if c.datasheet:
            return self._new_thermal_lubricant().isothermal()
        return Lubricant(**c.model_dump(include={*DATASHEET_KEYS, *OIL_LAW_KEYS}))

    def _new_material(self, name: str) -> Material:
        """The :class:`~tribodyn.Material` of ``[materials.<name>]``."""
        m = self.materials[name]
        return Material(E=m.E, nu=m.nu)

    def _new_ehl_options(self) -> EHLOptions:
        """:class:`~tribodyn.EHLOptions` from ``[numerics]`` (the surface sets' ς and τ₀:
        :class:`~tribodyn.config.build.BuiltSet`). The grid keys ``n`` and ``coupling_n``
        (0: automatic) are checked here, against the cycle's transient grid
        (:data:`~tribodyn.physics.limits.EHL_NODES_CYCLE`); the options take n as checked."""
        n = self.numerics
        nodes = EHL_NODES_CYCLE.check("n", n.n)
        EHL_NODES_CYCLE.check("coupling_n", n.coupling_n)
        opts = EHLOptions(**n.model_dump(include=EHL_OPTION_KEYS))
        return unchecked(type(opts), **{**vars(opts), "n": nodes or None})

    @property
    def surface_set_names(self) -> list[str]:
        return [s.name for s in self.surface_set_configs]

    def _build_set(self, s: SurfaceSetConfig, materials: dict[str, Material]) -> SurfaceSet:
        """The surface set ``s`` over the case's built ``materials`` (by key), with the
        Greenwood–Tripp roughness (:meth:`_with_surface_law` adds its surface law)."""
        cam = Body(materials[self.cam_config.material])
        substrate = materials[s.substrate]
        bad: list = []  # the set's values out of range, reported together
        if s.coating is None:
            tappet = Body(substrate)
            label = "uncoated"
        else:
            cm = self.materials[s.coating]
            thickness = s.coating_thickness
            assert thickness is not None  # required with a coating (schema validator)
            layer = materials[s.coating]
            coating = _collecting(bad, lambda: Coating.of(layer, thickness))
            tappet = Body(substrate, coating)
            label = f"{cm.label or s.coating} {thickness * 1e6:.3g} µm"
        sigma, _ = s.boundary_friction(self.materials)
        assert sigma is not None  # required by the case cross-check
        method = self.numerics.greenwood_tripp  # the roughness keys are Roughness's arguments
        rough = _collecting(bad, lambda: Roughness(**s.roughness.arguments(), method=method))
        if bad:
            raise RangeError(bad)
        return SurfaceSet(
            name=s.name,
            bodies=(cam, tappet),
            roughness=rough,
            boundary_shear_coefficient=float(sigma),
            coating_label=label,
            boundary_shear_strength=s.boundary_shear_strength,
            coating_material=s.coating,
            asperity_law=asperity_law_note(s),
        )

    def _with_surface_law(self, s: SurfaceSetConfig, surface: SurfaceSet) -> SurfaceSet:
        """``surface`` of ``s`` with the surface law of its asperity model ("surface", the
        default, or "measured"; Greenwood–Tripp: as it is)."""
        if s.asperity_model == "greenwood_tripp":
            return surface
        assert surface.roughness is not None  # Greenwood–Tripp from _build_set
        rough = measured_roughness(s, surface.roughness, surface.bodies, self.resolve_path)
        return dataclasses.replace(surface, roughness=rough)


def _collecting(bad: list, make: Callable[[], T]) -> T | None:
    """``make()``, or None with its :class:`~tribodyn.physics.limits.RangeError`'s items
    added to ``bad`` (so that every value of a set out of range is reported at once)."""
    try:
        return make()
    except RangeError as exc:
        bad += exc.items
        return None


def _given_keys(case: Case) -> frozenset[str]:
    """The dotted keys of the values the case file (or dict) gave (Case.input_given)."""
    top = case.model_fields_set
    out = {
        f"{Case.model_fields[attr].alias or attr}.{k}"
        for attr in ("engine", "cam_config", "valvetrain", "lubricant_config")
        if attr in top
        for k in getattr(case, attr).model_fields_set
    }
    if "materials" in top:
        for name, m in case.materials.items():
            out |= {f"materials.{name}.{k}" for k in m.model_fields_set}
    if "surface_set_configs" in top:
        for s in case.surface_set_configs:
            p = f"surface_sets[{s.name}]"
            out |= {f"{p}.roughness.{k}" for k in s.roughness.model_fields_set}
            out |= {f"{p}.{k}" for k in s.model_fields_set if k != "roughness"}
    return frozenset(out)


# ----------------------------------------------------------------------------- loading
def bundled_cases() -> dict[str, Path]:
    """Name → path of the case files shipped with tribodyn."""
    return {p.stem: p for p in sorted(CASES_DIR.glob("*.toml"))}


def load_case(path: PathLike | None = None) -> Case:
    """Load and validate a case file.

    ``path=None`` loads the bundled paper case; a bare name such as ``"andreou2023"`` or
    ``"example_table_cam"`` that is not an existing file selects a bundled case.
    """
    if path is None:
        return Case.from_toml(DEFAULT_CASE)
    return Case.from_toml(file_or_bundled(path, bundled_cases()))


def to_toml(data: dict, *, header: list[str] | None = None) -> str:
    """TOML text of a case dict (``tomli-w``), with ``header`` lines as comments."""
    lines = "".join(f"# {h.lstrip('# ')}\n" for h in (header or []))
    return lines + ("\n" if lines else "") + tomli_w.dumps(data)

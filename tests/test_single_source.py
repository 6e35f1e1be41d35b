"""Each default is written once: a case-file key, the constructor parameter it sets and a
command-line option that sets the same parameter do not each state it as a number.

For every pair (schema field, constructor parameter) and (command-line option,
constructor parameter) of :data:`SECTIONS` and :data:`OPTIONS`, matched by name or by the
declared renames, the default is read from the source (is it a number written out: a
literal, a tuple of literals, ``math.radians(171.0)``?) and from the objects (its value).
A pair states its default twice when

* both defaults are literals, or
* one is a literal and the other, of equal value, is not derived from that side (the
  schema or option default does not name the constructor, e.g. ``EHLOptions``, nor a
  module-level name built from it): the literal repeats a value written elsewhere, e.g. a
  typical value of :mod:`tribodyn.physics.typical`.

Every section of the schema modules is either mapped to its constructors or listed in
:data:`NO_CONSTRUCTOR`, so a new section is not silently left out of the check.
"""

from __future__ import annotations

import ast
import dataclasses
import functools
import inspect
import math
import textwrap
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import pytest
from pydantic import BaseModel

from tribodyn.cli.topography import topography_command
from tribodyn.config import schema, schema_surfaces, schema_valvetrain
from tribodyn.config.schema_fields import Section, _q
from tribodyn.contact.ehl.options import EHLOptions
from tribodyn.contact.ehl.thermal_field import ThermalOptions
from tribodyn.physics.lubricant import Lubricant
from tribodyn.physics.materials import Material
from tribodyn.physics.thermal_oil import ThermalLubricant
from tribodyn.physics.valvetrain_friction import BoreGeometry, GuideGeometry, JournalGeometry
from tribodyn.topography.analysis import analyse_surface
from tribodyn.topography.load_separation import synthetic_load_separation
from tribodyn.topography.synthetic import synthetic_surface
from tribodyn.valvetrain.cams import AccelerationCam, CircularArcCam
from tribodyn.valvetrain.camshaft import Camshaft
from tribodyn.valvetrain.dynamics import simulate_valvetrain
from tribodyn.valvetrain.fe import ModalBody
from tribodyn.valvetrain.flexible import TappetGeometry, ValveGeometry
from tribodyn.valvetrain.parameters import ValvetrainParameters
from tribodyn.valvetrain.spring import HelicalSpring
from tribodyn.valvetrain.tappet_rotation import TappetRotation

#: a rename: the parameter, or (parameter, the field's value in the parameter's unit)
Rename = str | tuple[str, Callable[[Any], Any]]


def _prefixed(prefix: str, names: tuple[str, ...]) -> dict[str, Rename]:
    return {prefix + n: n for n in names}


def _degrees(*names: str) -> dict[str, Rename]:
    """``<name>_deg`` [°] of a section sets ``<name>`` [rad]."""
    return {n + "_deg": (n, math.radians) for n in names}


#: (schema section, constructor or function it sets, {field: parameter} where names differ;
#: "-": the same name for another quantity, not compared)
SECTIONS: list[tuple[type[BaseModel], Callable, dict[str, Rename | list[Rename]]]] = [
    (schema.Numerics, EHLOptions, {}),
    (
        schema.Numerics,
        ThermalOptions,
        _prefixed("thermal_", ("x_nodes", "film_nodes", "solid_nodes"))
        | {"thermal_iterations": "step_iter", "thermal_tol": "tol", "tol": "-", "max_iter": "-"},
    ),
    (
        schema.Numerics,
        simulate_valvetrain,
        {
            "output_step_deg": "output_step",
            "max_step_deg": "max_step",
            "dynamics_rtol": "rtol",
            "dynamics_method": "method",
        },
    ),
    (schema.Engine, simulate_valvetrain, {"speed_rpm": "engine_speed"}),
    (
        schema.AuxiliaryFrictionConfig,
        BoreGeometry,
        _prefixed("bore_", ("guided_length", "clearance", "edge_offset", "friction_coefficient")),
    ),
    (
        schema.AuxiliaryFrictionConfig,
        GuideGeometry,
        _prefixed("guide_", ("length", "clearance", "friction_coefficient", "side_load"))
        | {"guide_stem_diameter": "stem_diameter"},
    ),
    (
        schema.AuxiliaryFrictionConfig,
        JournalGeometry,
        _prefixed("journal_", ("radius", "length", "clearance")),
    ),
    (schema.TappetRotationConfig, TappetRotation, {}),
    (schema_surfaces.LubricantConfig, Lubricant, {}),
    (
        schema_surfaces.LubricantConfig,
        ThermalLubricant,
        {
            "kinematic_viscosity_40_cst": "kinematic_viscosity_40",
            "kinematic_viscosity_100_cst": "kinematic_viscosity_100",
            "density_15": "density",
        },
    ),
    (schema_surfaces.MaterialConfig, Material, {}),
    (schema_surfaces.MeasuredSurfaceConfig, synthetic_load_separation, {}),
    (schema_surfaces.SurfaceSetConfig, EHLOptions, {}),
    (
        schema_valvetrain.AccelerationCamConfig,
        AccelerationCam,
        _degrees("event_angle", "ramp_angle", "nose_angle"),
    ),
    (schema_valvetrain.CircularArcCamConfig, CircularArcCam, _degrees("nose_angle")),
    (schema_valvetrain._BodyModes, ModalBody, {}),
    (schema_valvetrain.ValveConfig, ValveGeometry, {}),
    (schema_valvetrain.TappetConfig, TappetGeometry, {}),
    (schema_valvetrain.SpringConfig, HelicalSpring, {}),
    (schema_valvetrain.CamshaftConfig, Camshaft, {}),
    (schema_valvetrain.Valvetrain, ValvetrainParameters, {}),
]

#: sections whose keys set no constructor parameter of their own (or only other sections)
NO_CONSTRUCTOR = {
    "CaseInfo",  # names and text
    "LobeConfig",  # a lobe: changes of the case's own keys
    "RoughnessConfig",  # required keys, no defaults
    "StrengthConfig",  # absent keys: the material's typical strength, else not computed
    "StressConfig",  # switches of the study
    "TableCamConfig",  # file and units of a table
    "_CamBase",  # its keys are checked with each cam type above
    "Section",
}

#: (command, constructor or function it calls, {option: parameter} where names differ)
OPTIONS: list[tuple[Callable, Callable, dict[str, Rename | list[Rename]]]] = [
    (
        topography_command,
        synthetic_surface,
        {
            "grid": ("nb_grid_pts", lambda g: (g, g)),
            "pixel": "pixel_size",
            "cutoffs": [("short_cutoff", lambda c: c[0]), ("long_cutoff", lambda c: c[1])],
        },
    ),
    (
        topography_command,
        analyse_surface,
        {"min_defined": "min_defined_fraction", "filter_kind": "kind"},
    ),
]


# ----------------------------------------------------------------------------- reading
@functools.cache
def _tree(obj) -> ast.AST:
    return ast.parse(textwrap.dedent(inspect.getsource(obj)))


def _declaring(cls: type, name: str) -> type:
    """The class of ``cls``'s MRO that declares attribute ``name``."""
    return next(k for k in cls.__mro__ if name in k.__dict__.get("__annotations__", {}))


def _field_node(cls: type, name: str) -> ast.expr | None:
    """The default expression of class attribute ``name`` (dataclass field or schema
    field), from the class of the MRO that declares it."""
    for klass in cls.__mro__:
        if name not in klass.__dict__.get("__annotations__", {}):
            continue
        for node in ast.walk(_tree(klass)):
            if (
                isinstance(node, ast.AnnAssign)
                and isinstance(node.target, ast.Name)
                and node.target.id == name
            ):
                return _unwrap(node.value)
    return None


def _unwrap(node: ast.expr | None) -> ast.expr | None:
    """The default inside a field helper: ``_q(d, …)``, ``_lim(d, …)``, ``Field(d, …)``,
    ``typer.Option(d, …)`` (first argument), ``field(default=d)``."""
    if not isinstance(node, ast.Call):
        return node
    fn = node.func.attr if isinstance(node.func, ast.Attribute) else getattr(node.func, "id", "")
    if fn in ("_q", "_lim", "Field", "Option") and node.args:
        return node.args[0]
    if fn == "field":
        return next((k.value for k in node.keywords if k.arg == "default"), None)
    if fn == "_option":  # cli.contact: None (the case's value)
        return ast.Constant(None)
    return node


def _argument_node(fn: Callable, name: str) -> ast.expr | None:
    """The default expression of argument ``name`` of a function's source."""
    for node in ast.walk(_tree(fn)):
        if isinstance(node, ast.FunctionDef):
            a = node.args
            pos = a.posonlyargs + a.args
            pairs = list(zip(pos[len(pos) - len(a.defaults) :], a.defaults))
            pairs += [(k, d) for k, d in zip(a.kwonlyargs, a.kw_defaults) if d is not None]
            for arg, default in pairs:
                if arg.arg == name:
                    return _unwrap(default)
            return None
    return None


def default_node(obj, name: str) -> ast.expr | None:
    """Source expression of the default of ``name`` of a schema section, dataclass, class
    (its ``__init__``) or function."""
    if isinstance(obj, type) and (issubclass(obj, BaseModel) or dataclasses.is_dataclass(obj)):
        return _field_node(obj, name)
    return _argument_node(obj.__init__ if isinstance(obj, type) else obj, name)


def default_value(obj, name: str) -> Any:
    """The default of ``name`` (``inspect.Parameter.empty`` when required)."""
    if isinstance(obj, type) and issubclass(obj, BaseModel):
        d = obj.model_fields[name].default
        return inspect.Parameter.empty if d is ... else d
    d = inspect.signature(obj).parameters[name].default
    return getattr(d, "default", d)  # typer.Option → its default


def parameters(obj) -> list[str]:
    if isinstance(obj, type) and issubclass(obj, BaseModel):
        return list(obj.model_fields)
    return list(inspect.signature(obj).parameters)


_NUMBER_CALLS = ("radians", "deg2rad", "float", "int")


def is_literal(node: ast.expr | None) -> bool:
    """A number written out: a numeric constant (not a bool), its negation, arithmetic or
    a tuple of such, or one converted by ``math.radians``/``float``/``int``."""
    if isinstance(node, ast.Constant):
        return isinstance(node.value, (int, float)) and not isinstance(node.value, bool)
    if isinstance(node, ast.UnaryOp):
        return is_literal(node.operand)
    if isinstance(node, ast.BinOp):
        return is_literal(node.left) and is_literal(node.right)
    if isinstance(node, ast.Tuple):
        return bool(node.elts) and all(is_literal(e) for e in node.elts)
    if isinstance(node, ast.Call) and len(node.args) == 1 and not node.keywords:
        fn = (
            node.func.attr if isinstance(node.func, ast.Attribute) else getattr(node.func, "id", "")
        )
        return fn in _NUMBER_CALLS and is_literal(node.args[0])
    return False


def _module_names(obj) -> dict[str, ast.expr]:
    """Module-level assignments of the module that defines ``obj``."""
    tree = ast.parse(inspect.getsource(inspect.getmodule(obj)))
    out: dict[str, ast.expr] = {}
    for node in tree.body:
        if isinstance(node, ast.Assign) and node.value is not None:
            for t in node.targets:
                if isinstance(t, ast.Name):
                    out[t.id] = node.value
        elif isinstance(node, ast.AnnAssign) and isinstance(node.target, ast.Name) and node.value:
            out[node.target.id] = node.value
    return out


def _names(node: ast.expr) -> set[str]:
    return {n.id for n in ast.walk(node) if isinstance(n, ast.Name)} | {
        n.attr for n in ast.walk(node) if isinstance(n, ast.Attribute)
    }


def derives_from(obj, node: ast.expr | None, ctor) -> bool:
    """``node`` (a default in ``obj``'s module) names ``ctor`` (or a base class of it) or a
    module-level name of that module whose value names it
    (``_EHL_DEFAULTS = defaults_of(EHLOptions)``)."""
    if node is None:
        return False
    targets = {k.__name__ for k in ctor.__mro__[:-1]} if isinstance(ctor, type) else set()
    targets.add(ctor.__name__)
    names = _names(node)
    if targets & names:
        return True
    module = _module_names(obj)
    return any(targets & _names(module[n]) for n in names if n in module)


def _same(a, b) -> bool:
    if isinstance(a, tuple) and isinstance(b, tuple):
        return len(a) == len(b) and all(_same(x, y) for x, y in zip(a, b))
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        return not isinstance(a, bool) and not isinstance(b, bool) and math.isclose(a, b)
    return False


def _pairs(owner, ctor, renames) -> list[tuple[str, str, Callable[[Any], Any]]]:
    """(field, parameter, conversion) of each matched pair."""
    params = set(parameters(ctor))
    out = []
    for field in parameters(owner):
        targets = renames.get(field, field)
        for t in targets if isinstance(targets, list) else [targets]:
            param, convert = (t, lambda v: v) if isinstance(t, str) else t
            if param in params:
                out.append((field, param, convert))
    return out


def _where(obj, name: str) -> str:
    """Module, class (the one declaring a field) or function, and name."""
    if isinstance(obj, type) and (issubclass(obj, BaseModel) or dataclasses.is_dataclass(obj)):
        obj = _declaring(obj, name)
    return f"{obj.__module__}.{obj.__qualname__}.{name}"


def duplicates(mapping) -> list[str]:
    """The pairs of ``mapping`` whose default is written out on both sides (module text)."""
    found: dict[str, None] = {}  # once per pair of declarations (inherited fields)
    for owner, ctor, renames in mapping:
        for field, param, convert in _pairs(owner, ctor, renames):
            a_node, b_node = default_node(owner, field), default_node(ctor, param)
            a_lit, b_lit = is_literal(a_node), is_literal(b_node)
            if not (a_lit or b_lit):
                continue
            a, b = default_value(owner, field), default_value(ctor, param)
            if a is inspect.Parameter.empty or b is inspect.Parameter.empty:
                continue
            same = _same(convert(a), b) if not isinstance(a, bool) else False
            twice = (a_lit and b_lit) or (same and (a_lit or not derives_from(owner, a_node, ctor)))
            if twice:
                found[f"{_where(owner, field)} = {a!r} and {_where(ctor, param)} = {b!r}"] = None
    return list(found)


# ----------------------------------------------------------------------------- tests
def test_each_schema_default_is_written_once():
    found = duplicates(SECTIONS)
    assert not found, f"{len(found)} defaults written in two places:\n" + "\n".join(found)


def test_each_option_default_is_written_once():
    found = duplicates(OPTIONS)
    assert not found, f"{len(found)} defaults written in two places:\n" + "\n".join(found)


def test_every_section_is_mapped_or_has_no_constructor():
    mapped = {s.__name__ for s, _, _ in SECTIONS}
    sections = {
        name
        for module in (schema, schema_surfaces, schema_valvetrain)
        for name, obj in vars(module).items()
        if isinstance(obj, type) and issubclass(obj, Section) and obj.__module__ == module.__name__
    }
    assert sections - mapped - NO_CONSTRUCTOR == set()


@pytest.mark.parametrize("mapping", [SECTIONS, OPTIONS], ids=["sections", "options"])
def test_declared_renames_name_real_keys(mapping):
    """A rename names a key of its section (or option) and a parameter of its constructor
    ("-": the names agree but mean different things, so the pair is not compared)."""
    stale = []
    for owner, ctor, renames in mapping:
        params, fields = set(parameters(ctor)), set(parameters(owner))
        for field, targets in renames.items():
            for t in targets if isinstance(targets, list) else [targets]:
                param = t if isinstance(t, str) else t[0]
                if field not in fields or (param != "-" and param not in params):
                    stale.append(f"{owner.__name__}.{field} → {ctor.__name__}.{param}")
    assert not stale


# ----------------------------------------------------------------------------- probes
@dataclass(frozen=True)
class _ProbeOptions:
    step: float = 0.5
    angle: float = math.radians(30.0)


class _ProbeTwice(Section):
    step: float = _q(0.5, "", "written again")
    angle_deg: float = _q(30.0, "°", "written again, in other units")


_PROBE_DEFAULTS = {f.name: f.default for f in dataclasses.fields(_ProbeOptions)}


class _ProbeDerived(Section):
    step: float = _q(_PROBE_DEFAULTS["step"], "", "taken from the options")
    angle_deg: float = _q(math.degrees(_ProbeOptions.angle), "°", "converted")


class _ProbeConstant(Section):
    step: float = _q(EHLOptions().inlet_truncation * 100.0, "", "another object's value")


def test_the_check_sees_a_default_written_twice():
    """The check is able to fail: literal on both sides (also in other units), and a
    literal that repeats a value taken elsewhere; a default taken from the constructor
    passes."""
    renames = {"angle_deg": ("angle", math.radians)}
    assert len(duplicates([(_ProbeTwice, _ProbeOptions, renames)])) == 2
    assert duplicates([(_ProbeDerived, _ProbeOptions, renames)]) == []
    assert len(duplicates([(_ProbeConstant, _ProbeOptions, {})])) == 1


def test_the_workers_range_is_one_limit(tmp_path):
    """``numerics.workers`` and ``-j/--workers`` of run and engine: one range
    (:data:`tribodyn.physics.limits.WORKERS`), not restated in the commands."""
    from pathlib import Path

    from typer.testing import CliRunner

    import tribodyn
    from tribodyn.cli import app
    from tribodyn.config.schema import Numerics
    from tribodyn.config.schema_fields import field_bounds
    from tribodyn.physics.limits import WORKERS

    assert field_bounds(Numerics.model_fields["workers"]) == WORKERS.constraints()
    for command in (["run"], ["engine", "engine_dohc16"]):
        r = CliRunner().invoke(app, [*command, "-j", "5000", "-o", str(tmp_path / "out")])
        assert r.exit_code == 2
        assert f"-j/--workers must be an integer {WORKERS.describe()} (got 5000)" in r.output
    cli = Path(tribodyn.__file__).parent / "cli"
    assert not [p.name for p in cli.glob("*.py") if "4096" in p.read_text(encoding="utf-8")]

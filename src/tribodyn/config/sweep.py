"""Sweep files: a base case, fixed changes and axes over any case key (TOML, validated).

A sweep file names a base case (a bundled name or a case file), optional ``[fixed]``
changes applied to every point, and ``[[axes]]`` over dotted case key paths
(:mod:`tribodyn.config.paths`) given as lists or linear/logarithmic ranges. Axes are
crossed (full factorial, ``combine = "product"``) or zipped (``combine = "zip"``, or the
axes sharing a ``group``). ``docs/sweep-files.md`` documents every key.

Everything that can be checked before a run is checked here, with the key named as for
case files (:mod:`tribodyn.config.errors`): unknown keys, paths that do not exist in the
base case, values of the wrong type, and every axis value out of range (each value is
applied alone to the base case and the case validated). A *combination* of values that
is invalid only together becomes a failed point of the plan (:meth:`SweepSpec.points`),
recorded with its error, and does not stop the other points.
"""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Annotated, Any, ClassVar, Literal, Union

import numpy as np
from pydantic import (
    Field,
    StrictBool,
    StrictFloat,
    StrictInt,
    StrictStr,
    ValidationError,
    model_validator,
)

from .._typing import PathLike
from .._validation import InputError
from ..physics.limits import Limit
from .case import Case, bundled_cases, load_case, to_toml
from .errors import Problems, format_validation_error, problem_text, problems_message
from .paths import Key, PathError, parse_path, schema_field, set_path, strip_optional
from .schema import CAM_MODELS, Section, _q
from .schema_fields import field_bounds, field_extra
from .tomlfile import TomlFile, check_nesting, file_or_bundled, is_bundled_name

__all__ = [
    "SweepInfo",
    "AxisConfig",
    "SweepFile",
    "Axis",
    "SweepPoint",
    "SweepSpec",
    "load_sweep",
    "bundled_sweeps",
    "SWEEPS_DIR",
    "MAX_POINTS",
    "MAX_VALIDATED_VALUES",
    "RESERVED_NAMES",
]

#: Folder of the bundled sweep files.
SWEEPS_DIR = Path(__file__).resolve().parent.parent / "sweeps"
#: Largest number of points a sweep may have.
MAX_POINTS = 1_000_000
#: Axes with more values than this have only this many (spread over the axis, plus any
#: value outside the key's bounds) validated with the base case; every value is still
#: compared with the key's range (a value invalid only with the rest of the case then
#: becomes a failed point, like an invalid combination).
MAX_VALIDATED_VALUES = 200
#: Invalid values of one axis listed in the error (the rest are counted).
MAX_REPORTED_VALUES = 10
#: Dimension and variable names of the sweep Dataset an axis may not take.
RESERVED_NAMES = ("surface_set", "crank_angle", "ehl_crank", "point", "status", "error", "warnings")
_DIM_PATTERN = r"^[A-Za-z][A-Za-z0-9_]*$"

Scalar = Union[StrictBool, StrictInt, StrictFloat, StrictStr]  # noqa: UP007


class SweepInfo(Section):
    """``[sweep]``: what to run and what to keep."""

    name: str = _q(
        "sweep",
        "",
        "short name (reports, file names)",
        min_length=1,
        max_length=64,
        pattern=r"^[A-Za-z0-9][A-Za-z0-9_.+\-]*$",
    )
    description: str = _q("", "", "free text")
    case: str = _q(
        "andreou2023",
        "",
        "base case: a bundled case name or a case file (relative to the sweep file)",
        min_length=1,
    )
    mode: Literal["study", "dynamics", "engine"] = _q(
        "study",
        "",
        "per point: the full cam-cycle study, the valvetrain dynamics alone, or the whole "
        "engine's valvetrain (a case with [engine] cylinders)",
    )
    combine: Literal["product", "zip"] = _q(
        "product", "", "axes crossed (full factorial) or zipped (equal lengths)"
    )
    traces: bool = _q(
        False, "", "keep the cycle traces of every point (not only the summary scalars)"
    )


class AxisConfig(Section):
    """``[[axes]]``: one swept case key, by list or by range."""

    path: str = _q(
        ...,
        "",
        "dotted case key path, e.g. engine.speed_rpm or "
        "surface_sets[name=wcc_4um].coating_thickness",
        min_length=1,
    )
    name: str | None = _q(
        None,
        "",
        "dimension name in the results (default: the last key of the path)",
        max_length=64,
        pattern=_DIM_PATTERN,
    )
    values: list[Scalar] | None = _q(
        None, "", "the values (numbers, strings or booleans)", min_length=1
    )
    start: StrictInt | StrictFloat | None = _q(
        None, "", "first value of a range (in the key's unit)"
    )
    stop: StrictInt | StrictFloat | None = _q(None, "", "last value of a range (included)")
    num: StrictInt | None = _q(None, "", "number of values of a range", ge=2, le=MAX_POINTS)
    step: StrictInt | StrictFloat | None = _q(
        None, "", "step of a linear range (in the key's unit)", gt=0
    )
    spacing: Literal["linear", "log"] = _q("linear", "", "spacing of a range with num")
    group: str | None = _q(
        None,
        "",
        "axes with the same group are zipped into one dimension of that name",
        max_length=64,
        pattern=_DIM_PATTERN,
    )

    @model_validator(mode="before")
    @classmethod
    def _single_values(cls, data):
        """An array or table as an axis value: one line naming the axis key (not one per
        type the value fails to be)."""
        if not isinstance(data, dict):
            return data
        vals = data.get("values")
        items = [(f"values[{j}]", v) for j, v in enumerate(vals)] if isinstance(vals, list) else []
        items += [(k, data[k]) for k in ("start", "stop", "step", "num") if k in data]
        for where, v in items:
            if isinstance(v, (list, tuple, dict)):
                what = "a table" if isinstance(v, dict) else "an array"
                text = f"axis {data.get('path', '?')}: each value is one number, string or boolean"
                raise Problems(
                    [(where, f"{text} (got {what}); an axis sweeps one key over single values")]
                )
        return data

    @model_validator(mode="after")
    def _one_form(self):
        rng = [k for k in ("start", "stop", "num", "step") if getattr(self, k) is not None]
        if self.values is not None:
            if rng:
                raise Problems(
                    [(rng[0], "give either values or a range (start, stop, num or step), not both")]
                )
            kinds = {_kind(v) for v in self.values}
            if len(kinds) > 1:
                raise Problems(
                    [
                        (
                            "values",
                            "must all be numbers, all strings or all "
                            f"booleans (got {', '.join(sorted(kinds))})",
                        )
                    ]
                )
            return self
        if not rng:
            raise Problems([("", "give values = [...] or a range: start, stop and num (or step)")])
        start, stop = self.start, self.stop
        if start is None or stop is None:
            k = "start" if start is None else "stop"
            raise Problems([(k, "required key is missing (a range needs start and stop)")])
        if (self.num is None) == (self.step is None):
            raise Problems([("num", "give exactly one of num and step")])
        if self.step is not None and self.spacing == "log":
            raise Problems([("step", "a log range is given by num, not step")])
        if self.spacing == "log" and not (start > 0 and stop > 0):
            raise Problems([("start", "a log range needs start > 0 and stop > 0")])
        if self.step is not None:
            n = self._step_count()
            if n > MAX_POINTS:
                raise Problems([("step", f"gives {n} values (at most {MAX_POINTS})")])
        return self

    def _step_count(self) -> int:
        """Values of a range by step: start, start ± step, … up to stop (round-off kept)."""
        assert self.start is not None and self.stop is not None and self.step is not None
        return math.floor(abs(self.stop - self.start) / self.step * (1 + 1e-12)) + 1

    def generated(self) -> list:
        """The axis values (a range evaluated; integers stay integers when exact)."""
        if self.values is not None:
            return list(self.values)
        a, b = self.start, self.stop
        assert a is not None and b is not None  # a range has both ends (validated)
        vals: list
        if self.step is not None:
            d = self.step if b >= a else -self.step
            vals = [a + i * d for i in range(self._step_count())]
        elif self.spacing == "log":
            assert self.num is not None
            la, lb = math.log(a), math.log(b)
            vals = [math.exp(la + (lb - la) * i / (self.num - 1)) for i in range(self.num)]
            vals[0], vals[-1] = a, b
        else:
            assert self.num is not None
            vals = [a + (b - a) * i / (self.num - 1) for i in range(self.num)]
        ints = all(isinstance(v, int) for v in (a, b, self.step) if v is not None)
        if ints and self.spacing == "linear":
            vals = [int(round(v)) if abs(v - round(v)) < 1e-9 else v for v in vals]
        return [float(f"{v:.15g}") if isinstance(v, float) else v for v in vals]


class SweepFile(Section):
    """The whole sweep file."""

    sweep: SweepInfo = Field(default_factory=SweepInfo)
    fixed: dict[Annotated[str, Field(min_length=1)], Any] = _q(
        {}, "", "dotted case key path → value, applied to the base case at every point"
    )
    axes: list[AxisConfig] = Field(..., min_length=1)


def _kind(v) -> str:
    if isinstance(v, bool):
        return "booleans"
    if isinstance(v, (int, float)):
        return "numbers"
    return "strings"


# ----------------------------------------------------------------------------- spec
@dataclass(frozen=True)
class Axis:
    """A validated axis: its case key path, dimension name, values, unit and dimension."""

    path: str
    name: str
    values: tuple
    unit: str
    description: str
    dim: str  #: the dimension it spans (its name, or its group)


@dataclass
class SweepPoint:
    """One point of the plan: its position, axis values, changes and case (or error)."""

    index: int  #: position in the plan (C order over the dimensions)
    position: tuple  #: index along each dimension
    values: dict  #: axis name → value
    changes: dict  #: case key path → value
    case: Case | None = None  #: None if the combination is invalid
    error: str | None = None  #: why the combination is invalid
    key: str = ""  #: identity of the point (hash of case, mode and traces)

    @property
    def label(self) -> str:
        return ", ".join(f"{k} = {_fmt(v)}" for k, v in self.values.items())


def _fmt(v) -> str:
    return f"{v:.6g}" if isinstance(v, float) else str(v)


@dataclass
class SweepSpec(TomlFile):
    """A validated sweep: base case (with the fixed changes), axes and dimensions."""

    toml_kind: ClassVar[str] = "sweep"

    config: SweepFile
    base: Case
    axes: list[Axis]
    dims: list[tuple[str, list[Axis]]] = field(default_factory=list)
    source: Path | None = None
    base_source: str = ""

    @property
    def name(self) -> str:
        return self.config.sweep.name

    @property
    def mode(self) -> str:
        return self.config.sweep.mode

    @property
    def traces(self) -> bool:
        return self.config.sweep.traces

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(len(axes[0].values) for _, axes in self.dims)

    @property
    def n_points(self) -> int:
        return math.prod(self.shape)

    def to_toml(self) -> str:
        """The sweep as validated (base case path absolute), as TOML."""
        d = self.config.model_dump(mode="python", exclude_none=True)
        d["sweep"]["case"] = self.base_source
        if not d["fixed"]:
            d.pop("fixed")
        return to_toml(d, header=[f"tribodyn sweep {self.name!r}"])

    def points(self) -> list[SweepPoint]:
        """The plan: every combination, in C order over :attr:`dims`, each with its case
        validated (an invalid combination keeps its error and no case)."""
        return [self.point(i) for i in range(self.n_points)]

    def point(self, index: int) -> SweepPoint:
        """Point ``index`` of the plan (C order over :attr:`dims`), built alone: its case
        validated, or its error if the combination is invalid."""
        from .. import __version__

        n = self.n_points
        if not 0 <= index < n:
            raise InputError(f"point index must be in [0, {n - 1}] (got {index})")
        pos = tuple(int(j) for j in np.unravel_index(index, self.shape))
        values, changes = {}, {}
        for (_, axes), j in zip(self.dims, pos):
            for a in axes:
                values[a.name] = a.values[j]
                changes[a.path] = a.values[j]
        p = SweepPoint(index=index, position=pos, values=values, changes=changes)
        try:
            p.case = self.base.updated(changes)
        except InputError as exc:
            p.error = f"invalid combination: {problem_text(exc)}"
        ident = (
            p.case.to_toml(resolve_paths=True)
            if p.case is not None
            else repr(sorted(changes.items()))
        )
        h = hashlib.sha256(
            f"{ident}\n{self.mode}\n{self.traces}\n{__version__}".encode()
        ).hexdigest()
        p.key = h[:16]
        return p

    @classmethod
    def from_dict(cls, data: dict, *, base_dir=None, source=None) -> SweepSpec:
        """Validate a (TOML-shaped) dict; the base case and relative paths resolve against
        ``base_dir`` (default: the current folder)."""
        base_dir = Path(base_dir) if base_dir is not None else Path.cwd()
        if not isinstance(data, dict):
            raise InputError(f"a sweep must be a table (got {type(data).__name__})")
        check_nesting(data, source)
        try:
            cfg = SweepFile.model_validate(data)
        except ValidationError as exc:
            raise InputError(
                format_validation_error(exc, SweepFile, source, what="sweep")
            ) from None
        problems: list[tuple[str, str]] = []
        base, base_source = _load_base(cfg.sweep.case, base_dir, problems)
        if base is not None:
            base = _apply_fixed(base, cfg.fixed, problems)
        if base is None:
            raise InputError(problems_message(problems, source, "sweep"))
        if cfg.sweep.mode == "engine" and base.engine.cylinders is None:
            problems.append(
                (
                    "sweep.mode",
                    f'"engine" needs a base case with [engine] cylinders ({base.name!r} '
                    "describes one valve; see the guide: My engine's valvetrain friction)",
                )
            )
        axes = [
            a
            for a in (_axis(base, i, ax, problems) for i, ax in enumerate(cfg.axes))
            if a is not None
        ]
        dims = _dims(cfg, axes, problems)
        spec = cls(
            config=cfg, base=base, axes=axes, dims=dims, source=source, base_source=base_source
        )
        if not problems and spec.n_points > MAX_POINTS:
            problems.append(("axes", f"{spec.n_points} points (at most {MAX_POINTS})"))
        if problems:
            raise InputError(problems_message(problems, source, "sweep"))
        return spec


def _load_base(name: str, base_dir: Path, problems):
    p = Path(name).expanduser()
    cand = p if p.is_absolute() else base_dir / p
    try:
        if cand.exists():
            case = load_case(cand)
            return case, str(cand.resolve())
        if is_bundled_name(p, bundled_cases()):
            return load_case(p.stem), p.stem
        problems.append(
            (
                "sweep.case",
                f"no case file {str(cand)!r} and no bundled case "
                f"{name!r} (bundled: {', '.join(bundled_cases())})",
            )
        )
    except InputError as exc:
        problems.append(("sweep.case", f"the base case is invalid: {problem_text(exc)}"))
    return None, ""


def _check_path(base: Case, path: str):
    """Schema field of a path, checked against the base case's keys and entries."""
    data = base.to_dict()
    fi = schema_field(Case, path, data, variants={"cam": CAM_MODELS})
    set_path(data, path, None)  # raises if a selector matches nothing
    return fi


def _apply_fixed(base: Case, fixed: dict, problems):
    changes = {}
    for path, value in fixed.items():
        where = f'fixed."{path}"'
        try:
            _check_path(base, path)
        except PathError as exc:
            problems.append((where, str(exc)))
            continue
        changes[path] = value
    if problems:
        return None
    try:
        return base.updated(changes)
    except InputError as exc:
        problems.append(("fixed", problem_text(exc)))
        return None


def _axis(base: Case, i: int, ax: AxisConfig, problems) -> Axis | None:
    where = f"axes[{i}]"
    try:
        fi = _check_path(base, ax.path)
    except PathError as exc:
        problems.append((f"{where}.path", str(exc)))
        return None
    values = ax.generated()
    if strip_optional(fi.annotation) is int:
        bad = [v for v in values if isinstance(v, float)]
        if bad:
            problems.append((f"{where}.values", f"{ax.path} takes integers (got {_fmt(bad[0])})"))
            return None
    found = 0
    checked = _values_to_check(fi, values)
    for j in checked:
        v = values[j]
        try:
            base.updated({ax.path: v})
        except InputError as exc:
            found += 1
            if found > MAX_REPORTED_VALUES:
                continue
            key = (
                f"{where}.values[{j}]"
                if ax.values is not None
                else f"{where} (range value {j + 1} of {len(values)})"
            )
            problems.append((key, f"{_fmt(v)}: {problem_text(exc)}"))
    if found > MAX_REPORTED_VALUES:
        problems.append((where, f"and {found - MAX_REPORTED_VALUES} more invalid values"))
    tail = parse_path(ax.path)[-1]
    assert isinstance(tail, Key)  # checked by _check_path: a path ends at a key
    name = ax.name or tail.name
    return Axis(
        path=ax.path,
        name=name,
        values=tuple(values),
        unit=field_extra(fi).get("unit", ""),
        description=fi.description or "",
        dim=ax.group or name,
    )


def _values_to_check(fi, values) -> list[int]:
    """Indices of the axis values validated with the base case: all of them up to
    :data:`MAX_VALIDATED_VALUES`; beyond, every value is compared with the key's bounds
    and the values outside them (up to ``MAX_REPORTED_VALUES + 1``) are validated
    together with ``MAX_VALIDATED_VALUES`` values spread evenly over the axis."""
    n = len(values)
    if n <= MAX_VALIDATED_VALUES:
        return list(range(n))
    spread = {round(k * (n - 1) / (MAX_VALIDATED_VALUES - 1)) for k in range(MAX_VALIDATED_VALUES)}
    given: dict[str, Any] = field_bounds(fi)  # gt, ge, lt, le
    bounds = Limit(**given)
    outside: list[int] = []
    for j, v in enumerate(values):
        if len(outside) > MAX_REPORTED_VALUES:
            break
        # a value that is not a number too: the case validation says what is wrong
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not bounds.contains(v):
            outside.append(j)
    return sorted(spread.union(outside))


def _dims(cfg: SweepFile, axes: list[Axis], problems) -> list[tuple[str, list[Axis]]]:
    if cfg.sweep.combine == "zip" and axes:
        dim = axes[0].name
        axes[:] = [Axis(**{**a.__dict__, "dim": dim}) for a in axes]
    seen: dict[str, int] = {}
    for i, a in enumerate(axes):
        if a.name in seen:
            problems.append(
                (
                    f"axes[{i}].name",
                    f"duplicate dimension name {a.name!r} (also "
                    f"axes[{seen[a.name]}]); give each axis a "
                    "distinct name",
                )
            )
        seen.setdefault(a.name, i)
        if a.name in RESERVED_NAMES or a.dim in RESERVED_NAMES:
            problems.append(
                (
                    f"axes[{i}].name",
                    f"{a.name!r} is reserved (reserved: {', '.join(RESERVED_NAMES)})",
                )
            )
    paths: dict[str, int] = {}
    for i, a in enumerate(axes):
        if a.path in paths:
            problems.append(
                (f"axes[{i}].path", f"{a.path!r} is swept twice (also axes[{paths[a.path]}])")
            )
        paths.setdefault(a.path, i)
    dims: dict[str, list[Axis]] = {}
    for a in axes:
        dims.setdefault(a.dim, []).append(a)
    for dim, group in dims.items():
        lengths = {len(a.values) for a in group}
        if len(lengths) > 1:
            detail = ", ".join(f"{a.name}: {len(a.values)}" for a in group)
            key = "sweep.combine" if cfg.sweep.combine == "zip" else f"axes.group {dim!r}"
            problems.append((key, f"zipped axes need the same number of values ({detail})"))
    return list(dims.items())


# ----------------------------------------------------------------------------- loading
def bundled_sweeps() -> dict[str, Path]:
    """Name → path of the sweep files shipped with tribodyn."""
    return {p.stem: p for p in sorted(SWEEPS_DIR.glob("*.toml"))}


def load_sweep(path: PathLike) -> SweepSpec:
    """Load and validate a sweep file (or a bundled sweep by name)."""
    return SweepSpec.from_toml(file_or_bundled(path, bundled_sweeps()))

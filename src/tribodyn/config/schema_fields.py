"""The base of every case-file section (:class:`Section`: strict, frozen, unknown keys
rejected) and its field helpers: each field records its unit, allowed range and a
one-line description (shared limits: :mod:`tribodyn.physics.limits`); a field that sets a
constructor's parameter takes its default from there (:func:`defaults_of`).

A value is range-checked once, where it enters: a field given to a physics constructor
that checks its :class:`~tribodyn.physics.limits.Limit` (:func:`_arg`) records the range
for the docs and messages only, and building the case (:func:`tribodyn.config.build.collect`)
files the constructor's error under the key; any other field is checked here (:func:`_lim`,
:func:`_q` with bounds).
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from dataclasses import replace
from typing import Any, NamedTuple

from pydantic import BaseModel, ConfigDict, Field

from ..physics import limits as L

_NAME_PATTERN = r"^[A-Za-z0-9][A-Za-z0-9_.+\-]*$"
_BOUNDS = ("gt", "ge", "lt", "le")


def _q(default: Any, unit: str, doc: str, **constraints) -> Any:
    """A field with its unit recorded (used in error messages and the docs)."""
    return Field(default, description=doc, json_schema_extra={"unit": unit}, **constraints)


def field_extra(fi: Any) -> dict[str, Any]:
    """What a field records beside its type (``unit``, ``range``, ``auto``); {} if none."""
    extra = getattr(fi, "json_schema_extra", None)
    return extra if isinstance(extra, dict) else {}


def field_bounds(fi: Any) -> dict[str, float]:
    """The allowed range of a field as ``{"gt": …, "le": …}``: the bounds the schema
    checks, else those of the constructor that checks it (:func:`_arg`); {} if none."""
    checked = {
        k: getattr(m, k) for m in fi.metadata for k in _BOUNDS if getattr(m, k, None) is not None
    }
    return checked or dict(field_extra(fi).get("range") or {})


def defaults_of(obj: Callable) -> dict[str, Any]:
    """The parameter defaults of a constructor (dataclass or class) or function, by name:
    written once there, taken by the schema fields that set those parameters."""
    params = inspect.signature(obj).parameters
    return {k: p.default for k, p in params.items() if p.default is not p.empty}


def _lim(default: Any, limit: L.Limit, doc: str) -> Any:
    """A field whose unit and range are a shared limit of :mod:`tribodyn.physics.limits`,
    checked here: no constructor of the build checks it."""
    return _arg(default, limit, doc, **limit.constraints())


def _arg(default: Any, limit: L.Limit, doc: str, **constraints) -> Any:
    """A field whose unit and range are a shared limit, given to a physics constructor
    that checks it (the range is recorded, not checked here)."""
    extra: dict[str, Any] = {"unit": limit.unit, "range": limit.constraints()}
    if limit.auto is not None:  # the value outside the range that means "automatic"
        extra["auto"] = limit.auto
    return Field(default, description=doc, json_schema_extra=extra, **constraints)


class Converted(NamedTuple):
    """A key in another unit or name than the constructor argument it sets: argument =
    key × ``scale`` + ``offset`` (mm²/s: scale 1e-6; °C: offset 273.15 K); its range is the
    argument's ``limit`` (checked by the constructor), recorded in the key's ``unit``."""

    argument: str
    limit: L.Limit
    unit: str
    scale: float = 1.0
    offset: float = 0.0

    def value(self, key_value: float) -> float:
        """The argument's value of the key's."""
        return key_value * self.scale + self.offset

    @property
    def key_limit(self) -> L.Limit:
        """The argument's limit in the key's unit (bounds to 12 significant digits)."""
        s, o = self.scale, self.offset
        to: dict[str, Any] = {
            k: float(f"{(v - o) / s:.12g}") for k, v in self.limit.constraints().items()
        }
        return replace(self.limit, unit=self.unit, **to)

    def renamed(self, exc: L.RangeError, key: str, given: float) -> L.RangeError:
        """``exc`` with the argument's item that came from the key's value ``given``
        named ``key`` (a case key or a command-line option), in the key's unit and with
        the value as given."""
        return L.RangeError(
            [
                (key, self.key_limit, given)
                if name == self.argument and _same(value, self.value(given))
                else (name, limit, value)
                for name, limit, value in exc.items
            ]
        )


def _same(a, b) -> bool:
    """a == b, NaN equal to NaN (a value given as NaN is refused by its range too)."""
    return a == b or (a != a and b != b)


class Section(BaseModel):
    """Base of all case sections: unknown keys rejected, no silent type coercion."""

    model_config = ConfigDict(
        extra="forbid", strict=True, frozen=True, allow_inf_nan=False, validate_default=False
    )

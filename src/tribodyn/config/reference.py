"""The case-file and sweep-file key reference, read from the pydantic schema.

:func:`key_reference` walks a schema model and lists every key a file may contain, with its
section, type, default, unit, allowed range and description, exactly as the case is
checked (by the schema, or by the physics constructor a key is given to). The documentation site renders these rows, so the reference cannot drift
from the code.
"""

from __future__ import annotations

import math
import types
import typing
from dataclasses import dataclass
from typing import Any, Literal

import annotated_types as at
from pydantic import BaseModel
from pydantic_core import PydanticUndefined

from .schema_fields import field_bounds, field_extra

__all__ = ["KeyRow", "key_reference"]


@dataclass(frozen=True)
class KeyRow:
    """One key of a TOML file: ``section`` (``""`` at top level), ``key``, and its rules."""

    section: str
    key: str
    type: str
    default: str
    unit: str
    allowed: str
    description: str


def _strip(tp: Any) -> Any:
    """The type without ``Annotated`` wrappers."""
    while typing.get_origin(tp) is typing.Annotated:
        tp = typing.get_args(tp)[0]
    return tp


def _is_union(tp: Any) -> bool:
    return typing.get_origin(tp) in (typing.Union, types.UnionType)


def _models_in(tp: Any) -> list[tuple[str | None, type[BaseModel]]]:
    """The section models inside a field type, with their discriminating tag if any."""
    found: list[tuple[str | None, type[BaseModel]]] = []
    if typing.get_origin(tp) is typing.Annotated:
        inner, *meta = typing.get_args(tp)
        tag = next((m.tag for m in meta if hasattr(m, "tag")), None)
        return [(tag or t, m) for t, m in _models_in(inner)]
    if isinstance(tp, type) and issubclass(tp, BaseModel):
        return [(None, tp)]
    if _is_union(tp):
        for a in typing.get_args(tp):
            found += _models_in(a)
    return found


def _type_name(tp: Any) -> str:
    tp = _strip(tp)
    origin = typing.get_origin(tp)
    if origin is Literal:
        return " | ".join(f'"{a}"' if isinstance(a, str) else str(a) for a in typing.get_args(tp))
    if _is_union(tp):
        args = [a for a in typing.get_args(tp) if a is not type(None)]
        name = " | ".join(_type_name(a) for a in args)
        return name + (" (optional)" if len(args) < len(typing.get_args(tp)) else "")
    if origin in (list, tuple):
        args = [a for a in typing.get_args(tp) if a is not Ellipsis]
        return "list of " + (_type_name(args[0]) if args else "values")
    if origin is dict:
        return "table"
    if isinstance(tp, type) and tp in _TYPE_NAMES:
        return _TYPE_NAMES[tp]
    return getattr(tp, "__name__", str(tp))


#: the TOML names of the scalar types
_TYPE_NAMES = {bool: "boolean", int: "integer", float: "number", str: "string"}


def _fmt(v: Any) -> str:
    if v is None:
        return "none"
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float):
        return "inf" if math.isinf(v) else f"{v:.6g}"
    if isinstance(v, str):
        return f'"{v}"'
    if isinstance(v, (list, tuple)):
        return "[" + ", ".join(_fmt(x) for x in v) + "]"
    return str(v)


def _allowed(info: Any) -> str:
    bounds = field_bounds(info)  # checked by the schema or by the constructor it sets
    ops = (("ge", "≥"), ("gt", ">"), ("le", "≤"), ("lt", "<"))
    parts = [f"{op} {_fmt(bounds[attr])}" for attr, op in ops if attr in bounds]
    for m in info.metadata:
        if isinstance(m, at.MinLen) and m.min_length:
            parts.append(f"length ≥ {m.min_length}")
        if isinstance(m, at.MaxLen):
            parts.append(f"length ≤ {m.max_length}")
        pattern = getattr(m, "pattern", None)
        if pattern:
            parts.append(f"matches `{pattern}`")
    auto = field_extra(info).get("auto")  # the value that means automatic (numerics.n: 0)
    return ", ".join(parts) if auto is None else f"{_fmt(auto)} (automatic) or " + ", ".join(parts)


def _default(info: Any) -> str:
    if info.is_required():
        return "required"
    if info.default_factory is not None:
        return "(table)"
    d = info.default
    if d is PydanticUndefined:
        return ""
    return _fmt(d)


def key_reference(model: type[BaseModel], section: str = "") -> list[KeyRow]:
    """Every key of ``model`` and of its nested sections, in schema order.

    Nested section models give their own rows under ``section.key``; a list of sections is
    written ``section.key[]`` (a TOML array of tables); a table of sections keyed by name
    ``section.key.<name>``; variants chosen by a discriminating key ``section.key (tag)``.
    """
    rows: list[KeyRow] = []
    nested: list[tuple[str, type[BaseModel]]] = []
    for name, info in model.model_fields.items():
        key = info.alias or name
        tp = _strip(info.annotation)
        where = f"{section}.{key}" if section else key
        origin = typing.get_origin(tp)
        if origin is list and _models_in(typing.get_args(tp)[0]):
            nested += [(f"{where}[]", m) for _, m in _models_in(typing.get_args(tp)[0])]
            continue
        if origin is dict and _models_in(typing.get_args(tp)[1]):
            nested += [(f"{where}.<name>", m) for _, m in _models_in(typing.get_args(tp)[1])]
            continue
        models = _models_in(info.annotation)
        if models:
            many = len(models) > 1
            nested += [(f"{where} ({tag})" if many and tag else where, m) for tag, m in models]
            continue
        rows.append(
            KeyRow(
                section=section,
                key=key,
                type=_type_name(info.annotation),
                default=_default(info),
                unit=str(field_extra(info).get("unit", "")),
                allowed=_allowed(info),
                description=(info.description or "").replace("\n", " "),
            )
        )
    for where, m in nested:
        rows += key_reference(m, where)
    return rows

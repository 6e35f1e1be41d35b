"""Readable messages for case-file problems.

Pydantic validation errors become one line per problem: the dotted key path as it appears
in the file (``surface_sets[2].coating_thickness``), the allowed range with its unit or the
allowed choices, and the value given. Cross-field problems found by model validators are
raised as :class:`Problems` with their own key paths.
"""

from __future__ import annotations

import re
from collections.abc import Mapping
from typing import Any, get_args, get_origin

from pydantic import BaseModel, ValidationError

from .._validation import InputError
from .paths import Key, did_you_mean, format_path, keyed_fields, strip_optional
from .schema_fields import field_bounds, field_extra

__all__ = [
    "Problems",
    "CaseKeyError",
    "format_validation_error",
    "in_file_order",
    "out_of_range",
    "problem_text",
    "problems_message",
    "validation_problems",
]


class Problems(ValueError):
    """Cross-field problems found by a model validator: (relative key path, message)."""

    def __init__(self, items: list[tuple[str, str]]):
        super().__init__("; ".join(f"{p}: {m}" if p else m for p, m in items))
        self.items = items


class CaseKeyError(InputError):
    """A problem of one case key (``numerics.n``), filed under that key."""

    def __init__(self, key: str, message: str):
        super().__init__(message)
        self.key = key


def range_text(bounds: Mapping[str, float], unit: str, auto: float | None = None) -> str:
    """'> 0 m and <= 0.01 m' of ``{"gt": 0, "le": 0.01}`` (crank or cam degrees: °);
    '0 (automatic) or >= 32 and <= 4096' with the value ``auto`` that means automatic."""
    u = f" {unit}" if unit and not unit.startswith("deg") else ("°" if unit else "")
    symbols = (("gt", ">"), ("ge", ">="), ("lt", "<"), ("le", "<="))
    text = " and ".join(f"{sym} {_num(bounds[k])}{u}" for k, sym in symbols if k in bounds)
    return text if auto is None else f"{_num(auto)} (automatic) or {text}"


def out_of_range(bounds: Mapping[str, float], unit: str, value, auto=None) -> str:
    """The message of a case key whose value is outside its range."""
    return f"must be {range_text(bounds, unit, auto)} (got {_given(value)})"


def _num(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    return f"{v:.6g}"


def _given(v) -> str:
    if isinstance(v, float):
        g = f"{v:.6g}"
        return g if any(c in g for c in ".eni") else g + ".0"
    if isinstance(v, int):  # bool too
        return _num(v)
    if isinstance(v, str):
        return repr(v)
    if isinstance(v, dict):
        return "a table"
    if isinstance(v, list):
        return "an array"
    return repr(v)


def _resolve_loc(root, loc, variants) -> tuple[str, Any, Any]:
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
            fi = keyed_fields(cur).get(item) if isinstance(item, str) else None
            path = f"{path}.{item}" if path else str(item)
            if fi is None:
                cur = None
            elif item in variants:
                # a tagged union: the next location item is the tag
                cur = None
                if i + 1 < len(items) and items[i + 1] in variants[item]:
                    cur = variants[item][items[i + 1]]
                    i += 1
            else:
                cur = strip_optional(fi.annotation)
        elif get_origin(cur) is list:
            path = f"{path}[{item}]"
            cur = get_args(cur)[0]
            fi = None
        elif get_origin(cur) is dict:
            path = f"{path}.{format_path([Key(str(item))])}"  # quoted unless bare
            cur = get_args(cur)[1]
            fi = None
        else:
            path = f"{path}.{item}" if path else str(item)
            fi = None
            cur = None
        i += 1
    return path, fi, owner


def _error_lines(err: Mapping[str, Any], root, variants) -> list[tuple[str, str]]:
    typ, loc, ctx = err["type"], err["loc"], err.get("ctx") or {}
    inp = err.get("input")
    if typ == "value_error" and isinstance(ctx.get("error"), Problems):
        prefix, _, _ = _resolve_loc(root, loc, variants)
        return [
            (f"{prefix}.{p}" if prefix and p else (prefix or p), m) for p, m in ctx["error"].items
        ]
    path, fi, owner = _resolve_loc(root, loc, variants)
    got = f" (got {_given(inp)})"
    if typ in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        if fi is not None and field_bounds(fi):
            return [(path, out_of_range(field_bounds(fi), field_extra(fi).get("unit", ""), inp))]
        return [(path, f"must be {err['msg']}{got}")]
    if typ == "extra_forbidden":
        allowed = list(keyed_fields(owner))
        more = did_you_mean(str(loc[-1]), allowed)
        where = ""
        for key, models in variants.items():
            if owner in models.values():
                tag = owner.model_fields["type"].annotation.__args__[0]
                where = f" for {key} type {tag!r}"
        return [(path, f"unknown key{where}{more} (allowed: {', '.join(allowed)})")]
    if typ == "missing":
        return [(path, "required key is missing")]
    if typ == "union_tag_invalid":
        return [
            (f"{path}.type", f"must be one of {ctx.get('expected_tags')} (got {ctx.get('tag')!r})")
        ]
    if typ == "list_type":
        item = get_args(strip_optional(fi.annotation)) if fi is not None else ()
        if item and not (isinstance(item[0], type) and issubclass(item[0], BaseModel)):
            return [(path, f"must be an array ([…]){got}")]
        return [(path, f"must be an array of tables ([[{path}]]){got}")]
    if typ == "too_short":
        return [
            (
                path,
                f"must have at least {ctx.get('min_length')} entr"
                f"{'y' if ctx.get('min_length') == 1 else 'ies'}",
            )
        ]
    if typ in ("float_type", "float_parsing"):
        u = field_extra(fi).get("unit", "")
        return [(path, f"must be a number{f' [{u}]' if u else ''}{got}")]
    if typ in _TYPE_MESSAGES:
        return [(path, f"{_TYPE_MESSAGES[typ].format_map(ctx)}{got}")]
    if typ == "value_error":
        return [(path, f"{ctx.get('error', err['msg'])}")]
    return [(path, f"{err['msg']}{got}")]


#: pydantic error types whose message is a text with the error's context values in
#: braces (then the value given)
_TYPE_MESSAGES = {
    "int_type": "must be an integer",
    "int_parsing": "must be an integer",
    "int_from_float": "must be an integer",
    "bool_type": "must be true or false",
    "string_type": "must be a string",
    "finite_number": "must be a finite number",
    "string_too_short": "must not be empty",
    "literal_error": "must be {expected}",
    "string_too_long": "must have at most {max_length} characters",
    "string_pattern_mismatch": "must start with a letter or digit and contain only letters, "
    "digits, '_', '.', '+', '-'",
    **dict.fromkeys(
        ("union_tag_not_found", "model_type", "model_attributes_type", "dict_type"),
        "must be a table",
    ),
}


def problem_text(exc: InputError) -> str:
    """The problem lines of a case error joined by "; " (without its "invalid case" head)."""
    lines = str(exc).splitlines()
    if lines and lines[0].startswith("invalid case"):
        lines = lines[1:]
    return "; ".join(ln.strip() for ln in lines if ln.strip())


def validation_problems(
    exc: ValidationError, root: type[BaseModel], variants: dict | None = None
) -> list[tuple[str, str]]:
    """(dotted key, problem) of each error of ``exc`` (arguments: :func:`format_validation_error`)."""
    return [
        line
        for err in exc.errors(include_url=False)
        for line in _error_lines(err, root, variants or {})
    ]


def in_file_order(root: type[BaseModel], problems: list[tuple[str, str]]) -> list[tuple[str, str]]:
    """``problems`` sorted by the section of their key in the order of ``root``'s
    sections (stable: within a section, as given)."""
    order = [fi.alias or k for k, fi in root.model_fields.items()]

    def rank(problem: tuple[str, str]) -> int:
        section = re.split(r"[.\[]", problem[0], maxsplit=1)[0]
        return order.index(section) if section in order else len(order)

    return sorted(problems, key=rank)


def format_validation_error(
    exc: ValidationError,
    root: type[BaseModel],
    source: object = None,
    *,
    what: str = "case",
    variants: dict | None = None,
    more: list[tuple[str, str]] | None = None,
) -> str:
    """Readable multi-line message: one ``dotted.key: problem (got value)`` per line.

    root : the model class validated; what : how the message names it ("case", "sweep");
    variants : {key: {tag: model}} of tagged unions (the ``[cam]`` types), so that keys
    inside a variant are checked against that variant's fields; more : further
    (key, problem) lines, placed by their section (first in it)."""
    lines = validation_problems(exc, root, variants)
    if more:
        lines = in_file_order(root, more + lines)
    return problems_message(lines, source, what)


def problems_message(problems: list[tuple[str, str]], source: object, what: str) -> str:
    """``invalid <what> <source>: <n> problems``, then one ``key: problem`` line each."""
    n = len(problems)
    where = f" {source}" if source is not None else ""
    head = f"invalid {what}{where}: {n} problem{'s' if n != 1 else ''}"
    return head + "".join(f"\n  {p or '(top level)'}: {m}" for p, m in problems)

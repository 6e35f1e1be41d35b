"""Dotted key paths into a case: ``engine.speed_rpm``, ``surface_sets[2].coating_thickness``,
``surface_sets[name=wcc_4um].coating_thickness``, ``surface_sets[*].roughness.rms``,
``materials.wcc.E``.

Grammar: segments separated by dots; a segment is a key (letters, digits, ``_``, ``-``, or
any text in double quotes) followed by any number of selectors:

* ``[i]`` — entry ``i`` of an array (counted from 0);
* ``[*]`` — every entry of an array (or every value of a table);
* ``[key=value]`` — every entry of an array of tables whose ``key`` equals ``value``
  (compared as text, so ``[name=wcc_4um]`` and ``[name="wcc_4um"]`` are the same).

A path with ``[*]`` or ``[key=value]`` can address several places; setting it sets them
all. :func:`set_path` works on the plain dict of a case (``Case.to_dict()``) and
:func:`schema_field` finds the pydantic field a path ends on (its unit, type and range),
so that unknown keys are rejected before a case is built.
"""

from __future__ import annotations

import difflib
import re
import types
from dataclasses import dataclass
from typing import Any, Union, get_args, get_origin

from pydantic import BaseModel

from .._validation import InputError

__all__ = [
    "PathError",
    "Key",
    "Index",
    "All",
    "Match",
    "parse_path",
    "format_path",
    "set_path",
    "find_paths",
    "schema_field",
    "FILE_KEYS",
]

#: Key paths of a case whose values name files (relative to the case file); a result
#: folder holds copies of them, so that its case.toml runs from anywhere.
FILE_KEYS = ("cam.path", "surface_sets[*].measured_surface.topography")


class PathError(InputError):
    """A key path that cannot be parsed or does not exist."""


@dataclass(frozen=True)
class Key:
    name: str


@dataclass(frozen=True)
class Index:
    index: int


@dataclass(frozen=True)
class All:
    pass


@dataclass(frozen=True)
class Match:
    field: str
    value: str


Token = Union[Key, Index, All, Match]  # noqa: UP007  (a runtime alias, kept explicit)

_BARE = r"[A-Za-z0-9_\-]+"
_QUOTED = r'"[^"]*"'
_KEY_RE = re.compile(rf"({_BARE}|{_QUOTED})")
_SEL_RE = re.compile(rf'\[\s*(?:(\d+)|(\*)|({_BARE})\s*=\s*({_QUOTED}|[^\]"]+?))\s*\]')


def parse_path(path: str) -> tuple[Token, ...]:
    """Tokens of a dotted key path; :class:`PathError` if it cannot be parsed."""
    if not isinstance(path, str) or not path.strip():
        raise PathError(f"empty key path (got {path!r})")
    s = path.strip()
    tokens: list[Token] = []
    i = 0
    while True:
        m = _KEY_RE.match(s, i)
        if not m:
            raise PathError(
                f"cannot parse key path {path!r} at character {i + 1}: expected "
                "a key (letters, digits, _ or -, or text in double quotes)"
            )
        key = m.group(1)
        tokens.append(Key(key[1:-1] if key.startswith('"') else key))
        i = m.end()
        while i < len(s) and s[i] == "[":
            m = _SEL_RE.match(s, i)
            if not m:
                raise PathError(
                    f"cannot parse key path {path!r} at character {i + 1}: a "
                    "selector is [index], [*] or [key=value]"
                )
            if m.group(1) is not None:
                tokens.append(Index(int(m.group(1))))
            elif m.group(2) is not None:
                tokens.append(All())
            else:
                v = m.group(4).strip()
                tokens.append(Match(m.group(3), v[1:-1] if v.startswith('"') else v))
            i = m.end()
        if i == len(s):
            return tuple(tokens)
        if s[i] != ".":
            raise PathError(
                f"cannot parse key path {path!r} at character {i + 1}: expected '.', '[' or the end"
            )
        i += 1


def format_path(tokens) -> str:
    """The text of a token sequence (inverse of :func:`parse_path`)."""
    out = ""
    for t in tokens:
        if isinstance(t, Key):
            k = t.name if re.fullmatch(_BARE, t.name) else f'"{t.name}"'
            out = f"{out}.{k}" if out else k
        elif isinstance(t, Index):
            out += f"[{t.index}]"
        elif isinstance(t, All):
            out += "[*]"
        else:
            out += f"[{t.field}={t.value}]"
    return out


def _select(cur, tok, where: str) -> list:
    """The children of ``cur`` selected by one selector token."""
    if isinstance(tok, Index):
        if not isinstance(cur, list):
            raise PathError(f"{where}: [{tok.index}] needs an array (this is a {_kind(cur)})")
        if not 0 <= tok.index < len(cur):
            raise PathError(
                f"{where}[{tok.index}]: index out of range (the array has "
                f"{len(cur)} entries, [0] to [{len(cur) - 1}])"
            )
        return [cur[tok.index]]
    if isinstance(tok, All):
        if isinstance(cur, list):
            return list(cur)
        if isinstance(cur, dict):
            return list(cur.values())
        raise PathError(f"{where}: [*] needs an array or a table (this is a {_kind(cur)})")
    if not isinstance(cur, list):
        raise PathError(
            f"{where}: [{tok.field}={tok.value}] needs an array of tables (this is a {_kind(cur)})"
        )
    hits = [
        e
        for e in cur
        if isinstance(e, dict) and tok.field in e and _text(e[tok.field]) == tok.value
    ]
    if not hits:
        have = [_text(e[tok.field]) for e in cur if isinstance(e, dict) and tok.field in e]
        more = did_you_mean(tok.value, have)
        raise PathError(
            f"{where}[{tok.field}={tok.value}]: no entry has {tok.field} = "
            f"{tok.value!r} ({tok.field}s: {', '.join(have) or 'none'}){more}"
        )
    return hits


def did_you_mean(word: str, choices) -> str:
    """``"; did you mean 'x'?"`` with the closest of ``choices`` to ``word`` (difflib), or
    "" if none is close."""
    hint = difflib.get_close_matches(word, list(choices), n=1)
    return f"; did you mean {hint[0]!r}?" if hint else ""


def _text(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    return str(v)


def _kind(v) -> str:
    kinds: dict[type, str] = {dict: "table", list: "array"}
    return kinds.get(type(v), type(v).__name__)


def _walk(data, tokens):
    """Containers holding the last token's key, for each place the path addresses
    (missing tables on the way created); ``tokens`` of :func:`parse_path`, which start
    with a key."""
    # group tokens into (key, selectors) segments
    segs: list[tuple[Key, list]] = []
    for t in tokens:
        if isinstance(t, Key):
            segs.append((t, []))
        else:
            segs[-1][1].append(t)
    if segs[-1][1]:
        raise PathError(f"{format_path(tokens)}: a key path must end on a key, not a selector")
    curs = [data]
    done: list[Token] = []
    for key, sels in segs[:-1]:
        nxt = []
        where = format_path(done + [key])
        for c in curs:
            if not isinstance(c, dict):
                raise PathError(f"{format_path(done)}: is a {_kind(c)}, it has no key {key.name!r}")
            if key.name not in c:
                if sels:
                    raise PathError(f"{where}: not in the case")
                c[key.name] = {}
            items = [c[key.name]]
            for s in sels:
                items = [x for it in items for x in _select(it, s, where)]
                where += format_path([s])
            nxt.extend(items)
        done += [key, *sels]
        curs = nxt
    last = segs[-1][0].name
    for c in curs:
        if not isinstance(c, dict):
            raise PathError(f"{format_path(done)}: is a {_kind(c)}, it has no key {last!r}")
    return curs, last


def set_path(data: dict, path: str | list, value: Any) -> int:
    """Set ``value`` at every place ``path`` addresses in the dict ``data`` (in place);
    missing tables on the way and a missing last key are created (validation of the case
    decides whether they are allowed). Returns the number of places set."""
    tokens = parse_path(path) if isinstance(path, str) else tuple(path)
    curs, last = _walk(data, tokens)
    for c in curs:
        c[last] = value
    return len(curs)


def find_paths(data: dict, path: str) -> list[tuple[str, Any]]:
    """``(address, value)`` of every place ``path`` addresses that holds a value, each
    address a path of its own (``[*]`` and ``[key=value]`` replaced by the index or key
    they select), e.g. ``surface_sets[*].measured_surface.topography`` →
    ``[("surface_sets[1].measured_surface.topography", "pair.x3p")]``. Places where a
    key is absent are skipped."""
    tokens = parse_path(path)
    if not isinstance(tokens[-1], Key):
        raise PathError(f"{format_path(tokens)}: a key path starts and ends with a key")
    out: list[tuple[str, Any]] = []

    def visit(cur, i: int, done: list) -> None:
        if i == len(tokens):
            out.append((format_path(done), cur))
            return
        t = tokens[i]
        if isinstance(t, Key):
            if isinstance(cur, dict) and t.name in cur:
                visit(cur[t.name], i + 1, [*done, t])
        elif isinstance(t, Index):
            if isinstance(cur, list) and 0 <= t.index < len(cur):
                visit(cur[t.index], i + 1, [*done, t])
        elif isinstance(t, All):
            if isinstance(cur, list):
                for j, x in enumerate(cur):
                    visit(x, i + 1, [*done, Index(j)])
            elif isinstance(cur, dict):
                for k, x in cur.items():
                    visit(x, i + 1, [*done, Key(k)])
        elif isinstance(cur, list):
            for j, x in enumerate(cur):
                if isinstance(x, dict) and t.field in x and _text(x[t.field]) == t.value:
                    visit(x, i + 1, [*done, Index(j)])

    visit(data, 0, [])
    return out


# ----------------------------------------------------------------------------- schema
def strip_optional(ann):
    """X of an ``Optional[X]`` or ``X | None`` annotation; any other annotation as is."""
    if get_origin(ann) in (Union, types.UnionType):
        args = [a for a in get_args(ann) if a is not type(None)]
        if len(args) == 1:
            return args[0]
    return ann


def keyed_fields(model) -> dict:
    """Fields of a model keyed as they appear in the file (alias if any)."""
    return {(fi.alias or name): fi for name, fi in model.model_fields.items()}


def schema_field(root, path: str, data: dict | None = None, variants: dict | None = None):
    """The pydantic ``FieldInfo`` a path ends on, checked key by key against the models.

    root : the model class of the whole file (``Case``); data : the file's dict, to pick
    the variant of a tagged union (the ``[cam]`` type) from its ``type`` key; variants :
    ``{key: {tag: model}}``. Raises :class:`PathError` naming the first unknown key with
    the allowed keys (and a close match)."""
    tokens = parse_path(path)
    variants = variants or {}
    cur: Any = root
    fi = None
    done: list[Token] = []
    node = data
    for t in tokens:
        if isinstance(t, Key):
            if isinstance(cur, type) and issubclass(cur, BaseModel):
                fields = keyed_fields(cur)
                if t.name not in fields:
                    more = did_you_mean(t.name, fields)
                    where = format_path(done + [t])
                    raise PathError(f"{where}: unknown key{more} (allowed: {', '.join(fields)})")
                fi = fields[t.name]
                if t.name in variants:
                    tag = None
                    if isinstance(node, dict) and isinstance(node.get(t.name), dict):
                        tag = node[t.name].get("type")
                    cur = variants[t.name].get(tag or next(iter(variants[t.name])))
                else:
                    cur = strip_optional(fi.annotation)
                node = node.get(t.name) if isinstance(node, dict) else None
            elif get_origin(cur) is dict:
                cur = get_args(cur)[1]
                fi = None
                node = node.get(t.name) if isinstance(node, dict) else None
            else:
                raise PathError(f"{format_path(done + [t])}: {format_path(done)} has no keys")
        else:
            origin = get_origin(cur)
            if origin is list:
                cur = get_args(cur)[0]
            elif origin is dict and isinstance(t, All):
                cur = get_args(cur)[1]
            else:
                raise PathError(f"{format_path(done + [t])}: {format_path(done)} is not an array")
            fi = None
            if isinstance(node, list) and node:
                node = node[t.index] if isinstance(t, Index) and t.index < len(node) else node[0]
            elif isinstance(node, dict) and node:
                node = next(iter(node.values()))
        done.append(t)
    if fi is None:
        raise PathError(f"{format_path(tokens)}: not a single key of the case")
    if isinstance(cur, type) and issubclass(cur, BaseModel):
        raise PathError(
            f"{format_path(tokens)}: is a table; give one of its keys "
            f"({', '.join(keyed_fields(cur))})"
        )
    return fi

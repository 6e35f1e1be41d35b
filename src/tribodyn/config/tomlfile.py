"""Reading case and sweep files: UTF-8 TOML text, bounded in size and nesting.

A leading UTF-8 byte-order mark (written by some Windows editors) is accepted. Only
regular files are read (not pipes or devices: :mod:`tribodyn._user_files`). Files
larger than :data:`MAX_BYTES` and values nested deeper than :data:`MAX_NESTING` levels
(arrays or tables inside each other) are refused with :class:`~tribodyn.InputError`:
no case or sweep key needs more than a few levels, and unbounded nesting would exhaust
the interpreter's recursion limit while parsing or validating.
"""

from __future__ import annotations

import tomllib
from collections.abc import Iterable, Mapping
from pathlib import Path
from typing import Any, ClassVar, NoReturn, Self

from .._user_files import read_user_text
from .._validation import InputError

__all__ = [
    "MAX_BYTES",
    "MAX_NESTING",
    "TomlFile",
    "check_nesting",
    "file_or_bundled",
    "is_bundled_name",
    "parse_toml",
    "read_toml_text",
]

#: Largest case or sweep file [bytes] (the bundled ones are a few kB).
MAX_BYTES = 10_000_000
#: Deepest nesting of arrays and tables in a case or sweep file.
MAX_NESTING = 32

_BOM = "\ufeff"


def is_bundled_name(path: Path, bundled: Mapping[str, Path]) -> bool:
    """``path`` is the bare name of a bundled file (no folder; no suffix, or ``.toml``)."""
    return path.stem in bundled and path.parent == Path(".") and path.suffix in ("", ".toml")


def file_or_bundled(path, bundled: Mapping[str, Path]) -> Path:
    """``path`` if it exists; else the bundled file it names (:func:`is_bundled_name`),
    such as ``"andreou2023"``; else ``path`` (reading it then says that it is missing)."""
    p = Path(path)
    if not p.exists() and is_bundled_name(p, bundled):
        return bundled[p.stem]
    return p


def read_toml_text(path, what: str) -> str:
    """The text of the ``what`` file (``"case"``, ``"sweep"``) at ``path``: a regular file
    of at most :data:`MAX_BYTES`, UTF-8, an optional byte-order mark removed
    (:mod:`tribodyn._user_files`)."""
    return read_user_text(
        path,
        f"{what} file",
        limit=MAX_BYTES,
        legacy=False,
        hint=f"a {what} file is a short TOML text (put large tables in separate files)",
    ).text


def _depth(data) -> int:
    """Deepest nesting of dicts and lists in ``data`` (iterative: no recursion)."""
    deepest = 0
    stack = [(data, 0)]
    while stack:
        value, d = stack.pop()
        children: Iterable[Any]
        if isinstance(value, dict):
            children = value.values()
        elif isinstance(value, list):
            children = value
        else:
            continue
        deepest = max(deepest, d + 1)
        if deepest > MAX_NESTING:
            return deepest
        stack.extend((c, d + 1) for c in children)
    return deepest


def parse_toml(text: str, source=None) -> dict:
    """TOML text → dict, with the syntax error, or a nesting too deep to parse, as
    :class:`~tribodyn.InputError` (``source`` names the file in the message); the nesting
    of what parses is checked by ``from_dict`` (:func:`check_nesting`)."""
    where = f"{source}: " if source is not None else ""
    if not isinstance(text, str):
        raise InputError(f"{where}TOML text must be a string (got {type(text).__name__})")
    if text.startswith(_BOM):
        text = text[1:]
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"{where}TOML syntax error: {exc}") from None
    except RecursionError:
        _too_deep(where)
    return data


def _too_deep(where: str) -> NoReturn:
    raise InputError(
        f"{where}arrays or tables are nested more than {MAX_NESTING} levels deep; "
        "no key takes such values"
    )


def check_nesting(data, source=None) -> None:
    """:class:`~tribodyn.InputError` if dicts and lists in ``data`` nest deeper than
    :data:`MAX_NESTING` (for data given as Python objects rather than TOML text)."""
    if _depth(data) > MAX_NESTING:
        _too_deep(f"{source}: " if source is not None else "")


class TomlFile:
    """Loading from TOML for a class with ``from_dict(data, *, base_dir, source)``: the
    :class:`~tribodyn.config.Case` (``toml_kind = "case"``) and the sweep spec."""

    toml_kind: ClassVar[str]

    @classmethod
    def from_dict(cls, data: dict, *, base_dir=None, source=None) -> Self:
        raise NotImplementedError

    @classmethod
    def from_toml_string(cls, text: str, *, base_dir=None, source=None) -> Self:
        """Parse and validate TOML text (see ``from_dict`` for ``base_dir``)."""
        data = parse_toml(text, source)
        return cls.from_dict(data, base_dir=base_dir, source=source)

    @classmethod
    def from_toml(cls, path) -> Self:
        """Read and validate a file; relative paths resolve against its folder."""
        p = Path(path)
        text = read_toml_text(p, cls.toml_kind)
        return cls.from_toml_string(text, base_dir=p.resolve().parent, source=p)

"""The result records of the topography analysis as dicts (JSON and TOML output)."""

from __future__ import annotations

from dataclasses import fields
from typing import Any

__all__ = ["record_dict"]


def record_dict(record: Any, *derived: str) -> dict:
    """The dataclass fields of ``record`` in their order, then its ``derived`` properties,
    then ``"units"``: a copy of the record's ``UNITS`` (name → unit, SI)."""
    out = {f.name: getattr(record, f.name) for f in fields(record)}
    out.update((name, getattr(record, name)) for name in derived)
    out["units"] = dict(record.UNITS)
    return out

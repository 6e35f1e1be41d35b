"""The base of every case-file section (:class:`Section`: strict, frozen, unknown keys
rejected) and its field helpers: each field records its unit, allowed range and a
one-line description (shared limits: :mod:`tribodyn.physics.limits`); a field that sets a
constructor's parameter takes its default from there (:func:`defaults_of`).
"""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import Any

from pydantic import BaseModel, ConfigDict, Field

from ..physics import limits as L

_NAME_PATTERN = r"^[A-Za-z0-9][A-Za-z0-9_.+\-]*$"


def _q(default: Any, unit: str, doc: str, **constraints) -> Any:
    """A field with its unit recorded (used in error messages and the docs)."""
    return Field(default, description=doc, json_schema_extra={"unit": unit}, **constraints)


def defaults_of(obj: Callable) -> dict[str, Any]:
    """The parameter defaults of a constructor (dataclass or class) or function, by name:
    written once there, taken by the schema fields that set those parameters."""
    params = inspect.signature(obj).parameters
    return {k: p.default for k, p in params.items() if p.default is not p.empty}


def _lim(default: Any, limit: L.Limit, doc: str) -> Any:
    """A field whose unit and range are a shared limit of :mod:`tribodyn.physics.limits`
    (the physics constructors check the same range)."""
    return _q(default, limit.unit, doc, **limit.constraints())


class Section(BaseModel):
    """Base of all case sections: unknown keys rejected, no silent type coercion."""

    model_config = ConfigDict(
        extra="forbid", strict=True, frozen=True, allow_inf_nan=False, validate_default=False
    )

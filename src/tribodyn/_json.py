"""Strict JSON for every file and stream tribodyn writes: non-finite numbers (NaN, ±inf,
which JSON does not have and strict parsers reject) become ``null``, numpy scalars and
arrays plain numbers and lists, and the encoder refuses anything else non-finite
(``allow_nan=False``), so no ``NaN`` or ``Infinity`` token reaches a summary."""

from __future__ import annotations

import json
import math
from typing import Any

import numpy as np

__all__ = ["finite_json", "dumps"]


def finite_json(obj: Any) -> Any:
    """``obj`` with every non-finite float replaced by None, numpy scalars and arrays as
    Python numbers and lists, tuples as lists (recursively; dict keys kept)."""
    if isinstance(obj, dict):
        return {k: finite_json(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [finite_json(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return finite_json(obj.tolist())
    if isinstance(obj, np.generic):
        obj = obj.item()
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    return obj


def dumps(obj: Any, **kw) -> str:
    """:func:`json.dumps` of :func:`finite_json` ``(obj)``, strict (``allow_nan=False``)."""
    return json.dumps(finite_json(obj), allow_nan=False, **kw)

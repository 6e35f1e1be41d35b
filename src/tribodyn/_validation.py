"""Argument checks shared by the physics objects and solvers.

Every check raises :class:`InputError` (a ``ValueError``) whose message names the
argument, the allowed range and the offending value, e.g.
``E must be a finite number > 0 [Pa] (got -2.1e+11)``.
"""

from __future__ import annotations

import math
from numbers import Real

import numpy as np

__all__ = [
    "InputError",
    "check_real",
    "check_int",
    "check_bool",
    "check_choice",
    "check_positive",
    "check_nonnegative",
    "check_range",
    "check_array",
]


class InputError(ValueError):
    """Invalid input: the message names the argument and the allowed range."""


def _fmt(value) -> str:
    try:
        return f"{float(value):.6g}"
    except (TypeError, ValueError):
        return repr(value)


def check_real(name: str, value, unit: str = "") -> float:
    """Return ``value`` as a finite float or raise naming ``name``."""
    u = f" [{unit}]" if unit else ""
    if isinstance(value, bool) or not isinstance(value, (Real, np.integer, np.floating)):
        raise InputError(f"{name} must be a finite real number{u} (got {value!r})")
    v = float(value)
    if not math.isfinite(v):
        raise InputError(f"{name} must be a finite real number{u} (got {_fmt(value)})")
    return v


def check_int(name: str, value) -> int:
    """Return ``value`` as an int; integral floats (4.0) are accepted, bools and
    non-integral or non-numeric values are not."""
    if isinstance(value, bool) or not isinstance(value, (Real, np.integer, np.floating)):
        raise InputError(f"{name} must be an integer (got {value!r})")
    v = float(value)
    if not math.isfinite(v) or v != math.floor(v):
        raise InputError(f"{name} must be an integer (got {_fmt(value)})")
    return int(v)


def check_bool(name: str, value) -> bool:
    """Return ``value`` if it is a bool (or numpy bool); strings such as "no" are not."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise InputError(f"{name} must be True or False (got {value!r})")


def check_choice(name: str, value, choices) -> str:
    """Return ``value`` if it is one of ``choices`` (strings)."""
    if not isinstance(value, str) or value not in choices:
        allowed = ", ".join(repr(c) for c in choices)
        raise InputError(f"{name} must be one of {allowed} (got {value!r})")
    return value


def check_positive(name: str, value, unit: str = "") -> float:
    """Finite and strictly positive."""
    v = check_real(name, value, unit)
    if v <= 0.0:
        u = f" [{unit}]" if unit else ""
        raise InputError(f"{name} must be a finite number > 0{u} (got {_fmt(value)})")
    return v


def check_nonnegative(name: str, value, unit: str = "") -> float:
    """Finite and >= 0."""
    v = check_real(name, value, unit)
    if v < 0.0:
        u = f" [{unit}]" if unit else ""
        raise InputError(f"{name} must be a finite number >= 0{u} (got {_fmt(value)})")
    return v


def check_range(
    name: str,
    value,
    lo: float,
    hi: float,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
    unit: str = "",
) -> float:
    """Finite and inside [lo, hi] (ends open as requested)."""
    v = check_real(name, value, unit)
    bad_lo = v <= lo if lo_open else v < lo
    bad_hi = v >= hi if hi_open else v > hi
    if bad_lo or bad_hi:
        lb = "(" if lo_open else "["
        hb = ")" if hi_open else "]"
        u = f" [{unit}]" if unit else ""
        raise InputError(f"{name} must lie in {lb}{lo:g}, {hi:g}{hb}{u} (got {_fmt(value)})")
    return v


def check_array(
    name: str, value, *, ndim: int | None = 1, min_size: int = 1, finite: bool = True
) -> np.ndarray:
    """Convert to a float array; reject NaN/inf, wrong rank or too few entries."""
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name} must be an array of real numbers ({exc})") from None
    if ndim is not None and a.ndim != ndim:
        raise InputError(f"{name} must be a {ndim}-d array (got shape {a.shape})")
    if a.size < min_size:
        raise InputError(f"{name} must have at least {min_size} entries (got {a.size})")
    if finite and not np.all(np.isfinite(a)):
        raise InputError(f"{name} must contain only finite numbers (found NaN or inf)")
    return a

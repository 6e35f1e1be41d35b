"""Argument checks shared by the physics objects and solvers.

Every check raises :class:`InputError` (a ``ValueError``) whose message names the
argument, the allowed range and the offending value, e.g.
``E must be a finite number > 0 [Pa] (got -2.1e+11)``.

Numbers are converted safely: bools, strings, complex numbers and other non-real objects
are rejected; Python ints beyond the float range (``10**400``), NaN and ±inf give the same
:class:`InputError` as any other value outside the range (never ``OverflowError``).
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
    "short_repr",
]


class InputError(ValueError):
    """Invalid input: the message names the argument and the allowed range."""


#: integers beyond the int64 range are rejected (no count, size or index reaches it)
_INT_LIMIT = 2**63


def _fmt(value) -> str:
    """The value for a message: 6 significant digits, also for ints beyond float range."""
    if isinstance(value, int) and not isinstance(value, bool) and abs(value) >= 10**300:
        exponent = int(math.log10(abs(value)))  # exact enough for a message
        return f"{'-' if value < 0 else ''}~1e+{exponent}"
    try:
        return f"{float(value):.6g}"
    except (TypeError, ValueError, OverflowError):
        r = repr(value)
        return r if len(r) <= 60 else r[:57] + "..."


def _to_float(value) -> float | None:
    """float(value), or None if it does not fit (OverflowError) or is not a number."""
    try:
        return float(value)
    except (TypeError, ValueError, OverflowError):
        return None


def _scalar(value):
    """A 0-d numpy array (``np.array(2.5)``, ``a.sum(keepdims…)``) as its numpy scalar;
    anything else as is."""
    if isinstance(value, np.ndarray) and value.ndim == 0:
        return value[()]
    return value


def check_real(name: str, value, unit: str = "") -> float:
    """Return ``value`` as a finite float or raise naming ``name`` (a 0-d array counts
    as its scalar)."""
    u = f" [{unit}]" if unit else ""
    value = _scalar(value)
    if isinstance(value, (bool, np.bool_)) or not isinstance(
        value, (Real, np.integer, np.floating)
    ):
        raise InputError(f"{name} must be a finite real number{u} (got {short_repr(value)})")
    v = _to_float(value)
    if v is None or not math.isfinite(v):
        raise InputError(f"{name} must be a finite real number{u} (got {_fmt(value)})")
    return v


def short_repr(value) -> str:
    """repr() for a message: at most 60 characters, safe for ints of any size."""
    if isinstance(value, int) and not isinstance(value, bool):
        return str(value) if abs(value) < 10**20 else _fmt(value)
    try:
        r = repr(value)
    except Exception:  # a repr that fails must not hide the input error
        r = f"<{type(value).__name__}>"
    return r if len(r) <= 60 else r[:57] + "..."


def check_int(name: str, value) -> int:
    """Return ``value`` as an int; integral floats (4.0) are accepted, bools and
    non-integral or non-numeric values are not (a 0-d array counts as its scalar)."""
    value = _scalar(value)
    if isinstance(value, (bool, np.bool_)) or not isinstance(
        value, (Real, np.integer, np.floating)
    ):
        raise InputError(f"{name} must be an integer (got {short_repr(value)})")
    if isinstance(value, (int, np.integer)):
        i = int(value)
    else:
        v = _to_float(value)
        if v is None or not math.isfinite(v) or v != math.floor(v):
            raise InputError(f"{name} must be an integer (got {_fmt(value)})")
        i = int(v)
    if abs(i) >= _INT_LIMIT:
        raise InputError(f"{name} must be an integer of magnitude below 2**63 (got {_fmt(i)})")
    return i


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
    """Convert to a float array; reject non-numbers (strings, bools, complex), NaN/inf,
    numbers beyond the float range, wrong rank or too few entries."""
    try:
        raw = np.asarray(value)
        if raw.dtype.kind in "bcUSV":
            raise TypeError(f"got {raw.dtype.name} values")
        a = np.asarray(raw, dtype=float)
    except (TypeError, ValueError, OverflowError) as exc:
        msg = str(exc) if len(str(exc)) <= 80 else type(exc).__name__
        raise InputError(f"{name} must be an array of real numbers ({msg})") from None
    if ndim is not None and a.ndim != ndim:
        raise InputError(f"{name} must be a {ndim}-d array (got shape {a.shape})")
    if a.size < min_size:
        raise InputError(f"{name} must have at least {min_size} entries (got {a.size})")
    if finite and not np.all(np.isfinite(a)):
        raise InputError(f"{name} must contain only finite numbers (found NaN or inf)")
    return a

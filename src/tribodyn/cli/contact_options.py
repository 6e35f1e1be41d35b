"""The option strings of ``tribodyn contact``: numbers separated by commas (the coating's
``E,NU,THICKNESS``) and the roughness (``SIGMA`` or ``ETA,SIGMA,BETA``), each error naming
its option."""

from __future__ import annotations

import math
import re

from .._validation import InputError

__all__ = ["three_numbers", "roughness_numbers", "prefixed"]


def _numbers(text: str, option: str, names: str, counts=(3,)) -> tuple[float, ...]:
    """The finite numbers of ``text`` (separated by commas, semicolons or spaces), as many
    as one of ``counts``; else an InputError naming ``option``."""
    parts = [p for p in re.split(r"[,;\s]+", text.strip()) if p]
    try:
        vals = tuple(float(p) for p in parts)
    except ValueError:
        vals = ()
    if len(vals) not in counts or not all(math.isfinite(v) for v in vals):
        raise InputError(f"{option}: expected {names} separated by commas (got {text!r})")
    return vals


def three_numbers(text: str, option: str, names: str) -> tuple[float, float, float]:
    """Three numbers of ``text`` (``names`` says which, in the error)."""
    a, b, c = _numbers(text, option, f"three numbers {names}")
    return a, b, c


def roughness_numbers(text: str, model: str) -> tuple[float, float, float]:
    """(η, σ, β) of ``--roughness``: ``ETA,SIGMA,BETA``, or ``SIGMA`` alone for the
    surface law, with η and β from σ by the typical ratios (as a case file's set that
    gives only ``rms``; :func:`~tribodyn.physics.typical.typical_summits`)."""
    from ..physics import limits, typical

    gt = model == "greenwood_tripp"
    names = "three numbers eta [1/m²], sigma [m], beta [m]"
    if gt:
        names += " (greenwood_tripp needs all three)"
    else:
        names = f"sigma [m] (the surface law's one input) or {names}"
    vals = _numbers(text, "--roughness", names, (3,) if gt else (1, 3))
    if len(vals) == 3:
        return vals[0], vals[1], vals[2]
    sig = prefixed("--roughness", lambda: limits.ROUGHNESS_RMS.check("sigma", vals[0]))
    eta, beta = typical.typical_summits(sig)
    return eta, sig, beta


def prefixed(option: str, build):
    """Run ``build()``; re-raise an InputError with the option name in front."""
    try:
        return build()
    except InputError as exc:
        msg = str(exc)
        raise InputError(msg if msg.startswith(option) else f"{option}: {msg}") from None

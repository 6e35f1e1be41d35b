"""The output conventions, stated once (docs/conventions.md, *Output conventions*): the
crank-angle ranges of a run and of an engine, the sign of a change against the
reference set, and the samples the figures show as the cam event. The summary, the netCDF attributes, the report and the console quote
these texts."""

from __future__ import annotations

import math

__all__ = ["CRANK_ANGLE", "ENGINE_CRANK_ANGLE", "CHANGE", "EVENT_FRACTION", "change_pct", "finite"]

#: Crank angle of a run (``tribodyn run``, sweeps in study mode).
CRANK_ANGLE = (
    "crank angle [°] from the start of the simulation (crank = 2 × cam angle); the "
    "presented cycle is the last one simulated: 720–1440° with the default two cycles "
    "(numerics.cycles)"
)

#: Crank angle of an engine (``tribodyn engine``).
ENGINE_CRANK_ANGLE = "crank angle [°] of cylinder 1 from its firing TDC, 0–720°"

#: A change against the reference set.
CHANGE = (
    "change against the reference set (reference_set): 100·(x/x_ref − 1) %, "
    "negative = less than the reference"
)


#: A sample belongs to the cam event (in the figures, static and interactive) where the
#: contact force exceeds this share of its maximum.
EVENT_FRACTION = 0.05


def finite(v) -> float | None:
    """A number of ``summary.json``: ``v`` as a float, None where unknown (None, NaN, ±inf)."""
    if v is None:
        return None
    v = float(v)
    return v if math.isfinite(v) else None


def change_pct(value, reference) -> float | None:
    """Change of ``value`` against the reference set's ``reference`` in %:
    100 (x/x_ref − 1), negative = less (:data:`CHANGE`). None where either is unknown
    or the reference is not positive."""
    if value is None or reference is None:
        return None
    v, r = float(value), float(reference)
    if not (math.isfinite(v) and math.isfinite(r) and r > 0.0):
        return None
    return 100.0 * (v / r - 1.0)

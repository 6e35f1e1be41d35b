"""The lubrication-regime map of the Greenwood chart (paper Fig. 12), computed with the
study so that the figure only draws it.

The chart's axes are log-spaced in g_E = W' U^(−1/2) and g_V = G W'^(3/2) U^(−1/2)
(:mod:`tribodyn.physics.regimes`). Each axis spans at least :data:`CHART_GE` /
:data:`CHART_GV` and reaches a factor :data:`CHART_MARGIN` beyond the study's operating
points (samples with finite, positive g_V and g_E), on :data:`CHART_POINTS` values.
The map holds the regime of every grid node as an index into ``REGIMES``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..physics.regimes import REGIMES, lubrication_regime

__all__ = ["RegimeMap", "regime_code", "regime_map", "CHART_GE", "CHART_GV", "CHART_POINTS"]

#: Least range of the chart's g_E axis [-].
CHART_GE = (1e-2, 1e2)
#: Least range of the chart's g_V axis [-].
CHART_GV = (1e-2, 1e4)
#: Factor by which the axes reach beyond the outermost operating points.
CHART_MARGIN = 3.0
#: Log-spaced grid values per axis.
CHART_POINTS = 600


@dataclass(frozen=True)
class RegimeMap:
    """``regime[i, j]``: index into ``REGIMES`` of the regime at (g_V = ``gV[i]``,
    g_E = ``gE[j]``); ``gE``, ``gV`` the chart's axes [-], increasing."""

    gE: np.ndarray
    gV: np.ndarray
    regime: np.ndarray


def regime_code(gV, gE) -> np.ndarray:
    """The regime of (g_V, g_E) as an index into ``REGIMES`` (int8 array)."""
    labels = np.asarray(lubrication_regime(gV, gE))
    code = np.full(labels.shape, -1, dtype=np.int8)
    for k, r in enumerate(REGIMES):
        code[labels == r] = k
    return code


def _axis(values: np.ndarray, least: tuple[float, float]) -> np.ndarray:
    """Log-spaced axis over ``least`` widened to ``values`` ÷/× :data:`CHART_MARGIN`."""
    lo, hi = least
    if values.size:
        lo = min(lo, float(np.min(values)) / CHART_MARGIN)
        hi = max(hi, float(np.max(values)) * CHART_MARGIN)
    return 10 ** np.linspace(np.log10(lo), np.log10(hi), CHART_POINTS)


def regime_map(gV, gE) -> RegimeMap:
    """The :class:`RegimeMap` around the operating points (g_V, g_E) of a study (NaN
    where the contact is unloaded)."""
    gV, gE = np.asarray(gV, dtype=float), np.asarray(gE, dtype=float)
    ok = np.isfinite(gV) & np.isfinite(gE) & (gV > 0) & (gE > 0)
    ge_axis, gv_axis = _axis(gE[ok], CHART_GE), _axis(gV[ok], CHART_GV)
    GE, GV = np.meshgrid(ge_axis, gv_axis)
    return RegimeMap(ge_axis, gv_axis, regime_code(GV, GE))

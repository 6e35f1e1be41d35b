"""Stress map of a surface set: the von Mises field over x and depth z of the body closest
to failure, at the EHL sample of its greatest risk, computed in the study so that the
report's stress figure only plots stored arrays.

The instant and the body are those of :func:`~tribodyn.workflow.stress_study.closest_failure`
(the smallest safety factor over both bodies and all modes); the sample is the one where
the governing peak's trace is largest. The surface loads of that sample are rebuilt from
its recorded pressure and film (:func:`tribodyn.contact.stress.profile_surface_loads`: the
set's friction laws) and the stresses evaluated on a depth grid from the surface to 2.5 b
(:func:`tribodyn.physics.stress.subsurface_stress`; b the loaded half-width of
:func:`~tribodyn.contact.stress.loaded_half_width`), with 12 levels inside a coating and
the interface on the grid. Only the band |x − x_peak| ≤ 2.5 b is kept.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..contact.stress import loaded_half_width, profile_surface_loads, shear_options
from ..physics.materials import as_bodies
from ..physics.stress import subsurface_stress

__all__ = ["StressMap", "stress_map", "MAP_HALF_WIDTHS", "MAP_DEPTHS"]

#: the map reaches this many loaded half-widths b in depth and to each side of the peak
MAP_HALF_WIDTHS = 2.5
#: evenly spaced depth levels of the map from the surface to MAP_HALF_WIDTHS·b
MAP_DEPTHS = 121
#: levels inside a coating (its surface and the interface included)
_COATING_LEVELS = 13


@dataclass(frozen=True)
class StressMap:
    """The von Mises field of ``body`` at EHL sample ``index`` (crank ``crank_deg``):
    ``von_mises`` [Pa] on (``depths``, ``x``) [m]; the governing ``mode`` with its
    ``safety_factor`` and its peak at (``peak_x``, ``peak_z``) [m];
    ``coating_thickness`` [m] of that body (None: uncoated)."""

    body: str
    mode: str
    safety_factor: float
    index: int
    crank_deg: float
    peak_x: float
    peak_z: float
    x: np.ndarray
    depths: np.ndarray
    von_mises: np.ndarray
    coating_thickness: float | None


def stress_map(worst, trace, result, inputs, bodies, lubricant, roughness, options) -> StressMap:
    """The :class:`StressMap` of a set's closest failure ``worst`` (a dict of
    :func:`~tribodyn.workflow.stress_study.closest_failure`; its mode's stress ``trace``
    along the cycle picks the sample), from the cycle EHL pass ``result`` with its
    CycleInputs ``inputs``; the set's ``bodies``, ``lubricant``, ``roughness`` and EHL
    ``options``."""
    body = worst["body"]
    i = int(np.nanargmax(trace))
    x = np.asarray(result.x, float)[i]
    loads = profile_surface_loads(
        x,
        np.asarray(result.pressure, float)[i],
        np.asarray(result.film, float)[i],
        float(np.asarray(inputs.sliding_speed, float)[i]),
        bodies,
        lubricant,
        roughness,
        **shear_options(options),
    )
    b = loaded_half_width(x, loads.pressure)
    bod = as_bodies(bodies)[0 if body == "cam" else 1]
    hc = bod.coating.thickness if bod.coating is not None else None
    z = np.linspace(0.0, MAP_HALF_WIDTHS * b, MAP_DEPTHS)
    if hc is not None:  # resolve the coating, the interface on the grid (its coating side)
        z = np.unique(np.concatenate([z, np.linspace(0.0, hc, _COATING_LEVELS), [hc * (1 + 1e-9)]]))
    q = loads.traction_cam if body == "cam" else loads.traction_tappet
    st = subsurface_stress(x, loads.pressure, q, bod, z)
    keep = np.abs(st.x - worst["x_m"]) / b <= MAP_HALF_WIDTHS
    return StressMap(
        body=body,
        mode=worst["mode"],
        safety_factor=worst["safety_factor"],
        index=i,
        crank_deg=worst["crank_deg"],
        peak_x=worst["x_m"],
        peak_z=worst["z_m"],
        x=np.asarray(st.x)[keep],
        depths=np.asarray(st.depths),
        von_mises=np.asarray(st.von_mises)[:, keep],
        coating_thickness=hc,
    )

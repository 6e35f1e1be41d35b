"""Surface loads and subsurface stresses of the cam and the tappet at an EHL solution.

Loads on each body (per unit area, x along the contact, u₁ the cam's and u₂ the tappet's
surface speed relative to the contact, u_s = u₁ − u₂; bodies = (cam, tappet)):

* normal: p + p_a, the film pressure plus the local Greenwood–Tripp asperity pressure
  p_a(h) = K F_5/2(h/σ) (paper Eq. 6, E' of the surface materials);
* viscous shear of the film (Newtonian velocity profile between the surfaces, the Couette
  part by the solution's law τ_c, Newtonian or Eyring, capped at the limiting shear
  stress, signed like u_s; paper Eq. 16 with the Poiseuille part ±(h/2) dp/dx)::

      q_cam    = −τ_c − (h/2) dp/dx        q_tappet = +τ_c − (h/2) dp/dx

  (the faster surface is held back, the slower one dragged along; the pressure gradient
  pushes the oil, and with it both surfaces, towards lower pressure);
* boundary shear τ_b = τ₀ A_a/A + ς p_a (Eqs. 17–18) opposing the sliding of each
  surface: −sgn(u_s) τ_b on the cam, +sgn(u_s) τ_b on the tappet.

Each body's stresses follow from :func:`tribodyn.physics.stress.subsurface_stress` with
z into that body; the x axis is common to both bodies, so a traction in +x is the same
physical direction on each.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._typing import ArrayLike
from .._validation import InputError, check_array, check_real
from ..physics.friction import boundary_shear_stress
from ..physics.materials import Body, as_bodies, reduced_modulus
from ..physics.stress import StressOperator, SubsurfaceStress
from .ehl.options import EHLOptions
from .ehl.postprocess import _H_FLOOR, shear_stress  # films floored as the solver does

__all__ = [
    "SurfaceLoads",
    "surface_loads",
    "profile_surface_loads",
    "default_depths",
    "ehl_stresses",
    "loaded_half_width",
    "loaded_ends",
    "shear_options",
]

#: the EHL options' defaults, which the surface-shear keywords default to
_DEFAULTS = EHLOptions()


@dataclass
class SurfaceLoads:
    """Loads on the cam and the tappet on a common x grid [m], per unit area [Pa]."""

    x: np.ndarray
    pressure: np.ndarray  #: p + p_a, the same on both bodies
    fluid_pressure: np.ndarray  #: p
    asperity_pressure: np.ndarray  #: p_a
    viscous_shear: np.ndarray  #: Couette τ_c, signed like u_s (traction +τ_c on the tappet)
    poiseuille_shear: np.ndarray  #: −(h/2) dp/dx, on both surfaces
    boundary_shear: np.ndarray  #: τ_b ≥ 0 (magnitude)
    traction_cam: np.ndarray  #: q on the cam in +x
    traction_tappet: np.ndarray  #: q on the tappet in +x


def shear_options(options: EHLOptions | None) -> dict:
    """The surface-shear keywords of :func:`profile_surface_loads` taken from an
    :class:`~tribodyn.EHLOptions` (None: the defaults)."""
    options = options or _DEFAULTS
    return {
        "viscous_model": options.viscous_model,
        "limiting_shear": options.limiting_shear,
        "boundary_shear_coefficient": options.boundary_shear_coefficient,
        "boundary_shear_strength": options.boundary_shear_strength,
    }


def profile_surface_loads(
    x: ArrayLike,
    pressure: ArrayLike,
    film: ArrayLike,
    sliding_speed: float,
    bodies,
    lubricant,
    roughness=None,
    *,
    viscous_model: str = _DEFAULTS.viscous_model,
    limiting_shear: bool = _DEFAULTS.limiting_shear,
    boundary_shear_coefficient: float = _DEFAULTS.boundary_shear_coefficient,
    boundary_shear_strength: float = _DEFAULTS.boundary_shear_strength,
) -> SurfaceLoads:
    """Surface loads from a film and pressure profile (see the module docstring).

    ``roughness`` None: no asperity contact (p_a = τ_b = 0). The shear laws default to
    those of :class:`~tribodyn.EHLOptions`."""
    x = check_array("x", x)
    p = check_array("pressure", pressure)
    h = check_array("film", film)
    if p.shape != x.shape or h.shape != x.shape:
        raise InputError(f"pressure and film must have the shape of x {x.shape}")
    us = check_real("sliding_speed", sliding_speed, "m/s")
    return _loads(
        x,
        p,
        h,
        us,
        bodies,
        lubricant,
        roughness,
        viscous_model=viscous_model,
        limiting_shear=limiting_shear,
        boundary_shear_coefficient=boundary_shear_coefficient,
        boundary_shear_strength=boundary_shear_strength,
    )


def batch_surface_loads(
    x: np.ndarray,
    pressure: np.ndarray,
    film: np.ndarray,
    sliding_speed: np.ndarray,
    bodies,
    lubricant,
    roughness=None,
    options: EHLOptions | None = None,
) -> SurfaceLoads:
    """:func:`profile_surface_loads` of many profiles at once (the fast path of a cycle):
    ``x``, ``pressure``, ``film`` (samples, k) on uniform rows, ``sliding_speed``
    (samples,); finite float arrays, unchecked. The friction laws are those of
    ``options`` (an :class:`~tribodyn.EHLOptions`, default the defaults). The fields are
    (samples, k)."""
    x = np.asarray(x, float)
    us = np.asarray(sliding_speed, float)[:, None]
    return _loads(
        x,
        np.asarray(pressure, float),
        np.asarray(film, float),
        us,
        bodies,
        lubricant,
        roughness,
        **shear_options(options),
    )


def _loads(
    x,
    p,
    h,
    us,
    bodies,
    lubricant,
    roughness,
    *,
    viscous_model,
    limiting_shear,
    boundary_shear_coefficient,
    boundary_shear_strength,
) -> SurfaceLoads:
    cam, tappet = as_bodies(bodies)
    hf = np.maximum(h, _H_FLOOR)
    tau_c = shear_stress(p, h, us, lubricant, viscous_model, limiting_shear)
    if p.ndim == 1:
        dpdx = np.gradient(p, x)
    else:  # uniform rows
        dpdx = np.gradient(p, axis=-1) / (x[:, 1:2] - x[:, 0:1])
    pois = -0.5 * hf * dpdx
    if roughness is not None:
        e_s = reduced_modulus((cam, tappet), surface=True)
        if roughness.method == "exact" or roughness.law is not None:  # the solvers' path
            lam = h / roughness.rms
            pa = roughness.pressure_scale(e_s) * roughness.load_function(lam)[0]
        else:
            pa = np.asarray(roughness.asperity_pressure(h, e_s), float)
        area = np.asarray(roughness.contact_area_fraction(h, tabulated=True), float)
        tau_b = boundary_shear_stress(pa, area, boundary_shear_coefficient, boundary_shear_strength)
    else:
        pa = np.zeros_like(p)
        tau_b = np.zeros_like(p)
    sgn = np.sign(us)
    return SurfaceLoads(
        x=x,
        pressure=p + pa,
        fluid_pressure=p,
        asperity_pressure=pa,
        viscous_shear=tau_c,
        poiseuille_shear=pois,
        boundary_shear=tau_b,
        traction_cam=-tau_c + pois - sgn * tau_b,
        traction_tappet=tau_c + pois + sgn * tau_b,
    )


def surface_loads(result, bodies, lubricant, roughness=None, options=None) -> SurfaceLoads:
    """:func:`profile_surface_loads` of an :class:`~tribodyn.EHLResult` (its p, h, u_s)
    with the friction laws of ``options`` (an :class:`~tribodyn.EHLOptions`, default
    the defaults)."""
    return profile_surface_loads(
        result.x,
        result.pressure,
        result.film,
        result.sliding_speed,
        bodies,
        lubricant,
        roughness,
        **shear_options(options),
    )


def loaded_ends(pressure: np.ndarray, share: float) -> tuple[np.ndarray, np.ndarray]:
    """(first, last) node index where p > share · max p, along the last axis of
    ``pressure`` (one profile or rows of profiles); both 0 where p ≤ 0 everywhere."""
    p = np.asarray(pressure, float)
    on = (p > share * p.max(axis=-1, keepdims=True)) & (p.max(axis=-1, keepdims=True) > 0)
    first = np.argmax(on, axis=-1)
    last = np.where(on.any(axis=-1), p.shape[-1] - 1 - np.argmax(on[..., ::-1], axis=-1), 0)
    return first, last


def loaded_half_width(x: np.ndarray, pressure: np.ndarray, share: float = 0.01):
    """Half the extent [m] of the region where p > share · max p (≥ one grid step): a
    float for one profile, an array for rows of profiles (``x`` and ``pressure`` alike)."""
    x = np.asarray(x, float)
    first, last = loaded_ends(pressure, share)
    step = np.abs(x[..., 1] - x[..., 0])
    ends = np.take_along_axis(x, np.stack([first, last], axis=-1), axis=-1)
    b = np.maximum(0.5 * (ends[..., 1] - ends[..., 0]), step)
    return float(b) if b.ndim == 0 else b


def default_depths(body: Body, half_width: float, n_coating: int = 8, n_substrate: int = 40):
    """Depths [m] resolving the coating (n_coating levels down to z = h) and the
    substrate to max(1.5 b, 3h) (n_substrate levels, denser near the interface)."""
    b = float(half_width)
    if body.coating is None:
        return np.linspace(0.0, 1.5 * b, n_substrate + 1)[1:]
    h = body.coating.thickness
    coat = np.linspace(0.0, h, n_coating + 1)[1:]
    deep = max(1.5 * b, 3.0 * h)
    s = np.linspace(0.0, 1.0, n_substrate + 1)[1:] ** 1.5  # denser below the interface
    return np.concatenate([coat, h + (deep - h) * s])


def ehl_stresses(
    result, bodies, lubricant, roughness=None, options=None, depths=None
) -> tuple[SubsurfaceStress, SubsurfaceStress, SurfaceLoads]:
    """Stresses of the cam and the tappet at an EHL solution: (cam, tappet, loads).

    ``depths`` [m]: one array for both bodies, or None for :func:`default_depths` of each
    (from the loaded half-width). The solution grid must be uniform (the solvers' is)."""
    loads = surface_loads(result, bodies, lubricant, roughness, options)
    x = loads.x
    dx = float(x[1] - x[0])
    b = loaded_half_width(x, loads.pressure)
    out = []
    for body, q in zip(as_bodies(bodies), (loads.traction_cam, loads.traction_tappet), strict=True):
        z = default_depths(body, b) if depths is None else depths
        op = StressOperator(x.size, dx, body, z)
        out.append(op.apply(loads.pressure, q, x))
    return out[0], out[1], loads

"""Builders of a surface set's surface law (``asperity_model = "surface"``, the default,
or ``"measured"``): the load–separation law of its ``measured_surface`` (a measured map
or a self-affine spectrum; absent: the typical spectrum of :mod:`tribodyn.physics.typical`), see
:mod:`tribodyn.topography.load_separation`."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np

from .._validation import InputError
from ..physics.asperity import Roughness
from ..physics.materials import reduced_modulus

__all__ = [
    "asperity_law_note",
    "default_spectrum",
    "measured_map",
    "measured_roughness",
    "typical_surface_law",
]


def measured_map(s, resolve: Callable[[str], Path]) -> tuple[np.ndarray, float]:
    """(heights, pixel) of a surface set's measured map (its path made absolute by
    ``resolve``, the case's :meth:`~tribodyn.config.Case.resolve_path`; ``unit`` and
    ``physical_sizes`` for files without them), periodic and
    with zero mean (read-only: cached per process). Its RMS must match ``roughness.rms``
    within 10 %: the law is in h/σ of the map."""
    from ..topography.load_separation import read_periodic_heights

    m = s.measured_surface
    assert m is not None and m.topography is not None
    z, dx = read_periodic_heights(
        resolve(m.topography), unit=m.unit, physical_sizes=m.physical_sizes
    )
    sigma = float(z.std())
    rms = s.roughness.rms
    if abs(sigma - rms) > 0.1 * rms:
        raise InputError(
            f"the map's RMS height is {sigma:.4g} m but surface_sets.{s.name}.roughness."
            f"rms is {rms:.4g} m; set rms to the map's value (the law is in h/σ of the map)"
        )
    return z, dx


def _default_surface():
    """The ``measured_surface`` of a set without one: typical Hurst exponent and cutoffs
    (:mod:`tribodyn.physics.typical`), with the schema's grid, seed and hardness."""
    from ..physics import typical
    from .schema_surfaces import MeasuredSurfaceConfig

    return MeasuredSurfaceConfig(
        hurst=typical.SURFACE_HURST.value,
        short_cutoff=typical.SURFACE_SHORT_CUTOFF.value,
        long_cutoff=typical.SURFACE_LONG_CUTOFF.value,
    )


def default_spectrum() -> dict:
    """The spectrum of the default surface law (a set without ``measured_surface``):
    typical Hurst exponent and cutoffs (:mod:`tribodyn.physics.typical`), with the
    schema's grid, seed and hardness."""
    return _default_surface().model_dump()


def _synthetic_law(rms: float, m, e_s: float):
    """The load–separation law of a self-affine surface of composite RMS ``rms`` [m] with
    the spectrum, hardness, grid and seed of the ``measured_surface`` ``m``, at the pair's
    surface E' ``e_s`` [Pa] (cached by these parameters)."""
    from ..topography.load_separation import synthetic_load_separation

    assert m.hurst is not None and m.short_cutoff is not None and m.long_cutoff is not None
    return synthetic_load_separation(
        rms, m.hurst, m.short_cutoff, m.long_cutoff, e_s, m.hardness, m.grid, m.seed
    )


def typical_surface_law(rms: float, bodies):
    """The default surface law of a pair of ``bodies`` with composite RMS ``rms`` [m]: a
    self-affine surface with the typical spectrum (:func:`default_spectrum`) at the
    pair's surface E' (cached by these parameters)."""
    return _synthetic_law(rms, _default_surface(), reduced_modulus(bodies, surface=True))


def asperity_law_note(s) -> str:
    """Which asperity law a surface set uses, and why (for the run's output)."""
    if s.asperity_model == "greenwood_tripp":
        return 'Greenwood–Tripp: the case asks for it (asperity_model = "greenwood_tripp")'
    m = s.measured_surface
    if m is not None and m.topography is not None:
        return f"surface law of the measured map {m.topography} (measured_surface)"
    if m is not None:
        return (
            f"surface law of a self-affine surface σ {s.roughness.rms * 1e6:.3g} µm, "
            f"H {m.hurst:g}, wavelengths {m.short_cutoff * 1e6:.3g}–{m.long_cutoff * 1e6:.3g} "
            "µm (the case's measured_surface)"
        )
    d = default_spectrum()
    return (
        f"surface law of a self-affine surface with the set's σ {s.roughness.rms * 1e6:.3g} "
        f"µm and the typical spectrum H {d['hurst']:g}, wavelengths "
        f"{d['short_cutoff'] * 1e6:.3g}–{d['long_cutoff'] * 1e6:.3g} µm "
        "(tribodyn.physics.typical; the default: no measured_surface given)"
    )


def measured_roughness(s, rough: Roughness, bodies, resolve: Callable[[str], Path]) -> Roughness:
    """``rough`` with the load–separation law of the set's ``measured_surface`` (absent:
    the typical spectrum, :func:`default_spectrum`), computed at the pair's surface E'
    and the given hardness. Laws are cached per process by the surface's parameters (a
    map by its file's path, modification time and size), so sets, sweep points and
    engine lobes with the same surface and E' share one table. Errors name the set's
    field."""
    from ..topography.load_separation import measured_load_separation

    m = s.measured_surface or _default_surface()
    e_s = reduced_modulus(bodies, surface=True)
    where = f"surface_sets.{s.name}.measured_surface"
    try:
        if m.topography is not None:
            z, _ = measured_map(s, resolve)
            law = measured_load_separation(
                resolve(m.topography),
                e_s,
                m.hardness,
                unit=m.unit,
                physical_sizes=m.physical_sizes,
            )
            return rough.with_law(law, rms=float(z.std()))
        return rough.with_law(_synthetic_law(rough.rms, m, e_s))
    except InputError as e:
        raise InputError(f"{where}: {e}") from None

"""Asperity load–separation law of a measured or synthetic surface, for the EHL solver.

The composite topography z of the pair is pressed against a flat elastic half-space of
composite modulus E* = E'/2 with the contact pressure capped at the hardness H
(:func:`tribodyn.physics.rough_contact.solve_rough_contact`) at a series of mean-plane
separations ū = λσ. The mean pressure p̄(λ) and real-contact fraction A/A₀(λ) form a
:class:`~tribodyn.physics.asperity_law.LoadSeparationLaw`, which a
:class:`~tribodyn.Roughness` (``law=``) uses in place of Greenwood–Tripp.

The separation is the mean gap ū = ⟨g⟩ of the boundary-element solution, which counts the
(negative) gap of nodes flowing at the hardness; the fluid gap ⟨max(g, 0)⟩ is larger at
heavy load (e.g. 0.42σ at ū = 0.3σ on a ground-like surface), so against the fluid film
the law would carry more (17–30 % at ū ≈ 0.2–0.4σ). The EHL uses h = ū.

Maps: periodic maps are used as they are; a measured (non-periodic) map is detrended,
sampled down by an integer stride to at most ``max_points`` per side, and mirrored in x
and y into a periodic map of twice the size (continuous heights, no wrap-around step).
"""

from __future__ import annotations

import math
import stat
from functools import lru_cache
from pathlib import Path

import numpy as np

from .._validation import InputError, check_int, check_positive
from ..physics.asperity_law import LoadSeparationLaw
from ..physics.rough_contact import solve_rough_contact

__all__ = [
    "DEFAULT_SEPARATIONS",
    "load_separation_law",
    "synthetic_load_separation",
    "measured_load_separation",
    "periodic_heights",
    "read_periodic_heights",
]

#: λ = ū/σ of the computed points (from light to heavy load).
DEFAULT_SEPARATIONS = (3.5, 3.0, 2.5, 2.0, 1.75, 1.5, 1.25, 1.0, 0.8, 0.6, 0.45, 0.3, 0.2, 0.1, 0.0)


def load_separation_law(
    heights,
    pixel_size: float,
    reduced_modulus: float,
    hardness: float = math.inf,
    separations=DEFAULT_SEPARATIONS,
    source: str = "",
) -> LoadSeparationLaw:
    """Load–separation law of a periodic height map.

    Parameters
    ----------
    heights : periodic 2-D map z [m] (composite topography of the pair).
    pixel_size : [m].
    reduced_modulus : E' [Pa] of the pair (paper convention, E' = 2E*).
    hardness : H [Pa] of the softer surface (``inf``: elastic; then λ must stay > 0).
    separations : λ = ū/σ of the points, σ the map's RMS height.

    Raises InputError when a point does not converge (the law would be wrong there).
    """
    z = np.asarray(heights, dtype=float)
    z = z - z.mean()
    sigma = float(np.sqrt(np.mean(z**2)))
    e_star = 0.5 * check_positive("reduced_modulus", reduced_modulus, "Pa")
    lams = np.sort(np.asarray(separations, dtype=float))[::-1]
    if not math.isfinite(hardness):
        lams = lams[lams > 0.0]
    p, a, init = [], [], None
    for lam in lams:
        r = solve_rough_contact(z, pixel_size, e_star, lam * sigma, hardness, initial=init)
        if not r.converged:
            raise InputError(f"load–separation law at h/σ = {lam:g}: {r.message}")
        p.append(r.mean_pressure)
        a.append(r.area_fraction)
        init = r.pressure
    order = np.argsort(lams)
    return LoadSeparationLaw(
        lams[order], np.asarray(p)[order], np.asarray(a)[order], reduced_modulus, hardness, source
    )


def synthetic_load_separation(
    rms: float,
    hurst: float,
    short_cutoff: float,
    long_cutoff: float,
    reduced_modulus: float,
    hardness: float = math.inf,
    grid: int = 128,
    seed: int = 1,
) -> LoadSeparationLaw:
    """Law of a synthetic Gaussian self-affine surface (:func:`.synthetic_surface`) of
    RMS σ, Hurst exponent H and wavelengths ``short_cutoff``–``long_cutoff`` [m] on a
    ``grid`` × ``grid`` periodic map of side 2 × ``long_cutoff`` (pixel = side/grid;
    needs short_cutoff ≥ 2 pixels).

    Cached per process by the surface's parameters (however they are passed: as
    positional or keyword arguments, ints or floats), so surface sets, sweep points and
    engine lobes with the same surface and E' share one table."""
    return _synthetic_law(
        float(rms),
        float(hurst),
        float(short_cutoff),
        float(long_cutoff),
        float(reduced_modulus),
        float(hardness),
        check_int("grid", grid),
        check_int("seed", seed),
    )


#: What a synthetic law depends on besides its arguments (the on-disk cache's key,
#: :mod:`tribodyn._cache`): these modules' source and these distributions' versions.
_SYNTHETIC_LAW_CODE = (
    "tribodyn.topography.load_separation",
    "tribodyn.topography.synthetic",
    "tribodyn.physics.rough_contact",
)
_SYNTHETIC_LAW_DISTRIBUTIONS = ("SurfaceTopography", "numpy")


@lru_cache(maxsize=32)
def _synthetic_law(rms, hurst, short_cutoff, long_cutoff, reduced_modulus, hardness, n, seed):
    """The law of :func:`synthetic_load_separation` (``n`` its ``grid``), kept in memory
    and in the user's cache folder (:func:`tribodyn._cache.cached_arrays`: the same bits
    as computed)."""
    from .._cache import cached_arrays

    if not 32 <= n <= 512:
        raise InputError(f"grid must be within 32–512 points per side (got {n})")
    size = 2.0 * check_positive("long_cutoff", long_cutoff, "m")
    dx = size / n
    src = (
        f"synthetic surface σ {rms:.3g} m, H {hurst:g}, wavelengths {short_cutoff:.3g}–"
        f"{long_cutoff:.3g} m, {n}² points, seed {seed}"
    )
    args = (rms, hurst, short_cutoff, long_cutoff, reduced_modulus, hardness, n, seed)

    def compute() -> dict:
        from .synthetic import synthetic_surface

        t = synthetic_surface(
            (n, n),
            dx,
            rms=rms,
            hurst=hurst,
            short_cutoff=short_cutoff,
            long_cutoff=long_cutoff,
            seed=seed,
        )
        law = load_separation_law(t.heights(), dx, reduced_modulus, hardness, source=src)
        return {"lam": law.lam, "pressure": law.pressure, "area": law.area}

    def valid(a: dict) -> bool:  # a stored law the constructor accepts
        LoadSeparationLaw(a["lam"], a["pressure"], a["area"], reduced_modulus, hardness)
        return all(v.dtype == np.float64 for v in a.values())

    a = cached_arrays(
        "synthetic_load_separation",
        args,
        ("lam", "pressure", "area"),
        compute,
        modules=_SYNTHETIC_LAW_CODE,
        distributions=_SYNTHETIC_LAW_DISTRIBUTIONS,
        check=valid,
    )
    return LoadSeparationLaw(a["lam"], a["pressure"], a["area"], reduced_modulus, hardness, src)


def periodic_heights(topography, max_points: int = 128) -> tuple[np.ndarray, float]:
    """(heights, pixel size) of an areal SurfaceTopography map ready for the periodic
    contact: detrended; non-periodic maps sampled down to ≤ ``max_points`` per side and
    mirrored into a periodic map (module docstring)."""
    if getattr(topography, "dim", 2) != 2:
        raise InputError("a load–separation law needs an areal (2-D) topography map")
    if getattr(topography, "has_undefined_data", False):
        topography = topography.interpolate_undefined_data()
    t = topography.detrend("height") if not topography.is_periodic else topography
    z = np.asarray(t.heights(), dtype=float)
    sx, sy = t.physical_sizes
    nx, ny = z.shape
    if abs(sx / nx - sy / ny) > 1e-6 * sx / nx:
        raise InputError("a load–separation law needs square pixels")
    dx = sx / nx
    if topography.is_periodic:
        return z, dx
    stride = max(1, math.ceil(max(nx, ny) / max_points))
    z = z[::stride, ::stride]
    dx *= stride
    z = np.concatenate([z, z[::-1]], axis=0)
    z = np.concatenate([z, z[:, ::-1]], axis=1)
    return z, dx


def _file_identity(path) -> tuple | None:
    """(resolved path, inode, mtime_ns, ctime_ns, size) of an existing regular file: a
    file rewritten in place or replaced changes it. ``None`` if it cannot be stat-ed."""
    try:
        p = Path(path).expanduser().resolve()
        st = p.stat()
    except (OSError, RuntimeError, ValueError):  # ValueError: a NUL in the name
        return None
    if not stat.S_ISREG(st.st_mode):
        return None
    return (str(p), st.st_ino, st.st_mtime_ns, st.st_ctime_ns, st.st_size)


def _sizes_key(physical_sizes) -> tuple[float, ...] | None:
    if physical_sizes is None:
        return None
    try:
        return tuple(float(s) for s in np.atleast_1d(physical_sizes))
    except (TypeError, ValueError):
        raise InputError(
            f"physical_sizes must be one or two positive lengths (got {physical_sizes!r})"
        ) from None


def _read_periodic(path, max_points, unit, physical_sizes) -> tuple[np.ndarray, float]:
    from .reading import read_topography

    topo = read_topography(path, unit=unit, physical_sizes=physical_sizes)
    z, dx = periodic_heights(topo, max_points)
    z = z - z.mean()
    z.setflags(write=False)  # shared through the cache
    return z, dx


@lru_cache(maxsize=8)
def _read_periodic_cached(ident, max_points, unit, physical_sizes):
    return _read_periodic(ident[0], max_points, unit, physical_sizes)


def read_periodic_heights(
    path, max_points: int = 128, *, unit: str | None = None, physical_sizes=None
) -> tuple[np.ndarray, float]:
    """(heights with zero mean [m], pixel size [m]) of a measured map read from ``path``
    (any format of :func:`tribodyn.topography.read_topography`; ``unit`` and
    ``physical_sizes`` (Lx, Ly) in that unit only for files without them), made periodic
    by :func:`periodic_heights`. A file that cannot be read raises InputError.

    Cached per process by the file's resolved path, inode, modification time and size
    and the arguments; the cached heights are read-only (copy to change them)."""
    sizes = _sizes_key(physical_sizes)
    ident = _file_identity(path)
    if ident is None:  # missing or not a file: the reader says so
        return _read_periodic(path, max_points, unit, sizes)
    return _read_periodic_cached(ident, max_points, unit, sizes)


@lru_cache(maxsize=16)
def _measured_law_cached(ident, reduced_modulus, hardness, max_points, unit, physical_sizes):
    z, dx = _read_periodic_cached(ident, max_points, unit, physical_sizes)
    return load_separation_law(z, dx, reduced_modulus, hardness, source=f"measured map {ident[0]}")


def measured_load_separation(
    path,
    reduced_modulus: float,
    hardness: float = math.inf,
    max_points: int = 128,
    *,
    unit: str | None = None,
    physical_sizes=None,
) -> LoadSeparationLaw:
    """Law of a measured map read from ``path`` (see :func:`read_periodic_heights`).

    Cached per process: the same file (resolved path, inode, modification time, size),
    E', H, ``max_points``, ``unit`` and ``physical_sizes`` give the same law object, so
    a case validated again (``Case.updated``, sweep points, engine lobes) does not
    compute it again; a changed file is computed anew."""
    sizes = _sizes_key(physical_sizes)
    ident = _file_identity(path)
    if ident is None:
        z, dx = _read_periodic(path, max_points, unit, sizes)  # raises the reader's error
        return load_separation_law(z, dx, reduced_modulus, hardness, source=f"measured map {path}")
    return _measured_law_cached(
        ident, float(reduced_modulus), float(hardness), int(max_points), unit, sizes
    )

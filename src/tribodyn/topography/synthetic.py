"""Synthetic isotropic Gaussian surfaces with a known spectrum (SurfaceTopography's
``fourier_synthesis``), for tests and for users without measurements.

Prescribed isotropic 2-D power spectrum (self-affine between the cutoffs, Hurst exponent
H, flat roll-off below q_L, nothing above q_s)::

    C²ᴰ(q) = C₀ q^(−2−2H)      q_L ≤ q ≤ q_s         q_L = 2π/λ_L, q_s = 2π/λ_s
           = C₀ q_L^(−2−2H)    q < q_L
           = 0                 q > q_s

Fourier synthesis gives random phases and Gaussian amplitudes, hence Gaussian heights.
The expected profile moments of this spectrum follow from
M_n = (1/2π) ∫ qⁿ⁺¹ C²ᴰ(q) dq and m0 = M0, m2 = M2/2, m4 = 3M4/8 (see ``synthetic_moments``).
"""

from __future__ import annotations

import math
from typing import Any, TypedDict

import numpy as np

from .._validation import InputError, check_int, check_positive, check_range, short_repr
from .spectral_moments import SpectralMoments, isotropic_profile_moments

__all__ = ["synthetic_surface", "synthetic_moments", "DEFAULT_SYNTHETIC"]


#: Default synthetic surface: a ≈ 51 µm square scan at 0.1 µm pixels (like the paper's
#: 50× white-light measurement), σ = 0.25 µm, H = 0.8, wavelengths 2–25 µm.
class _SyntheticDefaults(TypedDict):
    nb_grid_pts: tuple[int, int]
    pixel_size: float  # [m]
    rms: float  # [m]
    hurst: float  # [-]
    short_cutoff: float  # [m]
    long_cutoff: float  # [m]


DEFAULT_SYNTHETIC: _SyntheticDefaults = dict(
    nb_grid_pts=(512, 512),
    pixel_size=0.1e-6,
    rms=0.25e-6,
    hurst=0.8,
    short_cutoff=2e-6,
    long_cutoff=25e-6,
)


def _check(nb_grid_pts, pixel_size, rms, hurst, short_cutoff, long_cutoff):
    from .filtering import MAX_MAP_POINTS

    try:
        nx, ny = (check_int("nb_grid_pts", n) for n in nb_grid_pts)
    except (TypeError, ValueError):
        raise InputError(f"nb_grid_pts must be (nx, ny) (got {short_repr(nb_grid_pts)})") from None
    if min(nx, ny) < 16:
        raise InputError(f"nb_grid_pts must be >= 16 per side (got {nx} × {ny})")
    if nx * ny > MAX_MAP_POINTS:
        raise InputError(
            f"nb_grid_pts must give at most {MAX_MAP_POINTS} points (4096 × 4096: the "
            f"analysis holds the map in memory several times) (got {nx} × {ny})"
        )
    dx = check_positive("pixel_size", pixel_size, "m")
    rms = check_positive("rms", rms, "m")
    hurst = check_range("hurst", hurst, 0.0, 1.0, lo_open=True)
    ls = check_positive("short_cutoff", short_cutoff, "m")
    ll = check_positive("long_cutoff", long_cutoff, "m")
    if not 2 * dx <= ls < ll <= min(nx, ny) * dx:
        raise InputError(
            f"cutoffs must satisfy 2Δ = {2 * dx:.4g} m ≤ short_cutoff "
            f"({ls:.4g} m) < long_cutoff ({ll:.4g} m) ≤ map size "
            f"{min(nx, ny) * dx:.4g} m"
        )
    return (nx, ny), dx, rms, hurst, ls, ll


def synthetic_surface(
    nb_grid_pts: int | tuple[int, int] = DEFAULT_SYNTHETIC["nb_grid_pts"],
    pixel_size: float = DEFAULT_SYNTHETIC["pixel_size"],
    *,
    rms: float = DEFAULT_SYNTHETIC["rms"],
    hurst: float = DEFAULT_SYNTHETIC["hurst"],
    short_cutoff: float = DEFAULT_SYNTHETIC["short_cutoff"],
    long_cutoff: float = DEFAULT_SYNTHETIC["long_cutoff"],
    seed: int | np.random.Generator | None = None,
    exact_rms: bool = True,
) -> Any:
    """Periodic isotropic Gaussian topography (SurfaceTopography ``Topography``, unit m).

    Parameters
    ----------
    nb_grid_pts : (nx, ny) grid points.
    pixel_size : Δ [m], the same in x and y.
    rms : σ [m]. With ``exact_rms`` (default) the heights are rescaled so that the RMS
        of this realisation is exactly σ (otherwise σ is the expectation).
    hurst : Hurst exponent H of the self-affine range, 0 < H ≤ 1.
    short_cutoff, long_cutoff : λ_s, λ_L [m] of the spectrum (see the module docstring).
        For 8-neighbour summit statistics that converge to the continuous values, keep
        λ_s ≳ 16 Δ.
    seed : int or ``numpy.random.Generator`` for reproducible surfaces.
    """
    from SurfaceTopography import Topography
    from SurfaceTopography.Generation import fourier_synthesis

    (nx, ny), dx, rms, hurst, ls, ll = _check(
        nb_grid_pts, pixel_size, rms, hurst, short_cutoff, long_cutoff
    )
    rng = np.random.default_rng(seed)
    t = fourier_synthesis(
        (nx, ny),
        (nx * dx, ny * dx),
        hurst=hurst,
        rms_height=rms,
        short_cutoff=ls,
        long_cutoff=ll,
        rolloff=1.0,
        rng=rng,
        unit="m",
    )
    h = t.heights()
    if exact_rms:
        h = h * (rms / np.sqrt(np.mean(h**2)))
    info = {
        "synthetic": {
            "rms": rms,
            "hurst": hurst,
            "short_cutoff": ls,
            "long_cutoff": ll,
            "pixel_size": dx,
        }
    }
    return Topography(h, (nx * dx, ny * dx), periodic=True, unit="m", info=info)


def synthetic_moments(
    rms: float = DEFAULT_SYNTHETIC["rms"],
    hurst: float = DEFAULT_SYNTHETIC["hurst"],
    short_cutoff: float = DEFAULT_SYNTHETIC["short_cutoff"],
    long_cutoff: float = DEFAULT_SYNTHETIC["long_cutoff"],
) -> SpectralMoments:
    """Expected direction-averaged profile moments of the prescribed spectrum (continuum
    integrals, normalised to m0 = σ²)."""
    rms = check_positive("rms", rms, "m")
    hurst = check_range("hurst", hurst, 0.0, 1.0, lo_open=True)
    qs = 2.0 * math.pi / check_positive("short_cutoff", short_cutoff, "m")
    ql = 2.0 * math.pi / check_positive("long_cutoff", long_cutoff, "m")
    if not ql < qs:
        raise InputError("short_cutoff must be < long_cutoff")

    def areal(n: int) -> float:  # 2π M_n / C₀
        flat = ql ** (-2.0 - 2.0 * hurst) * ql ** (n + 2) / (n + 2)
        p = n - 2.0 * hurst
        power = (qs**p - ql**p) / p if abs(p) > 1e-12 else math.log(qs / ql)
        return flat + power

    scale = rms**2 / areal(0)
    return isotropic_profile_moments(rms**2, scale * areal(2), scale * areal(4))

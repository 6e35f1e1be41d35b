"""Summit statistics of a sampled height map (pure functions: arrays in, numbers out).

A summit is a grid point higher than all 8 neighbours (the "8-point summit" of areal
summit analysis; Greenwood 1984). For each summit the local mean curvature is

    κ = −(∂²h/∂x² + ∂²h/∂y²)/2        [1/m]   (mean of the two principal curvatures)

and the Greenwood–Williamson/Greenwood–Tripp parameters follow as

    η = N_summits / A                  [1/m²]  (A: area over which summits can be found)
    β = 1/⟨κ⟩                          [m]     (radius of the mean summit curvature)

β is the reciprocal of the mean curvature (as in McCool 1986), not the mean of 1/κ,
which is dominated by nearly flat summits.

Sampling limitation: summits and curvatures of the *sampled* map converge to those of the
continuous surface only when the sampling interval Δ is small compared with the shortest
wavelength present. With a few pixels per shortest wavelength the 8-neighbour test misses
summits and the 3-point curvature stencil underestimates κ, so η and β depend on Δ
(Greenwood 1984, "A unified theory of surface roughness", Proc. R. Soc. A 393, 133).
For isotropic Gaussian surfaces whose shortest wavelength spans ≳ 16 pixels, η and β agree
with McCool's spectral-moment values to within a few per cent (see the tests).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .._validation import InputError, check_positive

__all__ = ["SummitStatistics", "find_summits", "summit_statistics"]


@dataclass(frozen=True)
class SummitStatistics:
    """Summit statistics of one map. SI units (see ``UNITS``)."""

    count: int
    area: float
    asperity_density: float
    mean_curvature: float
    summit_radius: float
    summit_height_mean: float
    summit_height_std: float
    nonconvex_fraction: float

    UNITS = {
        "area": "m²",
        "asperity_density": "1/m²",
        "mean_curvature": "1/m",
        "summit_radius": "m",
        "summit_height_mean": "m",
        "summit_height_std": "m",
    }


def find_summits(heights, periodic: bool = False) -> np.ndarray:
    """Boolean mask of points strictly higher than their 8 neighbours.

    For non-periodic maps the outermost rows/columns (incomplete neighbourhood) are never
    summits; periodic maps wrap around.
    """
    h = np.asarray(heights, dtype=float)
    if h.ndim != 2 or min(h.shape) < 3:
        raise InputError(f"heights must be a 2-d array of at least 3 × 3 (got shape {h.shape})")
    if periodic:
        h = np.pad(h, 1, mode="wrap")
    c = h[1:-1, 1:-1]
    mask = np.ones(c.shape, dtype=bool)
    nx, ny = h.shape
    for dx in (-1, 0, 1):
        for dy in (-1, 0, 1):
            if dx or dy:
                mask &= c > h[1 + dx : nx - 1 + dx, 1 + dy : ny - 1 + dy]
    if periodic:
        return mask
    out = np.zeros(np.shape(heights), dtype=bool)
    out[1:-1, 1:-1] = mask
    return out


def summit_statistics(
    heights: np.ndarray,
    mean_curvature: np.ndarray,
    pixel_size: tuple[float, float],
    periodic: bool = False,
) -> SummitStatistics:
    """Summit density, mean summit curvature/radius and summit heights of a map.

    Parameters
    ----------
    heights : 2-d array [m], zero mean plane (levelled and filtered).
    mean_curvature : 2-d array [1/m] of the same shape, κ = −(h_xx + h_yy)/2. NaN marks
        points outside the analysed region (e.g. the border of a non-periodic map, where the
        stencil does not fit, or a margin affected by filter end effects).
    pixel_size : (Δx, Δy) [m].
    periodic : whether the map wraps around (summit test across the edges).

    Returns
    -------
    SummitStatistics with η = N/A [1/m²] (N summits inside the analysed region of area A),
    ⟨κ⟩ [1/m], β = 1/⟨κ⟩ [m], the mean and standard deviation of summit heights above the
    mean plane [m] and the share of summits with κ ≤ 0 (a sign of under-resolved summits).
    """
    h = np.asarray(heights, dtype=float)
    kappa = np.asarray(mean_curvature, dtype=float)
    if kappa.shape != h.shape:
        raise InputError(
            f"mean_curvature must have the heights' shape {h.shape} (got {kappa.shape})"
        )
    dx, dy = (check_positive("pixel size", p, "m") for p in pixel_size)
    region = np.isfinite(kappa)
    mask = find_summits(h, periodic) & region
    area = float(np.count_nonzero(region)) * dx * dy
    k = kappa[mask]
    if k.size == 0:
        raise InputError("no summits found: the analysed region is too small or featureless")
    kbar = float(np.mean(k))
    if kbar <= 0.0:
        raise InputError("mean summit curvature is not positive: the map is not resolved")
    z = h[mask]
    return SummitStatistics(
        count=int(k.size),
        area=float(area),
        asperity_density=float(k.size / area),
        mean_curvature=kbar,
        summit_radius=1.0 / kbar,
        summit_height_mean=float(np.mean(z)),
        summit_height_std=float(np.std(z)),
        nonconvex_fraction=float(np.mean(k <= 0.0)),
    )

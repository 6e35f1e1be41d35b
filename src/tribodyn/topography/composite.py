"""Composite roughness of a surface pair (pure functions).

Greenwood & Tripp (1970) reduce the contact of two rough surfaces to one rough surface
against a smooth plane whose heights are the sum h = h₁ + h₂ of the two (statistically
independent) surfaces. Then

    σ² = σ₁² + σ₂²                              composite RMS roughness [m²]
    m_n = m_n,1 + m_n,2   (n = 0, 2, 4)         spectra and hence spectral moments add

(``SpectralMoments`` add so), and η, β of the pair follow from the summed moments by
McCool's formulas, or from the summits of the sum surface h₁ + h₂ sampled on a common grid.

Source: J. A. Greenwood, J. H. Tripp, "The contact of two nominally flat rough surfaces",
Proc. Instn Mech. Engrs 185 (1970) 625–633.
"""

from __future__ import annotations

import numpy as np

__all__ = ["sum_on_common_grid"]


def sum_on_common_grid(
    heights_1, pixel_size_1, periodic_1, heights_2, pixel_size_2, periodic_2, rtol: float = 1e-6
):
    """Sum surface h₁ + h₂ on the common grid, or ``None`` if the pixel sizes differ.

    Maps with equal pixel sizes but different extents are cropped to the common extent
    (origin at the first grid point); the result is periodic only if both maps are periodic
    with the same shape.

    Returns ``(heights, pixel_size, periodic)`` or ``None``.
    """
    h1, h2 = np.asarray(heights_1, dtype=float), np.asarray(heights_2, dtype=float)
    if not np.allclose(pixel_size_1, pixel_size_2, rtol=rtol, atol=0.0):
        return None
    nx, ny = min(h1.shape[0], h2.shape[0]), min(h1.shape[1], h2.shape[1])
    periodic = bool(periodic_1 and periodic_2 and h1.shape == h2.shape)
    return h1[:nx, :ny] + h2[:nx, :ny], tuple(float(p) for p in pixel_size_1), periodic

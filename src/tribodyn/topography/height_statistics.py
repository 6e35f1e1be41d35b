"""Height-distribution statistics (pure functions).

With heights z_i about their mean z̄ (ISO 25178-2 areal parameters on the filtered map)::

    σ   = Sq  = √⟨(z − z̄)²⟩                      [m]
    Ssk = ⟨(z − z̄)³⟩ / σ³                        [-]  (0 for a Gaussian)
    Sku = ⟨(z − z̄)⁴⟩ / σ⁴                        [-]  (3 for a Gaussian; not excess)

Greenwood–Tripp's statistical functions assume a Gaussian summit-height distribution;
Ssk ≠ 0 or Sku ≠ 3 (e.g. plateau-honed or polished-with-pits surfaces, Ssk < 0) flags
where that assumption is questionable (paper Fig. 7).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._typing import ArrayLike
from .._validation import InputError, check_array, check_positive
from .records import record_dict

__all__ = [
    "HeightStatistics",
    "GaussianReference",
    "height_statistics",
    "gaussian_pdf",
    "gaussian_reference",
]

#: The Gaussian reference curve spans at least this many σ each side of the mean …
GAUSSIAN_SPAN_SIGMA = 4.5
#: … on this many points.
GAUSSIAN_POINTS = 400


@dataclass(frozen=True)
class HeightStatistics:
    """σ (RMS about the mean) [m], mean [m], skewness Ssk [-], kurtosis Sku [-]."""

    rms: float
    mean: float
    skewness: float
    kurtosis: float

    UNITS = {"rms": "m", "mean": "m", "skewness": "-", "kurtosis": "-"}

    def gaussian_note(self, prefix: str = "S") -> str | None:
        """A note if the heights are not near-Gaussian (|Ssk| > 0.5 or |Sku − 3| > 1),
        naming the parameters ``prefix`` + "sk"/"ku" ("S" areal, "R" profile); else None."""
        if abs(self.skewness) > 0.5 or abs(self.kurtosis - 3.0) > 1.0:
            return (
                f"height distribution not Gaussian ({prefix}sk = {self.skewness:.2f}, "
                f"{prefix}ku = {self.kurtosis:.2f}; Gaussian 0 and 3)"
            )
        return None

    def to_dict(self) -> dict:
        return record_dict(self)


def height_statistics(heights: ArrayLike) -> HeightStatistics:
    """σ, mean, Ssk and Sku of a height array [m] (NaN/inf rejected)."""
    z = check_array("heights", heights, ndim=None, min_size=3).ravel()
    mean = float(np.mean(z))
    d = z - mean
    var = float(np.mean(d * d))
    if var <= 0.0:
        raise InputError("heights are constant: no roughness")
    d2 = d * d
    return HeightStatistics(
        rms=math.sqrt(var),
        mean=mean,
        skewness=float(np.mean(d2 * d)) / var**1.5,
        kurtosis=float(np.mean(d2 * d2)) / var**2,
    )


def gaussian_pdf(z, sigma: float, mean: float = 0.0):
    """Gaussian probability density [1/m] at heights z [m] with standard deviation σ [m]."""
    sigma = check_positive("sigma", sigma, "m")
    z = (np.asarray(z, dtype=float) - mean) / sigma
    return np.exp(-0.5 * z * z) / (sigma * math.sqrt(2.0 * math.pi))


@dataclass(frozen=True)
class GaussianReference:
    """The Gaussian with the heights' σ beside their distribution (paper Fig. 7): ``z``
    heights above the mean [m], uniform and symmetric over ±``span``, and ``pdf`` the
    Gaussian density there [1/m]."""

    z: np.ndarray
    pdf: np.ndarray

    @property
    def span(self) -> float:
        """Half-width of the grid [m]: max(GAUSSIAN_SPAN_SIGMA·σ, max |z − z̄|)."""
        return float(self.z[-1])


def gaussian_reference(
    heights: ArrayLike, stats: HeightStatistics, points: int = GAUSSIAN_POINTS
) -> GaussianReference:
    """:func:`gaussian_pdf` with σ = ``stats.rms`` on ``points`` heights about
    ``stats.mean`` that span every height of ``heights`` [m] and at least
    :data:`GAUSSIAN_SPAN_SIGMA` σ each side."""
    d = np.asarray(heights, dtype=float).ravel() - stats.mean
    span = max(GAUSSIAN_SPAN_SIGMA * stats.rms, float(np.max(np.abs(d))))
    z = np.linspace(-span, span, points)
    return GaussianReference(z, gaussian_pdf(z, stats.rms))

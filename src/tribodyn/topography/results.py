"""Result objects of the topography analysis (fields SI, units in ``UNITS``/``to_dict``).

Every result carries the band and sampling it was computed with: summit density and
radius depend strongly on both (η grows and β shrinks as shorter wavelengths are kept).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from .._validation import InputError
from ..physics.asperity import Roughness
from .filtering import Band, Sampling
from .height_statistics import GaussianReference, HeightStatistics
from .records import record_dict
from .spectral_moments import McCoolParameters, SpectralMoments
from .summits import SummitStatistics

__all__ = [
    "METHODS",
    "AsperityParameters",
    "SurfaceAnalysis",
    "PairAnalysis",
    "ProfileAnalysis",
]

#: Estimators of η and β: 8-neighbour summits, or McCool's spectral moments.
METHODS = ("summits", "spectral")
METHOD_LABELS = {"summits": "8-neighbour summits", "spectral": "spectral moments (McCool)"}


@dataclass(frozen=True)
class AsperityParameters:
    """η [1/m²], σ [m], β [m] of one estimator, plus the summit-height mean/std [m]."""

    method: str
    asperity_density: float
    rms: float
    summit_radius: float
    summit_height_mean: float
    summit_height_std: float

    UNITS = {
        "asperity_density": "1/m²",
        "rms": "m",
        "summit_radius": "m",
        "summit_height_mean": "m",
        "summit_height_std": "m",
        "roughness_parameter": "-",
    }

    @property
    def roughness_parameter(self) -> float:
        """ηβσ [-]."""
        return self.asperity_density * self.summit_radius * self.rms

    def to_roughness(self) -> Roughness:
        return Roughness(
            asperity_density=self.asperity_density, rms=self.rms, summit_radius=self.summit_radius
        )

    def to_dict(self) -> dict:
        return record_dict(self, "roughness_parameter")


def _parameters(
    method: str, stats: SummitStatistics | McCoolParameters, rms: float
) -> AsperityParameters:
    """The estimator ``method``'s η, β and summit heights (``stats``) with σ = ``rms``."""
    return AsperityParameters(
        method,
        stats.asperity_density,
        rms,
        stats.summit_radius,
        stats.summit_height_mean,
        stats.summit_height_std,
    )


def _check_method(method: str) -> str:
    if method not in METHODS:
        raise InputError(f"method must be one of {METHODS} (got {method!r})")
    return method


class HeightMap(Protocol):
    """What the analysis keeps of a filtered map (a SurfaceTopography ``Topography``,
    lengths in m)."""

    @property
    def nb_grid_pts(self) -> tuple[int, int]: ...

    @property
    def pixel_size(self) -> tuple[float, float]: ...

    @property
    def is_periodic(self) -> bool: ...

    def heights(self) -> np.ndarray: ...


class _TomlMixin(ABC):
    """Roughness block and ``Roughness`` from a result's estimators."""

    band: Band
    sampling: Sampling
    heights: HeightStatistics

    @property
    def rms(self) -> float:
        """σ, RMS height of the filtered heights [m]."""
        return self.heights.rms

    @abstractmethod
    def parameters(self, method: str = "summits") -> AsperityParameters:
        """η, σ, β of one estimator (:data:`METHODS`)."""

    @abstractmethod
    def describe_source(self) -> str:
        """What was analysed (one line)."""

    def describe_conditions(self) -> list[str]:
        """Band, sampling and notes (one line each); here those of one analysis (a
        surface or a profile)."""
        return [f"band {self.band.describe()}", f"sampling {self.sampling.describe()}"]

    def to_roughness(self, method: str = "summits") -> Roughness:
        """tribodyn ``Roughness`` (η, σ, β) from the chosen estimator."""
        return self.parameters(method).to_roughness()

    def toml_block(self, method: str = "summits") -> str:
        """Roughness block for a case file, with band and sampling as comments.

        Headed ``[surface_sets.roughness]``: pasted right below a ``[[surface_sets]]``
        entry, TOML makes it that surface pair's ``roughness`` table."""
        p = self.parameters(method)
        lines = [
            "[surface_sets.roughness]",
            "# paste below the [[surface_sets]] entry of this surface pair",
            f"# {self.describe_source()}: {METHOD_LABELS[_check_method(method)]}, "
            f"ηβσ = {p.roughness_parameter:.4g}",
        ]
        lines += [f"# {line}" for line in self.describe_conditions()]
        lines += [
            f"asperity_density = {p.asperity_density:.6g}  # η [1/m²]",
            f"rms = {p.rms:.6g}  # σ [m]",
            f"summit_radius = {p.summit_radius:.6g}  # β [m]",
        ]
        return "\n".join(lines) + "\n"


@dataclass(frozen=True)
class SurfaceAnalysis(_TomlMixin):
    """Roughness parameters of one measured (or synthetic) surface.

    ``summit_stats`` from 8-neighbour summits with 3-point curvature, ``mccool`` from the
    spectral moments ``moments`` of the same filtered map; ``heights`` holds σ, Ssk, Sku.
    ``slope_anisotropy`` = max/min of the mean-square slopes along x and y (1 = isotropic;
    McCool's formulas assume isotropy). ``topography`` is the filtered map (m).
    """

    name: str
    sampling: Sampling
    band: Band
    heights: HeightStatistics
    moments: SpectralMoments
    summit_stats: SummitStatistics
    mccool: McCoolParameters
    slope_anisotropy: float
    notes: tuple[str, ...] = ()
    source: dict | None = None
    topography: HeightMap | None = field(default=None, repr=False, compare=False)
    #: what was done to the input (band clipped, dropouts filled); shown as warnings
    warnings: tuple[str, ...] = ()
    #: points that were not measured (filled before filtering); None: all measured
    filled: object = field(default=None, repr=False, compare=False)
    #: the Gaussian with σ beside the measured heights (paper Fig. 7)
    gaussian: GaussianReference | None = field(default=None, repr=False, compare=False)

    @property
    def summits(self) -> AsperityParameters:
        return _parameters("summits", self.summit_stats, self.heights.rms)

    @property
    def spectral(self) -> AsperityParameters:
        return _parameters("spectral", self.mccool, self.mccool.rms)

    def parameters(self, method: str = "summits") -> AsperityParameters:
        return self.summits if _check_method(method) == "summits" else self.spectral

    def describe_source(self) -> str:
        return f"surface '{self.name}'"

    def to_dict(self) -> dict:
        return {
            "name": self.name,
            "source": self.source,
            "band": self.band.to_dict(),
            "sampling": self.sampling.to_dict(),
            "heights": self.heights.to_dict(),
            "moments": self.moments.to_dict(),
            "summits": self.summits.to_dict(),
            "summit_count": self.summit_stats.count,
            "summit_area": self.summit_stats.area,
            "nonconvex_summit_fraction": self.summit_stats.nonconvex_fraction,
            "spectral": self.spectral.to_dict(),
            "slope_anisotropy": self.slope_anisotropy,
            "filled_fraction": self.sampling.undefined_fraction,
            "warnings": list(self.warnings),
            "notes": list(self.notes),
        }


#: The label of a profile's η and β (:mod:`.profile`).
ISOTROPIC_LABEL = (
    "isotropic-surface estimate from one profile (McCool): valid only if the surface has no lay"
)


@dataclass(frozen=True)
class ProfileAnalysis(_TomlMixin):
    """Roughness of one profile (SI units). ``isotropic`` holds the isotropic-surface
    estimates of η and β (McCool from the profile moments); ``summits`` is None (a
    profile has no summits)."""

    name: str
    sampling: Sampling
    band: Band
    heights: HeightStatistics
    moments: SpectralMoments
    peak_count: int
    peak_density: float  #: counted peaks per length [1/m]
    peak_density_gaussian: float  #: (1/2π)√(m4/m2) [1/m]
    isotropic: McCoolParameters
    notes: tuple[str, ...] = ()
    warnings: tuple[str, ...] = ()
    source: dict | None = None
    profile: np.ndarray | None = field(default=None, repr=False, compare=False)
    filled: np.ndarray | None = field(default=None, repr=False, compare=False)
    #: the Gaussian with σ beside the measured heights (paper Fig. 7)
    gaussian: GaussianReference | None = field(default=None, repr=False, compare=False)
    topography: None = field(default=None, repr=False, compare=False)  # not a map
    summit_stats: None = None
    mccool: McCoolParameters = field(init=False)  # = isotropic

    kind = "profile"

    def __post_init__(self):
        object.__setattr__(self, "mccool", self.isotropic)

    @property
    def summits(self):
        return None

    @property
    def spectral(self) -> AsperityParameters:
        return _parameters("spectral", self.isotropic, self.heights.rms)

    @property
    def slope_anisotropy(self) -> float:
        return float("nan")

    def parameters(self, method: str = "spectral") -> AsperityParameters:
        if method == "summits":
            raise InputError(
                "a profile has no summits: use method='spectral' (the "
                "isotropic-surface estimate from the profile moments)"
            )
        _check_method(method)
        return self.spectral

    def to_roughness(self, method: str = "spectral"):
        return self.parameters(method).to_roughness()

    def toml_block(self, method: str = "spectral") -> str:
        block = super().toml_block("spectral" if method == "summits" else method)
        head, rest = block.split("\n", 1)
        return f"{head}\n# {ISOTROPIC_LABEL.upper()}\n{rest}"

    def describe_source(self) -> str:
        return f"profile '{self.name}'"

    def to_dict(self) -> dict:
        iso = self.spectral.to_dict()
        iso["label"] = ISOTROPIC_LABEL
        return {
            "name": self.name,
            "kind": "profile",
            "source": self.source,
            "band": self.band.to_dict(),
            "sampling": self.sampling.to_dict(),
            "heights": self.heights.to_dict(),
            "moments": self.moments.to_dict(),
            "peak_count": self.peak_count,
            "peak_density": self.peak_density,
            "peak_density_gaussian": self.peak_density_gaussian,
            "summits": None,
            "isotropic_estimate": iso,
            "spectral": iso,
            "filled_fraction": self.sampling.undefined_fraction,
            "warnings": list(self.warnings),
            "notes": list(self.notes),
            "units": {"peak_density": "1/m", "peak_density_gaussian": "1/m"},
        }


@dataclass(frozen=True)
class PairAnalysis(_TomlMixin):
    """Composite roughness of a pair (cam and tappet), Greenwood–Tripp's equivalent surface.

    σ = √(σ₁² + σ₂²). Spectral: moments of the sum surface are the sums of the moments
    (independent surfaces), then McCool. Summits: 8-neighbour analysis of the sum surface
    h₁ + h₂ on the common grid (``None`` if the two maps are sampled differently).
    ``sum_surface`` holds the measured heights of h₁ + h₂ [m] (flattened; ``None`` as for
    the summits), ``sum_heights`` their σ, Ssk, Sku, ``sum_gaussian`` the Gaussian with
    that σ beside them (paper Fig. 7).
    """

    first: SurfaceAnalysis | ProfileAnalysis
    second: SurfaceAnalysis | ProfileAnalysis
    moments: SpectralMoments
    mccool: McCoolParameters
    summit_stats: SummitStatistics | None
    sum_heights: HeightStatistics | None
    notes: tuple[str, ...] = ()
    sum_surface: np.ndarray | None = field(default=None, repr=False, compare=False)
    sum_gaussian: GaussianReference | None = field(default=None, repr=False, compare=False)

    @property
    def rms(self) -> float:
        """Composite σ = √(σ₁² + σ₂²) [m]."""
        return (self.first.rms**2 + self.second.rms**2) ** 0.5

    @property
    def summits(self) -> AsperityParameters | None:
        if self.summit_stats is None:
            return None
        return _parameters("summits", self.summit_stats, self.rms)

    @property
    def spectral(self) -> AsperityParameters:
        return _parameters("spectral", self.mccool, self.rms)

    def parameters(self, method: str = "summits") -> AsperityParameters:
        if _check_method(method) == "spectral":
            return self.spectral
        summits = self.summits
        if summits is None:
            raise InputError(
                "no composite summit analysis (the two maps are sampled "
                "differently); use method='spectral'"
            )
        return summits

    def describe_source(self) -> str:
        return f"composite of '{self.first.name}' + '{self.second.name}'"

    def describe_conditions(self) -> list[str]:
        a, b = self.first, self.second
        if a.band.describe() == b.band.describe():
            lines = [f"band {a.band.describe()}"]
        else:
            lines = [f"band {a.name}: {a.band.describe()}", f"band {b.name}: {b.band.describe()}"]
        if a.sampling == b.sampling:
            lines.append(f"sampling (both) {a.sampling.describe()}")
        else:
            lines += [
                f"sampling {a.name}: {a.sampling.describe()}",
                f"sampling {b.name}: {b.sampling.describe()}",
            ]
        return lines

    def to_dict(self) -> dict:
        return {
            "first": self.first.to_dict(),
            "second": self.second.to_dict(),
            "composite": {
                "rms": self.rms,
                "moments": self.moments.to_dict(),
                "summits": None if self.summits is None else self.summits.to_dict(),
                "summit_count": None if self.summit_stats is None else self.summit_stats.count,
                "sum_surface_heights": (
                    None if self.sum_heights is None else self.sum_heights.to_dict()
                ),
                "spectral": self.spectral.to_dict(),
                "notes": list(self.notes),
                "units": {"rms": "m"},
            },
        }

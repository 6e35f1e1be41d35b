"""Measured surface topography → Greenwood–Tripp roughness parameters (η, σ, β).

Reads instrument files through SurfaceTopography, fills dropouts, levels and band-pass
filters them (by default in the typical roughness band, clipped to what the measurement
resolves), and estimates summit density η and mean summit radius β in two ways side by side:
8-neighbour summits with local curvature, and McCool's spectral moments. Profiles (line
scans) give σ, Rsk, Rku, their spectral moments and isotropic-surface estimates of η, β. Two surfaces
(cam and tappet) combine into the pair's composite parameters. Results carry the band and
sampling, on which η and β strongly depend.

>>> from tribodyn.topography import analyse_surface, synthetic_surface
>>> r = analyse_surface(synthetic_surface(seed=1), band=(2e-6, 25e-6))
>>> roughness = r.to_roughness()            # tribodyn.Roughness(η, σ, β)
>>> print(r.toml_block())                   # doctest: +SKIP
"""

from .analysis import analyse_pair, analyse_surface, composite_roughness
from .errors import BandLimitError, InsufficientDataError, TopographyError, TopographyReadError
from .filtering import AUTO_BAND, TYPICAL_BAND, Band, Sampling, prepare_topography
from .height_statistics import HeightStatistics, height_statistics
from .profile import ProfileAnalysis, analyse_profile
from .reading import read_topography, write_topography
from .results import AsperityParameters, PairAnalysis, SurfaceAnalysis
from .spectral_moments import SpectralMoments, mccool_parameters
from .summits import SummitStatistics, summit_statistics
from .synthetic import synthetic_moments, synthetic_surface

__all__ = [
    "AUTO_BAND",
    "TYPICAL_BAND",
    "AsperityParameters",
    "ProfileAnalysis",
    "analyse_profile",
    "Band",
    "BandLimitError",
    "HeightStatistics",
    "InsufficientDataError",
    "PairAnalysis",
    "Sampling",
    "SpectralMoments",
    "SummitStatistics",
    "SurfaceAnalysis",
    "TopographyError",
    "TopographyReadError",
    "analyse_pair",
    "analyse_surface",
    "composite_roughness",
    "height_statistics",
    "mccool_parameters",
    "prepare_topography",
    "read_topography",
    "summit_statistics",
    "synthetic_moments",
    "synthetic_surface",
    "write_topography",
]

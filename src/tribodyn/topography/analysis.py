"""Measured topography → Greenwood–Tripp roughness parameters (orchestration).

``analyse_surface`` reads (or takes) a map, fills, levels and band-pass filters it
(:mod:`.filtering`), then computes on the same filtered map

* σ, Ssk, Sku of the heights (:mod:`.height_statistics`);
* η, β from 8-neighbour summits with 3-point mean curvature (:mod:`.summits`; second
  derivatives from SurfaceTopography's ``derivative``);
* η, β, α from the direction-averaged profile spectral moments (:mod:`.spectral_moments`;
  power-spectrum moments for periodic maps, spectral derivatives of the mirror-stitched
  map for filtered non-periodic ones, see ``profile_moments``).

Non-periodic maps lose a margin of one λ_s along each edge before summits and moments are
evaluated (filter end effects), see ``analysis_margin``. Points that were not measured
(dropouts, filled before filtering, see :mod:`.filtering`) are excluded from all statistics:
σ, Ssk, Sku, the summits and the moments are taken over measured points only.

Too little left: the analysis is refused (:class:`InsufficientDataError`) when the
measured points of the analysed interior hold fewer than ``MIN_SUMMITS`` = 25 summits.
η is a count: its relative standard error is ≈ 1/√N (Poisson), above 20 % for N < 25, and
β, the mean of a curvature distribution whose spread is comparable to its mean, is no
better. Fewer summits (too many dropouts, or a field of view too small for the band) leave
no meaningful estimate; below 200 summits the result carries a note with the uncertainty.

``composite_roughness`` combines two analyses (cam and tappet) into the pair's equivalent
surface (:mod:`.composite`).
"""

from __future__ import annotations

import math
from dataclasses import replace
from pathlib import Path
from typing import Any, Literal

import numpy as np

from .._typing import PathLike
from .composite import sum_on_common_grid
from .errors import InsufficientDataError
from .filtering import (
    AUTO_BAND,
    Band,
    BandSpec,
    Sampling,
    analysis_margin,
    input_warnings,
    prepare_topography,
)
from .height_statistics import gaussian_reference, height_statistics
from .reading import read_topography
from .results import PairAnalysis, ProfileAnalysis, SurfaceAnalysis
from .spectral_moments import (
    MIN_ALPHA_ISOTROPIC,
    SpectralMoments,
    isotropic_profile_moments,
    mccool_parameters,
)
from .summits import summit_statistics

__all__ = [
    "analyse_surface",
    "analyse_pair",
    "composite_roughness",
    "analyse_filtered",
    "analysis_margin",
    "analysis_region",
    "mean_curvature_field",
    "profile_moments",
    "MIN_PIXELS_PER_WAVELENGTH",
    "MIN_SUMMITS",
]

#: Shortest filtered wavelength, in pixels, above which 8-neighbour summit statistics are
#: treated as converged (Gaussian S-filter; see the tests and ``summits`` docstring).
MIN_PIXELS_PER_WAVELENGTH = 16.0
#: Fewest summits (on measured points of the analysed interior) for an estimate of η, β.
MIN_SUMMITS = 25
#: Summit-vs-spectral deviation above which a note is added.
NOTE_DEVIATION = 0.10
#: ηβσ of an isotropic Gaussian surface is at least 0.0204·√1.5 (McCool).
MIN_ETA_BETA_SIGMA = 0.375 / (6.0 * np.sqrt(3.0 * np.pi)) * np.sqrt(MIN_ALPHA_ISOTROPIC)


def analysis_region(shape, margin) -> np.ndarray:
    """Boolean mask of the analysed points: all but ``margin`` = (wx, wy) edge pixels."""
    (nx, ny), (wx, wy) = shape, margin
    if nx - 2 * wx < 3 or ny - 2 * wy < 3:
        raise InsufficientDataError(
            f"the map ({nx} × {ny} points) is too small for the band: excluding "
            f"{wx} × {wy} edge pixels (one λ_s) leaves no interior to analyse"
        )
    region = np.zeros((nx, ny), dtype=bool)
    region[wx : nx - wx, wy : ny - wy] = True
    return region


def mean_curvature_field(topography, region=None) -> np.ndarray:
    """κ = −(h_xx + h_yy)/2 [1/m] on the map's grid (SurfaceTopography's 3-point
    stencils); NaN outside ``region`` and on the border of non-periodic maps."""
    d2x, d2y = topography.derivative(2, interpolation="disable")
    kappa = -0.5 * (np.asarray(d2x) + np.asarray(d2y))
    if not topography.is_periodic:
        full = np.full(topography.nb_grid_pts, np.nan)
        full[1:-1, 1:-1] = kappa
        kappa = full
    if region is not None:
        kappa = np.where(region, kappa, np.nan)
    return kappa


def profile_moments(
    topography, band: Band | None = None, region=None, measured=None
) -> tuple[SpectralMoments, float]:
    """Direction-averaged profile moments and the slope anisotropy max/min(m2x, m2y).

    All derivatives are spectral (exact for the band-limited field):

    * periodic map: areal moments of the power spectrum (``moment_power_spectrum``,
      ``integrate_psd``), M_n = (2π)⁻² ∫ |q|ⁿ C²ᴰ d²q;
    * non-periodic, band-pass filtered map: the map is mirror-stitched again, which
      reproduces the smooth periodic field the filter produced; ∂h/∂x, ∂h/∂y and ∇²h are
      obtained with SurfaceTopography's Fourier ``filter`` (transfer functions iq_x, iq_y,
      −|q|²) and M2 = ⟨|∇h|²⟩, M4 = ⟨(∇²h)²⟩ are averaged over ``region`` (Parseval's
      identity restricted to the analysed interior, like the summit count);
      M0 = ⟨h²⟩ of the map (of its ``measured`` points, about their mean, if given);
    * non-periodic, unfiltered map: power-spectrum moments with SurfaceTopography's
      default Hann window.
    """
    if topography.is_periodic or band is None or band.kind == "none":
        m0 = topography.moment_power_spectrum(order=0, reliable=False)
        m2x = topography.integrate_psd(lambda qx, qy: qx**2, reliable=False)
        m2y = topography.integrate_psd(lambda qx, qy: qy**2, reliable=False)
        m4 = topography.moment_power_spectrum(order=4, reliable=False)
    else:
        nx, ny = topography.nb_grid_pts
        region = np.ones((nx, ny), dtype=bool) if region is None else region
        stitched = topography.mirror_stitch()

        def interior_mean_square(transfer, isotropic):  # ⟨(F⁻¹[T(q) ĥ])²⟩ over region
            field = stitched.filter(filter_function=transfer, isotropic=isotropic).heights()
            return float(np.mean(np.asarray(field)[:nx, :ny][region] ** 2))

        h = np.asarray(topography.heights())
        m0 = float(np.mean(h**2)) if measured is None else float(np.var(h[measured]))
        m2x = interior_mean_square(lambda qx, qy: 1j * qx, False)  # ∂h/∂x
        m2y = interior_mean_square(lambda qx, qy: 1j * qy, False)  # ∂h/∂y
        m4 = interior_mean_square(lambda q: -q * q, True)  # ∇²h
    moments = isotropic_profile_moments(m0, m2x + m2y, m4)
    return moments, float(max(m2x, m2y) / min(m2x, m2y))


def reliable_points(measured: np.ndarray, band: Band, pixel_size, periodic: bool) -> np.ndarray:
    """Measured points far enough from the filled holes to be analysed.

    The harmonic fill of a hole has its maximum on the hole's rim (maximum principle) and
    no roughness inside, and the band-pass filter spreads it over ≈ λ_s/4 (the Gaussian
    S-filter kernel has a standard deviation of 0.19 λ_s): points next to a hole pass the
    8-neighbour summit test more often than on the real surface. Excluded are (a) the 8
    neighbours of every filled point and (b) for holes wider than λ_s/4, all points within
    λ_s/4 of them. Holes narrower than λ_s/4 (scattered pixels) are filled accurately, as
    the band-limited surface is smooth on that scale. On isotropic Gaussian surfaces with
    28 % dropouts this keeps the summit density within ≈ 2 % of the complete surface's
    (tests/test_topography_files.py)."""
    from scipy import ndimage

    filled = ~measured
    if not filled.any():
        return measured.copy()
    reach = 1.0 if band.kind == "none" else band.short_wavelength / min(pixel_size) / 4.0
    r_big = max(1, int(math.ceil(reach)))
    pad = r_big + 1
    mode: Literal["wrap", "constant"] = "wrap" if periodic else "constant"
    f = np.pad(filled, pad, mode=mode)
    labels, _ = ndimage.label(f, structure=np.ones((3, 3), dtype=bool))
    big = np.zeros_like(f)
    for k, sl in enumerate(ndimage.find_objects(labels), start=1):
        if sl is not None and max(s.stop - s.start for s in sl) > reach:
            big[sl] |= labels[sl] == k
    near = ndimage.binary_dilation(f, structure=np.ones((3, 3), dtype=bool))
    if big.any():
        near |= ndimage.binary_dilation(big, structure=np.ones((2 * r_big + 1,) * 2, dtype=bool))
    return measured & ~near[pad:-pad, pad:-pad]


def analyse_filtered(
    topography,
    band: Band,
    sampling: Sampling,
    name: str = "surface",
    source: dict | None = None,
    filled=None,
) -> SurfaceAnalysis:
    """Analyse a map that is already levelled and filtered (heights in m); ``filled``
    marks points that were not measured (excluded from the statistics)."""
    heights = np.asarray(topography.heights(), dtype=float)
    measured = None if filled is None or not np.any(filled) else ~np.asarray(filled)
    kept = heights if measured is None else heights[measured]
    hstats = height_statistics(kept)
    region, sstats = _summits(topography, heights, band, topography.pixel_size, measured)
    if sstats.count < MIN_SUMMITS:
        share = (
            ""
            if measured is None
            else (f" ({1 - sampling.undefined_fraction:.0%} of the points measured)")
        )
        raise InsufficientDataError(
            f"only {sstats.count} summits on the measured points of the analysed interior"
            f"{share}: at least {MIN_SUMMITS} are needed for η and β (standard error "
            f"≈ 1/√N); use a larger measurement, fewer dropouts or a shorter band"
        )
    moments, anisotropy = profile_moments(topography, band, region, measured)
    mccool = mccool_parameters(moments)
    result = SurfaceAnalysis(
        name=name,
        sampling=sampling,
        band=band,
        heights=hstats,
        moments=moments,
        summit_stats=sstats,
        mccool=mccool,
        slope_anisotropy=anisotropy,
        source=source,
        topography=topography,
        filled=None if measured is None else ~measured,
        gaussian=gaussian_reference(kept, hstats),
    )
    return _with_notes(result)


def _summits(topography, h, band: Band, pixel_size, measured) -> tuple:
    """(analysed region, summit statistics) of the filtered map ``topography`` with
    heights h: the interior inside :func:`analysis_margin`, less the points near holes
    (:func:`reliable_points`) when ``measured`` (a mask; None: all measured) is given."""
    periodic = topography.is_periodic
    region = analysis_region(h.shape, analysis_margin(band, pixel_size, periodic))
    if measured is not None:
        region &= reliable_points(measured, band, pixel_size, periodic)
    curvature = mean_curvature_field(topography, region)
    return region, summit_statistics(h, curvature, pixel_size, periodic)


def _note_deviation(notes: list, summits: Any, spectral: Any, what: str = "") -> None:
    """Append to ``notes`` where the summit and spectral η or β (AsperityParameters)
    differ by more than :data:`NOTE_DEVIATION` (relative)."""
    d_eta = summits.asperity_density / spectral.asperity_density - 1.0
    d_beta = summits.summit_radius / spectral.summit_radius - 1.0
    if max(abs(d_eta), abs(d_beta)) > NOTE_DEVIATION:
        notes.append(
            f"{what}summit vs spectral estimates differ by {d_eta:+.0%} (η) and {d_beta:+.0%} (β)"
        )


def _sampling_note(band: Band, sampling: Sampling) -> str:
    dx = max(sampling.pixel_size)
    if band.kind == "none":
        return (
            "no short-wavelength filter: the 8-neighbour summit estimates depend on the "
            "pixel size and the instrument's noise; prefer a band with λ_s ≥ "
            f"{MIN_PIXELS_PER_WAVELENGTH:g} pixels"
        )
    ratio = band.wavelengths[0] / dx
    text = f"λ_s spans {ratio:.3g} pixels"
    if ratio < MIN_PIXELS_PER_WAVELENGTH * (1 - 1e-6):  # tolerate float32 pixel sizes
        text += (
            f" (< {MIN_PIXELS_PER_WAVELENGTH:g}): the 8-neighbour summit η and β depend "
            "on the sampling and need not converge to the continuous-surface (McCool) "
            "values; the spectral estimates are sampling-independent"
        )
    else:
        text += f" (≥ {MIN_PIXELS_PER_WAVELENGTH:g}): summit statistics resolved"
    return text


def _with_notes(r: SurfaceAnalysis) -> SurfaceAnalysis:
    notes = [_sampling_note(r.band, r.sampling)]
    _note_deviation(notes, r.summits, r.spectral)
    if r.slope_anisotropy > 1.5:
        notes.append(
            f"anisotropic texture (mean-square slope ratio {r.slope_anisotropy:.2f} "
            "between x and y): McCool's formulas assume isotropy"
        )
    if (note := r.heights.gaussian_note("S")) is not None:
        notes.append(f"{note}: Greenwood–Tripp's F_n assume Gaussian summit heights")
    if r.summits.roughness_parameter < MIN_ETA_BETA_SIGMA:
        notes.append(
            f"summit ηβσ = {r.summits.roughness_parameter:.3g} is below "
            f"{MIN_ETA_BETA_SIGMA:.3f}, the minimum for an isotropic Gaussian surface"
        )
    if r.summit_stats.count < 200:
        notes.append(
            f"only {r.summit_stats.count} summits: η and β carry a statistical "
            f"uncertainty of order {1 / np.sqrt(r.summit_stats.count):.0%}"
        )
    return replace(r, notes=tuple(notes), warnings=input_warnings(r.band, r.sampling))


def analyse_surface(
    source: PathLike | Any,
    band: BandSpec = AUTO_BAND,
    *,
    kind: str = "gaussian",
    detrend: str = "height",
    clip_band: bool = False,
    min_defined_fraction: float = 0.0,
    name: str | None = None,
    channel: int | None = None,
    physical_sizes: tuple[float, ...] | None = None,
    unit: str | None = None,
) -> SurfaceAnalysis | ProfileAnalysis:
    """Greenwood–Tripp parameters of one surface.

    Parameters
    ----------
    source : file name (any format SurfaceTopography reads) or a SurfaceTopography
        ``Topography`` (e.g. from :func:`synthetic_surface`) or ``UniformLineScan``.
    band : ``"auto"`` (default): the typical 2.5 µm–0.8 mm (ISO 3274, ISO 4288) clipped to
        what the measurement resolves, with a warning saying which band was used and why; (λ_s, λ_L) [m]: must
        lie within the measurement's range (see ``clip_band``); ``None``: level only.
    kind : ``"gaussian"`` (default, 50 % transmission at the cutoffs) or ``"step"``.
    detrend : ``"height"`` (plane), ``"curvature"`` (2nd-order polynomial, curved parts)
        or ``"center"``.
    clip_band : narrow an explicit band to the resolvable range instead of raising.
    min_defined_fraction : smallest accepted share of measured points (default 0: dropouts
        are filled and excluded from the statistics; the analysis is refused only when
        fewer than ``MIN_SUMMITS`` summits remain, see the module docstring).
    name : label (default: the file name, or "surface").
    channel, physical_sizes, unit : passed to :func:`read_topography`.

    Returns
    -------
    SurfaceAnalysis: σ, Ssk, Sku; η, β by summits and by McCool's spectral moments, with
    band, sampling, warnings and notes. ``.to_roughness(method)`` gives tribodyn's
    ``Roughness``. A line scan (profile) gives a :class:`ProfileAnalysis` instead
    (:func:`~tribodyn.topography.profile.analyse_profile`).

    The 8-neighbour summit estimates match the continuous-surface (McCool) values only if
    the shortest filtered wavelength spans many pixels (≳ 16); see the notes.
    """
    src = None
    if isinstance(source, (str, Path)):
        topo = read_topography(source, channel=channel, physical_sizes=physical_sizes, unit=unit)
        src = topo.info.get("source")
        name = Path(source).name if name is None else name
    else:
        topo = source
        name = "surface" if name is None else name
    filtering: dict[str, Any] = dict(
        kind=kind, detrend=detrend, clip_band=clip_band, min_defined_fraction=min_defined_fraction
    )
    if topo.dim == 1:
        from .profile import analyse_profile

        return analyse_profile(topo, band, name=name, source=src, **filtering)
    filtered, applied, sampling, filled = prepare_topography(topo, band, **filtering)
    return analyse_filtered(filtered, applied, sampling, name=name, source=src, filled=filled)


def _same_band(a: Band, b: Band) -> bool:
    """Equal bands, up to rounding of the pixel sizes the clipping used (1e-6)."""
    if a.kind != b.kind:
        return False
    pairs = ((a.short_wavelength, b.short_wavelength), (a.long_wavelength, b.long_wavelength))
    return all(
        x == y or (x is not None and y is not None and abs(x / y - 1.0) < 1e-6) for x, y in pairs
    )


def composite_roughness(
    first: SurfaceAnalysis | ProfileAnalysis, second: SurfaceAnalysis | ProfileAnalysis
) -> PairAnalysis:
    """Composite (equivalent-surface) parameters of a pair of analysed surfaces (areal
    maps, or a profile with its isotropic-surface estimates)."""
    from SurfaceTopography import Topography

    moments = first.moments + second.moments  # independent surfaces: moments add
    notes = []
    if not _same_band(first.band, second.band):
        notes.append("the two surfaces were filtered with different bands")
    summit_stats = sum_stats = sum_surface = sum_gaussian = None
    ta, tb = first.topography, second.topography
    if ta is None or tb is None:
        notes.append(
            "no composite summit analysis: a profile has no summits (the spectral "
            "composite is an isotropic-surface estimate)"
        )
    elif (
        combined := sum_on_common_grid(
            ta.heights(), ta.pixel_size, ta.is_periodic, tb.heights(), tb.pixel_size, tb.is_periodic
        )
    ) is None:
        notes.append(
            "no composite summit analysis: the maps have different pixel sizes "
            "(the spectral composite is used)"
        )
    else:
        h, (dx, dy), periodic = combined
        nx, ny = h.shape
        t = Topography(h, (nx * dx, ny * dy), periodic=periodic, unit="m")
        filled = np.zeros((nx, ny), dtype=bool)
        for r in (first, second):
            if r.filled is not None:
                filled |= np.asarray(r.filled)[:nx, :ny]
        sum_surface = h[~filled]
        sum_stats = height_statistics(sum_surface)
        sum_gaussian = gaussian_reference(sum_surface, sum_stats)
        band = max((first.band, second.band), key=lambda b: b.short_wavelength or 0.0)
        _, summit_stats = _summits(t, h, band, (dx, dy), ~filled if filled.any() else None)
        if (nx, ny) != tuple(ta.nb_grid_pts) or (nx, ny) != tuple(tb.nb_grid_pts):
            notes.append(f"sum surface h₁ + h₂ on the common {nx} × {ny} grid")
    pair = PairAnalysis(
        first=first,
        second=second,
        moments=moments,
        mccool=mccool_parameters(moments),
        summit_stats=summit_stats,
        sum_heights=sum_stats,
        notes=(),
        sum_surface=sum_surface,
        sum_gaussian=sum_gaussian,
    )
    if pair.summits is not None:
        _note_deviation(notes, pair.summits, pair.spectral, "composite ")
    return replace(pair, notes=tuple(notes))


def analyse_pair(
    first: PathLike | Any, second: PathLike | Any, band: BandSpec = AUTO_BAND, **kwargs: Any
) -> PairAnalysis:
    """Analyse two surfaces (e.g. cam and tappet) with the same settings and combine them.

    ``first``/``second``: file names or ``Topography`` objects; other arguments as
    :func:`analyse_surface` (``name`` is not accepted; file names label the surfaces).
    """
    a, b = (
        analyse_surface(s, band, **kwargs, name=None if isinstance(s, (str, Path)) else label)
        for s, label in ((first, "surface 1"), (second, "surface 2"))
    )
    return composite_roughness(a, b)

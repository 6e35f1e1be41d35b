"""Preparation of a measured topography: fill, level, band-pass filter.

Order of operations (each a SurfaceTopography pipeline step):

1. undefined points (dropouts: optical profilers lose pixels on steep or dark spots, often
   25–30 % of a scan) are filled with the harmonic interpolant
   (``interpolate_undefined_data("harmonic")``): inside each hole h solves Laplace's
   equation ∇²h = 0 with the measured heights around the hole as boundary values. It is
   the smoothest continuation (least ∫|∇h|²) and, by the maximum principle, has no
   interior extrema: a filled hole adds no summits and no curvature. The filled points are
   returned as a mask, so that the statistics are taken over measured points only
   (``analysis``); the share filled is reported (``Sampling.undefined_fraction``);
2. level: subtract the least-squares plane (``detrend("height")``) or second-order
   polynomial (``"curvature"``, for curved parts such as a cam flank); periodic
   (synthetic) maps only have their mean removed;
3. band-pass filter by wavelength λ, isotropic in the plane (q = 2π/λ = |q|):

   - ``"gaussian"`` (default): areal Gaussian filters with 50 % transmission at the cutoffs
     (ISO 16610-61 weighting, α = √(ln 2/π)); transfer function
     H(q) = exp(−ln2 (q/q_s)²) · [1 − exp(−ln2 (q/q_L)²)], q_s = 2π/λ_s, q_L = 2π/λ_L;
   - ``"step"``: ideal band-pass, H = 1 for q_L ≤ q ≤ q_s, else 0 (``shortcut``/``longcut``).

   Fourier filtering assumes periodic data. Non-periodic measurements are mirror-stitched
   (``mirror_stitch``: 2N_x × 2N_y, continuous heights across the seams), filtered and
   cropped back, which avoids the wrap-around jump of the raw data.

A band given explicitly must lie inside what the measurement resolves: λ_s ≥ 2Δ (Nyquist
wavelength of the coarser pixel direction, or the instrument's reliability cutoff if the
file states one) and λ_L ≤ min(L_x, L_y). Otherwise :class:`BandLimitError` is raised,
unless ``clip_band=True``, which narrows the band to the resolvable range and records it.

The default band (``band="auto"``, :data:`TYPICAL_BAND`) is the standard roughness band
of a ground surface, λ_s = 2.5 µm and λ_c = 0.8 mm (ISO 3274, ISO 4288:
:data:`~tribodyn.physics.typical.FILTER_SHORT_WAVELENGTH`, ``FILTER_LONG_WAVELENGTH``),
clipped to the measurement: λ_s = max(2.5 µm, 2Δ, reliability cutoff) and
λ_L = min(0.8 mm, min(L_x, L_y) − 2λ_s), i.e. at most the length that remains after the
analysis drops one λ_s along each edge (filter end effects, see
``analysis_margin``). Optical maps (fields of 10–70 µm) hold far less than
0.8 mm, so the band actually used is reported with a warning. Andreou et al. (2023)
filtered 0.25–250 µm: pass ``band=tribodyn.paper.TOPOGRAPHY_BAND`` (with ``clip_band``)
to reproduce their analysis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from .._validation import InputError, check_positive, check_range
from ..physics import typical
from .errors import BandLimitError, InsufficientDataError, TopographyError

__all__ = [
    "MAX_MAP_POINTS",
    "check_map_size",
    "TYPICAL_BAND",
    "AUTO_BAND",
    "FILTER_KINDS",
    "DETREND_MODES",
    "Band",
    "Sampling",
    "check_band",
    "check_filtering",
    "analysis_margin",
    "applied_band",
    "default_band",
    "band_pass",
    "prepare_topography",
]

#: Typical roughness band (λ_s, λ_c) [m] of a ground surface (module docstring).
TYPICAL_BAND = (typical.FILTER_SHORT_WAVELENGTH.value, typical.FILTER_LONG_WAVELENGTH.value)
#: ``band`` value that selects the typical band clipped to the measurement
AUTO_BAND = "auto"
#: A band as the API takes it: "auto", (λ_s, λ_L) [m], or None (level only).
BandSpec = tuple[float, float] | str | None
#: The default band must keep λ_L ≥ this × λ_s (else the field is too small for it)
MIN_BAND_RATIO = 4.0
FILTER_KINDS = ("gaussian", "step")
DETREND_MODES = ("height", "curvature", "center")
#: Smallest map accepted (grid points per side).
MIN_GRID_PTS = 16
#: Largest map accepted (grid points in all, 4096 × 4096): the analysis holds about ten
#: arrays of the map's size (filters, spectral derivatives), ~2 GB and ~30 s at this
#: size; a larger scan is cropped or subsampled first (instrument software, Gwyddion).
MAX_MAP_POINTS = 4096 * 4096


def check_map_size(shape, what: str = "the map") -> None:
    """A map (or profile) of more than :data:`MAX_MAP_POINTS` points is refused with
    :class:`~.errors.TopographyError` saying what to do."""
    n = math.prod(int(k) for k in shape)
    if n > MAX_MAP_POINTS:
        dims = " × ".join(str(int(k)) for k in shape)
        raise TopographyError(
            f"{what} has {dims} = {n} points, more than the {MAX_MAP_POINTS} "
            "the analysis handles in memory; crop it or subsample it "
            "(e.g. every second point in each direction) before the analysis"
        )


_LN2 = math.log(2.0)


@dataclass(frozen=True)
class Sampling:
    """Sampling of a topography map (two axes) or a profile (one axis), lengths in m:
    what the band checks read. ``undefined_fraction`` is the share of points that were
    undefined in the file and filled before the analysis."""

    nb_grid_pts: tuple[int, ...]
    pixel_size: tuple[float, ...]
    physical_sizes: tuple[float, ...]
    periodic: bool = False
    undefined_fraction: float = 0.0

    UNITS = {"pixel_size": "m", "physical_sizes": "m"}

    @classmethod
    def of(cls, topography, undefined_fraction: float = 0.0) -> Sampling:
        """The sampling of a SurfaceTopography map (lengths in m)."""
        return cls(
            tuple(int(k) for k in topography.nb_grid_pts),
            tuple(float(d) for d in topography.pixel_size),
            tuple(float(length) for length in topography.physical_sizes),
            bool(topography.is_periodic),
            float(undefined_fraction),
        )

    @property
    def nyquist_wavelength(self) -> float:
        """2·max(Δx, Δy): shortest wavelength resolved in every direction [m]."""
        return 2.0 * max(self.pixel_size)

    @property
    def longest_wavelength(self) -> float:
        """min(L_x, L_y): longest wavelength contained in every direction [m]."""
        return min(self.physical_sizes)

    def _layout(self) -> str:
        """Points, spacing and extent, in words."""
        if len(self.nb_grid_pts) == 1:
            return (
                f"profile of {self.nb_grid_pts[0]} points, spacing {_um(self.pixel_size[0])} "
                f"µm, length {_um(self.physical_sizes[0])} µm"
            )
        (nx, ny), (dx, dy), (lx, ly) = self.nb_grid_pts, self.pixel_size, self.physical_sizes
        return (
            f"{nx} × {ny} points, pixel {_um(dx)} × {_um(dy)} µm, "
            f"area {_um(lx)} × {_um(ly)} µm, {'periodic' if self.periodic else 'non-periodic'}"
        )

    def describe(self) -> str:
        """The layout, with the share of filled points if any."""
        text = self._layout()
        if self.undefined_fraction > 0:
            text += f", {self.undefined_fraction:.2%} undefined points filled"
        return text

    def to_dict(self) -> dict:
        """Points, pixel size and lengths [m], periodic, filled share."""
        return {
            "nb_grid_pts": list(self.nb_grid_pts),
            "pixel_size": list(self.pixel_size),
            "physical_sizes": list(self.physical_sizes),
            "periodic": self.periodic,
            "undefined_fraction": self.undefined_fraction,
            "units": dict(self.UNITS),
        }


@dataclass(frozen=True)
class Band:
    """Wavelength band of the band-pass filter [m]; ``kind`` "gaussian", "step" or "none".

    ``requested`` is the band asked for when it was clipped to the resolvable range.
    """

    short_wavelength: float | None
    long_wavelength: float | None
    kind: str = "gaussian"
    requested: tuple[float, float] | None = None
    reason: str = ""  #: why the band differs from the requested one

    UNITS = {"short_wavelength": "m", "long_wavelength": "m", "requested": "m"}

    @property
    def clipped(self) -> bool:
        return self.requested is not None

    @property
    def wavelengths(self) -> tuple[float, float]:
        """(λ_s, λ_L) [m]; a band of kind "none" has none (ValueError)."""
        if self.short_wavelength is None or self.long_wavelength is None:
            raise ValueError("a band of kind 'none' has no cutoff wavelengths")
        return self.short_wavelength, self.long_wavelength

    def transfer(self, q):
        """Transfer function H(|q|) of the filter (q in rad/m)."""
        q = np.asarray(q, dtype=float)
        if self.kind == "none":
            return np.ones_like(q)
        lo, hi = self.wavelengths
        qs, ql = 2.0 * np.pi / lo, 2.0 * np.pi / hi
        if self.kind == "step":
            return ((q <= qs) & (q >= ql)).astype(float)
        return np.exp(-_LN2 * (q / qs) ** 2) * -np.expm1(-_LN2 * (q / ql) ** 2)

    def describe(self) -> str:
        if self.kind == "none":
            return "no band-pass filter (levelled only)"
        kind = (
            "Gaussian, 50 % transmission at the cutoffs"
            if self.kind == "gaussian"
            else "ideal step"
        )
        lo, hi = self.wavelengths
        text = f"{_um(lo)}–{_um(hi)} µm ({kind})"
        if self.requested is not None:
            text += (
                f", clipped from the requested {_um(self.requested[0])}–"
                f"{_um(self.requested[1])} µm to the measurement's range"
            )
        return text

    def to_dict(self) -> dict:
        return {
            "short_wavelength": self.short_wavelength,
            "long_wavelength": self.long_wavelength,
            "kind": self.kind,
            "requested": list(self.requested) if self.requested else None,
            "clipped_because": self.reason or None,
            "units": dict(self.UNITS),
        }


def _um(x: float) -> str:
    return f"{x * 1e6:.4g}"


def analysis_margin(band: Band | None, pixel_size, periodic: bool) -> tuple[int, ...]:
    """Points excluded along each edge of a map (or profile) before summits (peaks) and
    moments are evaluated, one number per axis of ``pixel_size``.

    Periodic maps: none. Non-periodic maps: the curvature stencil's border (1) or, after
    band-pass filtering, one short-wavelength cutoff λ_s, the reach of the filter's end
    effects at the mirror-stitched edges (the Gaussian S-filter kernel has a standard
    deviation of 0.19 λ_s). Without the margin, summits and curvature near the edges are
    biased by O(λ_s/L).
    """
    if periodic:
        return (0,) * len(pixel_size)
    if band is None or band.kind == "none":
        return (1,) * len(pixel_size)
    return tuple(max(1, int(np.ceil(band.wavelengths[0] / p - 1e-9))) for p in pixel_size)


def input_warnings(band: Band, sampling: Sampling) -> tuple[str, ...]:
    """Warnings about what was done to the input: band clipped, dropouts filled."""
    out = []
    if band.requested is not None:
        lo, hi = band.wavelengths
        out.append(
            f"band {_um(lo)}–{_um(hi)} µm used "
            f"instead of the requested {_um(band.requested[0])}–"
            f"{_um(band.requested[1])} µm: {band.reason or 'clipped to the measurement'}"
        )
    if sampling.undefined_fraction > 0:
        out.append(
            f"{sampling.undefined_fraction:.1%} of the points were not measured "
            "(dropouts): filled by harmonic interpolation for the filter, excluded from "
            "the statistics"
        )
    return tuple(out)


def _shortest_wavelength(sampling: Sampling, reliability_cutoff: float | None) -> tuple[float, str]:
    """The shortest wavelength the measurement resolves [m] and why: its Nyquist
    wavelength 2Δ, or the instrument's reliability cutoff where that is longer."""
    if reliability_cutoff is not None and reliability_cutoff > sampling.nyquist_wavelength:
        return reliability_cutoff, (
            f"the instrument's reliability cutoff {_um(reliability_cutoff)} µm"
        )
    nyq = sampling.nyquist_wavelength
    return (
        nyq,
        f"the Nyquist wavelength 2Δ = {_um(nyq)} µm (pixel {_um(max(sampling.pixel_size))} µm)",
    )


def check_band(
    band,
    sampling: Sampling,
    *,
    kind: str = "gaussian",
    clip: bool = False,
    reliability_cutoff: float | None = None,
) -> Band:
    """Validate a band (λ_s, λ_L) [m] against the sampling; ``None`` means no filter.

    Raises :class:`BandLimitError` naming the violated limit unless ``clip`` is true.
    """
    if band is None:
        return Band(None, None, "none")
    try:
        lo, hi = band
    except (TypeError, ValueError):
        raise InputError(f"band must be (short, long) wavelengths in m (got {band!r})") from None
    lo = check_positive("band short-wavelength limit", lo, "m")
    hi = check_positive("band long-wavelength limit", hi, "m")
    if lo >= hi:
        raise BandLimitError(
            f"band limits must satisfy short < long (got {_um(lo)} µm ≥ {_um(hi)} µm)"
        )
    lo_min, why = _shortest_wavelength(sampling, reliability_cutoff)
    hi_max = sampling.longest_wavelength
    new_lo, new_hi = lo, hi
    if lo < lo_min * (1 - 1e-9):
        if not clip:
            raise BandLimitError(
                f"band short-wavelength limit {_um(lo)} µm is below {why}, the shortest "
                f"wavelength this measurement resolves; use a limit ≥ {_um(lo_min)} µm or "
                "clip the band to the measurement's range"
            )
        new_lo = lo_min
    if hi > hi_max * (1 + 1e-9):
        if not clip:
            raise BandLimitError(
                f"band long-wavelength limit {_um(hi)} µm exceeds the measured length "
                f"{_um(hi_max)} µm (shorter side of the map), the longest wavelength it "
                f"contains; use a limit ≤ {_um(hi_max)} µm or clip the band to the "
                "measurement's range"
            )
        new_hi = hi_max
    if new_lo >= new_hi:
        raise BandLimitError(
            f"no wavelengths left: the measurement resolves {_um(lo_min)}–{_um(hi_max)} µm"
        )
    clipped = (new_lo, new_hi) != (lo, hi)
    return Band(new_lo, new_hi, kind, requested=(lo, hi) if clipped else None)


def default_band(
    sampling: Sampling, *, kind: str = "gaussian", reliability_cutoff: float | None = None
) -> Band:
    """The typical band clipped to what the measurement resolves (module docstring).

    Raises :class:`InsufficientDataError` if fewer than a factor MIN_BAND_RATIO of
    wavelengths remain."""
    lo0, hi0 = TYPICAL_BAND
    lo, why_lo = lo0, ""
    lo_min, why = _shortest_wavelength(sampling, reliability_cutoff)
    if lo_min > lo:
        lo, why_lo = lo_min, f"λ_s raised to {why}"
    field = sampling.longest_wavelength
    usable = field - (0.0 if sampling.periodic else 2.0 * lo)
    hi, why_hi = hi0, ""
    if usable < hi:
        hi = usable
        why_hi = f"λ_L lowered to the field of view {_um(field)} µm" + (
            "" if sampling.periodic else f" less one λ_s at each edge ({_um(usable)} µm)"
        )
    if hi < MIN_BAND_RATIO * lo:
        raise InsufficientDataError(
            f"the measurement ({sampling.describe()}) is too small for any band: it "
            f"resolves wavelengths from {_um(lo)} µm, but its field leaves only {_um(usable)} "
            f"µm (at least {MIN_BAND_RATIO:g} × λ_s is needed)"
        )
    reason = "; ".join(t for t in (why_lo, why_hi) if t)
    return Band(lo, hi, kind, requested=TYPICAL_BAND if reason else None, reason=reason)


def band_pass(topography, band: Band):
    """Band-pass filter a gap-free, levelled map (mirror-stitched if non-periodic).

    Returns a new SurfaceTopography ``Topography`` (same grid, unit and periodicity).
    """
    from SurfaceTopography import Topography

    if band.kind == "none":
        heights = np.asarray(topography.heights(), dtype=float)
    else:
        nx, ny = topography.nb_grid_pts
        base = topography if topography.is_periodic else topography.mirror_stitch()
        if band.kind == "step":
            filtered = base.shortcut(cutoff_wavelength=band.short_wavelength).longcut(
                cutoff_wavelength=band.long_wavelength
            )
        else:
            filtered = base.filter(filter_function=band.transfer, isotropic=True)
        heights = np.asarray(filtered.heights(), dtype=float)[:nx, :ny]
    return Topography(
        np.ascontiguousarray(heights),
        tuple(topography.physical_sizes),
        periodic=bool(topography.is_periodic),
        unit=topography.unit,
        info=dict(topography.info),
    )


def check_filtering(detrend: str, min_defined_fraction: float) -> float:
    """The checks of the filtering options a map and a profile share: ``detrend`` one of
    :data:`DETREND_MODES`, ``min_defined_fraction`` in [0, 1] (returned as a float)."""
    if detrend not in DETREND_MODES:
        raise InputError(f"detrend must be one of {DETREND_MODES} (got {detrend!r})")
    return check_range("min_defined_fraction", min_defined_fraction, 0.0, 1.0)


def applied_band(
    band: BandSpec,
    sampling: Sampling,
    *,
    kind: str,
    clip: bool,
    reliability_cutoff: float | None = None,
) -> Band:
    """The band a filter applies: :func:`default_band` for ``"auto"``, else the given
    band checked against the sampling (:func:`check_band`); ``kind`` one of
    :data:`FILTER_KINDS`."""
    if kind not in FILTER_KINDS:
        raise InputError(f"filter kind must be one of {FILTER_KINDS} (got {kind!r})")
    if isinstance(band, str) and band == AUTO_BAND:
        return default_band(sampling, kind=kind, reliability_cutoff=reliability_cutoff)
    return check_band(band, sampling, kind=kind, clip=clip, reliability_cutoff=reliability_cutoff)


def prepare_topography(
    topography: Any,
    band: BandSpec = AUTO_BAND,
    *,
    kind: str = "gaussian",
    detrend: str = "height",
    clip_band: bool = False,
    min_defined_fraction: float = 0.0,
) -> tuple[Any, Band, Sampling, Any]:
    """Fill, level and band-pass filter a topography map (in m).

    Parameters
    ----------
    topography : SurfaceTopography ``Topography`` in metres (see ``read_topography``).
    band : ``"auto"`` (default: the typical 2.5 µm–0.8 mm clipped to the measurement,
        see the module docstring), (λ_s, λ_L) [m] (must fit, see ``clip_band``) or ``None``
        (level only).
    kind : ``"gaussian"`` (default) or ``"step"``, see the module docstring.
    detrend : ``"height"`` (plane, default), ``"curvature"`` (2nd-order polynomial) or
        ``"center"`` (mean only). Periodic maps always use ``"center"``.
    clip_band : narrow an explicit band that exceeds the resolvable range instead of raising.
    min_defined_fraction : smallest accepted share of measured points (default 0: any
        share; whether enough is left for summits is decided by the analysis).

    Returns
    -------
    (filtered Topography, Band actually applied, Sampling of the input, boolean mask of
    the filled (unmeasured) points)
    """
    if topography.dim != 2:
        raise InsufficientDataError("an areal (2-D) map is needed to identify summits")
    if topography.unit not in ("m", None):
        topography = topography.to_unit("m")
    min_defined_fraction = check_filtering(detrend, min_defined_fraction)
    nx, ny = topography.nb_grid_pts
    check_map_size((nx, ny))
    if min(nx, ny) < MIN_GRID_PTS:
        raise InsufficientDataError(
            f"the map has {nx} × {ny} points; at least {MIN_GRID_PTS} per side are needed"
        )
    heights = topography.heights()
    filled = np.ma.getmaskarray(heights) | ~np.isfinite(np.ma.getdata(heights))
    n_total = nx * ny
    n_defined = n_total - int(filled.sum())
    fraction = n_defined / n_total
    if fraction < min_defined_fraction or n_defined < MIN_GRID_PTS**2:
        raise InsufficientDataError(
            f"only {n_defined} of {n_total} points ({fraction:.1%}) are measured; at least "
            f"{min_defined_fraction:.0%} (and {MIN_GRID_PTS**2} points) are required"
        )
    sampling = Sampling.of(topography, undefined_fraction=1.0 - fraction)
    try:
        reliability = topography.short_reliability_cutoff()
    except Exception:  # instrument metadata incomplete: no cutoff
        reliability = None
    applied = applied_band(
        band, sampling, kind=kind, clip=clip_band, reliability_cutoff=reliability
    )

    if n_defined < n_total:
        from SurfaceTopography import Topography

        h = np.ma.masked_array(np.ma.getdata(heights), mask=filled)
        topography = Topography(
            h,
            topography.physical_sizes,
            periodic=topography.is_periodic,
            unit=topography.unit,
            info=dict(topography.info),
        )
        topography = topography.interpolate_undefined_data("harmonic")
    topography = topography.detrend(detrend_mode="center" if topography.is_periodic else detrend)
    return band_pass(topography, applied), applied, sampling, filled

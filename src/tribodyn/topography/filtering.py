"""Preparation of a measured topography: fill, level, band-pass filter.

Order of operations (each a SurfaceTopography pipeline step):

1. check the share of defined points (optical profilers drop pixels on steep or dark spots);
2. fill undefined points with harmonic functions (``interpolate_undefined_data``);
3. level: subtract the least-squares plane (``detrend("height")``) or second-order
   polynomial (``"curvature"``, for curved parts such as a cam flank); periodic
   (synthetic) maps only have their mean removed;
4. band-pass filter by wavelength λ, isotropic in the plane (q = 2π/λ = |q|):

   - ``"gaussian"`` (default): areal Gaussian filters with 50 % transmission at the cutoffs
     (ISO 16610-61 weighting, α = √(ln 2/π)); transfer function
     H(q) = exp(−ln2 (q/q_s)²) · [1 − exp(−ln2 (q/q_L)²)], q_s = 2π/λ_s, q_L = 2π/λ_L;
   - ``"step"``: ideal band-pass, H = 1 for q_L ≤ q ≤ q_s, else 0 (``shortcut``/``longcut``).

   Fourier filtering assumes periodic data. Non-periodic measurements are mirror-stitched
   (``mirror_stitch``: 2N_x × 2N_y, continuous heights across the seams), filtered and
   cropped back, which avoids the wrap-around jump of the raw data.

The band must lie inside what the measurement resolves: λ_s ≥ 2Δ (Nyquist wavelength of
the coarser pixel direction, or the instrument's reliability cutoff if the file states one)
and λ_L ≤ min(L_x, L_y). Otherwise :class:`BandLimitError` is raised, unless
``clip_band=True``, which narrows the band to the resolvable range and records it.
Note the paper's band (0.25–250 µm) with its 50× objective (Δ = 0.099 µm, ≈ 2985 µm²
scanned, i.e. ≈ 55 µm square): the 250 µm limit exceeds the scan and has no effect there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validation import InputError, check_positive, check_range
from .errors import BandLimitError, InsufficientDataError

__all__ = ["PAPER_BAND", "FILTER_KINDS", "DETREND_MODES", "Band", "Sampling", "check_band",
           "band_pass", "prepare_topography"]

#: Band of the paper (Section 2.2): wavelengths 0.25 µm to 250 µm [m].
PAPER_BAND = (0.25e-6, 250e-6)
FILTER_KINDS = ("gaussian", "step")
DETREND_MODES = ("height", "curvature", "center")
#: Smallest map accepted (grid points per side).
MIN_GRID_PTS = 16
_LN2 = math.log(2.0)


@dataclass(frozen=True)
class Sampling:
    """Sampling of a topography map. Lengths in m.

    ``undefined_fraction`` is the share of points that were undefined in the file and
    filled before the analysis.
    """

    nb_grid_pts: tuple[int, int]
    pixel_size: tuple[float, float]
    physical_sizes: tuple[float, float]
    periodic: bool
    undefined_fraction: float = 0.0

    UNITS = {"pixel_size": "m", "physical_sizes": "m"}

    @classmethod
    def of(cls, topography, undefined_fraction: float = 0.0) -> "Sampling":
        return cls(tuple(int(n) for n in topography.nb_grid_pts),
                   tuple(float(p) for p in topography.pixel_size),
                   tuple(float(s) for s in topography.physical_sizes),
                   bool(topography.is_periodic), float(undefined_fraction))

    @property
    def nyquist_wavelength(self) -> float:
        """2·max(Δx, Δy): shortest wavelength resolved in every direction [m]."""
        return 2.0 * max(self.pixel_size)

    @property
    def longest_wavelength(self) -> float:
        """min(L_x, L_y): longest wavelength contained in every direction [m]."""
        return min(self.physical_sizes)

    def describe(self) -> str:
        (nx, ny), (dx, dy), (lx, ly) = self.nb_grid_pts, self.pixel_size, self.physical_sizes
        text = (f"{nx} × {ny} points, pixel {_um(dx)} × {_um(dy)} µm, "
                f"area {_um(lx)} × {_um(ly)} µm, {'periodic' if self.periodic else 'non-periodic'}")
        if self.undefined_fraction > 0:
            text += f", {self.undefined_fraction:.2%} undefined points filled"
        return text

    def to_dict(self) -> dict:
        return {"nb_grid_pts": list(self.nb_grid_pts), "pixel_size": list(self.pixel_size),
                "physical_sizes": list(self.physical_sizes), "periodic": self.periodic,
                "undefined_fraction": self.undefined_fraction, "units": dict(self.UNITS)}


@dataclass(frozen=True)
class Band:
    """Wavelength band of the band-pass filter [m]; ``kind`` "gaussian", "step" or "none".

    ``requested`` is the band asked for when it was clipped to the resolvable range.
    """

    short_wavelength: float | None
    long_wavelength: float | None
    kind: str = "gaussian"
    requested: tuple[float, float] | None = None

    UNITS = {"short_wavelength": "m", "long_wavelength": "m", "requested": "m"}

    @property
    def clipped(self) -> bool:
        return self.requested is not None

    def transfer(self, q):
        """Transfer function H(|q|) of the filter (q in rad/m)."""
        q = np.asarray(q, dtype=float)
        if self.kind == "none":
            return np.ones_like(q)
        qs, ql = 2.0 * np.pi / self.short_wavelength, 2.0 * np.pi / self.long_wavelength
        if self.kind == "step":
            return ((q <= qs) & (q >= ql)).astype(float)
        return np.exp(-_LN2 * (q / qs) ** 2) * -np.expm1(-_LN2 * (q / ql) ** 2)

    def describe(self) -> str:
        if self.kind == "none":
            return "no band-pass filter (levelled only)"
        kind = ("Gaussian, 50 % transmission at the cutoffs" if self.kind == "gaussian"
                else "ideal step")
        text = f"{_um(self.short_wavelength)}–{_um(self.long_wavelength)} µm ({kind})"
        if self.clipped:
            text += (f", clipped from the requested {_um(self.requested[0])}–"
                     f"{_um(self.requested[1])} µm to the measurement's range")
        return text

    def to_dict(self) -> dict:
        return {"short_wavelength": self.short_wavelength, "long_wavelength": self.long_wavelength,
                "kind": self.kind, "requested": list(self.requested) if self.requested else None,
                "units": dict(self.UNITS)}


def _um(x: float) -> str:
    return f"{x * 1e6:.4g}"


def check_band(band, sampling: Sampling, *, kind: str = "gaussian", clip: bool = False,
               reliability_cutoff: float | None = None) -> Band:
    """Validate a band (λ_s, λ_L) [m] against the sampling; ``None`` means no filter.

    Raises :class:`BandLimitError` naming the violated limit unless ``clip`` is true.
    """
    if kind not in FILTER_KINDS:
        raise InputError(f"filter kind must be one of {FILTER_KINDS} (got {kind!r})")
    if band is None:
        return Band(None, None, "none")
    try:
        lo, hi = band
    except (TypeError, ValueError):
        raise InputError(f"band must be (short, long) wavelengths in m (got {band!r})") from None
    lo = check_positive("band short-wavelength limit", lo, "m")
    hi = check_positive("band long-wavelength limit", hi, "m")
    if lo >= hi:
        raise BandLimitError(f"band limits must satisfy short < long (got {_um(lo)} µm ≥ "
                             f"{_um(hi)} µm)")
    lo_min, why = sampling.nyquist_wavelength, (
        f"the Nyquist wavelength 2Δ = {_um(sampling.nyquist_wavelength)} µm "
        f"(pixel {_um(max(sampling.pixel_size))} µm)")
    if reliability_cutoff is not None and reliability_cutoff > lo_min:
        lo_min, why = reliability_cutoff, (f"the instrument's reliability cutoff "
                                           f"{_um(reliability_cutoff)} µm")
    hi_max = sampling.longest_wavelength
    new_lo, new_hi = lo, hi
    if lo < lo_min * (1 - 1e-9):
        if not clip:
            raise BandLimitError(
                f"band short-wavelength limit {_um(lo)} µm is below {why}, the shortest "
                f"wavelength this measurement resolves; use a limit ≥ {_um(lo_min)} µm or "
                "clip the band to the measurement's range")
        new_lo = lo_min
    if hi > hi_max * (1 + 1e-9):
        if not clip:
            raise BandLimitError(
                f"band long-wavelength limit {_um(hi)} µm exceeds the measured length "
                f"{_um(hi_max)} µm (shorter side of the map), the longest wavelength it "
                f"contains; use a limit ≤ {_um(hi_max)} µm or clip the band to the "
                "measurement's range")
        new_hi = hi_max
    if new_lo >= new_hi:
        raise BandLimitError(f"no wavelengths left: the measurement resolves "
                             f"{_um(lo_min)}–{_um(hi_max)} µm")
    clipped = (new_lo, new_hi) != (lo, hi)
    return Band(new_lo, new_hi, kind, requested=(lo, hi) if clipped else None)


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
            filtered = (base.shortcut(cutoff_wavelength=band.short_wavelength)
                        .longcut(cutoff_wavelength=band.long_wavelength))
        else:
            filtered = base.filter(filter_function=band.transfer, isotropic=True)
        heights = np.asarray(filtered.heights(), dtype=float)[:nx, :ny]
    return Topography(np.ascontiguousarray(heights), tuple(topography.physical_sizes),
                      periodic=bool(topography.is_periodic), unit=topography.unit,
                      info=dict(topography.info))


def prepare_topography(topography, band=PAPER_BAND, *, kind: str = "gaussian",
                       detrend: str = "height", clip_band: bool = False,
                       min_defined_fraction: float = 0.9):
    """Fill, level and band-pass filter a topography map (in m).

    Parameters
    ----------
    topography : SurfaceTopography ``Topography`` in metres (see ``read_topography``).
    band : (λ_s, λ_L) [m] or ``None`` (level only). Default: the paper's 0.25–250 µm.
    kind : ``"gaussian"`` (default) or ``"step"``, see the module docstring.
    detrend : ``"height"`` (plane, default), ``"curvature"`` (2nd-order polynomial) or
        ``"center"`` (mean only). Periodic maps always use ``"center"``.
    clip_band : narrow a band that exceeds the resolvable range instead of raising.
    min_defined_fraction : smallest accepted share of defined points (default 0.9).

    Returns
    -------
    (filtered Topography, Band actually applied, Sampling of the input)
    """
    if topography.dim != 2:
        raise InsufficientDataError("an areal (2-D) map is needed to identify summits")
    if topography.unit not in ("m", None):
        topography = topography.to_unit("m")
    min_defined_fraction = check_range("min_defined_fraction", min_defined_fraction, 0.0, 1.0)
    if detrend not in DETREND_MODES:
        raise InputError(f"detrend must be one of {DETREND_MODES} (got {detrend!r})")
    nx, ny = topography.nb_grid_pts
    if min(nx, ny) < MIN_GRID_PTS:
        raise InsufficientDataError(f"the map has {nx} × {ny} points; at least "
                                    f"{MIN_GRID_PTS} per side are needed")
    heights = topography.heights()
    n_total = nx * ny
    n_defined = int(np.ma.count(heights))
    fraction = n_defined / n_total
    if fraction < min_defined_fraction or n_defined < MIN_GRID_PTS**2:
        raise InsufficientDataError(
            f"only {n_defined} of {n_total} points ({fraction:.1%}) are defined; at least "
            f"{min_defined_fraction:.0%} (and {MIN_GRID_PTS**2} points) are required")
    sampling = Sampling.of(topography, undefined_fraction=1.0 - fraction)
    try:
        reliability = topography.short_reliability_cutoff()
    except Exception:  # instrument metadata incomplete: no cutoff
        reliability = None
    applied = check_band(band, sampling, kind=kind, clip=clip_band, reliability_cutoff=reliability)

    if n_defined < n_total:
        topography = topography.interpolate_undefined_data("harmonic")
    topography = topography.detrend(detrend_mode="center" if topography.is_periodic else detrend)
    return band_pass(topography, applied), applied, sampling

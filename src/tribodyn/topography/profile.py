"""Line scans (profiles): what a single profile can give.

A stylus profilometer records h(x) along one line. After levelling and the same Gaussian
band-pass as for areal maps (1-D, transfer function of :class:`~.filtering.Band`, the
profile mirrored at its ends), a profile gives

* σ = Rq, Rsk, Rku of the heights (ISO 4287);
* the profile spectral moments m0 = ⟨h²⟩ [m²], m2 = ⟨h'²⟩ [-], m4 = ⟨h''²⟩ [1/m²],
  with spectral derivatives of the filtered profile averaged over the analysed interior
  (Nayak 1971), and the bandwidth α = m0 m4/m2²;
* the density of profile peaks, counted (points higher than both neighbours) and, for a
  Gaussian profile, (1/2π)√(m4/m2) (Longuet-Higgins 1957; Nayak 1971, Eq. 21);
* **for an isotropic surface only**, the areal Greenwood–Williamson parameters from the
  profile moments, η = m4/(6π√3 m2) and β = 0.375√(π/m4) (McCool 1986; Nayak 1971): an
  isotropic surface's profiles in every direction have the direction-averaged moments
  used by :mod:`.spectral_moments`. A profile across the lay of a ground, honed or turned
  surface does not describe the other direction, and the estimate is then wrong; the
  result is labelled as an isotropic estimate everywhere it appears.

Undefined points are filled by linear interpolation (the 1-D harmonic interpolant, as for
maps) and excluded, with their neighbours, from the statistics. The analysis is refused
when fewer than ``MIN_PEAKS`` = 25 peaks remain (the count's standard error 1/√N would
exceed 20 %).

Sources: M. S. Longuet-Higgins, Phil. Trans. R. Soc. A 249 (1957) 321–387; P. R. Nayak,
J. Lubr. Technol. 93 (1971) 398–407; J. I. McCool, Wear 107 (1986) 37–60.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from .errors import InsufficientDataError
from .filtering import (
    AUTO_BAND,
    Band,
    BandSpec,
    Sampling,
    analysis_margin,
    applied_band,
    check_filtering,
    check_map_size,
    input_warnings,
)
from .height_statistics import gaussian_reference, height_statistics
from .results import ISOTROPIC_LABEL, ProfileAnalysis
from .spectral_moments import SpectralMoments, mccool_parameters

__all__ = ["ProfileAnalysis", "analyse_profile", "MIN_PEAKS", "ISOTROPIC_LABEL"]

#: Fewest peaks (measured interior) for a meaningful analysis.
MIN_PEAKS = 25
#: Smallest profile [points].
MIN_POINTS = 32


def _filter_profile(h: np.ndarray, dx: float, band: Band, periodic: bool) -> tuple:
    """(h, h', h'') of the band-pass filtered profile, derivatives spectral (exact for the
    band-limited profile). A non-periodic profile is mirrored at its ends (an even
    extension of length 2n, so the FFT sees no jump)."""
    n = h.size
    ext = h if periodic else np.concatenate([h, h[::-1]])
    m = ext.size
    q = 2.0 * np.pi * np.fft.rfftfreq(m, d=dx)
    spec = np.fft.rfft(ext) * band.transfer(q)
    return tuple(np.fft.irfft(spec * f, m)[:n] for f in (1.0, 1j * q, -q * q))


def analyse_profile(
    line: Any,
    band: BandSpec = AUTO_BAND,
    *,
    kind: str = "gaussian",
    detrend: str = "height",
    clip_band: bool = False,
    min_defined_fraction: float = 0.0,
    name: str | None = None,
    source: dict | None = None,
) -> ProfileAnalysis:
    """Roughness of a line scan (SurfaceTopography ``UniformLineScan`` in m, or any
    object with ``heights()``, ``pixel_size`` and ``physical_sizes``); arguments as
    :func:`~tribodyn.topography.analyse_surface` (``detrend``: "height" removes a line,
    "curvature" a parabola, "center" the mean)."""
    name = "profile" if name is None else name
    if getattr(line, "unit", "m") not in ("m", None):
        line = line.to_unit("m")
    min_defined_fraction = check_filtering(detrend, min_defined_fraction)
    raw = line.heights()
    check_map_size(np.shape(raw), "the profile")
    h = np.asarray(np.ma.getdata(raw), dtype=float).ravel()
    filled = np.ma.getmaskarray(raw).ravel() | ~np.isfinite(h)
    n = h.size
    dx = float(np.ravel(line.pixel_size)[0])
    periodic = bool(getattr(line, "is_periodic", False))
    if n < MIN_POINTS:
        raise InsufficientDataError(f"the profile has {n} points; at least {MIN_POINTS} are needed")
    measured = ~filled
    share = measured.mean()
    if share < min_defined_fraction or measured.sum() < MIN_POINTS:
        raise InsufficientDataError(
            f"only {int(measured.sum())} of {n} points ({share:.1%}) are measured"
        )
    sampling = Sampling((n,), (dx,), (n * dx,), periodic, float(1.0 - share))
    applied = applied_band(band, sampling, kind=kind, clip=clip_band)
    x = np.arange(n) * dx
    if filled.any():  # 1-D harmonic interpolation = linear
        h = h.copy()
        h[filled] = np.interp(x[filled], x[measured], h[measured])
    deg = 0 if periodic else {"height": 1, "curvature": 2, "center": 0}[detrend]
    h = h - np.polyval(np.polyfit(x[measured], h[measured], deg), x)
    if applied.kind == "none" and not periodic:  # unfiltered: finite differences
        hf = h
        d1, d2 = np.gradient(h, dx), np.gradient(np.gradient(h, dx), dx)
    else:
        hf, d1, d2 = _filter_profile(h, dx, applied, periodic)
    (margin,) = analysis_margin(applied, (dx,), periodic)
    region = np.zeros(n, dtype=bool)
    region[margin : n - margin] = True
    ok = measured & np.roll(measured, 1) & np.roll(measured, -1)  # with measured neighbours
    region &= ok
    if region.sum() < MIN_POINTS:
        raise InsufficientDataError(
            f"the profile ({sampling.describe()}) is too short for "
            f"the band: {int(region.sum())} points remain inside"
        )
    hstats = height_statistics(hf[measured])
    m0 = float(np.var(hf[measured]))
    m2 = float(np.mean(d1[region] ** 2))
    m4 = float(np.mean(d2[region] ** 2))
    left, right = (np.roll(hf, 1), np.roll(hf, -1))
    peaks = (hf > left) & (hf > right)
    if not periodic:
        peaks[[0, -1]] = False
    count = int((peaks & region).sum())
    if count < MIN_PEAKS:
        raise InsufficientDataError(
            f"only {count} peaks on the measured interior of the profile: at least "
            f"{MIN_PEAKS} are needed (standard error ≈ 1/√N); use a longer profile, fewer "
            "dropouts or a shorter band"
        )
    length = float(region.sum()) * dx
    moments = SpectralMoments(m0, m2, m4)
    iso = mccool_parameters(moments)
    result = ProfileAnalysis(
        name=name,
        sampling=sampling,
        band=applied,
        heights=hstats,
        moments=moments,
        peak_count=count,
        peak_density=count / length,
        peak_density_gaussian=math.sqrt(m4 / m2) / (2.0 * math.pi),
        isotropic=iso,
        source=source,
        profile=hf,
        filled=filled if filled.any() else None,
        gaussian=gaussian_reference(hf[measured], hstats),
    )
    return _with_profile_notes(result)


def _with_profile_notes(r: ProfileAnalysis) -> ProfileAnalysis:
    from dataclasses import replace

    notes = [f"η and β are an {ISOTROPIC_LABEL}"]
    if r.band.kind != "none":
        px = r.band.wavelengths[0] / r.sampling.pixel_size[0]
        if px < 16.0 * (1 - 1e-6):
            notes.append(
                f"λ_s spans {px:.3g} points (< 16): counted peaks depend on the "
                "sampling; the moment estimates do not"
            )
    if (note := r.heights.gaussian_note("R")) is not None:
        notes.append(note)
    if r.peak_count < 200:
        notes.append(
            f"only {r.peak_count} peaks: statistical uncertainty of order "
            f"{1 / math.sqrt(r.peak_count):.0%}"
        )
    return replace(r, notes=tuple(notes), warnings=input_warnings(r.band, r.sampling))

"""Subsurface stresses of a homogeneous or coated elastic half-plane (plane strain) under
arbitrary surface pressure p(x) and shear traction q(x).

Conventions (docs/conventions.md, "Engineering outputs"): z into the body, compression
negative, q positive in +x on the body's surface, so that at z = 0 σ_zz = −p and
σ_xz = −q (Johnson, *Contact Mechanics*, 1985, §2.1); out of plane σ_yy = ν(σ_xx + σ_zz)
with each layer's own ν. The coating (E_c, ν_c, thickness h) is perfectly bonded to the
substrate (E_s, ν_s): σ_zz, σ_xz, u_x, u_z continuous at z = h — the same layered theory
as the coated compliance of :mod:`.elasticity`.

Method: the field is split into

1. the homogeneous half-plane's exact field (independent of E and ν) for the loads
   interpolated piecewise-linearly between the nodes. Line loads P (normal) and Q (+x)
   at the origin give (Flamant; Johnson Eqs. 2.15, 2.19), r² = x² + z²::

       σ_xx = −(2/π)(P x²z + Q x³)/r⁴,  σ_zz = −(2/π)(P z³ + Q x z²)/r⁴,
       σ_xz = −(2/π)(P x z² + Q x²z)/r⁴.

   A hat load of width 2Δ centred on a node gives [F(d+Δ) − 2F(d) + F(d−Δ)]/Δ with F
   the second antiderivative in x of each kernel (below, d the offset), in closed form
   (arctangents and logarithms), convolved by DC-FFT (zero padding, linear convolution:
   no periodic images);
2. the layered correction (coated − homogeneous), which is smooth, vanishes as m → 0
   (O(mh)) and decays like e^{−m d(z)} with d = 2h − z in the coating and d = z in the
   substrate. It is evaluated in Fourier space: Airy stress function per layer
   φ = f(z) e^{imx}, σ_xx = f'', σ_zz = −m² f, σ_xz = −im f', with k = |m|, s = kz,
   t = kh::

       coating    f = (A + B s) e^{−s} + (C + D (s − t)) e^{s−t}
       substrate  f = (E + F (s − t)) e^{−(s−t)}

   (every term bounded), plane-strain displacements
   u_x ∝ [(1−ν) f_ss + ν f]/G, u_z ∝ [(1−ν) f_sss − (2−ν) f_s]/G, a 6×6 real system per
   wavenumber (two surface conditions, four interface conditions). The loads'
   piecewise-linear spectrum is P_DFT(m) Δ sinc²(mΔ/2); the field at the nodes then is
   the DFT of Σ_k T(m + 2πk/Δ) sinc²((m + 2πk/Δ)Δ/2) (aliases summed until
   m d(z) ≥ 40, so exact for the interpolated loads up to e^{−40}). The periodic
   domain is the 2N zero-padded grid: the correction kernel decays like h/x², its images
   from ≥ NΔ away change the field by O(h·b/(NΔ)²) (< 10⁻⁴ p₀ in the tests).

Accuracy: exact for piecewise-linear loads at the nodes (the tests reproduce McEwen's
closed form to 10⁻⁶ p₀ on 0.02b grids and a finite-element layered model within 1–2 %);
the error is the interpolation of the loads themselves (grid spacing).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy import fft as sp_fft

from .._typing import ArrayLike
from .._validation import InputError, check_array, check_positive
from . import limits as L
from .materials import Body
from .stress_kernels import (
    _DECAY,
    _MAX_ALIAS,
    _PERIOD_H,
    _alias_sums,
    _correction_values,
    _homogeneous_transfer,
    _layer_solutions,
    _load_spectra,
    _long_wave_limits,
    _max_principal,
    _peak_search,
    _vm2_points,
    von_mises,
)

__all__ = [
    "PEAKS",
    "StressPeak",
    "SubsurfaceStress",
    "StressOperator",
    "subsurface_stress",
    "von_mises",
]

#: Largest memory of a :class:`StressOperator`'s transfer functions [bytes], checked
#: before they are allocated.
MAX_TRANSFER_BYTES = 2**29

#: The peaks of a :class:`SubsurfaceStress` (attribute names), as traced along a cycle.
PEAKS = (
    "max_von_mises_coating",
    "max_von_mises_substrate",
    "max_tension_surface",
    "max_tension_coating",
    "max_interface_shear",
    "max_interface_tension",
)


@dataclass(frozen=True)
class StressPeak:
    """A maximum of a stress measure: value [Pa] at (x, z) [m]; NaN where not defined
    (e.g. coating quantities of a homogeneous body)."""

    value: float
    x: float
    z: float


_NAN_PEAK = StressPeak(math.nan, math.nan, math.nan)


@dataclass
class SubsurfaceStress:
    """Stress field of a body under surface loads, arrays (len(depths), len(x)) [Pa].

    Peaks: von Mises in the coating (0 ≤ z ≤ h) and in the substrate (z > h; the whole
    body when homogeneous); the largest tensile principal stress on the surface and in the
    coating; at the interface z = h the largest |σ_xz| and the largest tensile σ_zz.
    Peaks are over the evaluated grid (x nodes × given depths, plus z = 0 and both
    sides of z = h, always evaluated).
    """

    x: np.ndarray
    depths: np.ndarray
    sxx: np.ndarray
    szz: np.ndarray
    sxz: np.ndarray
    syy: np.ndarray
    von_mises: np.ndarray
    surface_sxx: np.ndarray  #: σ_xx at z = 0 [Pa]
    max_von_mises_coating: StressPeak
    max_von_mises_substrate: StressPeak
    max_tension_surface: StressPeak
    max_tension_coating: StressPeak
    max_interface_shear: StressPeak
    max_interface_tension: StressPeak
    interface_sxz: np.ndarray | None = None  #: σ_xz at z = h [Pa] (coated only)
    interface_szz: np.ndarray | None = None  #: σ_zz at z = h [Pa] (coated only)

    def peaks(self) -> dict[str, StressPeak]:
        """The six peaks by name (:data:`PEAKS`)."""
        return {k: getattr(self, k) for k in PEAKS}


#: samples of :meth:`StressOperator.peaks_batch` sharing one single-precision load scale
#: (consecutive groups from the first)
SCALE_GROUP = 8

#: largest single-precision spectra of the samples that :meth:`StressOperator.peaks_batch`
#: transforms and searches together [bytes] (with their fields, a few MB: within the
#: processor's cache; the results do not depend on it)
CHUNK_BYTES = 2**20


def _group_scale(pressure: np.ndarray, traction: np.ndarray) -> np.ndarray:
    """Per sample (row) the largest |p|, |q| [Pa] of its group of :data:`SCALE_GROUP`
    consecutive rows (at least 1e-300)."""
    ns = pressure.shape[0]
    out = np.empty(ns)
    for g in range(0, ns, SCALE_GROUP):
        sl = slice(g, g + SCALE_GROUP)
        top = max(float(np.abs(pressure[sl]).max()), float(np.abs(traction[sl]).max()))
        out[sl] = max(top, 1e-300)
    return out


def _peak(values: np.ndarray, x: np.ndarray, z: np.ndarray) -> StressPeak:
    if values.size == 0:
        return _NAN_PEAK
    i = np.unravel_index(int(np.argmax(values)), values.shape)
    return StressPeak(float(values[i]), float(x[i[-1]]), float(z[i[0]]))


def _check_grid(x) -> tuple[np.ndarray, float]:
    """x as floats and its spacing; uniform within the rounding of x's own precision (a
    float32 ``linspace`` is uniform to a few of its eps times |x|)."""
    raw = np.asarray(x)
    x = check_array("x", x)
    if x.size < 3:
        raise InputError(f"x must have at least 3 nodes (got {x.size})")
    L.STRESS_NODES.check("n (nodes of x)", x.size)
    d = np.diff(x)
    dx = float(d.mean())
    eps = float(np.finfo(raw.dtype if raw.dtype.kind == "f" else float).eps)
    tol = max(1e-6 * dx, 8.0 * eps * float(np.max(np.abs(x))))
    if not np.all(d > 0.0) or np.max(np.abs(d - dx)) > tol:
        raise InputError("x must be uniformly spaced and strictly increasing [m]")
    return x, dx


class StressOperator:
    """Linear map from surface loads (p, q) on a uniform grid of ``n`` nodes, spacing
    ``dx`` [m], to the stresses at ``depths`` [m] of ``body``: built once (kernels and
    layered transfer functions), applied to many load profiles with :meth:`apply`.

    Homogeneous and coated bodies use the same path; for a homogeneous body the layered
    correction is identically zero and skipped.
    """

    def __init__(self, n: int, dx: float, body: Body, depths: ArrayLike):
        if not isinstance(body, Body):
            raise InputError(f"body must be a Body (got {type(body).__name__})")
        n = L.STRESS_NODES.check("n (nodes of x)", n)
        dx = check_positive("dx", dx, "m")
        depths = check_array("depths", depths)
        L.STRESS_DEPTHS.check("len(depths)", depths.size)
        for v in (depths.min(), depths.max()):
            L.STRESS_DEPTH.check("depths", float(v))
        self.n, self.dx, self.body = int(n), float(dx), body
        self.depths = depths
        self.h = body.coating.thickness if body.coating is not None else None
        need = self._periodic_length()
        # evaluated depths: the user's, the surface and both sides of the interface
        extra = [0.0]
        if self.h is not None:
            extra += [self.h, self.h * (1.0 + 1e-9)]
        self._z = np.concatenate([depths, extra])
        self._in_coating = (
            self._z <= self.h if self.h is not None else np.zeros(self._z.size, dtype=bool)
        )
        self._nfft = int(sp_fft.next_fast_len(need, real=True))
        self._transfer = self._build()
        self._transfer32: np.ndarray | None = None

    @property
    def transfer_bytes(self) -> int:
        """Memory of the double-precision transfer functions [bytes]."""
        return int(self._transfer.nbytes)

    def _periodic_length(self) -> int:
        """The least periodic length of the transforms: ≥ 2× the grid (zero padding) and,
        on a coated body, n + 32 h/dx (the layered correction's tail, on the scale h, then
        sees images only from ≥ 32 h away). Refused, before allocating, beyond
        ``L.STRESS_FFT_LENGTH``."""
        lim = L.STRESS_FFT_LENGTH.le
        assert lim is not None
        need = 2 * self.n
        if self.h is not None:
            need = max(need, self.n + math.ceil(_PERIOD_H * self.h / self.dx))
        if need > lim:
            if self.h is not None and 2.0 * self.n <= lim:
                fine = _PERIOD_H * self.h / (lim - self.n)
                raise InputError(
                    f"the spacing of x (dx) must be >= {fine:.3g} m for this coating ({self.h:g} m thick) and "
                    f"{self.n} nodes (got {self.dx:g}): the layered correction needs a "
                    f"periodic length of {need:.3g} nodes (at most {lim:g})"
                )
            raise InputError(
                f"n (nodes of x) must be <= {lim // 2} (got {self.n}): the transforms need "
                f"{need:.3g} nodes (at most {lim:g})"
            )
        # the transfer functions: (depths + 3) × 6 × (nfft/2 + 1) complex numbers
        size = (self.depths.size + 3) * 6 * (need / 2 + 1) * 16
        if size > MAX_TRANSFER_BYTES:
            raise InputError(
                f"len(depths) × n (nodes of x) too large: {self.depths.size} depths on "
                f"{self.n} nodes need {size / 2**30:.3g} GiB of transfer functions (at most "
                f"{MAX_TRANSFER_BYTES / 2**30:g} GiB); evaluate fewer depths or nodes"
            )
        return need

    def _build(self) -> np.ndarray:
        """Transfer (depth, 6, nfreq): DFT of the hat-load influence (homogeneous, linear
        convolution in wrap-around order) plus the aliased layered correction."""
        nfreq = self._nfft // 2 + 1
        out = np.empty((self._z.size, 6, nfreq), dtype=complex)
        for i, z in enumerate(self._z):  # homogeneous kernels (cached by n, nfft, z/Δ)
            out[i] = _homogeneous_transfer(self.n, self._nfft, float(z) / self.dx)
        if self.h is not None:
            self._add_correction(out)
        return out

    def _add_correction(self, out: np.ndarray) -> None:
        coating = self.body.coating
        assert coating is not None and self.h is not None
        h, dx, nf = float(self.h), self.dx, self._nfft
        coat, sub = coating.material, self.body.material
        j = np.arange(nf // 2 + 1)
        base = 2.0 * math.pi * j / (nf * dx)  # wavenumbers of the DFT [rad/m]
        period = 2.0 * math.pi / dx
        dist = np.where(self._z <= h, 2.0 * h - self._z, self._z)
        kmax = np.minimum(np.ceil(_DECAY / (period * np.maximum(dist, 1e-300))), _MAX_ALIAS)
        kmax = kmax.astype(int)
        K = int(kmax.max())
        aliases = np.arange(-K, K + 1)
        m = base[None, :] + period * aliases[:, None]  # (alias, freq), signed
        k = np.abs(m)
        sg = np.sign(m)
        half = 0.5 * m * dx
        with np.errstate(invalid="ignore", divide="ignore"):
            sinc2 = np.where(half == 0.0, 1.0, (np.sin(half) / np.where(half == 0, 1, half)) ** 2)
        sol = np.zeros(k.shape + (6, 2))
        pos = k > 0.0
        sol[pos] = _layer_solutions(k[pos] * h, coat, sub)
        # long-wave limit of the coating's σ_xx correction (bonded thin layer: ε_xx of the
        # coating = that of the substrate's surface), finite as m → 0: split off as
        # L e^{−2|m|h}, whose field is exact in space (homogeneous kernels at depth 2h)
        lp, lq = _long_wave_limits(coat, sub)
        cut = np.exp(-2.0 * k * h)
        hom2 = _homogeneous_transfer(self.n, nf, 2.0 * h / dx)
        lim_p = -0.5 * lp * (hom2[0] + hom2[1])
        lim_q = 0.5 * lq * (hom2[3] + hom2[4])
        slope_basis = (hom2[0] - hom2[1]) / (4.0 * h)  # transfer |m| e^{−2|m|h}
        out_hom = out.copy()  # homogeneous transfers at each depth
        k0 = np.array([1e-3, 2e-3]) / h
        sol0 = _layer_solutions(k0 * h, coat, sub)
        dm = 2.0 * math.pi / (nf * dx)
        # rows deep enough for the base band alone: only |m| d(z) < 40 matters
        jms = np.full(self._z.size, j.size)
        zero = kmax == 0
        jms[zero] = np.minimum(j.size, np.ceil(_DECAY / (dm * np.maximum(dist[zero], 1e-300))) + 1)
        side = self._z <= h
        # the remainder's even parts (p → σ_xx, σ_zz; q → σ_xz) start like c|m|, a 1/x²
        # tail that the periodic images would feel: split off c|m|e^{−2|m|h} too (slopes
        # c of every row, by side of the interface at once)
        slopes = np.zeros((self._z.size, 6))
        for sd in (True, False):
            rows = np.flatnonzero(side == sd)
            if rows.size:
                lims = (lp, -lq) if sd else (0.0, 0.0)
                r0 = self._terms(
                    sol0, k0, np.ones(2), self._z[rows], h, lims, np.exp(-2.0 * k0 * h)
                )
                for c in (0, 1, 5):
                    slopes[rows, c] = (4.0 * r0[c][:, 0] - r0[c][:, 1]).real / (2.0 * k0[0])
        out[side, 0] += lim_p  # the coating's long-wave limit, added back exactly
        out[side, 3] += lim_q
        # rows with the same side, alias count and band are evaluated together
        groups: dict = {}
        for i in range(self._z.size):
            groups.setdefault((bool(side[i]), int(kmax[i]), int(jms[i])), []).append(i)
        for (sd, kz, jm), idx in groups.items():
            rows = np.array(idx)
            zr = self._z[rows]
            sl = (slice(K - kz, K + kz + 1), slice(0, jm))
            lims = (lp, -lq) if sd else (0.0, 0.0)
            kk = k[sl][None]
            posw = np.where(pos[sl], sinc2[sl], 0.0)
            # decay depth of the split-off slope term: 2h, or z deeper down (then it decays
            # at least as fast as the correction itself, e^{−|m|z}, and the aliases suffice)
            d = np.maximum(2.0 * h, zr)
            basis = np.broadcast_to(slope_basis, (rows.size, slope_basis.size)).copy()
            deep = d > 2.0 * h
            if np.any(deep):
                hz = out_hom[rows[deep]]
                basis[deep] = (hz[:, 0] - hz[:, 1]) / (2.0 * d[deep, None])
            s = kk * zr[:, None, None]
            w = s - (k[sl] * h)[None]
            e = np.exp(-s)
            # the slope term's decay e^{−|m|d} is e^{−s} itself where d = z
            cut_d = e if np.all(d == zr) else np.exp(-kk * d[:, None, None])
            cont = np.ascontiguousarray
            sums = _alias_sums(
                cont(sol[sl]),
                cont(k[sl]),
                cont(sg[sl]),
                posw,
                cont(cut[sl]),
                s,
                w,
                e,
                np.exp(w if sd else -w),
                cut_d,
                not sd,
                np.array(lims, dtype=float),
                slopes[rows],
            )
            for c in range(6):
                if c in (0, 1, 5):
                    out[rows, c] += slopes[rows, c][:, None] * basis
                    out[rows, c, :jm] += sums[:, c]
                else:  # purely imaginary
                    out[rows, c, :jm] += 1j * sums[:, c]

    @staticmethod
    def _terms(sol, k, sg, z, h, lims, cut):
        """Correction transfers (xx_p, zz_p, xz_p, xx_q, zz_q, xz_q) at depth z, less the
        long-wave limits ``lims`` · e^{−2|m|h} of σ_xx:
        σ_xx = p f1'' − i sg q f2'';  σ_zz = −p f1 + i sg q f2;  σ_xz = −i sg p f1' − q f2'."""
        f, fs, fss = _correction_values(sol, k, z, h)
        fss = fss - np.stack([lims[0] * cut, lims[1] * cut], axis=-1)
        return (
            fss[..., 0],
            -f[..., 0],
            -1j * sg * fs[..., 0],
            -1j * sg * fss[..., 1],
            1j * sg * f[..., 1],
            -fs[..., 1],
        )

    def _fields(self, pressure, traction):
        n, nf = self.n, self._nfft
        P = sp_fft.rfft(pressure, n=nf)
        Q = sp_fft.rfft(traction, n=nf)
        T = self._transfer
        f = sp_fft.irfft(T[:, :3] * P + T[:, 3:] * Q, n=nf, axis=-1)[..., :n]
        sxx, szz, sxz = f[:, 0], f[:, 1], f[:, 2]
        nu = np.where(self._in_coating, self.body.surface.nu, self.body.material.nu)[:, None]
        syy = nu * (sxx + szz)
        return sxx, szz, sxz, syy

    def peaks(self, pressure: np.ndarray, traction: np.ndarray, x: np.ndarray) -> dict:
        """Only the peaks {name: StressPeak} of loads on the grid (float arrays of length
        n, unchecked: the fast path of a cycle evaluation)."""
        sxx, szz, sxz, syy = self._fields(pressure, traction)
        return self._peaks(sxx, szz, sxz, syy, von_mises(sxx, szz, sxz, syy), x)

    def peaks_batch(self, pressure: np.ndarray, traction: np.ndarray, x0: np.ndarray) -> dict:
        """Peaks of many load profiles at once: ``pressure``, ``traction`` (samples, n)
        on grids starting at ``x0`` (samples,) [m]. Returns {name: (value, x, z)} of
        arrays (samples,), NaN where a peak does not exist.

        Single precision (the peaks to ~1e-6 of the load, at half the cost), the loads
        scaled by the largest |p|, |q| of each group of :data:`SCALE_GROUP` samples (so
        that a sample's result does not depend on how many are passed at once); the
        fields are formed and searched by compiled loops
        (:func:`.stress_kernels._peak_search`) without storing the von Mises and
        principal-stress fields, a few samples at a time (:meth:`_chunk`), so that their
        spectra and fields stay in the processor's cache between the steps."""
        nf = self._nfft
        scale = _group_scale(pressure, traction)[:, None]
        P = sp_fft.rfft((pressure / scale).astype(np.float32), n=nf, axis=-1)
        Q = sp_fft.rfft((traction / scale).astype(np.float32), n=nf, axis=-1)
        scale = scale[:, 0]
        if self._transfer32 is None:
            self._transfer32 = self._transfer.astype(np.complex64)
        ns = pressure.shape[0]
        val = np.empty((ns, 6), dtype=np.float32)
        row = np.empty((ns, 6), dtype=np.int64)
        col = np.empty((ns, 6), dtype=np.int64)
        # (σ_xx, σ_zz, σ_xz) of every depth row at the node of the substrate's peak
        column = np.empty((ns, self._z.size, 3, 1), dtype=np.float32)
        step = self._chunk
        for c0 in range(0, ns, step):
            sl = slice(c0, c0 + step)
            val[sl], row[sl], col[sl], column[sl, ..., 0] = self._search_chunk(P[sl], Q[sl])
        _, _, rows_of = self._search_rows
        out = {}
        for k, name in enumerate(PEAKS):
            if not np.any(rows_of[k]):
                nan = np.full(ns, np.nan)
                out[name] = (nan, nan.copy(), nan.copy())
                continue
            v = val[:, k].astype(np.float64)
            zr = self._z[row[:, k]]
            if k < 2:  # von Mises: the square root of the searched square
                v = np.sqrt(v)
            if k == 1:
                v, zr = self._refine_depth(column, row[:, k], v, zr, rows_of[k])
            out[name] = (v * scale, x0 + col[:, k] * self.dx, zr)
        return out

    @cached_property
    def _search_rows(self) -> tuple:
        """ν of each evaluated depth row (single precision), the interface row (−1: none)
        and the rows of each peak of :data:`PEAKS` (boolean masks)."""
        coat, nd = self._in_coating, self.depths.size
        nu = np.where(coat, self.body.surface.nu, self.body.material.nu).astype(np.float32)
        interface = nd + 1 if self.h is not None else -1
        every = np.arange(self._z.size)
        at_interface = every == interface
        rows_of = (coat, ~coat, every == nd, coat, at_interface, at_interface)
        return nu, interface, rows_of

    @cached_property
    def _chunk(self) -> int:
        """Samples searched together by :meth:`peaks_batch`: their single-precision
        spectra (depths × 3 × (nfft/2 + 1) × 8 bytes each) within :data:`CHUNK_BYTES`."""
        per = self._z.size * 3 * (self._nfft // 2 + 1) * 8
        return max(1, CHUNK_BYTES // per)

    def _search_chunk(self, p_hat: np.ndarray, q_hat: np.ndarray) -> tuple:
        """The peaks' values (squared for von Mises), depth rows and nodes (samples, 6)
        of the load spectra ``p_hat``, ``q_hat`` (samples, nfft/2 + 1; scaled, single
        precision), and the fields (samples, depth, 3) at the node of the substrate's
        von Mises peak (for :meth:`_refine_depth`)."""
        assert self._transfer32 is not None
        g = _load_spectra(self._transfer32, p_hat, q_hat)
        f = sp_fft.irfft(g, n=self._nfft, axis=-1, overwrite_x=True)
        nu, interface, _ = self._search_rows
        val, row, col = _peak_search(f, nu, self._in_coating, self.n, self.depths.size, interface)
        return val, row, col, f[np.arange(f.shape[0]), :, :, col[:, 1]]

    def _refine_depth(self, column, row, v, zr, rows):
        """An interior maximum of the von Mises stress between depth levels (``rows``,
        geometric below the coating): the parabola in ln z through the peak's level and
        its neighbours at the peak's node (``column``: the fields (samples, depth, 3, 1)
        at that node), its vertex where it lies between them."""
        idx = np.flatnonzero(rows)
        nr = idx.size
        if nr < 3:
            return v, zr
        nu = self._search_rows[0]
        zz = self._z[idx]
        r = np.searchsorted(idx, row)
        inner = (r > 0) & (r < nr - 1) & (zz[np.clip(r - 1, 0, nr - 1)] > 0)
        rm, rp = np.clip(r - 1, 0, nr - 1), np.clip(r + 1, 0, nr - 1)
        at = np.zeros(row.size, dtype=np.int64)
        vm_ = np.sqrt(_vm2_points(column, nu, idx[rm], at).astype(np.float64))
        vp_ = np.sqrt(_vm2_points(column, nu, idx[rp], at).astype(np.float64))
        with np.errstate(divide="ignore", invalid="ignore"):
            lm = np.log(np.maximum(zz[rm], 1e-300)) - np.log(np.maximum(zr, 1e-300))
            lp = np.log(np.maximum(zz[rp], 1e-300)) - np.log(np.maximum(zr, 1e-300))
            # quadratic through (lm, vm_), (0, v), (lp, vp_)
            d1 = (vm_ - v) / lm
            d2 = (vp_ - v) / lp
            cc = (d2 - d1) / (lp - lm)
            bb = d1 - cc * lm
            s = -bb / (2.0 * cc)
            ok = inner & (cc < 0) & (s > lm) & (s < lp)
            v = np.where(ok, v - bb * bb / (4.0 * cc), v)
            zr = np.where(ok, zr * np.exp(np.where(ok, s, 0.0)), zr)
        return v, zr

    def _peaks(self, sxx, szz, sxz, syy, vm, x) -> dict:
        """The peaks {name: StressPeak} of :data:`PEAKS`: von Mises, the tensile principal
        stress, |σ_xz| and σ_zz over the rows of each (:attr:`_search_rows`)."""
        sig1 = _max_principal(sxx, szz, sxz, syy)
        searched = (vm, vm, sig1, sig1, np.abs(sxz), szz)
        _, _, rows_of = self._search_rows
        return {
            name: _peak(f[rows], x, self._z[rows])
            for name, f, rows in zip(PEAKS, searched, rows_of, strict=True)
        }

    def apply(
        self, pressure: ArrayLike, traction: ArrayLike, x: ArrayLike | None = None
    ) -> SubsurfaceStress:
        """Stresses of loads ``pressure`` p and ``traction`` q [Pa] on the grid (arrays of
        length n; ``x`` the node positions [m], default 0, Δ, 2Δ, …)."""
        p = check_array("pressure", pressure)
        q = check_array("traction", traction)
        for name, a in (("pressure", p), ("traction", q)):
            if a.size != self.n:
                raise InputError(f"{name} must have {self.n} entries like x (got {a.size})")
            L.SURFACE_LOAD.check(name, a[np.argmax(np.abs(a))])
        x = self.dx * np.arange(self.n) if x is None else np.asarray(x, dtype=float)
        sxx, szz, sxz, syy = self._fields(p, q)
        vm = von_mises(sxx, szz, sxz, syy)
        res = self._peaks(sxx, szz, sxz, syy, vm, x)
        nu_user = self.depths.size
        i0 = nu_user  # surface row
        u = slice(0, nu_user)
        return SubsurfaceStress(
            x=x,
            depths=self.depths,
            sxx=sxx[u],
            szz=szz[u],
            sxz=sxz[u],
            syy=syy[u],
            von_mises=vm[u],
            surface_sxx=sxx[i0],
            interface_sxz=sxz[nu_user + 1] if self.h is not None else None,
            interface_szz=szz[nu_user + 1] if self.h is not None else None,
            **res,
        )


def subsurface_stress(
    x: ArrayLike, pressure: ArrayLike, traction: ArrayLike, body: Body, depths: ArrayLike
) -> SubsurfaceStress:
    """Plane-strain stresses of ``body`` (homogeneous or coated) under the surface loads.

    Parameters
    ----------
    x : uniformly spaced, increasing node positions [m] (≥ 3 nodes); the loads are
        interpolated linearly between nodes and zero outside.
    pressure : p(x) [Pa], positive in compression (σ_zz = −p at z = 0).
    traction : q(x) [Pa], shear traction in +x on the body's surface (σ_xz = −q at z = 0).
    body : :class:`~tribodyn.Body`; a coating is bonded to the substrate.
    depths : depths z ≥ 0 below the surface [m]; a depth equal to the coating thickness
        is on the coating's side.

    Returns
    -------
    :class:`SubsurfaceStress`: σ_xx, σ_zz, σ_xz, σ_yy = ν(σ_xx + σ_zz), von Mises, each
    (len(depths), len(x)) [Pa], and the peaks (see the class).
    """
    xg, dx = _check_grid(x)
    p = check_array("pressure", pressure)
    q = check_array("traction", traction)
    for name, a in (("pressure", p), ("traction", q)):
        if a.shape != xg.shape:
            raise InputError(f"{name} must have the shape of x {xg.shape} (got {a.shape})")
        L.SURFACE_LOAD.check(name, a[np.argmax(np.abs(a))])
    op = StressOperator(xg.size, dx, body, depths)
    return op.apply(p, q, xg)

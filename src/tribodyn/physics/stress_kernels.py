"""Kernels of the subsurface stresses (:mod:`.stress`): the homogeneous half-plane's
closed-form hat-load kernels (Flamant, Johnson Eqs. 2.15, 2.19) and their transfer
functions, and the layered correction's Airy solutions per wavenumber (method and
sources in :mod:`.stress`).
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numba import njit
from scipy import fft as sp_fft

#: alias terms are summed until m·d(z) reaches this (correction ∝ e^{−m d})
_DECAY = 40.0
#: the periodic length of the correction is at least this many coating thicknesses
_PERIOD_H = 32.0
#: at most this many alias terms on each side (reached only for Δ ≳ 1.3 h): the omitted
#: terms change the stresses by < 1.5e-3 p0 up to Δ = 40 h, < 2e-5 p0 up to Δ = 10 h
#: (Hertz load, 800/210 GPa layer)
_MAX_ALIAS = 8


def von_mises(sxx, szz, sxz, syy) -> np.ndarray:
    """σ_vM = √(½[(σx−σy)² + (σy−σz)² + (σz−σx)²] + 3τ²) [Pa]."""
    return np.sqrt(0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3.0 * sxz**2)


def _max_principal(sxx, szz, sxz, syy) -> np.ndarray:
    """Largest of the three principal stresses (in-plane pair and σ_yy) [Pa]."""
    s1 = 0.5 * (sxx + szz) + np.hypot(0.5 * (sxx - szz), sxz)
    return np.maximum(s1, syy)


# ------------------------------------------------------------ homogeneous half-plane
def _second_antiderivatives(u, z):
    """F with F'' = kernel (in u = x − s) for the kernels z³/r⁴, u z²/r⁴, u² z/r⁴, u³/r⁴;
    terms linear in u (they cancel in the second difference) dropped."""
    at = np.arctan2(u, z)  # atan(u/z), ±π/2 on the surface
    r2 = u * u + z * z
    with np.errstate(divide="ignore", invalid="ignore"):
        lg = np.where(r2 > 0.0, np.log(np.where(r2 > 0.0, r2, 1.0)), 0.0)
    ulg = u * lg
    zlg = z * lg
    f1 = 0.5 * u * at
    f2 = -0.5 * z * at
    f3 = 0.5 * (u * at - zlg)
    f4 = 0.5 * (ulg + 3.0 * z * at)
    return f1, f2, f3, f4


@lru_cache(maxsize=2048)
def _homogeneous_transfer(n: int, nf: int, z_rel: float) -> np.ndarray:
    """DFT (6, nf/2 + 1), read-only (cached), of the influence of unit hat loads at
    offsets d = kΔ, k = −(n−1)…(n−1), in wrap-around order, on (σ_xx, σ_zz, σ_xz) for p
    and for q, in the order (xx_p, zz_p, xz_p, xx_q, zz_q, xz_q), at depth z = z_rel Δ.
    Offsets are scaled by Δ (the kernels are homogeneous of degree 0)."""
    # F at the integer offsets −n…n once; F(k + 1), F(k), F(k − 1) are its shifted slices
    every = _second_antiderivatives(np.arange(-n, n + 1, dtype=float), z_rel)
    i1, i2, i3, i4 = (f[2:] - 2.0 * f[1:-1] + f[:-2] for f in every)
    ker = -2.0 / math.pi * np.array([i3, i1, i2, i4, i2, i3])
    wrap = np.zeros((6, nf))
    wrap[:, :n] = ker[:, n - 1 :]
    wrap[:, nf - n + 1 :] = ker[:, : n - 1]
    out = sp_fft.rfft(wrap, axis=-1)
    out.flags.writeable = False
    return out


# ------------------------------------------------------------- layered correction
def _layer_solutions(t: np.ndarray, coating, substrate) -> np.ndarray:
    """Coefficients (A, B, C, D, E, F) for unit surface conditions f(0) = 1, f_s(0) = 0
    (pressure) and f(0) = 0, f_s(0) = 1 (shear), shape (len(t), 6, 2); t = |m|h."""
    g = substrate.shear_modulus / coating.shear_modulus
    t = np.ascontiguousarray(t, dtype=float).ravel()
    return _layer_solve(t, float(g), float(coating.nu), float(substrate.nu))


@njit(cache=True, nogil=True)
def _layer_system(t, g, nc, ns, M):
    """The 6×6 conditions of the layered solution at t = |m|h into ``M``: rows 0–1 the
    surface (f, f_s), rows 2–5 the interface (f, f_s continuous, then u_x, u_z ∝
    [(1−ν)f_ss + νf]/G and [(1−ν)f_sss − (2−ν)f_s]/G continuous, × G_s); columns A, B,
    C, D of the coating basis e^{−s}, s e^{−s}, e^{s−t}, (s−t)e^{s−t} and E, F of the
    substrate's e^{−(s−t)}, (s−t)e^{−(s−t)}."""
    et = math.exp(-t)
    # coating basis at s = t, derivatives 0…3 of the four functions (columns A…D)
    c0 = (et, t * et, 1.0, 0.0)
    c1 = (-et, (1.0 - t) * et, 1.0, 1.0)
    c2 = (et, (t - 2.0) * et, 1.0, 2.0)
    c3 = (-et, (3.0 - t) * et, 1.0, 3.0)
    # substrate basis at s = t, derivatives 0…3 (columns E, F)
    s0, s1, s2, s3 = (1.0, 0.0), (-1.0, 1.0), (1.0, -2.0), (-1.0, 3.0)
    M[:] = 0.0
    M[0, 0], M[0, 2], M[0, 3] = 1.0, et, -t * et
    M[1, 0], M[1, 1], M[1, 2], M[1, 3] = -1.0, 1.0, et, (1.0 - t) * et
    for j in range(4):
        M[2, j] = c0[j]
        M[3, j] = c1[j]
        M[4, j] = g * ((1.0 - nc) * c2[j] + nc * c0[j])
        M[5, j] = g * ((1.0 - nc) * c3[j] - (2.0 - nc) * c1[j])
    for j in range(2):
        M[2, 4 + j] = -s0[j]
        M[3, 4 + j] = -s1[j]
        M[4, 4 + j] = -((1.0 - ns) * s2[j] + ns * s0[j])
        M[5, 4 + j] = -((1.0 - ns) * s3[j] - (2.0 - ns) * s1[j])


@njit(cache=True, nogil=True)
def _layer_solve(t, g, nc, ns):
    """:func:`_layer_solutions` for every t: the system of :func:`_layer_system` with
    right-hand sides e_0 (pressure) and e_1 (shear), solved by Gaussian elimination with
    partial pivoting."""
    out = np.empty((t.size, 6, 2))
    M = np.empty((6, 6))
    b = np.empty((6, 2))
    for i in range(t.size):
        _layer_system(t[i], g, nc, ns, M)
        b[:] = 0.0
        b[0, 0] = 1.0
        b[1, 1] = 1.0
        for c in range(6):
            piv = c
            for r in range(c + 1, 6):
                if abs(M[r, c]) > abs(M[piv, c]):
                    piv = r
            if piv != c:
                for k in range(6):
                    M[c, k], M[piv, k] = M[piv, k], M[c, k]
                for k in range(2):
                    b[c, k], b[piv, k] = b[piv, k], b[c, k]
            for r in range(c + 1, 6):
                f = M[r, c] / M[c, c]
                if f != 0.0:
                    for k in range(c, 6):
                        M[r, k] -= f * M[c, k]
                    for k in range(2):
                        b[r, k] -= f * b[c, k]
        for c in range(5, -1, -1):
            for k in range(2):
                acc = b[c, k]
                for j in range(c + 1, 6):
                    acc -= M[c, j] * out[i, j, k]
                out[i, c, k] = acc / M[c, c]
    return out


def _correction_values(sol, k, z, h):
    """Correction (layered − homogeneous) of f, f_s, f_ss at depths z (all in the
    coating, z ≤ h, or all in the substrate) for wavenumbers k ≥ 0, both unit loads:
    arrays (len(z), *k.shape, 2)."""
    z = np.atleast_1d(np.asarray(z, dtype=float))
    s = (k * z.reshape((-1,) + (1,) * k.ndim))[..., None]
    t = (k * h)[..., None]
    A, B, C, D, E, F = (sol[..., i, :] for i in range(6))
    e = np.exp(-s)
    # homogeneous: pressure f = (1 + s)e^{-s}, shear f = s e^{-s}
    a0 = np.array([1.0, 0.0])
    b0 = np.array([1.0, 1.0])
    w = s - t
    if z[0] <= h:
        g = np.exp(w)
        dA, dB = A - a0, B - b0
        f = (dA + dB * s) * e + (C + D * w) * g
        fs = (-dA + dB * (1.0 - s)) * e + (C + D * (1.0 + w)) * g
        fss = (dA + dB * (s - 2.0)) * e + (C + D * (2.0 + w)) * g
    else:
        g = np.exp(-w)
        hom0 = a0 * e
        hom1 = b0 * e
        # substrate − homogeneous, homogeneous written as (a0 + b0 s)e^{-s}
        f = (E + F * w) * g - (hom0 + hom1 * s)
        fs = (-E + F * (1.0 - w)) * g - (-hom0 + hom1 * (1.0 - s))
        fss = (E + F * (w - 2.0)) * g - (hom0 + hom1 * (s - 2.0))
    return f, fs, fss


def _long_wave_limits(coating, substrate) -> tuple[float, float]:
    """m → 0 limits of the coating's σ_xx correction per unit p̃ (L_p) and per unit
    i·sgn(m)·q̃ (L_q): the layer takes the substrate surface's strain ε_xx, so
    σ_xx,c = [2G_c ε_xx + ν_c σ_zz]/(1 − ν_c) with the homogeneous surface field
    σ_xx = −p (pressure) or 2i sgn(m) q̃ (shear, Hilbert transform) beneath it."""
    g = coating.shear_modulus / substrate.shear_modulus
    nc, ns = coating.nu, substrate.nu
    lp = 1.0 - (g * (1.0 - 2.0 * ns) + nc) / (1.0 - nc)
    lq = 2.0 * (g * (1.0 - ns) / (1.0 - nc) - 1.0)
    return lp, lq


# ------------------------------------------------------------- batched peak search
@njit(cache=True, nogil=True)
def _load_spectra(transfer, p_hat, q_hat):
    """Spectra of (σ_xx, σ_zz, σ_xz) at every depth for many loads: ``transfer``
    (depth, 6, nfreq) times the load spectra (samples, nfreq), G = T_p P + T_q Q, shape
    (samples, depth, 3, nfreq); the same single-precision products and sums as NumPy's
    broadcast expression, without its temporaries."""
    ns, nfq = p_hat.shape
    nz = transfer.shape[0]
    out = np.empty((ns, nz, 3, nfq), dtype=p_hat.dtype)
    for s in range(ns):
        for r in range(nz):
            for c in range(3):
                tp = transfer[r, c]
                tq = transfer[r, c + 3]
                o = out[s, r, c]
                for j in range(nfq):
                    o[j] = tp[j] * p_hat[s, j] + tq[j] * q_hat[s, j]
    return out


@njit(cache=True, nogil=True)
def _vm2_at(sxx, szz, sxz, nu):
    """Squared von Mises stress of one point with σ_yy = ν(σ_xx + σ_zz) (plane strain),
    in the precision of the arguments: ½[(σx−σy)² + (σy−σz)² + (σz−σx)²] + 3τ²."""
    syy = nu * (sxx + szz)
    a = sxx - syy
    b = syy - szz
    c = szz - sxx
    return np.float32(0.5) * ((a * a + b * b) + c * c) + np.float32(3.0) * (sxz * sxz)


@njit(cache=True, nogil=True)
def _peak_search(fields, nu, coat, n, surface, interface):
    """Largest value and its (depth row, node) of each peak of :data:`.stress.PEAKS` for
    every sample of ``fields`` (samples, depth, 3, ≥ n): squared von Mises in the coating
    rows (``coat``) and below them, the largest principal stress (in-plane pair and
    σ_yy = ν(σ_xx + σ_zz)) on the surface row ``surface`` and in the coating rows, |σ_xz|
    and σ_zz on the row ``interface`` (< 0: none). The first of equal values in (row,
    node) order wins, as ``np.argmax`` over the rows in order. Returns values (samples, 6)
    (−inf where a peak has no rows) and rows, nodes (samples, 6)."""
    ns, nz = fields.shape[0], fields.shape[1]
    val = np.full((ns, 6), -np.inf, dtype=np.float32)
    row = np.zeros((ns, 6), dtype=np.int64)
    col = np.zeros((ns, 6), dtype=np.int64)
    half = np.float32(0.5)
    for s in range(ns):
        for r in range(nz):
            f = fields[s, r]
            v = nu[r]
            principal = coat[r] or r == surface
            for i in range(n):
                sxx, szz, sxz = f[0, i], f[1, i], f[2, i]
                vm = _vm2_at(sxx, szz, sxz, v)
                k = 0 if coat[r] else 1
                if vm > val[s, k]:
                    val[s, k], row[s, k], col[s, k] = vm, r, i
                if principal:
                    syy = v * (sxx + szz)
                    s1 = half * (sxx + szz) + np.float32(math.hypot(half * (sxx - szz), sxz))
                    if syy > s1:
                        s1 = syy
                    if r == surface and s1 > val[s, 2]:
                        val[s, 2], row[s, 2], col[s, 2] = s1, r, i
                    if coat[r] and s1 > val[s, 3]:
                        val[s, 3], row[s, 3], col[s, 3] = s1, r, i
                if r == interface:
                    if abs(sxz) > val[s, 4]:
                        val[s, 4], row[s, 4], col[s, 4] = abs(sxz), r, i
                    if szz > val[s, 5]:
                        val[s, 5], row[s, 5], col[s, 5] = szz, r, i
    return val, row, col


@njit(cache=True, nogil=True)
def _vm2_points(fields, nu, rows, cols):
    """Squared von Mises stress of each sample of ``fields`` (samples, depth, 3, ·) at its
    depth row ``rows[s]`` and node ``cols[s]`` (as :func:`_peak_search` forms it)."""
    ns = fields.shape[0]
    out = np.empty(ns, dtype=fields.dtype)
    for s in range(ns):
        r, i = rows[s], cols[s]
        out[s] = _vm2_at(fields[s, r, 0, i], fields[s, r, 1, i], fields[s, r, 2, i], nu[r])
    return out


# ------------------------------------------------------- layered correction, aliases
@njit(cache=True, nogil=True)
def _unit_correction(sol, a, j, u, sv, wv, ev, gv, substrate):
    """f, f_s, f_ss of the correction for unit load ``u`` (0: pressure, 1: shear) at one
    wavenumber and depth: the expressions of :func:`_correction_values`."""
    a0 = 1.0 if u == 0 else 0.0
    if not substrate:
        dA, dB = sol[a, j, 0, u] - a0, sol[a, j, 1, u] - 1.0
        C, D = sol[a, j, 2, u], sol[a, j, 3, u]
        f = (dA + dB * sv) * ev + (C + D * wv) * gv
        fs = (-dA + dB * (1.0 - sv)) * ev + (C + D * (1.0 + wv)) * gv
        fss = (dA + dB * (sv - 2.0)) * ev + (C + D * (2.0 + wv)) * gv
    else:
        E, F = sol[a, j, 4, u], sol[a, j, 5, u]
        h0, h1 = a0 * ev, 1.0 * ev
        f = (E + F * wv) * gv - (h0 + h1 * sv)
        fs = (-E + F * (1.0 - wv)) * gv - (-h0 + h1 * (1.0 - sv))
        fss = (E + F * (wv - 2.0)) * gv - (h0 + h1 * (sv - 2.0))
    return f, fs, fss


@njit(cache=True, nogil=True)
def _alias_sums(sol, k, sg, posw, cut, s, w, e, g, cutd, substrate, lims, slopes):
    """Alias sums Σ_a T_c(m_a) w_a of the six correction transfers (xx_p, zz_p, xz_p,
    xx_q, zz_q, xz_q; :meth:`.stress.StressOperator._terms`) at depth rows all on one
    side of the interface: ``sol`` (alias, freq, 6, 2) the layer coefficients, ``k``,
    ``sg`` |m| and sgn m, ``posw`` the alias weights sinc² (0 at m = 0), ``cut``
    e^{−2|m|h}; per row ``s`` = |m|z, ``w`` = s − |m|h, ``e`` = e^{−s}, ``g`` = e^{w}
    (coating) or e^{−w} (``substrate``), ``cutd`` the slope term's decay e^{−|m|d};
    ``lims`` the long-wave limits of σ_xx taken off (× ``cut``), ``slopes`` (row, 6) the
    split-off slope terms c|m|e^{−|m|d} of xx_p, zz_p, xz_q. Returns (row, 6, freq): the
    sums of the real transfers (xx_p, zz_p, xz_q) and of the imaginary parts of the
    others (purely imaginary), in alias order, each term rounded as in NumPy."""
    nr, na, nq = s.shape
    out = np.zeros((nr, 6, nq))
    for r in range(nr):
        c0, c1, c5 = slopes[r, 0], slopes[r, 1], slopes[r, 5]
        for a in range(na):
            for j in range(nq):
                wt = posw[a, j]
                if wt == 0.0:
                    continue
                sv, wv, ev, gv = s[r, a, j], w[r, a, j], e[r, a, j], g[r, a, j]
                kv, sgv, cd = k[a, j], sg[a, j], cutd[r, a, j]
                f0, fs0, fss0 = _unit_correction(sol, a, j, 0, sv, wv, ev, gv, substrate)
                f1, fs1, fss1 = _unit_correction(sol, a, j, 1, sv, wv, ev, gv, substrate)
                fss0 = fss0 - lims[0] * cut[a, j]
                fss1 = fss1 - lims[1] * cut[a, j]
                out[r, 0, j] += (fss0 - (c0 * kv) * cd) * wt
                out[r, 1, j] += ((-f0) - (c1 * kv) * cd) * wt
                out[r, 2, j] += (-sgv * fs0) * wt
                out[r, 3, j] += (-sgv * fss1) * wt
                out[r, 4, j] += (sgv * f1) * wt
                out[r, 5, j] += ((-fs1) - (c5 * kv) * cd) * wt
    return out

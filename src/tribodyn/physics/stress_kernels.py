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


def _homogeneous_kernels(n: int, dx: float, z: float) -> np.ndarray:
    """Influence of unit hat loads at offsets d = kΔ, k = −(n−1)…(n−1), on (σ_xx, σ_zz,
    σ_xz) for p and for q: array (6, 2n − 1) in the order (xx_p, zz_p, xz_p, xx_q, zz_q,
    xz_q). Offsets are scaled by Δ (the kernels are homogeneous of degree 0)."""
    k = np.arange(-(n - 1), n, dtype=float)
    zz = z / dx
    fp = _second_antiderivatives(k + 1.0, zz)
    f0 = _second_antiderivatives(k, zz)
    fm = _second_antiderivatives(k - 1.0, zz)
    i1, i2, i3, i4 = (a - 2.0 * b + c for a, b, c in zip(fp, f0, fm, strict=True))
    c = -2.0 / math.pi
    return c * np.array([i3, i1, i2, i4, i2, i3])


@lru_cache(maxsize=2048)
def _homogeneous_transfer(n: int, nf: int, z_rel: float) -> np.ndarray:
    ker = _homogeneous_kernels(n, 1.0, z_rel)
    wrap = np.zeros((6, nf))
    wrap[:, :n] = ker[:, n - 1 :]
    wrap[:, nf - n + 1 :] = ker[:, : n - 1]
    out = sp_fft.rfft(wrap, axis=-1)
    out.flags.writeable = False
    return out


# ------------------------------------------------------------- layered correction
def _layer_solutions(t: np.ndarray, coating, substrate) -> np.ndarray:
    """Coefficients (A, B, C, D, E, F) for unit surface conditions f(0) = 1, f_s(0) = 0
    (pressure) and f(0) = 0, f_s(0) = 1 (shear), shape (len(t), 6, 2)."""
    g = substrate.shear_modulus / coating.shear_modulus
    nc, ns = coating.nu, substrate.nu
    et = np.exp(-t)
    one, zero = np.ones_like(t), np.zeros_like(t)
    # coating basis at s = t: values and derivatives 0…3 of e^{-s}, s e^{-s}, e^{s-t},
    # (s-t)e^{s-t}; substrate basis e^{-(s-t)}, (s-t)e^{-(s-t)} at s = t
    cb = [
        [et, t * et, one, zero],
        [-et, (1.0 - t) * et, one, one],
        [et, (t - 2.0) * et, one, 2.0 * one],
        [-et, (3.0 - t) * et, one, 3.0 * one],
    ]
    sb = [[one, zero], [-one, one], [one, -2.0 * one], [-one, 3.0 * one]]
    n = t.size
    M = np.zeros((n, 6, 6))
    M[:, 0, :4] = np.stack([one, zero, et, -t * et], axis=-1)
    M[:, 1, :4] = np.stack([-one, one, et, (1.0 - t) * et], axis=-1)
    for j in range(4):
        M[:, 2, j] = cb[0][j]
        M[:, 3, j] = cb[1][j]
        M[:, 4, j] = g * ((1.0 - nc) * cb[2][j] + nc * cb[0][j])
        M[:, 5, j] = g * ((1.0 - nc) * cb[3][j] - (2.0 - nc) * cb[1][j])
    for j in range(2):
        M[:, 2, 4 + j] = -sb[0][j]
        M[:, 3, 4 + j] = -sb[1][j]
        M[:, 4, 4 + j] = -((1.0 - ns) * sb[2][j] + ns * sb[0][j])
        M[:, 5, 4 + j] = -((1.0 - ns) * sb[3][j] - (2.0 - ns) * sb[1][j])
    rhs = np.zeros((n, 6, 2))
    rhs[:, 0, 0] = 1.0
    rhs[:, 1, 1] = 1.0
    return np.linalg.solve(M, rhs)


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

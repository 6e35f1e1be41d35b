"""Robust fit of a lift table: noise level, curvature jumps, penalised quintic spline.

A flat follower sees R = r_b + s + s''. Real lift tables have curvature jumps (circular-arc
cams, polynomial cams with ramps) and measurement noise; an interpolating spline rings
across a jump in s'' (Gibbs) and differentiates noise twice. This module

1. estimates the noise σ from the fourth differences of the table (robust median:
   σ = 1.4826 med|Δ⁴y|/√70; difference-based variance estimation, Gasser, Sroka &
   Jennen-Steinmetz, Biometrika 73 (1986) 625; Hall, Kay & Titterington, Biometrika 77
   (1990) 521); a jump in s'' only spoils a few differences, which the median ignores;
2. finds the jumps in s'': at each table point and several window widths, a local least
   squares fit y ≈ cubic(u) + c₂u₊² + c₃u₊³ (u = x − ξ) estimates the jump Δs'' = 2c₂ and
   its standard error from σ; a jump is reported where |Δs''| exceeds 8 standard errors
   and 1 % of the base radius; its position is refined by the least residual, where the
   jump model must explain the window significantly better than a smooth quintic (so a
   fast but continuous change of s'' is not taken for a jump);
3. fits a periodic quintic B-spline with knots at the table angles and a four-fold knot at
   each jump (so s, s' stay continuous and s'' may jump there), minimising
   Σ(y − s)² + λ∫(s''')² (the smoothing spline of Reinsch/Wahba, penalty integrated piece
   by piece so the jumps are free), λ chosen so that the RMS residual equals the table's
   precision (Morozov's discrepancy principle).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from scipy.interpolate import BSpline, PPoly

__all__ = ["estimate_noise", "find_curvature_jumps", "fit_periodic_lift", "LiftFit"]

TWO_PI = 2.0 * math.pi
_K = 5  # quintic
_JUMP_Z = 8.0  # significance of a jump (standard errors)
_JUMP_REL = 0.01  # and at least this share of the base radius


def estimate_noise(y) -> float:
    """Robust noise σ of a densely sampled smooth table from its 4th differences [units
    of y] (periodic)."""
    y = np.asarray(y, float)
    d4 = np.roll(y, -2) - 4 * np.roll(y, -1) + 6 * y - 4 * np.roll(y, 1) + np.roll(y, 2)
    # an exact base circle (all five values equal) says nothing about the noise
    same = np.ones(y.size, bool)
    for k in (-2, -1, 1, 2):
        same &= np.roll(y, k) == y
    d4 = d4[~same]
    if d4.size == 0:
        return 0.0
    return float(1.4826 * np.median(np.abs(d4)) / math.sqrt(70.0))


def _lsq_rss(A, y):
    """Batched least squares: coefficients, (AᵀA)⁻¹ and residual sum of squares."""
    AtA = np.einsum("nik,nil->nkl", A, A)
    inv = np.linalg.inv(AtA)
    coef = np.einsum("nkl,nl->nk", inv, np.einsum("nik,ni->nk", A, y))
    res = y - np.einsum("nik,nk->ni", A, coef)
    return coef, inv, np.sum(res * res, axis=1)


def _local_fits(x, y, xi, w, period):
    """Jump model (cubic + c₂u₊² + c₃u₊³) and smooth model (quintic) at positions ξ over
    the w table points on each side: (Δs'' = 2c₂, its standard error per unit σ, rss of
    the jump model, rss of the smooth model)."""
    n = x.size
    j0 = np.searchsorted(x, xi)
    offs = np.arange(-w, w)
    idx = (j0[:, None] + offs[None, :]) % n
    xx = x[idx] + period * np.floor_divide(j0[:, None] + offs[None, :], n)
    sc = np.abs(xx - xi[:, None]).max(axis=1)[:, None]
    u = (xx - xi[:, None]) / sc  # scaled for conditioning
    up = np.where(u > 0.0, u, 0.0)
    yy = y[idx]
    one = np.ones_like(u)
    coef, inv, rss = _lsq_rss(np.stack([one, u, u * u, u**3, up * up, up**3], -1), yy)
    _, _, rss5 = _lsq_rss(np.stack([one, u, u * u, u**3, u**4, u**5], -1), yy)
    s2 = sc[:, 0] ** 2
    return 2.0 * coef[:, 4] / s2, 2.0 * np.sqrt(inv[:, 4, 4]) / s2, rss, rss5


def find_curvature_jumps(
    x, y, sigma: float, base_radius: float, period: float = TWO_PI
) -> list[tuple[float, float]]:
    """Positions [rad] and sizes Δs'' [m/rad²] of the jumps of s'' in a periodic table."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    h = float(np.median(np.diff(x)))
    sig = max(sigma, 1e-12)
    scales = [w for w in (4, 8, 16, 32, 64, 128) if w * h <= math.radians(10.0) or w == 4]
    best = {}  # index → (z, w, jump)
    for w in scales:
        jump, se, rss, rss5 = _local_fits(x, y, x, w, period)
        z = np.abs(jump) / (se * sig)
        hit = np.nonzero((z > _JUMP_Z) & (np.abs(jump) > _JUMP_REL * base_radius))[0]
        for i in hit:
            if i not in best:
                best[i] = (z[i], w, jump[i])
    if not best:
        return []
    idx = np.array(sorted(best))
    # clusters of neighbouring hits (a jump is seen from a whole window)
    clusters, cur = [], [idx[0]]
    for i in idx[1:]:
        if i - cur[-1] <= 2 * best[cur[-1]][1]:
            cur.append(i)
        else:
            clusters.append(cur)
            cur = [i]
    clusters.append(cur)
    if len(clusters) > 1 and (clusters[0][0] + x.size - clusters[-1][-1]) <= 2 * scales[0]:
        clusters[0] = clusters.pop() + clusters[0]
    out = []
    for cl in clusters:
        w = min(best[i][1] for i in cl)
        jmax = max(cl, key=lambda i: abs(best[i][2]))
        cand = x[jmax] + h * np.linspace(-3.0, 3.0, 121)
        jump, _, rss, rss5 = _local_fits(x, y, cand, w, period)
        k = int(np.argmin(rss))
        # at its best position the jump must explain what a smooth quintic arc cannot
        # (a fast but continuous change of s'', or a step of the jerk, does not)
        if abs(jump[k]) > _JUMP_REL * base_radius and rss5[k] - rss[k] > (_JUMP_Z * sig) ** 2:
            out.append((float(cand[k] % period), float(jump[k])))
    return sorted(out)


def _deriv(t, k, n):
    """Sparse map of B-spline coefficients (degree k, knots t, n of them) to those of the
    derivative (degree k − 1, knots t[1:-1]); zero-length supports give 0."""
    den = t[k + 1 : k + n] - t[1:n]
    f = np.where(den > 0.0, k / np.where(den > 0.0, den, 1.0), 0.0)
    rows = np.arange(n - 1)
    return sp.csr_matrix(
        (np.concatenate([-f, f]), (np.concatenate([rows, rows]), np.concatenate([rows, rows + 1]))),
        shape=(n - 1, n),
    )


@dataclass
class LiftFit:
    """Result of :func:`fit_periodic_lift`: piecewise quintic (``breaks``, ``coeffs``
    highest power first, on [x₀, x₀ + 2π)), jumps [(angle, Δs'')], precision used and
    RMS residual [m]."""

    breaks: np.ndarray
    coeffs: np.ndarray
    jumps: list
    precision: float
    rms_residual: float


def fit_periodic_lift(
    x, y, base_radius: float, precision: float | None = None, quantum: float = 0.0
) -> LiftFit:
    """Penalised periodic quintic spline through the table (see module docstring).

    precision : RMS deviation allowed [m] (None: the estimated noise, at least the
        table's rounding ``quantum``/√12)."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    P = TWO_PI
    sigma = estimate_noise(y)
    if precision is None:
        precision = max(sigma, quantum / math.sqrt(12.0))
    # floor: a table exact to the last float digit is still fitted to 1e-9 of its lift
    precision = max(precision, 1e-9 * float(np.ptp(y)))
    jumps = find_curvature_jumps(x, y, max(precision, sigma, 1e-12), base_radius)
    x0 = x[0]
    tau = list(x)
    for a, _ in jumps:
        a = x0 + (a - x0) % P
        # drop a table knot closer than a tenth of a spacing to the jump
        j = int(np.argmin(np.abs(np.asarray(tau) - a)))
        if abs(tau[j] - a) < 0.1 * (x[1] - x[0]) and tau[j] != x0:
            tau.pop(j)
        tau += [a] * 4
    tau = np.sort(np.asarray(tau))
    m = tau.size
    t = np.concatenate([tau[m - _K :] - P, tau, tau[: _K + 1] + P])
    n = m + _K  # basis functions before folding

    def fold(B):
        B = sp.csr_matrix(B)
        main = B[:, :m].tolil()
        main[:, :_K] = main[:, :_K] + B[:, m : m + _K]
        return main.tocsr()

    A = fold(BSpline.design_matrix(x, t, _K))
    # ∫(s''')² by 3-point Gauss on every interval of one period
    D = _deriv(t[2:-2], _K - 2, n - 2) @ _deriv(t[1:-1], _K - 1, n - 1) @ _deriv(t, _K, n)
    lo, hi = t[_K : _K + m], t[_K + 1 : _K + m + 1]
    keep = hi > lo
    g, gw = np.polynomial.legendre.leggauss(3)
    mid, half = 0.5 * (lo + hi)[keep], 0.5 * (hi - lo)[keep]
    xg = (mid[:, None] + half[:, None] * g[None, :]).ravel()
    wg = (half[:, None] * gw[None, :]).ravel()
    B3 = fold(BSpline.design_matrix(xg, t[3:-3], _K - 3) @ D)
    R = (B3.T @ sp.diags(wg) @ B3).tocsc()
    AtA = (A.T @ A).tocsc()
    Aty = A.T @ y
    lam0 = AtA.diagonal().sum() / max(R.diagonal().sum(), 1e-300)

    def solve(u):
        c = spla.splu((AtA + (lam0 * 10.0**u) * R).tocsc()).solve(Aty)
        return c, float(np.sqrt(np.mean((A @ c - y) ** 2)))

    lo_u, hi_u = -24.0, 24.0
    c, r = solve(lo_u)
    if r < precision:
        for _ in range(40):
            mid_u = 0.5 * (lo_u + hi_u)
            cm, rm = solve(mid_u)
            if rm > precision:
                hi_u = mid_u
            else:
                lo_u, c, r = mid_u, cm, rm
            if hi_u - lo_u < 0.02:
                break
    cfull = np.concatenate([c, c[:_K]])
    pp = PPoly.from_spline(BSpline(t, cfull, _K))
    brk = pp.x
    idx = np.nonzero(np.diff(brk) > 0.0)[0]
    idx = idx[(brk[idx] >= x0 - 1e-12) & (brk[idx + 1] <= x0 + P + 1e-12)]
    breaks = np.append(brk[idx], brk[idx[-1] + 1])
    return LiftFit(breaks, pp.c[:, idx], jumps, float(precision), r)

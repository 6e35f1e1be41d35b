"""Robust fit of a lift table: noise level, base circle, curvature jumps, penalised spline.

A flat follower sees R = r_b + s + s''. Real lift tables have curvature jumps (circular-arc
cams, ramps) and measurement noise; an interpolating spline rings across a jump in s''
(Gibbs) and differentiates noise twice. This module

1. estimates the noise σ from the fourth differences of the table (robust median:
   σ = 1.4826 med|Δ⁴y|/√70; difference-based variance estimation, Gasser, Sroka &
   Jennen-Steinmetz, Biometrika 73 (1986) 625; Hall, Kay & Titterington, Biometrika 77
   (1990) 521); a jump in s'' only spoils a few differences, which the median ignores;
2. finds the base circle: the longest run of table points with |s| within the noise band
   (4σ, at least the rounding step); the fit is exactly s = s' = s'' = 0 there (a cam's
   base circle is r_b, with zero lift, not a noisy curve);
3. finds the jumps in s'': at each point of the table (bin means of at most
   ``_DETECT_POINTS`` points, so the cost is O(n)) and several window widths, a local
   least-squares fit y ≈ cubic(u) + c₂u₊² + c₃u₊³ (u = x − ξ; solved by QR, rank-deficient
   windows report nothing) estimates Δs'' = 2c₂ and its standard error from σ; a jump is
   reported where |Δs''| exceeds 8 standard errors and 25 % of the base radius, at the
   position of least residual, if the jump model explains the window significantly better
   than a smooth quintic (so a fast but continuous change of s'' is not taken for a jump);
4. fits a periodic quintic B-spline, minimising Σ(y − s)² + λ∫(s''')² (the smoothing
   spline of Reinsch/Wahba, penalty integrated piece by piece), with knots at every
   other table point (at most ``_MAX_KNOTS``: the least-squares problem is overdetermined,
   so an exact table needs no regularisation), a four-fold knot at each jump (s, s'
   continuous, s'' free to jump), a three-fold knot at each end of the base circle, and
   every B-spline inside the base circle removed (s ≡ 0 there, exactly); λ is chosen so
   that the RMS residual equals the table's precision (Morozov's discrepancy principle).
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
_JUMP_REL = 0.25  # and at least this share of the base radius (smaller: smoothed)
_DETECT_POINTS = 3600  # jump detection on at most this many bin means (0.1°)
_MAX_KNOTS = 7200  # spline knots (besides jumps and base-circle ends)


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


def _lsq_rss(A, y, col):
    """Batched least squares by QR: coefficients, variance factor (AᵀA)⁻¹ of coefficient
    ``col`` and residual sum of squares; rank-deficient rows get variance inf."""
    Q, Rm = np.linalg.qr(A)
    d = np.abs(np.diagonal(Rm, axis1=1, axis2=2))
    ok = d.min(axis=1) > 1e-10 * d.max(axis=1)
    Rm[~ok] = np.eye(A.shape[2])
    Rinv = np.linalg.inv(Rm)  # triangular, well conditioned where ok
    coef = np.einsum("nkl,nl->nk", Rinv, np.einsum("nik,ni->nk", Q, y))
    res = y - np.einsum("nik,nk->ni", A, coef)
    var = np.where(ok, np.sum(Rinv[:, col, :] ** 2, axis=1), np.inf)
    coef[~ok] = 0.0
    return coef, var, np.sum(res * res, axis=1)


def _local_fits(x, y, xi, w, period, sigma, center=None):
    """Local models at positions ξ over the w table points on each side (u = x − ξ): the
    jump model cubic + c₂u₊² + c₃u₊³ (s'' jumps by Δs'' = 2c₂) and two models with a
    continuous s'' (a quintic; a cubic whose jerk steps, + u₊³, u₊⁴). Returns (Δs'', its
    z-score against the larger of σ and the jump model's residual scatter, so model error
    is not taken for a jump; rss of the jump model; least rss without a jump). With
    ``center`` (an index) every ξ uses the same window around it, so rss compare."""
    n = x.size
    j0 = np.searchsorted(x, xi) if center is None else np.full(np.size(xi), center)
    offs = np.arange(-w, w)
    idx = (j0[:, None] + offs[None, :]) % n
    xx = x[idx] + period * np.floor_divide(j0[:, None] + offs[None, :], n)
    sc = np.abs(xx - xi[:, None]).max(axis=1)[:, None]
    u = (xx - xi[:, None]) / sc  # scaled for conditioning
    up = np.where(u > 0.0, u, 0.0)
    yy = y[idx]
    base = [np.ones_like(u), u, u * u, u**3]
    coef, var, rss = _lsq_rss(np.stack(base + [up * up, up**3], -1), yy, 4)
    _, _, rss5 = _lsq_rss(np.stack(base + [u**4, u**5], -1), yy, 0)
    _, _, rss3 = _lsq_rss(np.stack(base + [up**3, up**4], -1), yy, 0)
    scatter = np.sqrt(rss / max(2 * w - 6, 1))
    s2 = sc[:, 0] ** 2
    jump = 2.0 * coef[:, 4] / s2
    z = np.abs(coef[:, 4]) / (np.sqrt(var) * np.maximum(sigma, scatter))
    return jump, np.where(np.isfinite(z), z, 0.0), rss, np.minimum(rss5, rss3)


def _bin_means(x, y, k):
    """Means of k consecutive points (x and y): the table for jump detection."""
    m = (x.size // k) * k
    return x[:m].reshape(-1, k).mean(axis=1), y[:m].reshape(-1, k).mean(axis=1)


def find_curvature_jumps(
    x, y, sigma: float, base_radius: float, period: float = TWO_PI
) -> list[tuple[float, float]]:
    """Positions [rad] and sizes Δs'' [m/rad²] of the jumps of s'' in a periodic table.

    Tables longer than ``_DETECT_POINTS`` are reduced to bin means of k points first
    (noise σ/√k), so the cost is O(n)."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    k = max(1, math.ceil(x.size / _DETECT_POINTS))
    if k > 1:
        x, y = _bin_means(x, y, k)
        sigma = sigma / math.sqrt(k)
    h = float(np.median(np.diff(x)))
    sig = max(sigma, 1e-12)
    # windows up to 10° (model error of the local cubics), up to 20° for a noisy table
    # (σ > 1 nm), where a jump of a few mm in R needs the wider window to stand out
    span = math.radians(20.0 if sigma > 1e-9 else 10.0)
    scales = [w for w in (4, 8, 16, 32, 64, 128, 256) if w * h <= span or w == 4]
    scales = [w for w in scales if 2 * w < x.size]
    best: dict[int, tuple[float, int, float]] = {}  # index → (z, w, jump)
    for w in scales:
        jump, z, _, _ = _local_fits(x, y, x, w, period, sig)
        hit = np.nonzero((z > _JUMP_Z) & (np.abs(jump) > _JUMP_REL * base_radius))[0]
        for i in hit:  # keep the most significant window of each point
            if int(i) not in best or z[i] > best[int(i)][0]:
                best[int(i)] = (float(z[i]), w, float(jump[i]))
    if not best:
        return []
    idx = np.array(sorted(best))
    # clusters of neighbouring hits (a jump is seen from a whole window)
    clusters, cur = [], [idx[0]]
    for i in idx[1:]:
        if i - cur[-1] <= 4:
            cur.append(i)
        else:
            clusters.append(cur)
            cur = [i]
    clusters.append(cur)
    if len(clusters) > 1 and (clusters[0][0] + x.size - clusters[-1][-1]) <= 2 * scales[0]:
        clusters[0] = clusters.pop() + clusters[0]
    out: list[tuple[float, float]] = []
    for cl in clusters:
        # located with the most significant window (least residual), then tested with
        # every window from the narrowest (least model error) up, centred there
        jtop = max(cl, key=lambda i: best[i][0])
        wtop = best[jtop][1]
        cand = x[jtop] + h * np.linspace(-wtop / 2, wtop / 2, 10 * wtop + 1)
        rss = _local_fits(x, y, cand, wtop, period, sig, center=jtop)[2]
        pos = float(cand[int(np.argmin(rss))])
        jw = int(np.argmin(np.abs((x - pos + 0.5 * period) % period - 0.5 * period)))
        for w in [v for v in scales if v <= wtop]:
            cand = pos + h * np.linspace(-w / 2, w / 2, 10 * w + 1)
            jump, z, rss, rss0 = _local_fits(x, y, cand, w, period, sig, center=jw)
            j = int(np.argmin(rss))
            # the jump must beat a continuous s'' at that one's best position too (a
            # misplaced step of the jerk looks like a small jump)
            s_eff = max(sig, math.sqrt(rss[j] / max(2 * w - 6, 1)))
            gain = float(np.min(rss0)) - float(rss[j])
            if abs(jump[j]) <= _JUMP_REL * base_radius and z[j] > _JUMP_Z:
                break  # measured precisely and small: wider windows only add model error
            if abs(jump[j]) > _JUMP_REL * base_radius and gain > (_JUMP_Z * s_eff) ** 2:
                a = float(cand[j] % period)
                # one jump seen by two clusters (hits of a wide window) is kept once
                if all(abs((a - b + 0.5 * period) % period - 0.5 * period) > 4 * h for b, _ in out):
                    out.append((a, float(jump[j])))
                break
    return sorted(out)


def base_circle(y, band: float) -> tuple[int, int] | None:
    """(first, last) index of the longest circular run of |y| ≤ band (gaps of up to two
    points closed, so isolated noise peaks do not split it), or None."""
    on = np.abs(np.asarray(y, float)) <= band
    n = on.size
    if not on.any() or on.all():
        return None
    # close gaps of ≤ 2 points between base points
    near = (
        on
        | (np.roll(on, 1) & (np.roll(on, -1) | np.roll(on, -2)))
        | (np.roll(on, 2) & np.roll(on, -1))
    )
    start = int(np.argmin(near))  # an event point: runs do not wrap in the scan below
    r = np.roll(near, -start)
    best, cur, first = (0, 0, 0), 0, 0
    for i, v in enumerate(r.tolist()):
        if v:
            if cur == 0:
                first = i
            cur += 1
            if cur > best[0]:
                best = (cur, first, i)
        else:
            cur = 0
    if best[0] < 3:
        return None
    return (best[1] + start) % n, (best[2] + start) % n


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
    highest power first, on [x₀, x₀ + 2π)), jumps [(angle, Δs'')], precision used [m] and
    the base circle (from, to) [rad] where s ≡ 0 (None if none)."""

    breaks: np.ndarray
    coeffs: np.ndarray
    jumps: list
    precision: float
    base_circle: tuple[float, float] | None = None


def _penalised_fit(xs, ys, x0, tau, base, precision):
    """Periodic quintic spline on knots ``tau`` (sorted, in [x₀, x₀ + 2π)) minimising
    Σ(y − s)² + λ∫(s‴)², λ by the discrepancy principle; B-splines inside the base
    circle ``base`` = (closing edge, opening edge) [rad, in x₀'s period] are removed.
    Returns (PPoly breaks, coefficients, fitted values at xs)."""
    P = TWO_PI
    m = tau.size
    t = np.concatenate([tau[m - _K :] - P, tau, tau[: _K + 1] + P])
    n = m + _K  # basis functions before folding

    def fold(B):  # periodic: basis functions m … m + K − 1 are 0 … K − 1 again
        B = sp.coo_matrix(B)
        return sp.csr_matrix((B.data, (B.row, B.col % m)), shape=(B.shape[0], m))

    free = np.ones(m, bool)
    if base is not None:
        hi_edge, lo_edge = base
        a0, a1 = t[:n], t[_K + 1 : n + _K + 1]
        inside = ((a0 >= hi_edge - P - 1e-12) & (a1 <= lo_edge + 1e-12)) | (
            (a0 >= hi_edge - 1e-12) & (a1 <= lo_edge + P + 1e-12)
        )
        free[np.arange(n)[inside] % m] = False
    A = fold(BSpline.design_matrix(xs, t, _K))[:, free]
    # ∫(s‴)² by 3-point Gauss on every interval of one period
    D = _deriv(t[2:-2], _K - 2, n - 2) @ _deriv(t[1:-1], _K - 1, n - 1) @ _deriv(t, _K, n)
    lo, hi = t[_K : _K + m], t[_K + 1 : _K + m + 1]
    keep = hi > lo
    g, gw = np.polynomial.legendre.leggauss(3)
    mid, half = 0.5 * (lo + hi)[keep], 0.5 * (hi - lo)[keep]
    xg = (mid[:, None] + half[:, None] * g[None, :]).ravel()
    wg = (half[:, None] * gw[None, :]).ravel()
    B3 = fold(BSpline.design_matrix(xg, t[3:-3], _K - 3) @ D)[:, free]
    R = (B3.T @ sp.diags(wg) @ B3).tocsc()
    AtA = (A.T @ A).tocsc()
    Aty = A.T @ ys
    lam0 = AtA.diagonal().sum() / max(R.diagonal().sum(), 1e-300)

    def solve(u):
        c = spla.splu((AtA + (lam0 * 10.0**u) * R).tocsc()).solve(Aty)
        return c, float(np.sqrt(np.mean((A @ c - ys) ** 2)))

    lo_u, hi_u = -20.0, 14.0
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
    cf = np.zeros(m)
    cf[free] = c
    pp = PPoly.from_spline(BSpline(t, np.concatenate([cf, cf[:_K]]), _K))
    brk = pp.x
    idx = np.nonzero(np.diff(brk) > 0.0)[0]
    idx = idx[(brk[idx] >= x0 - 1e-12) & (brk[idx + 1] <= x0 + P + 1e-12)]
    breaks = np.append(brk[idx], brk[idx[-1] + 1])
    coeffs = pp.c[:, idx]
    if base is not None:  # pieces inside the base circle: exactly zero
        inside = (breaks[1:] <= base[1] + 1e-12) | (breaks[:-1] >= base[0] - 1e-12)
        coeffs[:, inside] = 0.0
    return breaks, coeffs, A @ c


def _knots(xs, x0, stride, h, special):
    """Every ``stride``-th table point, none closer than two knot spacings to the
    ``special`` knots [(angle, multiplicity)], which are added with their multiplicity
    (so each B-spline keeps table points in its support: the fit stays determined)."""
    tau = xs[::stride]
    for a, _ in special:
        tau = tau[(np.abs(tau - a) >= 1.5 * stride * h) | (tau == x0)]
    if tau[0] != x0:
        tau = np.insert(tau, 0, x0)
    extra = [a for a, mu in special for _ in range(mu)]
    return np.sort(np.concatenate([tau, extra]))


def fit_periodic_lift(
    x, y, base_radius: float, precision: float | None = None, quantum: float = 0.0
) -> LiftFit:
    """Penalised periodic quintic spline through the table (see module docstring).

    precision : RMS deviation allowed [m] (None: the estimated noise, at least the
        table's rounding ``quantum``/√12).

    Two passes when the table has a base circle: a free fit locates where the lift
    leaves zero (its fitted lift exceeds four times its RMS on the middle of the base
    circle), then the final fit is exactly zero up to there."""
    x = np.asarray(x, float)
    y = np.asarray(y, float)
    P = TWO_PI
    sigma = estimate_noise(y)
    if precision is None:
        precision = max(sigma, quantum / math.sqrt(12.0))
    # floor: a table exact to the last float digit is still fitted to 1e-9 of its lift
    precision = max(precision, 1e-9 * float(np.ptp(y)))
    jumps = find_curvature_jumps(x, y, max(precision, sigma, 1e-12), base_radius)
    h = float(np.median(np.diff(x)))
    tiny = 1e-9 * float(np.ptp(y))
    band = max(4.0 * max(sigma, precision), quantum, tiny)
    bc = base_circle(y, band)
    stride = max(1, math.ceil(x.size / _MAX_KNOTS))
    x0 = x[0] if bc is None else x[bc[0]] + 0.5 * ((x[bc[1]] - x[bc[0]]) % P)
    xs = x0 + (x - x0) % P
    order = np.argsort(xs)
    xs, ys = xs[order], y[order]
    special = [(x0 + (a - x0) % P, 4) for a, _ in jumps]
    tau = _knots(xs, x0, stride, h, special)
    breaks, coeffs, yfit = _penalised_fit(xs, ys, x0, tau, None, precision)
    base = None
    if bc is not None:
        # the base circle around x0: from x0 to the first event point, and back
        on = np.abs(ys) <= band
        k_open = int(np.argmin(on))  # first event point after x0
        k_close = xs.size - 1 - int(np.argmin(on[::-1]))  # last event point before x0 + P
        core = np.r_[0 : max(1, k_open // 2), min(xs.size - 1, (k_close + xs.size) // 2) : xs.size]
        b2 = max(4.0 * float(np.sqrt(np.mean(yfit[core] ** 2))), tiny)
        # walk from the event into the base circle while the fitted lift is > b2
        up = yfit > b2
        j_open = k_open
        while j_open > 1 and up[j_open - 1]:
            j_open -= 1
        j_close = k_close
        while j_close < xs.size - 2 and up[j_close + 1]:
            j_close += 1
        lo_edge = xs[max(j_open - 1, 0)]  # last base-circle point before the event
        hi_edge = xs[min(j_close + 1, xs.size - 1)]
        # a curvature jump found next to an edge is the edge
        for a, _ in special:
            if abs(a - lo_edge) <= 2.5 * h:
                lo_edge = a
            if abs(a - hi_edge) <= 2.5 * h:
                hi_edge = a
        if x0 < lo_edge < hi_edge < x0 + P:
            base = (hi_edge, lo_edge)
            special += [(e, 4) for e in (lo_edge, hi_edge) if all(e != a for a, _ in special)]
            tau = _knots(xs, x0, stride, h, special)
            breaks, coeffs, _ = _penalised_fit(xs, ys, x0, tau, base, precision)
    return LiftFit(
        breaks,
        coeffs,
        jumps,
        float(precision),
        None if base is None else (float(base[0] % P), float(base[1] % P)),
    )

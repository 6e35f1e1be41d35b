"""Compiled kernels of the transient march between its Newton solves (numba): the
committed level's arrays, the BDF history moved onto a new grid, the predictor's
extrapolated pressure and cavitated set (:mod:`.transient`) and a new grid's dense
influence matrix (:mod:`.grid`).

Each kernel performs, node by node, the same floating-point operations in the same order
as the NumPy expressions it replaces (linear interpolation as ``numpy.interp``, the
maximum as ``numpy.maximum``), so the march's results do not depend on whether it runs
compiled. Grids are ascending (uniform grids of :class:`~.grid.Grid`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from ...physics.lubricant import density_terms

__all__ = [
    "interp_point",
    "interp_sorted",
    "committed_level",
    "rebased_history",
    "bdf_history",
    "extrapolated_pressure",
    "predicted_cavitation",
    "symmetric_toeplitz",
]

_OPTS = dict(cache=True, nogil=True, fastmath=False)
#: helpers inlined into their callers (no call with array arguments per node)
_INLINE = dict(_OPTS, inline="always")


@njit(**_INLINE)
def _interval(v, xp, j):
    """The largest j' ≥ j with xp[j'] ≤ v (xp ascending, xp[j] ≤ v ≤ xp[-1])."""
    while j + 1 < xp.size and xp[j + 1] <= v:
        j += 1
    return j


@njit(**_OPTS)
def interp_sorted(x, xp, fp, left, right, out):
    """``numpy.interp(x, xp, fp, left, right)`` into ``out`` for ascending x and xp (one
    pass over both): fp[j] at a node, else slope·(x − xp[j]) + fp[j] in the interval
    xp[j] < x < xp[j + 1], from the interval's other end where that is NaN (an infinite
    slope), fp[j] where both are NaN and the ends are equal; NaN stays NaN."""
    j = 0
    top = xp.size - 1
    for i in range(x.size):
        v = x[i]
        if v != v:
            out[i] = v
        elif v < xp[0]:
            out[i] = left
        elif v > xp[top]:
            out[i] = right
        else:
            j = _interval(v, xp, j)
            if j == top or xp[j] == v:
                out[i] = fp[j]
                continue
            slope = (fp[j + 1] - fp[j]) / (xp[j + 1] - xp[j])
            r = slope * (v - xp[j]) + fp[j]
            if r != r:
                r = slope * (v - xp[j + 1]) + fp[j + 1]
                if r != r and fp[j] == fp[j + 1]:
                    r = fp[j]
            out[i] = r
    return out


@njit(**_OPTS)
def interp_point(v, xp, fp):
    """``numpy.interp(v, xp, fp)`` at one point v (xp ascending)."""
    return interp_sorted(np.full(1, v), xp, fp, fp[0], fp[fp.size - 1], np.empty(1))[0]


@njit(**_OPTS)
def committed_level(Q, P, H, p_ref, h_ref, x, law, rho0, q, p, h, rho_h):
    """A solved level in physical units, in place: total and fluid pressure q = Q p_ref,
    p = P p_ref [Pa], film h = H h_ref [m] and ρh = ρ₀ (ρ/ρ₀)(p) h [kg/m²] (the
    lubricant's law, :func:`~tribodyn.physics.lubricant.density_terms`); returns the
    central film h(0) [m]."""
    for i in range(Q.size):
        q[i] = Q[i] * p_ref
        p[i] = P[i] * p_ref
        h[i] = H[i] * h_ref
        rho_h[i] = rho0 * density_terms(p[i], law)[0] * h[i]
    return interp_point(0.0, x, h)


@njit(**_OPTS)
def rebased_history(x, x_old, f_old, rho0, r_old, xe2_lo, xe2_hi, rebase, out):
    """ρh of an old level on the grid x [kg/m²], in place: interpolated inside the old
    grid x_old; outside it continued from its end value with the old parabola,
    f_end + ρ₀ (x² − x_end²)/(2 R_old) (x_end² given: ``xe2_lo``, ``xe2_hi``); then
    re-based on the new radius, + ρ₀ x² (1/(2 R_new) − 1/(2 R_old)) (``rebase``: the
    bracket)."""
    interp_sorted(x, x_old, f_old, 0.0, 0.0, out)
    lo, hi = x_old[0], x_old[x_old.size - 1]
    two_r = 2.0 * r_old
    for i in range(x.size):
        v = x[i]
        x2 = v * v
        if v < lo:
            out[i] = f_old[0] + rho0 * (x2 - xe2_lo) / two_r
        elif v > hi:
            out[i] = f_old[f_old.size - 1] + rho0 * (x2 - xe2_hi) / two_r
        out[i] = out[i] + rho0 * x2 * rebase
    return out


@njit(**_OPTS)
def bdf_history(f1, f2, a0, a1, a2, scale, out):
    """The old levels' term of the variable-step BDF2 derivative, in place:
    f_old = −(a₁ f₁ + a₂ f₂)/a₀ / ``scale`` (f₁, f₂ the last two levels' ρh on the new
    grid; ``scale`` ρ₀ h_ref makes it the scaled ρ̄H of :mod:`.reynolds`)."""
    for i in range(f1.size):
        out[i] = -(a1 * f1[i] + a2 * f2[i]) / a0 / scale
    return out


@njit(**_OPTS)
def extrapolated_pressure(x, x1, q1, x0, q0, ratio, out):
    """max(q₁ + r (q₁ − q₀), 0) on the grid x, in place: the total pressures of the last
    two levels (q₁ on x1, q₀ on x0 [Pa], zero outside their grids) extrapolated linearly
    in time with the step ratio r (NaN stays NaN, −0 becomes 0, as ``numpy.maximum``)."""
    a1 = interp_sorted(x, x1, q1, 0.0, 0.0, np.empty(x.size))
    a0 = interp_sorted(x, x0, q0, 0.0, 0.0, out)
    for i in range(x.size):
        v = a1[i] + ratio * (a1[i] - a0[i])
        out[i] = v if v > 0.0 or v != v else 0.0
    return out


@njit(**_OPTS)
def predicted_cavitation(p1, p0, q1, ratio, share, out):
    """Nodes whose fluid pressure extrapolated from the last two levels on one grid,
    p₁ + r (p₁ − p₀), is at most ``share`` × max|q₁| (none if q₁ has a NaN), in place."""
    peak = 0.0
    for i in range(q1.size):
        a = abs(q1[i])
        if a != a:
            peak = a
            break
        if a > peak:
            peak = a
    limit = share * peak
    for i in range(p1.size):
        out[i] = p1[i] + ratio * (p1[i] - p0[i]) <= limit
    return out


@njit(**_OPTS)
def symmetric_toeplitz(c, out):
    """The symmetric Toeplitz matrix K[i, j] = c[|i − j|] into ``out`` (n × n, n = c.size):
    the dense influence matrix of a uniform grid from its coefficients."""
    n = c.size
    for i in range(n):
        for j in range(i):
            out[i, j] = c[i - j]
        for j in range(i, n):
            out[i, j] = c[j - i]
    return out

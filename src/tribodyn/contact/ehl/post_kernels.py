"""Compiled kernels of the post-processing of an EHL solution (numba): the integrals,
extrema, outlet meniscus and inlet-truncation estimate of :mod:`.postprocess` in one pass
over the node arrays, and the statistics of :mod:`.validity`'s checks.

The equations are those of the two modules' docstrings; the shear stresses are computed
by the caller (the laws of :mod:`tribodyn.physics.friction`). Sums are pairwise, in the
order of NumPy's ``sum`` of a contiguous array (blocks of up to 128 entries summed in 8
interleaved partial sums, larger ranges halved at a multiple of 8), so the integrals are
the same numbers as ``np.sum`` gives and more accurate than a running sum.
"""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from .kernels import all_finite

__all__ = ["pairwise_sum", "abs_sum", "solution_integrals", "validity_stats"]

_OPTS = dict(cache=True, nogil=True, fastmath=False)

#: largest range summed in 8 interleaved partial sums; larger ranges are halved
_BLOCK = 128


@njit(**_OPTS)
def _block(a, lo, n):
    """Σ a[lo : lo + n] for n ≤ 128: a running sum below 8 entries, else 8 interleaved
    partial sums combined pairwise and the rest (n mod 8 entries) added one by one."""
    if n < 8:
        s = 0.0
        for i in range(lo, lo + n):
            s += a[i]
        return s
    r0, r1, r2, r3 = a[lo], a[lo + 1], a[lo + 2], a[lo + 3]
    r4, r5, r6, r7 = a[lo + 4], a[lo + 5], a[lo + 6], a[lo + 7]
    end = lo + n - n % 8
    for i in range(lo + 8, end, 8):
        r0 += a[i]
        r1 += a[i + 1]
        r2 += a[i + 2]
        r3 += a[i + 3]
        r4 += a[i + 4]
        r5 += a[i + 5]
        r6 += a[i + 6]
        r7 += a[i + 7]
    s = ((r0 + r1) + (r2 + r3)) + ((r4 + r5) + (r6 + r7))
    for i in range(end, lo + n):
        s += a[i]
    return s


@njit(**_OPTS)
def _half(n):
    """Length of the first half of a range of n > 128 entries: n // 2 down to a multiple
    of 8."""
    return n // 2 - (n // 2) % 8


@njit(**_OPTS)
def _pairwise(a, lo, n):
    """Σ a[lo : lo + n], pairwise (module docstring): the ranges above 128 entries are
    split in two and their sums added, left + right, walked with an explicit stack
    (numba's cache does not hold recursive functions)."""
    if n <= _BLOCK:
        return _block(a, lo, n)
    starts = np.empty(64, np.int64)  # halving: depth < 64 for any array
    sizes = np.empty(64, np.int64)
    left = np.empty(64)
    right_next = np.zeros(64, np.bool_)  # the left half's sum is in ``left``
    top = 0
    starts[0], sizes[0] = lo, n
    while True:
        m = sizes[top]
        if m > _BLOCK:  # descend into the left half
            right_next[top] = False
            starts[top + 1], sizes[top + 1] = starts[top], _half(m)
            top += 1
            continue
        value = _block(a, starts[top], m)
        top -= 1
        while top >= 0 and right_next[top]:  # both halves done: combine, go up
            value = left[top] + value
            top -= 1
        if top < 0:
            return value
        left[top] = value  # the left half is done: the right half next
        right_next[top] = True
        half = _half(sizes[top])
        starts[top + 1], sizes[top + 1] = starts[top] + half, sizes[top] - half
        top += 1


@njit(**_OPTS)
def pairwise_sum(a):
    """Σ aᵢ of a 1-D array, pairwise (module docstring); 0 for an empty array."""
    return 0.0 + _pairwise(a, 0, a.size)


@njit(**_OPTS)
def abs_sum(a):
    """Σ |aᵢ| of a 1-D array, pairwise."""
    return pairwise_sum(np.abs(a))


@njit(**_OPTS)
def _first_extreme(a, largest):
    """Index of the first largest (or smallest) entry of ``a``; the first NaN if any
    (as ``np.argmax``/``np.argmin``)."""
    k = 0
    for i in range(a.size):
        if math.isnan(a[i]):
            return i
        if (a[i] > a[k]) if largest else (a[i] < a[k]):
            k = i
    return k


@njit(**_OPTS)
def _meniscus(x, p, ipk, zero, direction):
    """Outlet meniscus x_c [m]: the first node downstream of the peak ``ipk`` (along
    ``direction`` = ±1) with p ≤ ``zero``; p ∝ (x_c − x)² near a Reynolds boundary, so √p
    of the two nodes before it is extrapolated linearly to zero (that node itself where
    they do not rise towards the peak). NaN if there is none."""
    n = p.size
    k = 1
    while 0 <= ipk + direction * k < n:
        if p[ipk + direction * k] <= zero:
            j1 = ipk + direction * (k - 1)
            j2 = ipk + direction * (k - 2) if k >= 2 else j1
            s1 = math.sqrt(p[j1])
            s2 = math.sqrt(max(p[j2], 0.0))
            if s2 > s1 > 0 and j1 != j2:
                return x[j1] + (x[j1] - x[j2]) * s1 / (s2 - s1)
            return x[ipk + direction * k]
        k += 1
    return np.nan


@njit(**_OPTS)
def _end_slope(p, e, dx):
    """|dp/dx| [Pa/m] at the end node ``e`` (one-sided, to its neighbour)."""
    nb = e + 1 if e == 0 else e - 1
    return abs(p[nb] - p[e]) / dx


@njit(**_OPTS)
def solution_integrals(x, p, h, pa, tau, tau_b, dx, direction, zero_share):
    """One pass over a solution on a uniform grid (spacing ``dx`` [m]; ``direction`` of
    the entrainment ±1, 0 for a symmetric domain): (Σ|τ|, Σ(h/2) dp/dx, Σp, Σp_a, Σ τ_b
    [sums, times dx the integrals], the far-field rolling share (h/2)|dp/dx| |x_in| at
    the inlet node (0 if ``direction`` is 0), index of h_min, index of the peak
    pressure, the outlet meniscus x_c (NaN if none), whether p and h are finite, and the
    inlet load deficit |dp/dx| x_e²/2 summed over the inlet ends [N/m]).

    dp/dx: central differences, one-sided at the ends (as ``np.gradient``). The meniscus
    is searched downstream of the peak (``direction`` ≥ 0: towards +x) for the first
    pressure ≤ ``zero_share`` · p_max."""
    n = p.size
    roll = np.empty(n)  # (h/2) dp/dx
    roll[0] = 0.5 * h[0] * ((p[1] - p[0]) / dx)
    for i in range(1, n - 1):
        roll[i] = 0.5 * h[i] * ((p[i + 1] - p[i - 1]) / (2.0 * dx))
    roll[n - 1] = 0.5 * h[n - 1] * ((p[n - 1] - p[n - 2]) / dx)
    s_tau = abs_sum(tau)
    s_roll = pairwise_sum(roll)
    s_p = pairwise_sum(p)
    s_pa = pairwise_sum(pa)
    s_b = pairwise_sum(tau_b)
    inlet = 0 if direction > 0 else n - 1
    roll_in = 0.0
    if direction != 0:
        nb = inlet + 1 if inlet == 0 else inlet - 1
        roll_in = 0.5 * h[inlet] * abs(p[nb] - p[inlet]) / dx * abs(x[inlet])
    i_min = _first_extreme(h, False)
    ipk = _first_extreme(p, True)
    x_cav = _meniscus(x, p, ipk, zero_share * p[ipk], 1 if direction >= 0 else -1)
    finite = all_finite(p) and all_finite(h)
    deficit = 0.0
    for e in (0, n - 1):
        if e == inlet or direction == 0:
            deficit += _end_slope(p, e, dx) * x[e] ** 2 / 2.0
    return s_tau, s_roll, s_p, s_pa, s_b, roll_in, i_min, ipk, x_cav, finite, deficit


@njit(**_OPTS)
def validity_stats(x, h, p, pa, low, high):
    """(h finite everywhere, h_min [m], largest |x| of the zone holding the load between
    the shares ``low`` and ``high`` of ∫q dx, q = max(p + p_a, 0) (0 if that integral is
    not positive and finite), peak of p + p_a [Pa]).

    The zone's ends are the first nodes where the running sum of q reaches each share."""
    finite = all_finite(h)
    h_min = h[_first_extreme(h, False)]
    q = p + pa
    p_max = q[_first_extreme(q, True)]
    c = np.empty(q.size)
    acc = 0.0
    for i in range(q.size):
        acc += 0.0 if q[i] < 0.0 else q[i]  # NaN stays NaN
        c[i] = acc
    total = c[-1]
    if not (total > 0.0 and math.isfinite(total)):
        return finite, h_min, 0.0, p_max
    lo = np.searchsorted(c, low * total)
    hi = min(np.searchsorted(c, high * total), x.size - 1)
    return finite, h_min, max(abs(x[lo]), abs(x[hi])), p_max

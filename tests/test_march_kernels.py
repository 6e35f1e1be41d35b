"""The march's compiled kernels give bit for bit the NumPy expressions they replace."""

import numpy as np
import pytest

from tribodyn import Lubricant
from tribodyn.contact.ehl import march_kernels as mk

RNG = np.random.default_rng(7)


def _grids():
    """Pairs (x, xp) of ascending grids that overlap, contain each other, share nodes or
    lie apart, as a transient's old and new grids do."""
    a = np.linspace(-2e-3, 1e-3, 385)
    yield a, a  # the same grid
    yield a, a.copy()
    yield np.linspace(-2.2e-3, 1.1e-3, 385), a  # a longer new grid
    yield np.linspace(-1.5e-3, 0.7e-3, 385), a  # a shorter one
    yield np.linspace(-2.5e-3, 0.5e-3, 129), a  # shifted, other size
    yield np.sort(RNG.uniform(-3e-3, 2e-3, 300)), np.sort(RNG.uniform(-2e-3, 1e-3, 50))
    yield np.linspace(2e-3, 3e-3, 20), a  # all outside
    yield np.concatenate(([-2e-3, -2e-3], a[::7], [1e-3, 1e-3])), a  # on nodes and ends


def _values(n):
    """Node values with the awkward cases: zeros of either sign, a NaN, infinities."""
    f = RNG.normal(size=n) * 1e8
    f[::11] = 0.0
    f[3::13] = -0.0
    return f


@pytest.mark.parametrize("k", range(8))
def test_interpolation_equals_numpy(k):
    x, xp = list(_grids())[k]
    fp = _values(xp.size)
    for left, right in ((0.0, 0.0), (fp[0], fp[-1]), (-3.5, 7.25)):
        out = mk.interp_sorted(x, xp, fp, left, right, np.empty(x.size))
        np.testing.assert_array_equal(out, np.interp(x, xp, fp, left, right), strict=True)
    # NaN and infinite node values (NaN slopes retried from the interval's other end)
    fp[[5, 6, 20]] = [np.inf, np.inf, np.nan]
    fp[-2] = -np.inf
    out = mk.interp_sorted(x, xp, fp, 0.0, 0.0, np.empty(x.size))
    np.testing.assert_array_equal(out, np.interp(x, xp, fp, 0.0, 0.0))
    for v in (*x[:: max(1, x.size // 17)], 0.0, xp[0], xp[-1], xp[-1] * 2, np.nan):
        assert mk.interp_point(v, xp, fp) == pytest.approx(np.interp(v, xp, fp), abs=0, nan_ok=True)


def test_interpolation_keeps_signed_zeros_and_nan_points():
    xp = np.linspace(0.0, 1.0, 5)
    fp = np.array([-0.0, -0.0, 1.0, 2.0, -0.0])
    x = np.array([np.nan, 0.0, 0.1, 0.25, 1.0])
    out = mk.interp_sorted(x, xp, fp, 0.0, 0.0, np.empty(x.size))
    ref = np.interp(x, xp, fp, 0.0, 0.0)
    np.testing.assert_array_equal(out, ref)
    np.testing.assert_array_equal(np.signbit(out), np.signbit(ref))


def _rebased_numpy(x, x_old, f_old, rho0, R_old, R_new):
    """The old level re-based on a new grid and radius, as NumPy expressions."""
    f = np.interp(x, x_old, f_old)
    for side, idx in ((x < x_old[0], 0), (x > x_old[-1], -1)):
        if np.any(side):
            xe = x_old[idx]
            f[side] = f_old[idx] + rho0 * (x[side] ** 2 - xe**2) / (2.0 * R_old)
    return f + rho0 * x**2 * (0.5 / R_new - 0.5 / R_old)


@pytest.mark.parametrize("k", range(8))
def test_rebased_history_equals_numpy(k):
    x, x_old = list(_grids())[k]
    f_old = 850.0 * RNG.uniform(1e-7, 1e-5, x_old.size)
    for R_old, R_new in ((0.02, 0.02), (0.0131, 0.0173), (0.05, -0.4)):
        rebase = 0.5 / R_new - 0.5 / R_old
        args = (850.0, R_old, x_old[0] ** 2, x_old[-1] ** 2, rebase, np.empty(x.size))
        out = mk.rebased_history(x, x_old, f_old, *args)
        ref = _rebased_numpy(x, x_old, f_old, 850.0, R_old, R_new)
        np.testing.assert_array_equal(out, ref, strict=True)


@pytest.mark.parametrize("k", range(8))
def test_extrapolated_pressure_equals_numpy(k):
    x, x1 = list(_grids())[k]
    x0 = np.linspace(x1[0] * 0.97, x1[-1] * 1.05, x1.size)
    q1, q0 = np.abs(_values(x1.size)), np.abs(_values(x0.size))
    q1[4], q0[9] = np.nan, np.inf
    for ratio in (1.0, 0.5, 2.7):
        a1 = np.interp(x, x1, q1, 0.0, 0.0)
        a0 = np.interp(x, x0, q0, 0.0, 0.0)
        ref = np.maximum(a1 + ratio * (a1 - a0), 0.0)
        out = mk.extrapolated_pressure(x, x1, q1, x0, q0, ratio, np.empty(x.size))
        np.testing.assert_array_equal(out, ref, strict=True)
        np.testing.assert_array_equal(np.signbit(out), np.signbit(ref))


def test_maximum_of_signed_zeros_and_nan_equals_numpy():
    """−0 (from −0 + r·(−0 − 0)) becomes +0 and NaN stays NaN, as numpy.maximum does."""
    x = np.linspace(0.0, 1.0, 6)
    q1 = np.array([-0.0, -0.0, np.nan, 1.0, 0.0, -1.0])
    q0 = np.array([0.0, -0.0, 1.0, 3.0, 0.0, 2.0])
    ref = np.maximum(q1 + 1.5 * (q1 - q0), 0.0)
    out = mk.extrapolated_pressure(x, x, q1, x, q0, 1.5, np.empty(6))
    np.testing.assert_array_equal(out, ref)
    np.testing.assert_array_equal(np.signbit(out), np.signbit(ref))


@pytest.mark.parametrize("nan", [False, True])
def test_predicted_cavitation_equals_numpy(nan):
    n = 385
    p1, p0 = _values(n), _values(n)
    q1 = _values(n)
    if nan:
        q1[7] = np.nan
    for ratio, share in ((0.5, 1e-12), (1.3, 0.1)):
        ref = p1 + ratio * (p1 - p0) <= share * float(np.max(np.abs(q1)))
        out = mk.predicted_cavitation(p1, p0, q1, ratio, share, np.empty(n, dtype=np.bool_))
        np.testing.assert_array_equal(out, ref, strict=True)


@pytest.mark.parametrize(
    "oil",
    [Lubricant(0.005, 1.5e-8), Lubricant(0.005, 1.5e-8, compressible=False)],
    ids=["compressible", "incompressible"],
)
def test_committed_level_equals_the_lubricants_methods(oil):
    n = 385
    x = np.linspace(-2e-3, 1e-3, n)
    Q, P, H = RNG.uniform(0, 3, n), RNG.uniform(-1e-3, 3, n), RNG.uniform(0.5, 9, n)
    p_ref, h_ref = 3.7e8, 2.1e-7
    out = [np.empty(n) for _ in range(4)]
    hc = mk.committed_level(Q, P, H, p_ref, h_ref, x, oil.rheology_law, oil.density, *out)
    q, p, h = Q * p_ref, P * p_ref, H * h_ref
    for got, ref in zip(out, (q, p, h, oil.density_at(p) * h)):
        np.testing.assert_array_equal(got, ref, strict=True)
    assert hc == float(np.interp(0.0, x, h))


def test_bdf_history_equals_numpy():
    n = 385
    f1, f2 = 850.0 * RNG.uniform(1e-7, 1e-5, n), 850.0 * RNG.uniform(1e-7, 1e-5, n)
    for r in (1.0, 0.37, 2.9):
        a0, a1, a2 = (1 + 2 * r) / (1 + r), -(1 + r), r * r / (1 + r)
        scale = 850.0 * 3.1e-7
        ref = -(a1 * f1 + a2 * f2) / a0 / scale
        out = mk.bdf_history(f1, f2, a0, a1, a2, scale, np.empty(n))
        np.testing.assert_array_equal(out, ref, strict=True)


def test_symmetric_toeplitz_equals_scipy():
    from scipy import linalg

    for n in (1, 2, 7, 385):
        c = RNG.normal(size=n)
        K = mk.symmetric_toeplitz(c, np.empty((n, n)))
        np.testing.assert_array_equal(K, linalg.toeplitz(c), strict=True)
        assert K.flags.c_contiguous

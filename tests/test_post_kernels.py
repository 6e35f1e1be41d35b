"""The compiled post-processing kernels against the NumPy expressions they replace: the
sums bit for bit (NumPy's pairwise order), the extrema, the outlet meniscus of a
Reynolds-boundary profile, the inlet estimates and the load zone of the validity check."""

import math

import numpy as np
import pytest

from tribodyn.contact.ehl.post_kernels import (
    abs_sum,
    pairwise_sum,
    solution_integrals,
    validity_stats,
)


@pytest.mark.parametrize("n", [0, 1, 7, 8, 9, 127, 128, 129, 255, 256, 385, 1000, 4099])
def test_sums_are_numpys_bit_for_bit(n):
    rng = np.random.default_rng(n)
    a = rng.standard_normal(n) * 10.0 ** rng.uniform(-6, 6, n)
    assert pairwise_sum(a) == np.sum(a)
    assert abs_sum(a) == np.sum(np.abs(a))
    assert pairwise_sum(a[::3]) == np.sum(a[::3])  # strided


def test_sum_is_pairwise_not_running():
    # 1 followed by many entries below half an ulp of 1: a running sum drops all of them
    a = np.concatenate([[1.0], np.full(4095, 1e-17)])
    running = 0.0
    for v in a:
        running += v
    assert running == 1.0
    assert pairwise_sum(a) == pytest.approx(1.0 + 4095e-17, rel=1e-15)


def _profile(direction, n=385):
    """x, a Hertz-like p that falls to zero as (x_c − x)² at the outlet x_c, a film, a
    shear stress and an asperity pressure."""
    x = np.linspace(-3.0, 1.5, n) * 1e-4
    if direction < 0:
        x = -x[::-1]
    xc = 1.2345e-4 * (1 if direction >= 0 else -1)
    s = direction if direction else 1
    p = np.where(s * (xc - x) > 0, 1e9 * ((xc - x) / 1e-4) ** 2 * np.exp(-((x / 1e-4) ** 2)), 0.0)
    h = 1e-7 + x**2 / 0.04
    rng = np.random.default_rng(3)
    tau = rng.standard_normal(n) * 1e7
    pa = np.abs(rng.standard_normal(n)) * 1e6
    return x, p, h, tau, pa, xc


@pytest.mark.parametrize("direction", [1, -1, 0])
def test_solution_integrals_match_numpy(direction):
    x, p, h, tau, pa, xc = _profile(direction)
    dx = x[1] - x[0]
    tau_b = 0.1 * pa
    s_tau, s_roll, s_p, s_pa, s_b, roll_in, i_min, ipk, x_cav, finite, deficit = solution_integrals(
        x, p, h, pa, tau, tau_b, dx, direction, 1e-12
    )
    assert s_tau == np.sum(np.abs(tau))
    assert s_roll == np.sum(0.5 * h * np.gradient(p, dx))
    assert (s_p, s_pa, s_b) == (np.sum(p), np.sum(pa), np.sum(tau_b))
    assert (i_min, ipk) == (np.argmin(h), np.argmax(p))
    assert finite
    n = x.size
    inlet = n - 1 if direction < 0 else 0
    nb = 1 if inlet == 0 else n - 2
    far = 0.5 * h[inlet] * abs(p[nb] - p[inlet]) / dx * abs(x[inlet])
    assert roll_in == (far if direction else 0.0)
    ends = [0, n - 1] if direction == 0 else [inlet]
    expected = sum(abs(p[e + 1 if e == 0 else e - 1] - p[e]) / dx * x[e] ** 2 / 2 for e in ends)
    assert deficit == pytest.approx(expected, rel=1e-15)
    if direction != 0:  # p ∝ (x_c − x)² times a smooth factor: x_c within a fraction of dx
        assert abs(x_cav - xc) < 0.05 * abs(dx)


def test_meniscus_extrapolates_a_parabola_exactly():
    x = np.arange(10.0)
    p = np.maximum(6.5 - x, 0.0) ** 2  # zero from x = 7 on, x_c = 6.5
    out = solution_integrals(x, p, np.ones(10), p, p, p, 1.0, 1, 1e-12)
    assert out[8] == pytest.approx(6.5, rel=1e-14)
    # the peak at the last node: no zero downstream
    assert math.isnan(solution_integrals(x, x, np.ones(10), x, x, x, 1.0, 1, 1e-12)[8])


def test_non_finite_and_nan_extrema():
    x, p, h, tau, pa, _ = _profile(1)
    p[10] = np.nan
    out = solution_integrals(x, p, h, pa, tau, pa, x[1] - x[0], 1, 1e-12)
    assert out[9] is False and out[7] == 10  # np.argmax: the first NaN
    h[5] = np.inf
    assert solution_integrals(x, p * 0, h, pa, tau, pa, x[1] - x[0], 1, 1e-12)[9] is False


def _zone(x, q, low, high):
    c = np.cumsum(np.clip(q, 0.0, None))
    if c[-1] <= 0.0 or not np.isfinite(c[-1]):
        return 0.0
    lo, hi = np.searchsorted(c, [low * c[-1], high * c[-1]])
    return float(max(abs(x[lo]), abs(x[min(hi, x.size - 1)])))


@pytest.mark.parametrize("seed", range(5))
def test_validity_stats_match_numpy(seed):
    rng = np.random.default_rng(seed)
    x, p, h, _, pa, _ = _profile(1)
    p = p - 1e8 * rng.random(x.size)  # some negative pressures, clipped in the zone
    finite, h_min, zone, p_max = validity_stats(x, h, p, pa, 0.01, 0.99)
    assert finite and h_min == h.min() and p_max == np.max(p + pa)
    assert zone == _zone(x, p + pa, 0.01, 0.99)
    assert validity_stats(x, h, -np.abs(p) - pa, pa, 0.01, 0.99)[2] == 0.0  # nothing carried
    h[3] = np.nan
    assert validity_stats(x, h, p, pa, 0.01, 0.99)[0] is False

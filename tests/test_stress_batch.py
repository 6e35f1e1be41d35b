"""The batched peak path of a cycle (physics.stress.StressOperator.peaks_batch and its
compiled kernels) against the double-precision fields of StressOperator.apply, NumPy
searches over those fields, and the layered solution's own boundary conditions."""

import math

import numpy as np
import pytest

from tribodyn import Body, Coating, Material
from tribodyn.physics.stress import PEAKS, SCALE_GROUP, StressOperator
from tribodyn.physics.stress_kernels import _layer_solutions, _peak_search

STEEL = Material(E=210e9, nu=0.3)
B = 1e-4  # half-width [m]
P0 = 1e9  # peak pressure [Pa]
N = 256
DX = 6.0 * B / N


def loads(ns, seed=0):
    """Hertz-like pressures of varied width, centre and peak with a sliding traction of
    varied sign and size, on the operator's grid: (p, q) arrays (ns, N) [Pa]."""
    rng = np.random.default_rng(seed)
    x = DX * np.arange(N)
    p, q = np.zeros((ns, N)), np.zeros((ns, N))
    for i in range(ns):
        b = B * rng.uniform(0.5, 1.0)
        c = x[N // 2] + B * rng.uniform(-0.5, 0.5)
        p[i] = P0 * rng.uniform(0.3, 1.0) * np.sqrt(np.clip(1.0 - ((x - c) / b) ** 2, 0, None))
        q[i] = rng.uniform(-0.2, 0.2) * p[i]
    return p, q


@pytest.fixture(scope="module", params=["uncoated", "coated"])
def operator(request):
    body = Body(STEEL) if request.param == "uncoated" else Body(STEEL, Coating(400e9, 0.22, 5e-6))
    z = DX * np.geomspace(2.0, 100.0, 12)
    if body.coating is not None:
        z = np.concatenate([[2.5e-6], z[z > 5e-6]])
    return StressOperator(N, DX, body, z)


def test_batched_peaks_match_the_double_precision_fields(operator):
    p, q = loads(5)
    x0 = np.linspace(0.0, 1e-3, 5)
    pk = operator.peaks_batch(p, q, x0)
    for i in range(5):
        ref = operator.apply(p[i], q[i], x0[i] + DX * np.arange(N)).peaks()
        for name in PEAKS:
            v, x, z = (a[i] for a in pk[name])
            r = ref[name]
            if math.isnan(r.value):
                assert math.isnan(v) and math.isnan(x) and math.isnan(z)
                continue
            if name == "max_von_mises_substrate":
                # refined between depth levels (parabola in ln z): at least the levels'
                # maximum, and the field's maximum at the refined depth within 0.5 %
                assert v >= r.value - 1e-5 * P0
                at = StressOperator(N, DX, operator.body, [z]).apply(p[i], q[i])
                assert v == pytest.approx(at.von_mises[0].max(), rel=5e-3)
                assert abs(x - r.x) <= 2 * DX
                continue
            # single precision: the values to ~1e-6 of the load
            assert v == pytest.approx(r.value, abs=1e-5 * P0)
            assert abs(x - r.x) <= DX * (1 + 1e-9)
            assert z == r.z


def test_a_sample_does_not_depend_on_the_batch_it_is_in(operator):
    p, q = loads(3 * SCALE_GROUP + 3, seed=1)
    x0 = np.zeros(p.shape[0])
    whole = operator.peaks_batch(p, q, x0)
    for g in range(0, p.shape[0], SCALE_GROUP):
        sl = slice(g, g + SCALE_GROUP)
        part = operator.peaks_batch(p[sl], q[sl], x0[sl])
        for name in PEAKS:
            for a, b in zip(whole[name], part[name], strict=True):
                np.testing.assert_array_equal(a[sl], b)


def test_compiled_peak_search_is_numpy_argmax():
    rng = np.random.default_rng(2)
    ns, nz, n = 3, 7, 40
    f = rng.standard_normal((ns, nz, 3, n + 9)).astype(np.float32)
    # ties at the largest von Mises stress below the coating and tension on the surface:
    # the first in (row, node) order wins
    f[:, 2, :, 5] = f[:, 2, :, 30] = [10.0, -10.0, 5.0]  # (σ_xx, σ_zz, σ_xz)
    f[:, 5, :, 7] = f[:, 5, :, 8] = [20.0, 19.0, 0.0]
    coat = np.array([True, True, False, False, False, True, True])
    nu = np.where(coat, 0.22, 0.3).astype(np.float32)
    surface, interface = 5, 6
    val, row, col = _peak_search(f, nu, coat, n, surface, interface)
    sxx, szz, sxz = (f[:, :, c, :n].astype(np.float64) for c in range(3))
    syy = nu[None, :, None] * (sxx + szz)
    vm2 = 0.5 * ((sxx - syy) ** 2 + (syy - szz) ** 2 + (szz - sxx) ** 2) + 3.0 * sxz**2
    s1 = np.maximum(0.5 * (sxx + szz) + np.hypot(0.5 * (sxx - szz), sxz), syy)
    every = np.arange(nz)
    fields = (vm2, vm2, s1, s1, np.abs(sxz), szz)
    rows = (coat, ~coat, every == surface, coat, every == interface, every == interface)
    for k in range(6):
        for s in range(ns):
            a = np.where(rows[k][:, None], fields[k][s], -np.inf)
            r, c = np.unravel_index(np.argmax(a), a.shape)
            assert (row[s, k], col[s, k]) == (r, c)
            assert val[s, k] == pytest.approx(a[r, c], rel=1e-6)


def test_layer_solutions_meet_the_boundary_conditions():
    """The coefficients satisfy f(0) = 1, f_s(0) = 0 (pressure) and f(0) = 0, f_s(0) = 1
    (shear) and, at the interface s = t, continuity of f, f_s and of the displacements
    u_x ∝ [(1−ν)f_ss + νf]/G, u_z ∝ [(1−ν)f_sss − (2−ν)f_s]/G."""
    coat, sub = Material(E=400e9, nu=0.22), STEEL
    t = np.geomspace(1e-3, 30.0, 50)
    sol = _layer_solutions(t, coat, sub)
    A, B_, C, D, E, F = (sol[:, i, :] for i in range(6))
    tt = t[:, None]
    et = np.exp(-tt)

    def coating(d):  # d-th derivative in s of the coating's f at s
        def at(s):
            es, ws = np.exp(-s), np.exp(s - tt)
            w = s - tt
            sgn = (-1.0) ** d
            return (sgn * A + sgn * B_ * (s - d)) * es + (C + D * (w + d)) * ws

        return at

    # surface s = 0
    np.testing.assert_allclose(coating(0)(0.0 * tt), [[1.0, 0.0]] * t.size, atol=1e-12)
    np.testing.assert_allclose(coating(1)(0.0 * tt), [[0.0, 1.0]] * t.size, atol=1e-12)
    # interface s = t: substrate f = (E + F(s−t))e^{−(s−t)}, derivatives at s = t
    sub_d = [E, F - E, E - 2.0 * F, 3.0 * F - E]
    c_d = [coating(d)(tt) for d in range(4)]
    g = sub.shear_modulus / coat.shear_modulus
    scale = 1.0 + np.abs(sol).max(axis=1)
    np.testing.assert_allclose(c_d[0] / scale, sub_d[0] / scale, atol=1e-12)
    np.testing.assert_allclose(c_d[1] / scale, sub_d[1] / scale, atol=1e-12)
    ux_c = g * ((1 - coat.nu) * c_d[2] + coat.nu * c_d[0])
    ux_s = (1 - sub.nu) * sub_d[2] + sub.nu * sub_d[0]
    uz_c = g * ((1 - coat.nu) * c_d[3] - (2 - coat.nu) * c_d[1])
    uz_s = (1 - sub.nu) * sub_d[3] - (2 - sub.nu) * sub_d[1]
    np.testing.assert_allclose(ux_c / scale, ux_s / scale, atol=1e-11)
    np.testing.assert_allclose(uz_c / scale, uz_s / scale, atol=1e-11)
    assert np.all(np.isfinite(et))


def test_a_sample_does_not_depend_on_the_chunk_it_is_searched_in(operator, monkeypatch):
    import tribodyn.physics.stress as stress

    p, q = loads(2 * SCALE_GROUP + 3, seed=3)
    x0 = np.zeros(p.shape[0])
    out = []
    for size in (1, 2**40):  # one sample at a time, all at once
        monkeypatch.setattr(stress, "CHUNK_BYTES", size)
        op = StressOperator(N, DX, operator.body, operator.depths)
        assert op._chunk == 1 if size == 1 else op._chunk >= p.shape[0]
        out.append(op.peaks_batch(p, q, x0))
    for name in PEAKS:
        for a, b in zip(out[0][name], out[1][name], strict=True):
            np.testing.assert_array_equal(a, b)


def test_operators_are_kept_by_grid_body_and_depths(operator, monkeypatch):
    import tribodyn.workflow.stress_study as study

    monkeypatch.setattr(study, "_OPERATORS", type(study._OPERATORS)())
    z = operator.depths
    first = study._operator(N, DX, operator.body, z)
    assert study._operator(N, DX, Body(STEEL, operator.body.coating), z.copy()) is first
    other = study._operator(N, DX, operator.body, z[:-1])
    assert other is not first and other.depths.size == z.size - 1
    assert study._operator(N, 1.5 * DX, operator.body, z) is not first
    # beyond the budget the least recently used goes first
    monkeypatch.setattr(study, "_KEEP_BYTES", 2.5 * 1.5 * first.transfer_bytes)
    study._operator(N, DX, operator.body, z)  # the first, now the most recent
    study._operator(N, 2.0 * DX, operator.body, z)
    kept = list(study._OPERATORS.values())
    assert first in kept and other not in kept

"""Transient EHL: relaxation after a load step, passage through zero entrainment."""

import math

import numpy as np
import pytest

from ehl_cases import E_PRIME, OIL, PAIR, R, conditions
from independent import squeeze_balance_error
from tribodyn import Lubricant, TransientEHL, solve_ehl
from tribodyn.physics.regimes import hamrock_groups, moes_central


def test_load_step_relaxes_to_new_steady_state():
    w, u, _, _ = conditions(20, 10)
    tr = TransientEHL(PAIR, OIL)
    start = tr.start_steady(w, R, u, 0.5)
    b = math.sqrt(8 * w * R / (math.pi * E_PRIME))
    dt = 0.05 * b / u
    hc = []
    for _ in range(120):
        r = tr.step(dt, 1.5 * w, R, u, 0.5)
        assert r.converged, r.message
        assert r.hydrodynamic_load == pytest.approx(1.5 * w, rel=1e-9)
        hc.append(r.central_film)
    # the steady solution of the same discrete problem (on the transient's grid, whose
    # extent in Hertz half-widths b at the new load is given explicitly)
    b1 = math.sqrt(8 * 1.5 * w * R / (math.pi * E_PRIME))
    target = solve_ehl(
        1.5 * w, R, u, 0.5, PAIR, OIL, n=r.x.size, inlet=-r.x[0] / b1, outlet=r.x[-1] / b1
    )
    assert target.x[0] == pytest.approx(r.x[0], rel=1e-12)
    # the film first keeps its old thickness (the oil must be squeezed out) ...
    assert hc[0] > 1.02 * target.central_film
    # ... then relaxes to the new steady solution
    assert r.central_film == pytest.approx(target.central_film, rel=2e-3)
    assert r.min_film == pytest.approx(target.min_film, rel=2e-3)
    assert start.central_film > target.central_film


def test_passage_through_zero_entrainment_keeps_a_film():
    """u_e ramps from +u to −u through zero at constant load (cam-nose-like); the steady
    theory predicts h → 0 at u_e = 0, the squeeze term keeps the film finite."""
    w = 4e4  # N/m
    R_ = 0.005
    u0 = 1.0
    oil = Lubricant(0.055, 1.05e-8)
    tr = TransientEHL(PAIR, oil)
    tr.start_steady(w, R_, u0, 3.0)
    T = 2e-3  # ramp duration [s]
    nstep = 80
    dt = T / nstep
    hc, ue_hist, squeeze, profiles = [], [], [], []
    for k in range(1, nstep + 1):
        ue = u0 * (1 - 2 * k / nstep)
        r = tr.step(dt, w, R_, ue, 3.0)
        assert r.converged, r.message
        assert np.all(np.isfinite(r.film)) and np.all(np.isfinite(r.pressure))
        profiles.append((r.x.copy(), r.pressure.copy(), r.film.copy()))
        hc.append(r.central_film)
        ue_hist.append(ue)
        squeeze.append(r.squeeze_velocity)
    hc = np.array(hc)
    i0 = int(np.argmin(np.abs(ue_hist)))
    assert ue_hist[i0] == pytest.approx(0.0, abs=1e-12)
    # at u_e = 0 the load is carried by squeeze alone: the transient Reynolds equation,
    # recomputed from the profiles of the last three steps (measured: 1.4e-4)
    b = math.sqrt(8 * w * R_ / (math.pi * E_PRIME))
    assert squeeze_balance_error(profiles[i0 - 2 : i0 + 1], dt, oil, b) < 0.01
    # quasi-steady estimate at the smallest non-zero |u_e| of the ramp
    W, U, Gg = hamrock_groups(w, R_, u0 * 2 / nstep, 0.055, 1.05e-8, E_PRIME)
    h_qs = float(moes_central(W, U, Gg, R_))
    assert hc[i0] > 2 * h_qs  # squeeze film outlives the steady film
    assert hc.min() > 0.0
    # the film decreases through the reversal (oil is squeezed out, not created): without
    # entrainment only the approach of the surfaces can carry the load
    assert hc[i0] < hc[0]
    assert squeeze[i0] > 0.0 and squeeze[i0] == pytest.approx(-(hc[i0] - hc[i0 - 1]) / dt)


def _reversal_film(nstep, order):
    """h_c at u_e = 0 (half-way through the ramp of the test above) with nstep steps."""
    oil = Lubricant(0.055, 1.05e-8)
    tr = TransientEHL(PAIR, oil, time_order=order)
    tr.start_steady(4e4, 0.005, 1.0, 3.0)
    profiles = []
    for k in range(1, nstep // 2 + 1):
        r = tr.step(2e-3 / nstep, 4e4, 0.005, 1.0 * (1 - 2 * k / nstep), 3.0)
        assert r.converged, r.message
        profiles.append((r.x.copy(), r.pressure.copy(), r.film.copy()))
    # the step solved the transient Reynolds equation of its own scheme (independent check)
    b = math.sqrt(8 * 4e4 * 0.005 / (math.pi * E_PRIME))
    assert squeeze_balance_error(profiles[-(order + 1) :], 2e-3 / nstep, oil, b) < 0.01
    return r.central_film


@pytest.mark.parametrize("order, expected", [(2, 2.0), (1, 1.0)])
def test_time_step_halving_gives_the_scheme_order(order, expected):
    """Halving the step through the reversal: the differences of h_c at u_e = 0 fall as
    dtᵖ with p the order of the time scheme (BDF2: 2, backward Euler: 1); the 80-step film
    (25 µs steps) is within 0.2 % (BDF2) or 2 % (BDF1) of the Richardson extrapolation."""
    h = [_reversal_film(n, order) for n in (20, 40, 80)]
    d1, d2 = h[0] - h[1], h[1] - h[2]
    assert d1 != 0.0 and d2 != 0.0
    p = math.log2(abs(d1 / d2))
    assert p == pytest.approx(expected, abs=0.35)
    extrapolated = h[2] - d2 / (2**expected - 1)
    assert h[2] == pytest.approx(extrapolated, rel=2e-3 if order == 2 else 2e-2)


def test_transient_requires_a_start_and_positive_dt():
    from tribodyn import InputError

    tr = TransientEHL(PAIR, OIL)
    with pytest.raises(InputError, match="start"):
        tr.step(1e-6, 1e5, R, 1.0, 0.0)
    tr.start_film(1e-6, 1e5, R, 1.0, 0.0)
    with pytest.raises(InputError, match="^dt must"):
        tr.step(0.0, 1e5, R, 1.0, 0.0)


def test_compiled_gmres_matches_the_numpy_loop(monkeypatch):
    """The compiled LU-preconditioned GMRES (gmres_kernels.gmres_lu) solves the Newton systems
    of a rough-surface load and entrainment transient to its tolerance (true residual,
    by the NumPy matrix-free product), and gives the same films, loads and Newton
    iterations as the NumPy loop in newton.gmres."""
    from tribodyn import Roughness
    from tribodyn.contact.ehl import reynolds

    krylov, original = [], reynolds.Linearization.gmres_lu

    def checked(lin, fac, piv, rtol, max_it):
        out = original(lin, fac, piv, rtol, max_it)
        if out is not None and out[0] is not None:
            x, its = out
            res = np.linalg.norm(lin.matvec(x) - lin.rhs) / np.linalg.norm(lin.rhs)
            assert res < 10 * rtol, (res, its)
            krylov.append(its)
        return out

    def none(*args):
        return None

    rough = Roughness(asperity_density=8.3e9, rms=0.2e-6, summit_radius=0.669e-6)

    def run(compiled):
        # without the compiled kernel (None: not applicable) gmres runs its NumPy loop
        monkeypatch.setattr(reynolds.Linearization, "gmres_lu", checked if compiled else none)
        tr = TransientEHL(PAIR, Lubricant(0.055, 1.05e-8), roughness=rough)
        tr.start_steady(4e4, 0.005, 1.0, 3.0)
        out = []
        for k in range(1, 25):
            r = tr.step(2.5e-5, 4e4 * (1 + 0.02 * k), 0.005, 1.0 - 0.08 * k, 3.0)
            assert r.converged, r.message
            out.append((r.central_film, r.min_film, r.asperity_load, r.iterations))
        return np.array(out)

    ref = run(False)
    new = run(True)
    assert sum(k > 0 for k in krylov) > 20  # the compiled kernel did Krylov iterations
    assert ref[:, 2].max() > 0.0  # asperities carry load: the mixed branch is exercised
    np.testing.assert_allclose(new[:, :3], ref[:, :3], rtol=1e-9)
    np.testing.assert_array_equal(new[:, 3], ref[:, 3])


def newton_matrix(AP, B, col, c, free, cav, D, K, ks, dX) -> np.ndarray:
    """Reference dense Newton matrix of reynolds.Linearization from its definition: free
    rows c_i[A_P + ks B K | B·1], cavitated rows [e_i − ks D_i K_i | −D_i], boundary rows
    e_i, load row [ΔX … | 0]; bands as (5, n), row d + 2 multiplying v[i + d]."""
    n = D.size

    def banded(A):
        M = np.zeros((n, n))
        for d in range(-2, 3):
            i = np.arange(max(0, -d), min(n, n - d))
            M[i, i + d] = A[d + 2, i]
        return M

    eye = np.eye(n)
    J = np.zeros((n + 1, n + 1))
    J[:n, :n] = np.where(
        free[:, None],
        c[:, None] * (banded(AP) + ks * banded(B) @ K),
        eye - np.where(cav, ks * D, 0.0)[:, None] * K,
    )
    J[:n, n] = np.where(free, c * col, np.where(cav, -D, 0.0))
    J[n, :n] = dX
    return J


@pytest.mark.parametrize("elastic", [True, False])
def test_compiled_gmres_solves_a_random_newton_system(elastic):
    """gmres_kernels.gmres_lu on a random banded Newton system with a symmetric Toeplitz K
    and a perturbed LU as preconditioner: the solution of the assembled dense matrix (LAPACK
    solve), and a clean failure (ok = False) when the system holds a NaN."""
    from scipy import linalg

    from tribodyn.contact.ehl import gmres_kernels as g
    from tribodyn.contact.ehl import kernels as k

    rng = np.random.default_rng(7)
    n = 120
    AP = rng.normal(size=(5, n))
    AP[2] += 6.0  # diagonally dominant bands
    AH = 0.1 * rng.normal(size=(5, n))
    D = 0.05 * rng.random(n)
    B, col = k.coupling_bands(AP, AH, D)
    c = 1.0 + rng.random(n)
    cav = np.zeros(n, dtype=bool)
    cav[90:100] = True
    free = ~cav
    free[0] = free[-1] = False
    K = linalg.toeplitz(1.0 / (1.0 + np.arange(n))) if elastic else np.zeros((0, 0))
    ks, dX = 0.3, 0.01
    J = newton_matrix(AP, B, col, c, free, cav, D, K if elastic else np.zeros((n, n)), ks, dX)
    fac, piv = linalg.lu_factor(J * (1.0 + 0.05 * rng.random(J.shape)))  # an earlier matrix
    b = rng.normal(size=n + 1)
    system = (AP, B, col, c, free, cav, D, K, ks, elastic, dX)
    x, its, ok = g.gmres_lu(g.GETRS, g.SYMV, system, fac, piv + 1, b, 1e-12, 30)
    assert ok and 0 < its <= 30
    exact = np.linalg.solve(J, b)
    assert np.linalg.norm(x - exact) <= 1e-9 * np.linalg.norm(exact)
    bad = AP.copy()
    bad[2, 40] = np.nan
    _, _, ok = g.gmres_lu(g.GETRS, g.SYMV, (bad, *system[1:]), fac, piv + 1, b, 1e-12, 30)
    assert not ok


def test_compiled_gmres_with_a_single_precision_preconditioner():
    """Flexible GMRES with float32 LU factors (gmres_kernels.SGETRS) of the matrix assembled in
    single precision (kernels.dense_matrix_t, tiny entries flushed) solves the
    double-precision Newton system to its tolerance (checked against LAPACK's dense solve
    of the double-precision matrix assembled from its definition); factors beyond single
    precision's range are refused (newton then factorises in double precision)."""
    from scipy import linalg

    from tribodyn.contact.ehl import gmres_kernels as g
    from tribodyn.contact.ehl import kernels as k
    from tribodyn.contact.ehl import reynolds

    rng = np.random.default_rng(11)
    n = 150
    AP = rng.normal(size=(5, n))
    AP[2] += 6.0
    AH = 0.1 * rng.normal(size=(5, n))
    D = 0.05 * rng.random(n)
    D[60:70] = 1e-200  # far from the contact: subnormal in single precision
    B, col = k.coupling_bands(AP, AH, D)
    c = 1.0 + rng.random(n)
    cav = np.zeros(n, dtype=bool)
    cav[100:110] = True
    cav[60:70] = True
    free = ~cav
    free[0] = free[-1] = False
    K = linalg.toeplitz(1.0 / (1.0 + np.arange(n)))
    ks, dX = 0.3, 0.01
    rows = (AP, B, col, c, free, cav, D)
    J = newton_matrix(*rows, K, ks, dX)
    J64 = k.dense_matrix_t(*rows, K, ks, dX, True, 0.0, np.empty((n + 1, n + 1)))
    np.testing.assert_allclose(J64.T, J, rtol=1e-13, atol=1e-15 * np.abs(J).max())
    earlier = [a * (1.0 + 0.05 * rng.random(a.shape)) for a in (AP, B)]  # an earlier matrix
    J32 = k.dense_matrix_t(
        earlier[0],
        earlier[1],
        col,
        c,
        free,
        cav,
        D,
        K,
        ks,
        dX,
        True,
        reynolds._FLUSH,
        np.empty((n + 1, n + 1), dtype=np.float32),
    ).T
    tiny = np.finfo(np.float32).tiny
    assert not np.any((J32 != 0.0) & (np.abs(J32) < tiny))  # no subnormal entries
    fac, piv = linalg.lu_factor(J32, overwrite_a=True, check_finite=False)
    assert fac.dtype == np.float32 and g.flush_factors(fac.T.reshape(-1), g.FACTOR_FLUSH)
    b = rng.normal(size=n + 1)
    b[5] = 1e-300  # a subnormal entry in single precision
    system = (*rows, K, ks, True, dX)
    x, its, ok = g.gmres_lu(g.SGETRS, g.SYMV, system, fac, piv + 1, b, 1e-12, 30)
    assert ok and 0 < its <= 30
    exact = np.linalg.solve(J, b)
    assert np.linalg.norm(x - exact) <= 1e-9 * np.linalg.norm(exact)
    assert not g.flush_factors(np.full(16, 1e39), g.FACTOR_FLUSH)


def test_factor_flush_and_step_motion_kernels():
    """gmres_kernels.flush_factors zeroes entries below rel·max|f| (either sign) and refuses a
    NaN or infinite entry wherever it sits; kernels.step_motion gives the largest |δQ|
    and |Q| (NaN kept) and whether the cavitated set gained or released nodes."""
    from tribodyn.contact.ehl import gmres_kernels as g
    from tribodyn.contact.ehl import kernels as k

    f = np.array([3e-21, -4.0, 2.0, -3e-20, 1e-19], dtype=np.float32)
    assert g.flush_factors(f, 1e-20)
    # threshold 1e-20 * 4 = 4e-20: 3e-21 and -3e-20 go, 1e-19 stays (exact float32)
    assert np.array_equal(f, np.array([0.0, -4.0, 2.0, 0.0, 1e-19], dtype=np.float32))
    for bad in (np.nan, np.inf, -np.inf):
        for at in (0, 2, 4):
            f = np.ones(5, dtype=np.float32)
            f[at] = bad
            assert not g.flush_factors(f, 1e-20)
    dq, q = np.array([0.5, -2.0, 1.0]), np.array([1.0, 3.0, -7.0])
    before = np.array([False, True, True, False])
    assert k.step_motion(dq, q, before, before) == (2.0, 7.0, False, False)
    assert k.step_motion(dq, q, before, np.array([True, True, True, False]))[2:] == (True, False)
    assert k.step_motion(dq, q, before, np.array([False, False, True, False]))[2:] == (False, True)
    du, qn, _, _ = k.step_motion(np.array([1.0, np.nan, 5.0]), q, before, before)
    assert math.isnan(du) and qn == 7.0


def test_warmup_compiles_the_fallback_variants(monkeypatch):
    """gmres_kernels.compile_fallbacks (run by ``tribodyn warmup``) compiles the argument types
    of the double-precision fallback of a transient's factorisation: after such a march
    it adds no new compiled variant."""
    from tribodyn import Roughness
    from tribodyn.contact.ehl import gmres_kernels as g
    from tribodyn.contact.ehl import kernels as k
    from tribodyn.contact.ehl import newton

    factor = newton._factor

    def double_only(lin, dtype):  # the single-precision factorisation fails
        return None if dtype == np.float32 else factor(lin, dtype)

    monkeypatch.setattr(newton, "_factor", double_only)
    rough = Roughness(asperity_density=8.3e9, rms=0.2e-6, summit_radius=0.669e-6)
    tr = TransientEHL(PAIR, Lubricant(0.055, 1.05e-8), roughness=rough)
    tr.start_steady(4e4, 0.005, 1.0, 3.0)
    for j in range(3):
        assert tr.step(2.5e-5, 4e4 * (1 + 0.02 * j), 0.005, 1.0, 3.0).converged
    kernels = (k.dense_matrix_t, g.gmres_lu)  # called from Python (the rest inside)
    before = [set(map(str, f.signatures)) for f in kernels]
    assert all(before)
    g.compile_fallbacks()
    assert [set(map(str, f.signatures)) for f in kernels] == before


def _asperity_march(monkeypatch, predicted_cavitation: bool):
    """(Newton iterations, [h_c, h_min, asperity share] per step) of a march whose
    asperities carry > 99 % of the load, with or without the predictor's cavitated set."""
    from tribodyn import Roughness
    from tribodyn.contact.ehl import transient

    count = [0]
    newton = transient.newton

    def counted(sysm, st, *a, **k):
        if not predicted_cavitation:
            st.cav = None
        out = newton(sysm, st, *a, **k)
        count[0] += out.iterations
        return out

    monkeypatch.setattr(transient, "newton", counted)
    tr = TransientEHL(PAIR, Lubricant(0.005, 1.5e-8), Roughness(1e9, 1.5e-6, 200e-6))
    w0, r0 = 1e5, 0.01
    tr.start_steady(w0, r0, 0.5, 0.5)
    rows = []
    for k in range(1, 21):
        s = k / 20
        r = tr.step(
            4e-4, w0 * (1 + 0.5 * math.sin(math.pi * s)), r0, 0.5 * math.cos(math.pi * s), 0.5
        )
        assert r.converged, r.message
        share = r.asperity_load / (r.asperity_load + r.hydrodynamic_load)
        rows.append((r.central_film, r.min_film, share))
    monkeypatch.setattr(transient, "newton", newton)
    return count[0], np.array(rows)


def test_asperity_dominated_march_starts_newton_from_the_predicted_cavitation(monkeypatch):
    """Where the asperities carry nearly all the load, P = Q − Pa(H) of the predicted Q is
    noise and its cavitated set far from the solution's; the set of the extrapolated fluid
    pressure saves most Newton iterations and gives the same solutions."""
    its, rows = _asperity_march(monkeypatch, True)
    its_std, rows_std = _asperity_march(monkeypatch, False)
    assert rows[:, 2].min() > 0.99
    np.testing.assert_allclose(rows, rows_std, rtol=1e-9)
    assert its < 0.5 * its_std


@pytest.mark.parametrize(
    "oil",
    [
        Lubricant(0.005, 1.5e-8),
        Lubricant(0.005, 1.5e-8, viscosity_model="barus"),
        Lubricant(0.005, 1.5e-8, compressible=False),
    ],
    ids=["roelands", "barus", "incompressible"],
)
@pytest.mark.parametrize("asperities", ["greenwood_tripp", "law", "smooth"])
def test_compiled_evaluation_equals_the_lubricants_methods(monkeypatch, oil, asperities):
    """A residual evaluation in one compiled call (film, asperity pressure, rheology and
    stencil) equals the evaluation through the Lubricant's and Roughness's NumPy methods,
    at the iterates of a transient step (time term active)."""
    from tribodyn import Roughness
    from tribodyn.contact.ehl import reynolds
    from tribodyn.physics.asperity import greenwood_tripp
    from tribodyn.physics.asperity_law import LoadSeparationLaw

    rough = None
    if asperities != "smooth":
        rough = Roughness(1e9, 1.5e-6, 200e-6)
    if asperities == "law":
        lam = np.linspace(-1.0, 4.0, 11)
        f = rough.pressure_scale(1.0) * greenwood_tripp(2.5, lam)
        law = LoadSeparationLaw(lam, f * 2.3e11, np.minimum(0.1 * f / f[0], 1.0), 2.3e11)
        rough = Roughness(1e9, 1.5e-6, 200e-6, law=law)
    seen = []
    evaluate = reynolds.ReynoldsSystem.evaluate

    def kept(self, Q, H0, defo=None):
        seen.append((self, np.array(Q), H0))
        return evaluate(self, Q, H0, defo)

    tr = TransientEHL(PAIR, oil, roughness=rough)
    tr.start_steady(1e5, 0.01, 0.5, 0.5)
    monkeypatch.setattr(reynolds.ReynoldsSystem, "evaluate", kept)
    assert tr.step(4e-4, 1.1e5, 0.01, 0.5, 0.5).converged
    sysm, Q, H0 = seen[-1]
    assert sysm.time_coef != 0.0 and sysm.elastic
    a, b = evaluate(sysm, Q, H0), sysm._evaluate_per_node(Q, H0)
    assert a.load == pytest.approx(b.load, abs=1e-14)
    for k in ("H", "pa", "dpa", "P", "R", "AP", "AH"):
        x, y = getattr(a, k), getattr(b, k)
        atol = 1e-13 * np.max(np.abs(y)) if k == "R" else 0.0  # R ≈ 0 at the solution
        assert np.allclose(x, y, rtol=1e-12, atol=atol), k
    if asperities != "smooth":
        assert np.max(b.pa) > 0.01 * np.max(Q)  # the asperities carry load

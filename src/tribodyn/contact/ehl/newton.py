"""Semismooth Newton solver of the discretised Reynolds complementarity system.

Unknowns (Q, H₀); the cavitation condition P ≥ 0, R ≤ 0, P·R = 0 is written as
min(P_i, −c_i R_i) = 0 (c_i: row scaling) and solved by a semismooth Newton method with a
non-monotone Armijo line search. The Newton systems are solved by dense LU, by GMRES
preconditioned with an earlier LU, or — above the dense limit — by GMRES with a two-grid
preconditioner (coarse-grid LU + Jacobi smoothing).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

import numpy as np
from scipy import linalg
from scipy.linalg import lapack

from .gmres_kernels import FACTOR_FLUSH, flush_factors, givens_step
from .kernels import (
    all_finite,
    cavitated_nodes,
    jacobi_diagonal,
    merit,
    row_scale,
    step_motion,
)
from .newton_kernels import given_active_set, iterate_terms, trial_point
from .reynolds import Linearization, ReynoldsSystem

__all__ = [
    "ROUND_OFF_PRESSURE",
    "State",
    "NewtonOutcome",
    "newton",
    "gmres",
    "CoarseLevel",
    "TwoGridPreconditioner",
    "jacobi_scale",
]

_NONMONOTONE = 6
#: A converged fluid pressure below this share of the largest (total) pressure is zero
#: up to round-off (a cavitated node): the complementarity rows of a Newton step are
#: solved to the linear solver's accuracy, and a single-precision preconditioner leaves
#: residues of either sign there (≈ 1e-27 of the peak on a rigid contact).
ROUND_OFF_PRESSURE = 1e-12
#: A given start set (``State.cav``, a transient predictor's) replaces the cavitated set
#: of the start's P and R at nodes whose asperity pressure exceeds this share of the
#: largest total pressure: there P = Q − Pa(H) of a predicted Q is the difference of two
#: nearly equal numbers (an error δH of the predicted film moves Pa by D·δH, more than the
#: fluid pressure), and its cavitation boundary lies tens of nodes from the solution's,
#: which the active set then crosses one node per Newton iteration. Elsewhere P of the
#: predicted Q is the better guess (it carries the boundary's motion on fluid films).
_ASPERITY_SHARE = 0.03
_WATCHDOG = 100.0
#: GMRES solves a Newton system to the relative residual η_k = min(_GMRES_TOL_MAX,
#: max(_GMRES_TOL, |F_k|)), |F_k| = √merit the scaled residual at the iterate: a forcing
#: term of the residual's order keeps Newton's quadratic convergence (Dembo, Eisenstat &
#: Steihaug, SIAM J. Numer. Anal. 19 (1982) 400–408; Eisenstat & Walker, SIAM J. Sci.
#: Comput. 17 (1996) 16–32), so the early iterations of a solve, far from the solution,
#: take fewer Krylov iterations and the last ones are solved as tightly as before.
_GMRES_TOL = 1e-6
_GMRES_TOL_MAX = 1e-4
_MAX_KRYLOV = 30
_MAX_KRYLOV_BEFORE_REFACTOR = 12
_MAX_KRYLOV_TWO_GRID = 200


class Factorization(NamedTuple):
    """LU factors of a Newton matrix (``lu_factor``'s ``fac``, ``piv``, and ``piv1`` =
    piv + 1, LAPACK's 1-based pivots as the compiled GMRES reads them), also GMRES's
    preconditioner."""

    fac: np.ndarray
    piv: np.ndarray
    piv1: np.ndarray


def _factor(lin: Linearization, dtype) -> Factorization | None:
    """LU of the Newton matrix of ``lin`` in ``dtype`` (float32 or float64), assembled
    in LAPACK's column-major order and factorised in place; None where the factorisation
    fails or a factor is not finite (single precision's range exceeded)."""
    try:
        J = lin.dense_column_major(dtype)
        fac, piv = linalg.lu_factor(J, overwrite_a=True, check_finite=False)
    except (linalg.LinAlgError, ValueError):
        return None
    if fac.dtype == np.float32:
        if not flush_factors(fac.T.reshape(-1), FACTOR_FLUSH):  # a view: fac is column-major
            return None
    elif not np.isfinite(fac).all():
        return None
    return Factorization(fac, piv, piv + 1)


def _fresh_solve(lin: Linearization, rtol) -> tuple[Factorization | None, np.ndarray | None]:
    """(factorisation, Newton direction) with a new LU of this Newton matrix: single
    precision factors (half the factorisation's cost; GMRES's triangular solves read half
    the memory, so that with the dense influence matrix of the products the working set
    fits a core's cache; GMRES preconditioned with them solves the double-precision
    system to ``rtol`` in one or two iterations), else, where they fail or that GMRES
    fails, double-precision factors and their direct solve."""
    lu = _factor(lin, np.float32)
    if lu is not None:
        delta, _ = gmres(lin, lu, rtol)
        if delta is not None:
            return lu, delta
    lu = _factor(lin, np.float64)
    if lu is None:
        return None, None
    return lu, _lu_solver(lu)(lin.rhs)


def _lu_solver(lu: Factorization):
    """v ↦ LU⁻¹ v (LAPACK getrs, no wrapper) with the factors of ``lu``."""
    fac, piv = lu.fac, lu.piv
    getrs = _SGETRS if fac.dtype == np.float32 else _GETRS
    return lambda v: getrs(fac, piv, v.astype(fac.dtype))[0].astype(float)


_GETRS = lapack.get_lapack_funcs("getrs", (np.zeros(1),))
_SGETRS = lapack.get_lapack_funcs("getrs", (np.zeros(1, dtype=np.float32),))


def gmres(lin: Linearization, lu, rtol, max_it=None):
    """Right-preconditioned flexible GMRES for lin·x = rhs with an earlier LU (a
    :class:`Factorization`, or any object with a ``solve`` method) as preconditioner,
    started from the preconditioned solution (see :func:`.gmres_kernels.gmres_lu`), in compiled
    code where :meth:`.Linearization.gmres_lu` can (an LU on a dense-product grid), else
    by the NumPy loop below (also the two-grid preconditioner's). Returns (x, iterations)
    or (None, its)."""
    max_it = max_it or _MAX_KRYLOV
    if isinstance(lu, Factorization):  # compiled, dense-product grids
        out = lin.gmres_lu(lu.fac, lu.piv1, rtol, max_it)
        if out is not None:
            return out
    b = lin.rhs
    bn = float(np.linalg.norm(b))
    if bn == 0.0:
        return np.zeros_like(b), 0
    if hasattr(lu, "solve"):  # a preconditioner object
        prec = lu.solve
    else:  # a Factorization
        prec = _lu_solver(lu)
    x0 = prec(b)
    r0 = b - lin.matvec(x0)
    beta = float(np.linalg.norm(r0))
    if not np.isfinite(beta):
        return None, 0
    if beta <= rtol * bn:
        return x0, 0
    V = np.zeros((max_it + 1, b.size))
    Z = np.zeros((max_it, b.size))  # M⁻¹v_j (flexible GMRES: M⁻¹ may be inexact)
    Hm = np.zeros((max_it + 1, max_it))
    cs, sn = np.zeros(max_it), np.zeros(max_it)
    gv = np.zeros(max_it + 1)
    gv[0] = beta
    V[0] = r0 / beta
    for j in range(max_it):
        Z[j] = prec(V[j])
        w = lin.matvec(Z[j])
        Vj = V[: j + 1]
        h = Vj @ w  # classical Gram–Schmidt, twice (CGS2)
        w -= h @ Vj
        h2 = Vj @ w
        w -= h2 @ Vj
        Hm[: j + 1, j] = h + h2
        Hm[j + 1, j] = np.linalg.norm(w)
        if Hm[j + 1, j] > 0.0:
            V[j + 1] = w / Hm[j + 1, j]
        if not givens_step(Hm, cs, sn, gv, j):
            return None, j + 1
        done = abs(gv[j + 1]) <= rtol * bn  # False for a NaN residual
        if done or j == max_it - 1 or not math.isfinite(gv[j + 1]):
            if not done:
                return None, j + 1
            y = linalg.solve_triangular(Hm[: j + 1, : j + 1], gv[: j + 1], check_finite=False)
            return x0 + Z[: j + 1].T @ y, j + 1
    return None, max_it


def _release(cav_std, prev_cav, release):
    """Free `release` cavitated nodes ahead of each node that has just left the cavitated
    set (the boundary is moving outward). The Reynolds LCP otherwise moves a free boundary
    by one node per active-set update; nodes freed too far re-cavitate together in the
    next update, so the boundary is found in O(log) iterations."""
    cav = cav_std.copy()
    if prev_cav is None or release <= 1:
        return cav
    n = cav.size
    for j in np.flatnonzero(prev_cav & ~cav_std):
        for d in (1, -1):
            if 0 < j + d < n - 1 and cav_std[j + d] and not cav_std[j - d]:
                k, cnt = j + d, 1
                while cnt < release and 0 < k < n - 1 and cav[k]:
                    cav[k] = False
                    k += d
                    cnt += 1
    return cav


@dataclass
class State:
    """Scaled solution: total pressure Q = P + Pa (the unknown), h₀, and derived P, H
    (and Pa, where the solve's last evaluation gives it)."""

    Q: np.ndarray
    H0: float
    P: np.ndarray = None  # type: ignore[assignment]  # set by ReynoldsSystem.evaluate
    H: np.ndarray = None  # type: ignore[assignment]
    #: cavitated nodes to start from (a transient predictor's), else those of P and R
    cav: np.ndarray | None = None
    #: asperity pressure Pa(H) at H (set by :func:`newton`; None: not evaluated)
    Pa: np.ndarray | None = None
    #: ln μ/μ₀ at P by the lubricant's law (set by :func:`newton` from its last
    #: evaluation; None: not evaluated, or a lubricant with per-node properties)
    lnmu: np.ndarray | None = None
    #: the scaled deformation K Q of this Q where its maker computed it (a transient
    #: predictor's film), for the solve's first evaluation; None: not computed
    KQ: np.ndarray | None = None


def jacobi_scale(sysm, ev):
    """c_i ≈ 1/|J_ii|, J = A_P + B K (only a scaling of the rows; :func:`.kernels.row_scale`)."""
    kc = sysm.kcoef if sysm.kcoef is not None else _NO_COEF
    return row_scale(ev.AP, ev.AH, ev.dpa, kc, sysm.kcoef is not None)


_NO_COEF = np.zeros(3)


class CoarseLevel:
    """Dense LU of the Newton matrix at a coarse-grid solution, for preconditioning the
    same problem on finer grids (two-grid)."""

    def __init__(self, sysm, st: State):
        ev = sysm.evaluate(st.Q, st.H0)
        c = jacobi_scale(sysm, ev)
        self.lin = Linearization(sysm, c, cavitated_nodes(ev.P, ev.R, c), ev)
        self.lu = linalg.lu_factor(self.lin.dense_column_major(), check_finite=False)
        self.X = sysm.g.X
        self._transfer: dict = {}

    def transfer(self, X):
        """Prolongation P (linear interpolation) and restriction R (averaging, Pᵀ with
        unit row sums) between this grid and the fine grid X (same domain)."""
        key = (X.size, X[0], X[-1])
        if key not in self._transfer:
            from scipy import sparse

            xc = self.X
            j = np.clip(np.searchsorted(xc, X, side="right") - 1, 0, xc.size - 2)
            t = (X - xc[j]) / (xc[j + 1] - xc[j])
            rows = np.r_[np.arange(X.size), np.arange(X.size)]
            P = sparse.csr_matrix(
                (np.r_[1 - t, t], (rows, np.r_[j, j + 1])), shape=(X.size, xc.size)
            )
            Rt = P.T.tocsr()
            Rm = sparse.diags(1.0 / np.asarray(Rt.sum(axis=1)).ravel()) @ Rt
            self._transfer[key] = (P, Rm.tocsr())
        return self._transfer[key]


class TwoGridPreconditioner:
    """M⁻¹ r = P J_c⁻¹ R r followed by one Jacobi sweep on the fine system.

    Residuals are moved between grids unscaled (Reynolds rows are flux densities, the
    same on every grid) and re-scaled with the coarse rows' scaling."""

    def __init__(self, coarse: CoarseLevel, lin: Linearization, sysm):
        self.coarse, self.lin = coarse, lin
        self.P, self.R = coarse.transfer(sysm.g.X)
        kc = sysm.kcoef if sysm.kcoef is not None else _NO_COEF
        diag = jacobi_diagonal(lin.AP, lin.AH, lin.D, kc, sysm.kcoef is not None)
        dsc = np.where(lin.free, lin.c * diag, 1.0)
        if sysm.kcoef is not None:
            dsc[lin.cav] = 1.0 - lin.D[lin.cav] * sysm.kcoef[0]
        dsc[lin.bnd] = 1.0
        self.dinv = 1.0 / np.where(np.abs(dsc) > 1e-12, dsc, 1.0)

    def solve(self, r):
        lin, cl = self.lin, self.coarse.lin
        rf = r[:-1].copy()
        rf[lin.free] /= lin.c[lin.free]
        rc = self.R @ rf
        rc[cl.free] *= cl.c[cl.free]
        rc[cl.bnd] = 0.0
        zc = linalg.lu_solve(self.coarse.lu, np.r_[rc, r[-1]], check_finite=False)
        z = np.r_[self.P @ zc[:-1], zc[-1]]
        z[:-1] += 0.8 * (r[:-1] - lin.matvec(z)[:-1]) * self.dinv
        return z


@dataclass
class NewtonOutcome:
    """Result of :func:`newton`: the last iterate, whether it converged, the iteration
    count, a message, and the LU factorisation of the last Newton matrix (or None) for
    reuse as a preconditioner."""

    state: State
    converged: bool
    iterations: int
    message: str
    lu: object = None


# trial points of the line search may overflow (e.g. exp(αp)); they are rejected by their
# non-finite merit, and the accepted solution is checked for finiteness
@np.errstate(over="ignore", invalid="ignore", under="ignore", divide="ignore")
def newton(
    sysm: ReynoldsSystem, st: State, tol, max_iter, lu=None, coarse=None, release_blocks=True
) -> NewtonOutcome:
    """Solve ``sysm`` from ``st``: semismooth Newton on min(P_i, −c_i R_i) = 0 and the load balance, unknowns (Q, H₀),
    with a non-monotone Armijo line search on |Φ|² + load residual² (c frozen within a
    search) and a small budget of full steps that may raise it (watchdog). Iterates may
    dip below zero pressure; the min-function clamps them on the next iteration.
    The Newton systems are solved by LU, by GMRES preconditioned with an earlier LU, or —
    given a ``coarse`` level — by GMRES with the two-grid preconditioner (no dense matrix
    on this grid; a dense LU only as fallback), GMRES to a relative residual of the
    residual's order (:data:`_GMRES_TOL`, :data:`_GMRES_TOL_MAX`).

    ``release_blocks``: free growing blocks of cavitated nodes ahead of a cavitation
    boundary that moves outward (:func:`_release`), for cold starts whose boundaries
    lie far from the start; False frees one node per iteration, which is faster from a
    warm start whose boundaries move by a few nodes (a transient step: the blocks
    overshoot and re-cavitate there, 7 % more iterations over a cam cycle).

    ``st.cav``: cavitated nodes to start from where asperities carry the pressure
    (:data:`_ASPERITY_SHARE`); the standard set is tried if its step fails.

    Converged when the relative update is below ``tol`` (residual < 10³·tol), when the
    residual is at round-off, or when a full step on an unchanged active set converges
    quadratically with a predicted next update C·u_k² < tol, C = u_k/u_{k−1}²
    (the usual a-posteriori estimate of a quadratically converging Newton iteration, cf.
    Deuflhard, *Newton Methods for Nonlinear Problems*, Springer 2004; it saves the
    iteration that would only confirm convergence)."""
    i0 = sysm.g.i0
    elastic = sysm.kcoef is not None
    kc = sysm.kcoef if elastic else _NO_COEF

    def terms(ev):
        """(c, |Φ|² + load², cavitated set) at an iterate (c frozen within a line search)."""
        return iterate_terms(ev.AP, ev.AH, ev.dpa, kc, elastic, ev.P, ev.R, ev.load)

    Q, H0 = st.Q.copy(), st.H0
    ev = sysm.evaluate(Q, H0, st.KQ)
    c, m0, cav_std = terms(ev)
    msg = "maximum iterations reached"
    ok = False
    prev_cav, release, release_cap = None, 1, 1 << 30
    history = [m0]  # non-monotone (Grippo–Lampariello–Lucidi) acceptance
    watchdog = 2  # full Newton steps allowed to raise the merit (warm starts)
    upd_prev = None
    it = 0
    for it in range(1, max_iter + 1):
        first: tuple = ()  # active sets tried before the standard one
        if release > 1:
            first = (_release(cav_std, prev_cav, release),)
        elif it == 1 and st.cav is not None and st.cav.shape == cav_std.shape:
            # the given set where the asperities carry the pressure (_ASPERITY_SHARE)
            given, differs = given_active_set(ev.pa, Q, _ASPERITY_SHARE, st.cav, cav_std)
            if differs:
                first = (given,)
        gmres_tol = min(_GMRES_TOL_MAX, max(_GMRES_TOL, math.sqrt(max(m0, 0.0))))
        accepted = False
        fresh_lu = False
        for cav in (*first, cav_std):
            lin = Linearization(sysm, c, cav, ev)
            delta = None
            fresh_lu = lu is None
            if coarse is not None and lu is None:
                delta, _ = gmres(
                    lin, TwoGridPreconditioner(coarse, lin, sysm), gmres_tol, _MAX_KRYLOV_TWO_GRID
                )
                fresh_lu = True  # nothing stale to refresh
            if delta is None and lu is not None:
                delta, nkry = gmres(lin, lu, gmres_tol)
                if delta is None or nkry > _MAX_KRYLOV_BEFORE_REFACTOR:
                    lu = None
            if delta is None:
                lu, delta = _fresh_solve(lin, gmres_tol)
                if lu is None or delta is None:
                    continue
                fresh_lu = True
            if not all_finite(delta):
                lu = None
                continue
            dQ, dH0 = delta[:-1], delta[-1]
            step = 1.0
            ref = max(history[-_NONMONOTONE:])
            for _ in range(30):
                Qn = trial_point(Q, dQ, step)
                H0n = H0 + step * dH0
                evn = sysm.evaluate(Qn, H0n)
                mn = merit(evn.P, evn.R, evn.load, c)
                if math.isfinite(mn) and (
                    mn <= (1.0 - 1e-4 * step) * ref
                    or (step == 1.0 and watchdog > 0 and mn <= _WATCHDOG * ref)
                ):
                    if not mn <= (1.0 - 1e-4 * step) * ref:
                        watchdog -= 1  # a full step that raised the merit: limited budget
                    accepted = True
                    break
                step *= 0.5
            if accepted:
                break
        if not accepted and lu is not None and not fresh_lu:
            lu = None  # Krylov direction from a stale preconditioner: retry
            continue
        if not accepted:
            msg = f"line search failed (merit {m0:.2e})"
            break
        du, qn, overshoot, moved = step_motion(
            dQ, Qn, cav_std if prev_cav is None else prev_cav, cav_std
        )
        if overshoot:
            if release > 1:
                # a released block overshot: later blocks at most half as large (no cycling)
                release_cap = max(1, release // 2)
            release = 1
        elif moved and release_blocks:
            release = min(2 * release, release_cap)
        else:
            release = 1
        prev_cav = cav_std
        upd = step * max(du / max(qn, 1e-30), abs(dH0) / max(abs(evn.H[i0]), 1e-30))
        c, m0, cav_std = terms(evn)  # re-scale at the accepted point
        Q, H0, ev = Qn, H0n, evn
        history.append(m0)
        res = math.sqrt(max(m0, 0.0))
        # converged: update below tol, or residual at round-off with an update so small
        # that the next (quadratic) one would be
        # … or quadratic convergence (same active set, full step) predicting the next
        # update C·upd² below tol, C = upd/upd_prev² (Deuflhard's a-posteriori estimate)
        quad = (
            upd_prev is not None
            and not (overshoot or moved)
            and step == 1.0
            and upd < math.sqrt(tol)
            and upd**3 < tol * upd_prev**2
            and res < 1e3 * tol
        )
        upd_prev = upd
        if (upd < tol and res < 1e3 * tol) or (res < 1e-13 and upd < math.sqrt(tol)) or quad:
            ok = True
            msg = f"converged in {it} Newton iterations (update {upd:.1e}, residual {res:.1e})"
            break
    P = np.maximum(ev.P, 0.0) if ok else ev.P  # cavitated nodes are 0 up to round-off
    # ln μ(P) = ln μ(max(P, 0)): the laws hold μ₀ below zero pressure
    return NewtonOutcome(State(Q, H0, P, ev.H, Pa=ev.pa, lnmu=ev.lnmu), ok, it, msg, lu)

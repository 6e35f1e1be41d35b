"""Compiled kernels of the discrete Reynolds system (numba): stencil and banded
derivatives, the Newton matrix's banded part, its matrix-free product, its dense form,
and GMRES on it preconditioned with an earlier LU factorisation.

Pure array arithmetic on node arrays. :func:`evaluate` computes a residual evaluation in
one call, reading the lubricant's rheology, the Greenwood–Tripp table and a
load–separation law's curve through the compiled elementwise functions of
:mod:`tribodyn.physics.lubricant`, :mod:`~tribodyn.physics.asperity` and
:mod:`~tribodyn.physics.asperity_law`; :func:`assemble` alone takes the rheology
evaluated by the caller, so a lubricant with per-node properties (e.g. temperature
fields) can stand in. (numba's cache of a kernel is not renewed when only a function it
calls from another module changes; clear the package's ``__pycache__`` after editing
those.) Bands are stored as (5, n)
arrays, row d + 2 holding offset d (A[d + 2, i] multiplies v[i + d]). The equations are
those of :mod:`.reynolds` (finite volumes, arithmetic-mean face coefficients,
second-order upwind Couette term, backward-difference time term).
"""

from __future__ import annotations

import math

import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.extending import get_cython_function_address, intrinsic

from ...physics.asperity import greenwood_tripp_tabulated
from ...physics.asperity_law import log_curve_at
from ...physics.lubricant import density_terms, viscosity_terms

__all__ = [
    "assemble",
    "evaluate",
    "row_scale",
    "merit",
    "cavitated_nodes",
    "newton_rows",
    "step_motion",
    "NO_ASPERITIES",
    "TABLE_ASPERITIES",
    "LAW_ASPERITIES",
    "GIVEN_ASPERITIES",
    "NO_TABLE",
    "NO_CURVE",
    "coupling_bands",
    "newton_matvec",
    "dense_matrix_t",
    "jacobi_diagonal",
    "givens_step",
    "GETRS",
    "SGETRS",
    "SYMV",
    "gmres_lu",
    "flush_factors",
    "compile_fallbacks",
    "VECTOR_FLUSH",
    "FACTOR_FLUSH",
]

_OPTS = dict(cache=True, nogil=True, fastmath=False)


@njit(**_OPTS)
def assemble(
    P, H, rho, drho, lnmu, dlnmu, lam, h_floor, abs_ubar, s, dX, time_coef, f_old, ff, cf, R, AP, AH
):
    """Reynolds residual R (interior rows) and banded ∂R/∂P (AP), ∂R/∂H (AH), in place.

    R_i = [ε_{i+½}(P_{i+1} − P_i) − ε_{i−½}(P_i − P_{i−1})]/ΔX² − |ū| Σ_k c_k g_{i−sk}/ΔX
          − c_t (f_i − f_old,i),   ε = φ_f λ ρ H³ e^(−ln μ/μ₀),  f = ρ H,  g = φ_c ρ H,
    c = (1.5, −2, 0.5) (first order, (1, −1), next to the upstream boundary). φ_f (ff) and
    φ_c (cf) are per-node factors of the generalized Reynolds equation, frozen in a solve
    (1 for the isothermal equation)."""
    n = P.size
    eps = np.empty(n)
    deP = np.empty(n)
    deH = np.empty(n)
    for i in range(n):
        hf = H[i] if H[i] > h_floor else h_floor
        e = ff[i] * lam * rho[i] * hf * hf * hf * np.exp(-lnmu[i])
        eps[i] = e
        deP[i] = e * (drho[i] / rho[i] - dlnmu[i])
        deH[i] = 3.0 * e / hf if H[i] > h_floor else 0.0
    R[:] = 0.0
    AP[:, :] = 0.0
    AH[:, :] = 0.0
    idx2 = 1.0 / (dX * dX)
    cu = abs_ubar / dX
    for i in range(1, n - 1):
        efp = 0.5 * (eps[i + 1] + eps[i])
        efm = 0.5 * (eps[i] + eps[i - 1])
        R[i] = (efp * (P[i + 1] - P[i]) - efm * (P[i] - P[i - 1])) * idx2
        AP[3, i] += efp * idx2
        AP[1, i] += efm * idx2
        AP[2, i] -= (efp + efm) * idx2
        cp = 0.5 * (P[i + 1] - P[i]) * idx2
        cm = 0.5 * (P[i] - P[i - 1]) * idx2
        AP[3, i] += cp * deP[i + 1]
        AP[2, i] += (cp - cm) * deP[i]
        AP[1, i] -= cm * deP[i - 1]
        AH[3, i] += cp * deH[i + 1]
        AH[2, i] += (cp - cm) * deH[i]
        AH[1, i] -= cm * deH[i - 1]
        # upwind Couette term −|ū| Σ c_k f[i − s k]/ΔX
        j2 = i - 2 * s
        if 0 <= j2 <= n - 1:
            c0, c1, c2 = 1.5, -2.0, 0.5
        else:
            c0, c1, c2 = 1.0, -1.0, 0.0
        j1 = i - s
        R[i] -= cu * (
            c0 * cf[i] * rho[i] * H[i]
            + c1 * cf[j1] * rho[j1] * H[j1]
            + (c2 * cf[j2] * rho[j2] * H[j2] if c2 != 0.0 else 0.0)
        )
        AP[2, i] -= cu * c0 * cf[i] * drho[i] * H[i]
        AH[2, i] -= cu * c0 * cf[i] * rho[i]
        AP[2 - s, i] -= cu * c1 * cf[j1] * drho[j1] * H[j1]
        AH[2 - s, i] -= cu * c1 * cf[j1] * rho[j1]
        if c2 != 0.0:
            AP[2 - 2 * s, i] -= cu * c2 * cf[j2] * drho[j2] * H[j2]
            AH[2 - 2 * s, i] -= cu * c2 * cf[j2] * rho[j2]
        if time_coef != 0.0:
            R[i] -= time_coef * (rho[i] * H[i] - f_old[i])
            AP[2, i] -= time_coef * drho[i] * H[i]
            AH[2, i] -= time_coef * rho[i]


#: How :func:`evaluate` obtains the asperity pressure: none (smooth surfaces), from a
#: Greenwood–Tripp table, from a load–separation law's curve, or given by the caller
#: (the paper's polynomial fits).
NO_ASPERITIES, TABLE_ASPERITIES, LAW_ASPERITIES, GIVEN_ASPERITIES = 0, 1, 2, 3
#: The table argument of :func:`evaluate` where no table is read …
NO_TABLE = (np.zeros(0), np.zeros(0), 0.0, 1.0, 2.5)
#: … and its curve argument where no law is read.
NO_CURVE = (np.zeros(2), np.zeros((4, 1)), np.zeros((3, 1)), 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)


@njit(**_OPTS)
def evaluate(
    Q,
    H0,
    geom,
    defo,
    asperities,
    table,
    curve,
    ka,
    sig,
    law,
    p_ref,
    lam,
    h_floor,
    abs_ubar,
    s,
    dX,
    time_coef,
    f_old,
    ff,
    cf,
    H,
    pa,
    dpa,
    P,
    lnmu,
    R,
    AP,
    AH,
):
    """One residual evaluation of :class:`~.reynolds.ReynoldsSystem` at (Q, H₀), in
    place (``lnmu``: ln μ/μ₀ at the nodes, kept for the post-processing); returns the
    load residual ΔX ΣQ − 1.

    Film H = H₀ + X²/2 + ``defo`` (``defo`` = K Q, empty for rigid surfaces); asperity
    pressure Pa = k_a F(H/σ̄), dPa/dH = (k_a/σ̄) dF/dλ from the Greenwood–Tripp
    ``table`` (``asperities`` = :data:`TABLE_ASPERITIES`), a load–separation law's
    ``curve`` (:data:`LAW_ASPERITIES`), zero (:data:`NO_ASPERITIES`) or as given in
    ``pa``, ``dpa`` (:data:`GIVEN_ASPERITIES`);
    fluid pressure P = Q − Pa; the rheology of the lubricant's ``law`` at p = P p_ref
    (ρ/ρ₀, dρ̄/dP = p_ref (1/ρ₀) dρ/dp, ln μ/μ₀, d ln μ/dP = p_ref d ln μ/dp); then
    the residual R and bands AP, AH of :func:`assemble`."""
    n = Q.size
    rho = np.empty(n)
    drho = np.empty(n)
    dlnmu = np.empty(n)
    elastic = defo.size > 0
    for i in range(n):
        h = H0 + geom[i]
        if elastic:
            h = h + defo[i]
        H[i] = h
        if asperities == TABLE_ASPERITIES or asperities == LAW_ASPERITIES:
            if asperities == TABLE_ASPERITIES:
                f, df = greenwood_tripp_tabulated(h / sig, table)
            else:
                f, df = log_curve_at(h / sig, curve)
            pa[i] = ka * f
            dpa[i] = ka / sig * df
        elif asperities == NO_ASPERITIES:
            pa[i] = 0.0
            dpa[i] = 0.0
        p = Q[i] - pa[i]
        P[i] = p
        pd = p * p_ref
        r, dr = density_terms(pd, law)
        lm, dlm = viscosity_terms(pd, law)
        rho[i] = r
        drho[i] = dr * p_ref
        lnmu[i] = lm
        dlnmu[i] = dlm * p_ref
    assemble(
        P,
        H,
        rho,
        drho,
        lnmu,
        dlnmu,
        lam,
        h_floor,
        abs_ubar,
        s,
        dX,
        time_coef,
        f_old,
        ff,
        cf,
        R,
        AP,
        AH,
    )
    return dX * np.sum(Q) - 1.0


@njit(**_OPTS)
def coupling_bands(AP, AH, D):
    """B = A_H − A_P D (δP = δQ − D δH) and its row sums B·1."""
    n = D.size
    B = AH.copy()
    col = np.zeros(n)
    for k in range(5):
        d = k - 2
        for i in range(n):
            j = i + d
            if 0 <= j < n:
                B[k, i] -= AP[k, i] * D[j]
            col[i] += B[k, i]
    return B, col


@njit(**_OPTS)
def newton_matvec(AP, B, col, c, free, cav, D, v, vh, dh, dX, out):
    """Newton-matrix product (see :class:`~.reynolds.Linearization`) given δH = K v + vh."""
    n = v.size
    for i in range(n):
        acc = 0.0
        for k in range(5):
            j = i + k - 2
            if 0 <= j < n:
                acc += AP[k, i] * v[j] + B[k, i] * (dh[j] - vh)
        acc += col[i] * vh
        if free[i]:
            out[i] = c[i] * acc
        elif cav[i]:
            out[i] = v[i] - D[i] * dh[i]
        else:
            out[i] = v[i]
    s = 0.0
    for i in range(n):
        s += v[i]
    out[n] = dX * s


@njit(**_OPTS)
def _edge_stencil(W, Kk, i):
    """Σ_d W_d,i Kk_i+d over the offsets d = −2…2 inside the grid (rows near its ends)."""
    n = Kk.size
    acc = 0.0
    for d in range(5):
        j = i + d - 2
        if 0 <= j < n:
            acc += W[d, i] * Kk[j]
    return acc


@njit(**_OPTS)
def dense_matrix_t(AP, B, col, c, free, cav, D, K, kscale, dX, elastic, flush, out):
    """The dense (n+1)² Newton matrix J with the scaled influence matrix kscale·K (free
    rows c_i[A_P + B K | B·1], cavitated rows [e_i − D_i K_i | −D_i], boundary rows e_i,
    load row [ΔX … | 0]) transposed, written into ``out`` ((n+1)², C order, float32 or
    float64): ``out.T`` is J in column-major order, as
    LAPACK's getrf takes it, without a copy. Column k of J's elastic part is
    Σ_d w_d,i K_k,i+d over the rows i (K symmetric: K_i+d,k = K_k,i+d) with the row
    weights w = c_i kscale B (free rows) or −D_i kscale (d = 0, cavitated rows), a
    contiguous stencil along row k of K. Row weights and banded entries of magnitude
    below ``flush`` are set to zero (for single precision: no subnormal numbers, whose
    arithmetic is many times slower, enter the factorisation)."""
    n = D.size
    out[:, :] = 0.0
    W = np.zeros((5, n))
    A = np.zeros((5, n))  # c_i A_P of the free rows
    for i in range(n):
        if free[i]:
            for d in range(5):
                W[d, i] = c[i] * kscale * B[d, i]
                A[d, i] = c[i] * AP[d, i]
        elif cav[i]:
            W[2, i] = -D[i] * kscale
    for i in range(n):
        for d in range(5):
            if abs(W[d, i]) < flush:
                W[d, i] = 0.0
            if abs(A[d, i]) < flush:
                A[d, i] = 0.0
    if elastic:
        for k in range(n):
            Kk = K[k]
            row = out[k]
            for i in range(min(2, n)):
                row[i] = _edge_stencil(W, Kk, i)
            for i in range(2, n - 2):
                row[i] = (
                    W[0, i] * Kk[i - 2]
                    + W[1, i] * Kk[i - 1]
                    + W[2, i] * Kk[i]
                    + W[3, i] * Kk[i + 1]
                    + W[4, i] * Kk[i + 2]
                )
            for i in range(max(2, n - 2), n):
                row[i] = _edge_stencil(W, Kk, i)
    for i in range(n):
        if free[i]:
            for d in range(5):
                j = i + d - 2
                if 0 <= j < n:
                    out[j, i] += A[d, i]
            v = c[i] * col[i]
            out[n, i] = v if abs(v) >= flush else 0.0
        else:
            out[i, i] += 1.0
            if cav[i]:
                out[n, i] = -D[i] if abs(D[i]) >= flush else 0.0
        out[i, n] = dX
    return out


@njit(**_OPTS)
def jacobi_diagonal(AP, AH, D, kcoef, elastic):
    """diag(A_P + (A_H − A_P D) K) with K_ij = kcoef[|i − j|]."""
    n = D.size
    diag = AP[2].copy()
    if elastic:
        for k in range(5):
            d = k - 2
            kd = kcoef[abs(d)]
            for i in range(max(0, -d), min(n, n - d)):
                diag[i] += (AH[k, i] - AP[k, i] * D[i + d]) * kd
    return diag


@njit(**_OPTS)
def row_scale(AP, AH, D, kcoef, elastic):
    """Row scaling of the Newton system, c_i = 1/max(d_i, 1e-300 + 1e-14 max d) with
    d = |:func:`jacobi_diagonal`| (the end rows take their neighbours' d); NaN throughout
    if a d is NaN."""
    n = D.size
    d = np.abs(jacobi_diagonal(AP, AH, D, kcoef, elastic))
    d[0], d[n - 1] = d[1], d[n - 2]
    big = -np.inf
    for v in d:
        if not v <= big:  # larger, or NaN (which stays)
            big = v
            if v != v:
                break
    floor = 1e-300 + 1e-14 * big
    c = np.empty(n)
    for i in range(n):
        v = d[i]
        c[i] = 1.0 / (v if v > floor or v != v else floor)
    return c


@njit(**_OPTS)
def merit(P, R, load, c):
    """Merit |Φ|² + load² of the complementarity system, Φ_i = min(P_i, −c_i R_i)
    (NaN if either is), Φ = P at the end nodes."""
    n = P.size
    phi = np.empty(n)
    for i in range(n):
        a, b = P[i], -c[i] * R[i]
        phi[i] = a if a <= b or a != a else b
    phi[0], phi[n - 1] = P[0], P[n - 1]
    return np.dot(phi, phi) + load * load


@njit(**_OPTS)
def cavitated_nodes(P, R, c):
    """The active set of the complementarity system: P_i < −c_i R_i (the end nodes are
    not cavitated)."""
    n = P.size
    cav = np.empty(n, dtype=np.bool_)
    for i in range(n):
        cav[i] = P[i] < -c[i] * R[i]
    cav[0] = cav[n - 1] = False
    return cav


@njit(**_OPTS)
def step_motion(dQ, Qn, before, after):
    """(max |δQ|, max |Q_new|, overshoot, moved) of an accepted Newton step: the largest
    update and iterate (NaN if an entry is), and whether the cavitated set ``after``
    gained nodes outside ``before`` (overshoot) or released nodes of it (moved)."""
    du = 0.0
    q = 0.0
    for i in range(dQ.size):
        a = abs(dQ[i])
        if a > du or a != a:  # NaN stays
            du = a
        b = abs(Qn[i])
        if b > q or b != b:
            q = b
    over = False
    moved = False
    for i in range(after.size):
        over |= after[i] and not before[i]
        moved |= before[i] and not after[i]
    return du, q, over, moved


@njit(**_OPTS)
def newton_rows(AP, AH, D, R, P, load, c, cav):
    """Row data of the Newton system for (δQ, δH₀) (:class:`~.reynolds.Linearization`)
    with the cavitated nodes ``cav`` (the end nodes are boundary rows): B = A_H − A_P D
    and B·1 (:func:`coupling_bands`), the cavitated, boundary and free rows, and the
    right-hand side −c_i R_i (free), −P_i (cavitated and boundary), −(ΔX ΣQ − 1)."""
    n = D.size
    B, col = coupling_bands(AP, AH, D)
    cv = cav.copy()
    cv[0] = cv[n - 1] = False
    bnd = np.zeros(n, dtype=np.bool_)
    bnd[0] = bnd[n - 1] = True
    free = np.empty(n, dtype=np.bool_)
    rhs = np.empty(n + 1)
    for i in range(n):
        free[i] = not (cv[i] or bnd[i])
        rhs[i] = -R[i] * c[i] if free[i] else -P[i]
    rhs[n] = -load
    return B, col, cv, bnd, free, rhs


def _scipy_routine(module: str, name: str) -> int:
    """The address of a LAPACK/BLAS routine of SciPy's Cython exports (all arguments by
    pointer, no result), which compiled code calls through :func:`_call_address`; it is
    passed to the kernels as an integer argument, which keeps them cacheable (and, unlike
    a ctypes function, costs nothing to pass)."""
    return int(get_cython_function_address(f"scipy.linalg.cython_{module}", name))


@intrinsic
def _call_address(typingctx, address, pointers):
    """Call the C function ``void f(void *, …)`` at ``address`` with the addresses
    ``pointers`` (a tuple of integers, e.g. ``a.ctypes.data``) as its arguments."""
    if not (
        isinstance(address, types.Integer)
        and isinstance(pointers, types.UniTuple)
        and isinstance(pointers.dtype, types.Integer)
    ):
        return None

    def codegen(context, builder, sig, args):
        ptr = ir.IntType(8).as_pointer()
        fnty = ir.FunctionType(ir.VoidType(), [ptr] * pointers.count)
        fn = builder.inttoptr(args[0], fnty.as_pointer())
        tup = args[1]
        builder.call(
            fn,
            [builder.inttoptr(builder.extract_value(tup, i), ptr) for i in range(pointers.count)],
        )
        return context.get_dummy_value()

    return types.none(address, pointers), codegen


#: dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
GETRS = _scipy_routine("lapack", "dgetrs")
#: sgetrs: the same in single precision (a preconditioner's factors stored as float32)
SGETRS = _scipy_routine("lapack", "sgetrs")
#: dsymv(uplo, n, alpha, a, lda, x, incx, beta, y, incy): y = αAx + βy for a symmetric A,
#: read from one triangle (half the memory of a general product; the influence matrix
#: of a uniform grid is symmetric Toeplitz)
SYMV = _scipy_routine("blas", "dsymv")


#: Single-precision triangular solves: entries of the right-hand side below this share of
#: its largest are zero (:func:`_lu_solve`), …
VECTOR_FLUSH = 1e-12
#: … and so are factor entries below this share of the largest (:func:`flush_factors`):
#: their products in the solves stay normal numbers (subnormal arithmetic takes many
#: times longer on x86), and at float32's resolution of 6e-8 they do not change the
#: preconditioned vector (measured: by < 3e-14 relative).
FACTOR_FLUSH = 1e-20
_SINGLE_MAX = float(np.finfo(np.float32).max)


def flush_factors(fac, rel) -> bool:
    """Zero the entries of the contiguous vector ``fac`` (a factor matrix's storage,
    e.g. ``fac.T.ravel()`` of a column-major one) below ``rel`` times its largest
    magnitude, in place; False if an entry is not finite or beyond single precision.
    The largest magnitude is max(max fac, −min fac) by NumPy's vectorised reductions
    (NaN propagates through them)."""
    big = max(float(fac.max()), -float(fac.min()))
    if not big <= _SINGLE_MAX:  # inf, NaN, or beyond single precision
        return False
    _zero_below(fac, rel * big)
    return True


@njit(**_OPTS)
def _zero_below(fac, thr):
    """fac_i ← 0 where |fac_i| < thr (finite entries), as a select that vectorises."""
    for i in range(fac.size):
        v = fac[i]
        fac[i] = v if abs(v) >= thr else 0.0


@njit(**_OPTS)
def _lu_solve(getrs, fac, piv1, x, buf, ints, trans):
    """x ← A⁻¹ x in place for A = P L U factorised by LAPACK getrf (``fac`` column-major,
    ``piv1`` the 1-based pivots), through ``buf`` (a vector of ``fac``'s precision:
    float64 with ``getrs`` = :data:`GETRS`, float32 with :data:`SGETRS`);
    ``ints`` = [n, 1, n, n, info], ``trans`` = [ord("N")]. In single precision the
    vector is scaled by a power of two to a largest entry near 1 and entries below
    :data:`VECTOR_FLUSH` are zero (no subnormal numbers in the solve)."""
    single = buf.itemsize == 4
    scale = 1.0
    if single:
        big = 0.0
        for v in x:
            big = max(big, abs(v))
        if big > 0.0 and big <= 1e300:
            scale = math.ldexp(1.0, math.frexp(big)[1])
        for i in range(x.size):
            v = x[i] / scale
            buf[i] = v if abs(v) >= VECTOR_FLUSH else 0.0
    else:
        for i in range(x.size):
            buf[i] = x[i]
    _call_address(
        getrs,
        (
            trans.ctypes.data,
            ints[0:].ctypes.data,
            ints[1:].ctypes.data,
            fac.ctypes.data,
            ints[2:].ctypes.data,
            piv1.ctypes.data,
            buf.ctypes.data,
            ints[3:].ctypes.data,
            ints[4:].ctypes.data,
        ),
    )
    for i in range(x.size):
        x[i] = buf[i] * scale


@njit(**_OPTS)
def _product(symv, uplo, ints, reals, K, x, y):
    """y = alpha·K x + beta·y by BLAS ``symv`` for the symmetric K (``uplo``: the triangle
    read, ``ints`` = [n, n, 1], ``reals`` = [alpha, beta]); x and y of K's size."""
    _call_address(
        symv,
        (
            uplo.ctypes.data,
            ints[0:].ctypes.data,
            reals[0:].ctypes.data,
            K.ctypes.data,
            ints[1:].ctypes.data,
            x.ctypes.data,
            ints[2:].ctypes.data,
            reals[1:].ctypes.data,
            y.ctypes.data,
            ints[2:].ctypes.data,
        ),
    )


@njit(**_OPTS)
def _apply(symv, system, z, out, work):
    """Newton-matrix product out = J z for ``system`` = (AP, B, col, c, free, cav, D, K,
    kscale, elastic, dX), with δH = kscale·K v + vh (the dense symmetric K, by BLAS
    symv); ``work`` = (dh, [n, n, 1], [1, 0], [ord("U")])."""
    AP, B, col, c, free, cav, D, K, kscale, elastic, dX = system
    dh, ints, reals, uplo = work
    n = D.size
    vh = z[n]
    if elastic:
        _product(symv, uplo, ints, reals, K, z, dh)
        for i in range(n):
            dh[i] = kscale * dh[i] + vh
    else:
        dh[:] = vh
    newton_matvec(AP, B, col, c, free, cav, D, z[:n], vh, dh, dX, out)


@njit(**_OPTS)
def _dot(a, b):
    """Σ a_k b_k with four partial sums (independent additions: the products pipeline
    instead of waiting on one running sum)."""
    n = a.size
    s0 = s1 = s2 = s3 = 0.0
    top = n - n % 4
    for k in range(0, top, 4):
        s0 += a[k] * b[k]
        s1 += a[k + 1] * b[k + 1]
        s2 += a[k + 2] * b[k + 2]
        s3 += a[k + 3] * b[k + 3]
    for k in range(top, n):
        s0 += a[k] * b[k]
    return (s0 + s1) + (s2 + s3)


@njit(**_OPTS)
def _norm(v):
    return math.sqrt(_dot(v, v))


@njit(**_OPTS)
def givens_step(Hm, cs, sn, gv, j):
    """GMRES's least-squares update for the new column ``j`` of the Hessenberg matrix
    ``Hm`` (Saad 2003, §6.5.3): the earlier Givens rotations (cos ``cs``, sin ``sn``)
    applied to it, then rotation j, c = H_jj/d, s = H_j+1,j/d with d = √(H_jj² + H_j+1,j²),
    which zeroes H_j+1,j and turns the residual vector: g_j+1 = −s g_j, g_j = c g_j; the
    residual norm is |g_j+1|. In place; returns False for a breakdown (d = 0)."""
    for i in range(j):
        tt = cs[i] * Hm[i, j] + sn[i] * Hm[i + 1, j]
        Hm[i + 1, j] = -sn[i] * Hm[i, j] + cs[i] * Hm[i + 1, j]
        Hm[i, j] = tt
    den = math.hypot(Hm[j, j], Hm[j + 1, j])
    if den == 0.0:
        return False
    cs[j] = Hm[j, j] / den
    sn[j] = Hm[j + 1, j] / den
    Hm[j, j] = den
    Hm[j + 1, j] = 0.0
    gv[j + 1] = -sn[j] * gv[j]
    gv[j] = cs[j] * gv[j]
    return True


@njit(**_OPTS)
def gmres_lu(getrs, symv, system, fac, piv1, b, rtol, max_it):
    """Right-preconditioned flexible GMRES for J x = b (J: the Newton matrix of
    :class:`~.reynolds.Linearization`, ``system`` = (AP, B, col, c, free, cav, D, K,
    kscale, elastic, dX) with the dense influence matrix K, M = LU of an
    earlier Newton matrix, applied by ``getrs`` = :data:`GETRS` with the factors ``fac``
    and 1-based pivots ``piv1`` of ``scipy.linalg.lu_factor``; ``symv`` = :data:`SYMV`
    for the products with K), started from x₀ = M⁻¹b; Arnoldi with classical Gram–Schmidt
    applied twice (CGS2) and Givens rotations, in the flexible form that keeps the
    preconditioned directions z_j = M⁻¹v_j and returns x₀ + Z y (Saad, *Iterative
    Methods for Sparse Linear Systems*, 2nd ed., SIAM 2003, Alg. 6.9, §9.3.2 and
    Alg. 9.6), so that J Z = V H holds to double round-off even where M⁻¹ is applied
    inexactly. Stops when the residual estimate |g_{j+1}| ≤ rtol·|b|. The factors may
    be float32 (with ``getrs`` = :data:`SGETRS`): the preconditioner then reads half the
    memory, and GMRES still solves the double-precision system to ``rtol``.

    Returns (x, iterations, ok); ok is False for a non-finite residual, a breakdown or
    no convergence within ``max_it`` iterations."""
    m = b.size
    bn = _norm(b)
    if bn == 0.0:
        return np.zeros(m), 0, True
    ints = np.array([m, 1, m, m, 0], dtype=np.int32)
    trans = np.array([78], dtype=np.uint8)  # "N"
    n = m - 1
    work = (
        np.empty(n),
        np.array([n, n, 1], dtype=np.int32),
        np.array([1.0, 0.0]),
        np.array([85], dtype=np.uint8),  # "U"
    )
    buf = np.empty_like(fac[:, 0])
    x0 = b.copy()
    _lu_solve(getrs, fac, piv1, x0, buf, ints, trans)
    w = np.empty(m)
    _apply(symv, system, x0, w, work)
    r0 = b - w
    beta = _norm(r0)
    if not math.isfinite(beta):
        return x0, 0, False
    if beta <= rtol * bn:
        return x0, 0, True
    # rows are written before they are read (np.empty: no zeroing of the rows a call
    # never reaches, which would also evict the factors from the cache)
    V = np.empty((max_it + 1, m))
    Z = np.empty((max_it, m))  # the preconditioned directions M⁻¹v_j (flexible GMRES)
    Hm = np.zeros((max_it + 1, max_it))
    cs = np.zeros(max_it)
    sn = np.zeros(max_it)
    gv = np.zeros(max_it + 1)
    h = np.zeros(max_it + 1)
    gv[0] = beta
    for i in range(m):
        V[0, i] = r0[i] / beta
    t = np.empty(m)
    for j in range(max_it):
        t[:] = V[j]
        _lu_solve(getrs, fac, piv1, t, buf, ints, trans)
        Z[j] = t
        _apply(symv, system, t, w, work)
        for i in range(j + 1):
            Hm[i, j] = 0.0
        for _ in range(2):  # CGS2
            for i in range(j + 1):
                h[i] = _dot(V[i], w)
            for i in range(j + 1):
                hi = h[i]
                for k in range(m):
                    w[k] -= hi * V[i, k]
                Hm[i, j] += hi
        hn = _norm(w)
        Hm[j + 1, j] = hn
        if hn > 0.0:
            for k in range(m):
                V[j + 1, k] = w[k] / hn
        if not givens_step(Hm, cs, sn, gv, j):
            return x0, j + 1, False
        done = abs(gv[j + 1]) <= rtol * bn  # False for a NaN residual
        if done or j == max_it - 1 or not math.isfinite(gv[j + 1]):
            if not done:
                return x0, j + 1, False
            k = j + 1  # y = Hm[:k, :k]⁻¹ g (upper triangular)
            y = np.zeros(k)
            for i in range(k - 1, -1, -1):
                acc = gv[i]
                for q in range(i + 1, k):
                    acc -= Hm[i, q] * y[q]
                y[i] = acc / Hm[i, i]
            t[:] = 0.0
            for i in range(k):
                yi = y[i]
                for q in range(m):
                    t[q] += yi * Z[i, q]
            return x0 + t, k, True
    return x0, max_it, False


def compile_fallbacks() -> None:
    """Compile (into numba's cache) the kernel variants that a cycle study reaches only
    on fallbacks, on a small system with the argument types of the solvers' calls: the
    double-precision factorisation (:func:`dense_matrix_t` into float64, as the two-grid
    coarse level also builds it, GMRES with float64 factors)."""
    from scipy import linalg

    n = 8
    AP = np.zeros((5, n))
    AP[2] = 1.0
    B, col = coupling_bands(AP, np.ones((5, n)), np.zeros(n))
    c, D = np.ones(n), np.zeros(n)
    cav = np.zeros(n, dtype=np.bool_)
    free = ~cav
    free[0] = free[-1] = False
    K = np.eye(n)
    rows = (AP, B, col, c, free, cav, D)
    J = dense_matrix_t(*rows, K, 1.0, 0.1, True, 0.0, np.empty((n + 1, n + 1))).T
    fac, piv = linalg.lu_factor(J, overwrite_a=True, check_finite=False)
    system = (*rows, K, 1.0, True, 0.1)
    gmres_lu(GETRS, SYMV, system, fac, piv + 1, np.ones(n + 1), 1e-6, 30)

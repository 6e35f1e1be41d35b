"""Compiled GMRES on the Newton matrix of :mod:`.kernels`, right-preconditioned with an
earlier LU factorisation (numba): the triangular solves and the dense influence-matrix
product call LAPACK getrs and BLAS symv of SciPy's Cython exports by address, the
factors in double or single precision (flushed of entries too small for single
precision's normal range).
"""

from __future__ import annotations

import math

import numpy as np
from llvmlite import ir
from numba import njit, types
from numba.extending import get_cython_function_address, intrinsic

from .kernels import coupling_bands, dense_matrix_t, newton_matvec

__all__ = [
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

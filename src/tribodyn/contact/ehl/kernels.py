"""Compiled kernels of the discrete Reynolds system (numba): stencil and banded
derivatives, the Newton matrix's banded part, its matrix-free product and its dense
form (GMRES on it: :mod:`.gmres_kernels`).

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
from numba import njit

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
    "all_finite",
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


@njit(**_OPTS)
def all_finite(v) -> bool:
    """Whether every entry of ``v`` is finite."""
    for x in v:
        if not math.isfinite(x):
            return False
    return True

"""Thermal Grubin inlet of a rolling line contact, solved outside the package.

A reference for the thermal film reduction h_T/h_iso, written from the equations and
sharing no code with the package's thermal solver.

Geometry (Grubin 1949): the gap upstream of the Hertz zone is the rigid Hertzian one,
h(x) = h₀ + (b²/2R)[|X|√(X²−1) − ln(|X| + √(X²−1))], X = x/b ≤ −1, and h₀ is the film
for which the pressure becomes infinite at the edge X = −1 (the reduced pressure
q = (1 − e^{−αp})/α reaches 1/α).

Lubricant: Newtonian, μ = μ₀ exp(αp − βθ), θ = T − T₀, incompressible, constant k
and ρc. Both walls move at u (pure rolling) and stay at T₀.

Flow (Dowson's generalized Reynolds, viscosity varying across the film): with
G = dq/dx = e^{−αp} dp/dx, u(z) = u + (G/μ₀) ∫₀ᶻ (z' − c) e^{βθ} dz', where c =
∫z e^{βθ}dz / ∫e^{βθ}dz makes u(h) = u. The flow per unit width is u h₀ at every x, which
gives G. The αp factor cancels out of the velocity; the dissipation is
Φ = μ(∂u/∂z)² = G² (z − c)² e^{βθ} / (μ₀ (1 − αq)).

Energy (steady, thin film, no conduction along x):
ρc (u ∂θ/∂x + w ∂θ/∂z) = k ∂²θ/∂z² + Φ, with θ = 0 on the walls and on the oil that
enters the domain at its upstream end; the mid-film back-flow of the inlet leaves there.
Finite volumes on (x, ζ = z/h): cell-centred, conservative, first-order upwind, the
cross-film volume flux from the discrete continuity of each cell (so the flow that enters
a column leaves it), one sparse solve per Picard iteration; h₀ by root finding on q(−b)
at the frozen temperature, iterated to a fixed point with the temperature.
"""

import math

import numpy as np
from scipy import optimize, sparse
from scipy.sparse import linalg as splinalg


def hertz_gap_shape(X):
    """(h − h₀)/(b²/2R) of the rigid Hertzian line contact outside the Hertz zone."""
    a = np.abs(np.asarray(X, dtype=float))
    s = np.sqrt(np.maximum(a * a - 1.0, 0.0))
    return a * s - np.log(a + s)


def grubin_inlet(
    *,
    load,
    radius,
    e_prime,
    speed,
    mu0,
    alpha,
    beta,
    k,
    rho_c,
    x_far=-12.0,
    nx=240,
    nz=40,
    heating=True,
    convection=True,
    tol=1e-7,
    max_iter=200,
    thinning=None,
):
    """Grubin inlet film h₀ [m], isothermal or thermal, and the temperature field.

    load [N/m], radius [m], e_prime [Pa], speed = u of both walls [m/s], mu0 [Pa s],
    alpha [1/Pa], beta [1/K], k [W/(m K)], rho_c [J/(m³ K)]. x_far: upstream end in
    units of b; nx, nz: cells along x (clustered at the Hertz edge) and across the film.
    ``convection=False`` drops ρc Dθ/Dt (local balance k θ'' = −Φ). ``thinning``:
    λ(θ) = ln(μ₀/μ(T₀ + θ)) at ambient pressure, to replace βθ by another law.
    Returns dict(h0, theta (nx, nz), X (nx,), zeta (nz,), iterations, max_rise).
    """
    b = math.sqrt(8.0 * load * radius / (math.pi * e_prime))
    scale = b * b / (2.0 * radius)
    # x faces clustered at X = −1 (quadratic stretching), cells between them
    s = np.linspace(0.0, 1.0, nx + 1)
    Xf = -1.0 - (-1.0 - x_far) * s[::-1] ** 2
    Xc = 0.5 * (Xf[1:] + Xf[:-1])
    dx = np.diff(Xf) * b  # [m]
    g_c, g_f = hertz_gap_shape(Xc) * scale, hertz_gap_shape(Xf) * scale
    dz = 1.0 / nz
    zeta = (np.arange(nz) + 0.5) * dz

    def col_integrals(theta):
        """Per column: c/h and ∫₀^ζ (ζ' − c/h) e^{βθ} dζ' at the cell centres (midpoint
        sums) and j = −∫₀¹ of that (the flow coefficient: flux = u h − G h³ j/μ₀)."""
        e = np.exp(beta * theta if thinning is None else thinning(theta))
        cbar = (e * zeta).sum(axis=-1) / e.sum(axis=-1)
        f = (zeta - cbar[..., None]) * e * dz
        S = np.cumsum(f, axis=-1) - 0.5 * f  # integral up to each centre
        j = -S.sum(axis=-1) * dz
        return cbar, e, S, j

    def edge_q(h0, jc):
        # G = dq/dx = μ₀ u (h − h₀)/(h³ j) on each cell, q(−b) = Σ G Δx
        h = h0 + g_c
        return float(np.sum(mu0 * speed * (h - h0) / (h**3 * jc) * dx))

    def solve_h0(jc, guess):
        f = lambda lh: edge_q(math.exp(lh), jc) - 1.0 / alpha  # noqa: E731
        lo, hi = math.log(guess) - 8.0, math.log(guess) + 8.0
        return math.exp(optimize.brentq(f, lo, hi, xtol=1e-13, rtol=1e-13))

    theta = np.zeros((nx, nz))
    # isothermal start: j = 1/12 (exact for the midpoint rule too: the sum vanishes)
    h0 = solve_h0(col_integrals(theta)[3], 1e-7)
    iterations = 0
    for it in range(1, max_iter + 1):
        if not heating:
            break
        iterations = it
        # flow and heat at the frozen θ
        _, _, _, jc = col_integrals(theta)
        h0 = solve_h0(jc, h0)
        hc = h0 + g_c
        G = mu0 * speed * (hc - h0) / (hc**3 * jc)  # dq/dx per cell
        q = np.cumsum(G * dx) - 0.5 * G * dx  # reduced pressure at the centres
        press = 1.0 / np.maximum(1.0 - alpha * q, 1e-300)  # e^{αp}
        cbar, e, _, _ = col_integrals(theta)
        phi = G[:, None] ** 2 * ((zeta - cbar[:, None]) * hc[:, None]) ** 2 * e
        phi *= press[:, None] / mu0  # [W/m³]
        # velocities on the x faces (θ averaged from the two cells; upstream end: cell 0)
        th_f = np.vstack([theta[:1], 0.5 * (theta[1:] + theta[:-1]), theta[-1:]])
        hf = h0 + g_f
        _, _, Sf, jf = col_integrals(th_f)
        Gf = mu0 * speed * (hf - h0) / (hf**3 * jf)
        uf = speed + Gf[:, None] / mu0 * Sf * hf[:, None] ** 2
        M = hf[:, None] * uf * dz  # volume flux per unit width through each face [m²/s]
        M *= (speed * h0) / M.sum(axis=1, keepdims=True)  # the flow u h₀ (quadrature)
        # cross-film fluxes from each cell's continuity: F_{j+½} − F_{j−½} = −(M_e − M_w)
        F = np.zeros((nx, nz + 1))
        F[:, 1:] = -np.cumsum(M[1:] - M[:-1], axis=1)
        F[:, -1] = 0.0  # = 0 up to round-off (u h₀ through every face)
        assert np.all(M[-1] >= 0.0)  # no back-flow out of the Hertz zone
        theta_new = _energy(theta.shape, hc, dx, dz, M, F, phi, k, rho_c, convection)
        change = float(np.max(np.abs(theta_new - theta)))
        theta = theta_new
        h_old = h0
        h0 = solve_h0(col_integrals(theta)[3], h0)
        if change < tol * max(1.0, float(theta.max())) and abs(h0 / h_old - 1.0) < tol:
            break
    else:
        raise RuntimeError("thermal Grubin inlet did not converge")
    return {
        "h0": h0,
        "theta": theta,
        "X": Xc,
        "zeta": zeta,
        "iterations": iterations,
        "max_rise": float(theta.max()),
        "half_width": b,
    }


def _energy(shape, h, dx, dz, M, F, phi, k, rho_c, convection):
    """Assemble and solve the finite-volume energy equation for θ (nx, nz)."""
    nx, nz = shape
    idx = np.arange(nx * nz).reshape(nx, nz)
    rows, cols, vals = [], [], []
    diag = np.zeros((nx, nz))

    def add(r, c, v):
        rows.append(r.ravel())
        cols.append(c.ravel())
        vals.append(v.ravel())

    # conduction across the film: k Δx/(h Δζ) per face, walls at θ = 0 half a cell away
    Gz = k * dx / (h * dz)
    Gz2 = np.broadcast_to(Gz[:, None], (nx, nz - 1))
    diag[:, :-1] += Gz2
    diag[:, 1:] += Gz2
    add(idx[:, :-1], idx[:, 1:], -Gz2)
    add(idx[:, 1:], idx[:, :-1], -Gz2)
    diag[:, 0] += 2.0 * Gz
    diag[:, -1] += 2.0 * Gz
    if convection:
        # x faces: face i between cells i−1 and i (face 0: upstream end, face nx: edge)
        for face in range(nx + 1):
            m = rho_c * M[face]
            out_w = face - 1  # cell on the upstream side
            out_e = face  # cell on the downstream side
            pos, neg = np.maximum(m, 0.0), np.minimum(m, 0.0)
            if out_w >= 0:  # leaves cell out_w (pos) / enters it from out_e (neg)
                diag[out_w] += pos
                if out_e < nx:
                    add(idx[out_w], idx[out_e], neg)
            if out_e < nx:
                diag[out_e] -= neg
                if out_w >= 0:
                    add(idx[out_e], idx[out_w], -pos)
                # upstream end: inflow at θ = 0 adds nothing
        # ζ faces (interior): F_{j+½} between cells j and j+1
        Fi = rho_c * F[:, 1:-1]
        pos, neg = np.maximum(Fi, 0.0), np.minimum(Fi, 0.0)
        diag[:, :-1] += pos
        add(idx[:, 1:], idx[:, :-1], -pos)
        diag[:, 1:] -= neg
        add(idx[:, :-1], idx[:, 1:], neg)
    add(idx, idx, diag)
    A = sparse.csc_matrix(
        (np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
        shape=(nx * nz, nx * nz),
    )
    rhs = (phi * h[:, None] * dz * dx[:, None]).ravel()
    return splinalg.spsolve(A, rhs).reshape(nx, nz)


def roelands_thinning(mu0, t0, beta):
    """λ(θ) = ln(μ(T₀)/μ(T₀ + θ)) of Roelands' temperature law at ambient pressure, for
    :func:`grubin_inlet`'s ``thinning``: ln μ + 9.67 = (ln μ₀ + 9.67)((T − 138)/(T₀ − 138))^−S₀
    (μ in Pa s, T in K), with S₀ = β(T₀ − 138)/(ln μ₀ + 9.67) so that −d ln μ/dT = β at T₀.
    mu0 [Pa s], t0 [K], beta [1/K]."""
    l0 = math.log(mu0) + 9.67
    s0 = beta * (t0 - 138.0) / l0

    def thinning(th):
        return math.log(mu0) + 9.67 - l0 * ((t0 + th - 138.0) / (t0 - 138.0)) ** (-s0)

    return thinning


def grubin_isothermal_h0(*, load, radius, e_prime, speed, mu0, alpha):
    """Grubin's isothermal h₀ [m] by adaptive quadrature of 1/α = 12μ₀u∫(h−h₀)/h³ dx
    over the whole inlet (−∞ < X ≤ −1), to check the finite-volume quadrature."""
    from scipy import integrate

    b = math.sqrt(8.0 * load * radius / (math.pi * e_prime))
    scale = b * b / (2.0 * radius)

    def qedge(h0):
        def f(t):  # X = −1 − t²/(1 − t): t ∈ [0, 1)
            X = -1.0 - t * t / (1.0 - t)
            dXdt = (2.0 * t * (1.0 - t) + t * t) / (1.0 - t) ** 2
            g = hertz_gap_shape(X) * scale
            return 12.0 * mu0 * speed * g / (h0 + g) ** 3 * dXdt * b

        return integrate.quad(f, 0.0, 1.0, limit=400, epsabs=0.0, epsrel=1e-11)[0]

    return math.exp(
        optimize.brentq(lambda lh: qedge(math.exp(lh)) - 1.0 / alpha, math.log(1e-10), -5.0)
    )

"""Energy equation of the film coupled to heat conduction in both moving solids.

Unknown: the temperature rise θ = T − Tᵢ above the inlet (sump) temperature on a thermal
grid: nodes x_i (uniform, the EHL domain), across the film ζ_j = j/(m−1) (j = 0 on body 1,
j = m−1 on body 2; these wall nodes are the solids' surface nodes) and into each solid
s_k (:func:`~tribodyn.physics.heat_conduction.depth_grid`, θ = 0 at the last depth).

Film (ζ coordinates, multiplied by h; Dowson 1962 / Yang & Wen 1990)::

    ρc (h ∂θ/∂t + h u ∂θ/∂x + Ω ∂θ/∂ζ) = (1/h) ∂/∂ζ(k ∂θ/∂ζ) + h [Φ + ε_T T (u ∂p/∂x + ∂p/∂t)]

Ω = w − ζ(u ∂h/∂x + ∂h/∂t) from continuity, ρΩ(ζ) = −∫₀^ζ [∂(ρh)/∂t + ∂(ρuh)/∂x] dζ'.
Conduction across the film, convection along and across it; x-conduction in the film is
neglected (thin film). Φ: viscous dissipation; ε_T T Dp/Dt: compression heating (cooling
where the oil expands). Solids: ρc(∂θ/∂t + u ∂θ/∂x) = ∇·(k∇θ) with their own layers.
Interfaces: continuity of θ and of heat flux; the boundary-friction heat q_b = τ_b|u_s| of
the asperity contacts enters at the two surfaces, half at each (conduction then shares
it out). Inflow boundaries (oil and solid material entering the domain) are at Tᵢ.

Finite volumes; first-order upwind convection; backward Euler in time. For every x the
unknowns form one chain (deep in body 1 → surface → film → surface → deep in body 2), so
the matrix has the five diagonals 0, ±1 (chain) and ±N_z (neighbouring x), solved by
sparse LU.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from scipy import sparse
from scipy.sparse import linalg as splinalg

from ...physics.heat_conduction import DepthGrid

__all__ = ["EnergyInputs", "solve_energy", "chain_size", "solid_chain"]


def chain_size(m: int, g1: DepthGrid, g2: DepthGrid) -> int:
    return (g1.s.size - 2) + m + (g2.s.size - 2)


def solid_chain(body: int, f0: int, m: int, ns: int) -> np.ndarray:
    """Chain positions of the depth nodes 0 (the surface) … ns−1 of solid ``body`` (0, 1)
    with the film's node j = 0 at ``f0``: body 1 runs down the chain from film node 0,
    body 2 up from film node m − 1."""
    return f0 - np.arange(ns) if body == 0 else f0 + m - 1 + np.arange(ns)


@dataclass
class EnergyInputs:
    """Fields on the thermal grid (n x-nodes, m film nodes), SI.

    dx : x spacing [m]; h : film used for heat [m] (n,); u : film velocity (n, m) [m/s];
    rho, rc, k : film density, ρc, conductivity (n, m); phi : dissipation (n, m) [W/m³];
    comp : compression coefficient ε_T Dp/Dt (n, m) [W/(m³ K)]; T_inlet [K];
    speeds : (u₁, u₂) surface speeds [m/s]; grids : (DepthGrid, DepthGrid);
    q_surface : boundary-friction heat per area (n,) [W/m²];
    dt : time step [s] or None (steady); theta_old : previous θ (n, N_z) or None;
    rho_h_old : previous ρh (n,) [kg/m²] for ∂(ρh)/∂t; theta_lag : θ at which the
    heating part of the compression term is taken (n, N_z) or None.
    """

    dx: float
    h: np.ndarray
    u: np.ndarray
    rho: np.ndarray
    rc: np.ndarray
    k: np.ndarray
    phi: np.ndarray
    comp: np.ndarray
    T_inlet: float
    speeds: tuple
    grids: tuple
    q_surface: np.ndarray
    dt: float | None = None
    theta_old: np.ndarray | None = None
    rho_h_old: np.ndarray | None = None
    theta_lag: np.ndarray | None = None


def _upwind(aP, aW, aE, F):
    """Add first-order upwind convection with signed coefficient F (= capacity·u/Δx)."""
    aP += np.abs(F)
    aW += np.maximum(F, 0.0)
    aE += np.maximum(-F, 0.0)


def solve_energy(e: EnergyInputs) -> np.ndarray:
    """θ (n, N_z) in chain order: body-1 depth nodes deepest first, the film nodes
    j = 0…m−1 (j = 0, m−1 the surfaces), body-2 depth nodes shallowest first."""
    n, m = e.u.shape
    g1, g2 = e.grids
    n1, n2 = g1.s.size - 2, g2.s.size - 2  # interior depth nodes (1…ns−1)
    Nz = n1 + m + n2
    f0 = n1  # chain index of film node j = 0
    mats = tuple(np.zeros((n, Nz)) for _ in range(6))
    aP, aW, aE, aD, aU, b = mats  # west, east, chain −1, +1, rhs
    dx = e.dx
    dz = 1.0 / (m - 1)
    h = e.h
    wz = np.full(m, dz)
    wz[0] = wz[-1] = 0.5 * dz  # ζ control-volume widths

    # ---- film: conduction across
    kf = 0.5 * (e.k[:, 1:] + e.k[:, :-1])  # faces j+½
    G = kf / (h[:, None] * dz)
    fs = slice(f0, f0 + m)
    aP[:, fs][:, :-1] += G
    aU[:, fs][:, :-1] += G
    aP[:, fs][:, 1:] += G
    aD[:, fs][:, 1:] += G
    # ---- film: convection along x and across (Ω from continuity)
    cap = e.rc * h[:, None] * wz[None, :]  # ρc h Δζ
    F = cap * e.u / dx
    sub = (aP[:, fs], aW[:, fs], aE[:, fs])
    _upwind(*sub, F)
    mflux = e.rho * e.u * h[:, None]  # ρ u h on the nodes
    dmdx = np.gradient(mflux, dx, axis=0)
    if e.dt is not None and e.rho_h_old is not None:
        rho_e = np.sum(e.rho * wz, axis=1)
        dmdx = dmdx + ((rho_e * h - e.rho_h_old) / e.dt)[:, None]
    from ...physics.film_thermal import cumtrapz

    rho_omega = -cumtrapz(dmdx, np.full(n, dz))
    rho_omega -= rho_omega[:, -1:] * np.linspace(0.0, 1.0, m)[None, :]  # Ω = 0 on walls
    Fz = e.rc / e.rho * rho_omega  # ρc Ω
    inner = slice(f0 + 1, f0 + m - 1)
    Fzi = Fz[:, 1:-1]
    aP[:, inner] += np.abs(Fzi)
    aD[:, inner] += np.maximum(Fzi, 0.0)
    aU[:, inner] += np.maximum(-Fzi, 0.0)
    # ---- film: sources (dissipation; compression ε_T T Dp/Dt implicit in θ where the
    # diagonal stays dominant, the rest lagged at theta_lag)
    vol = h[:, None] * wz[None, :]
    b[:, fs] += vol * e.phi
    comp = vol * e.comp
    b[:, fs] += comp * e.T_inlet
    room = 0.5 * aP[:, fs]  # conduction + convection on the diagonal
    implicit = np.minimum(comp, room)
    aP[:, fs] -= implicit
    if e.theta_lag is not None:
        b[:, fs] += (comp - implicit) * e.theta_lag[:, fs]
    if e.dt is not None:
        aP[:, fs] += cap / e.dt
        if e.theta_old is not None:
            b[:, fs] += cap / e.dt * e.theta_old[:, fs]
    # ---- boundary-friction heat at the two surfaces
    b[:, f0] += 0.5 * e.q_surface
    b[:, f0 + m - 1] += 0.5 * e.q_surface

    # ---- solids
    for body, (g, u_b) in enumerate(zip(e.grids, e.speeds)):
        idx = solid_chain(body, f0, m, g.s.size - 1)  # node k → chain
        _solid(mats, g, u_b, idx, body == 1, dx, e.dt, e.theta_old)
    return _solve(mats, Nz)


def _solid(mats, g: DepthGrid, u_b, idx, deeper_is_up, dx, dt, theta_old):
    """Add the conduction equation of one moving solid (chain positions ``idx`` of its
    depth nodes 0…ns−1; ``deeper_is_up``: increasing depth is +1 in the chain)."""
    aP, aW, aE, aD, aU, b = mats
    n = aP.shape[0]
    ns = g.s.size - 1  # nodes 0…ns−1 unknown, ns: θ = 0
    Gs = g.face_conductance()  # between k and k+1
    Cn = g.node_capacity()
    Kx = g.node_x_conductance()
    for k in range(ns):
        c = idx[k]
        aP[:, c] += Gs[k]  # to deeper node (θ = 0 past the grid)
        if k + 1 < ns:
            (aU if deeper_is_up else aD)[:, c] += Gs[k]
        if k >= 1:
            aP[:, c] += Gs[k - 1]
            (aD if deeper_is_up else aU)[:, c] += Gs[k - 1]
        # x convection and conduction; inflow end at θ = 0, outflow end insulated
        _upwind(aP[:, c], aW[:, c], aE[:, c], np.full(n, Cn[k] * u_b / dx))
        kx = Kx[k] / dx**2
        aW[1:, c] += kx
        aE[:-1, c] += kx
        aP[1:, c] += kx
        aP[:-1, c] += kx
        aP[0 if u_b >= 0 else n - 1, c] += kx  # Dirichlet ghost at the inflow end
        if dt is not None:
            aP[:, c] += Cn[k] / dt
            if theta_old is not None:
                b[:, c] += Cn[k] / dt * theta_old[:, c]


def _solve(mats, Nz):
    aP, aW, aE, aD, aU, b = mats
    n = aP.shape[0]
    # drop couplings through the domain ends (ghost θ = 0: inflow at Tᵢ)
    aW[0] = 0.0
    aE[-1] = 0.0
    N = n * Nz
    diag = aP.ravel()
    up = -aU.ravel()[:-1]
    down = -aD.ravel()[1:]
    east = -aE.ravel()[:-Nz]
    west = -aW.ravel()[Nz:]
    A = sparse.diags([diag, up, down, east, west], [0, 1, -1, Nz, -Nz], shape=(N, N), format="csc")
    theta = splinalg.splu(A, permc_spec="COLAMD").solve(b.ravel())
    return theta.reshape(n, Nz)

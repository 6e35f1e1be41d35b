"""Flow, shear and heat generation across a film whose viscosity varies through its
thickness (thermal EHL).

Film 0 ≤ z ≤ h between surface a (z = 0, speed u_a) and surface b (z = h, speed u_b);
ζ = z/h on m nodes. With the fluidity integrals (Yang & Wen 1990, J. Tribol. 112:631;
Newtonian flow, viscosity η(z))::

    F₀ = ∫₀ʰ dz/η,   F₁ = ∫₀ʰ z dz/η,   I₀(z) = ∫₀ᶻ dz'/η,   I₁(z) = ∫₀ᶻ z' dz'/η

the velocity is u(z) = u_a + (u_b − u_a) I₀/F₀ + p_x (I₁ − I₀ F₁/F₀) and the mass flow
q = ∫ρu dz = −C p_x + D with::

    C = ρ' F₁/F₀ − ρ'',  D = h ρ_e u_a + (u_b − u_a) ρ'/F₀,
    ρ' = ∫₀ʰ ρ I₀ dz,   ρ'' = ∫₀ʰ ρ I₁ dz,   ρ_e = (1/h) ∫₀ʰ ρ dz

(for constant η, ρ: C = ρh³/(12η), D = ρh(u_a + u_b)/2 — the Reynolds equation's
coefficients). The generalized Reynolds equation is d/dx(C dp/dx) − dD/dx − ∂(ρ_e h)/∂t = 0.

Shear: the Couette part of the stress is uniform across the film. With the Eyring law
γ̇ = (τ_E/η) sinh(τ/τ_E) it is τ_c = τ_E asinh(|u_b − u_a|/(τ_E F₀)) (the isothermal
solver's τ_E asinh(ηu_s/(τ_E h)) for constant η), capped by the smallest limiting shear
stress across the film (the hottest layer shears first). Heat generated per volume is the
stress times the shear rate at each layer, with the stress τ(z) = s τ_c + p_x (z − F₁/F₀)
(momentum balance: linear in z) and the shear rate du/dz of the velocity profile::

    Φ(z) = (s τ_c + p_x (z − F₁/F₀)) (s γ̇_c + γ̇_p),   s = sign(u_b − u_a),
    γ̇_c = |u_b − u_a|/(η F₀),   γ̇_p = p_x (z − F₁/F₀)/η

The cross terms integrate to zero (∫ dz/η (z − F₁/F₀) = 0), so ∫Φ dz = τ_c|u_b − u_a| +
∫η γ̇_p² dz, the friction power of the film; locally they move the heat towards the surface
where Couette and Poiseuille shear add (in an inlet, the faster one), as in the full
thermal-EHL energy equation (Sadeghi & Dow 1987, J. Tribol. 109:512; Yang & Wen 1990).
Integrals: trapezoidal on the ζ nodes; the flow factors are taken relative to the same
quadrature at uniform properties, so they are exactly 1 for an isothermal film.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["FilmFlow", "film_flow", "cumtrapz"]


def cumtrapz(f, dz):
    """Cumulative trapezoid along the last axis, starting at 0 (same shape as f)."""
    out = np.zeros_like(f)
    out[..., 1:] = np.cumsum(0.5 * (f[..., 1:] + f[..., :-1]), axis=-1) * dz[..., None]
    return out


def _trapz(f, dz):
    return (np.sum(f, axis=-1) - 0.5 * (f[..., 0] + f[..., -1])) * dz


@dataclass(slots=True, init=False, repr=False, eq=False)
class FilmFlow:
    """Across-film quantities at every x (arrays (n,) or (n, m)); see :func:`film_flow`."""

    F0: np.ndarray
    F1: np.ndarray
    C: np.ndarray
    D: np.ndarray
    rho_e: np.ndarray
    u: np.ndarray
    gamma_c: np.ndarray
    gamma_p: np.ndarray
    tau_c: np.ndarray
    dissipation: np.ndarray
    C_ref: np.ndarray
    D_ref: np.ndarray
    flow_factor: np.ndarray
    couette_factor: np.ndarray


def film_flow(
    h, px, ua, ub, eta, rho, tau_e, tau_l, *, eta_ref, rho_ref, eyring=True, limiting=True
) -> FilmFlow:
    """Flow, shear and dissipation of the film.

    h, px : film [m] and dp/dx [Pa/m], shape (n,); ua, ub : surface speeds [m/s];
    eta, rho : viscosity [Pa·s] and density [kg/m³] on the ζ nodes, shape (n, m);
    tau_e : Eyring stress [Pa], shape (n,); tau_l : limiting shear stress on the nodes
    (n, m); eta_ref, rho_ref : uniform reference properties (n,) for the flow factors
    C/C_ref and D/D_ref. ``eyring=False``: Newtonian τ_c = |u_b − u_a|/F₀.
    """
    n, m = eta.shape
    z = np.linspace(0.0, 1.0, m)[None, :] * h[:, None]
    dz = h / (m - 1)
    f = FilmFlow()

    def coeffs(e, r):
        inv = 1.0 / e
        I0 = cumtrapz(inv, dz)
        I1 = cumtrapz(z * inv, dz)
        F0, F1 = I0[:, -1], I1[:, -1]
        rp = _trapz(r * I0, dz)
        rpp = _trapz(r * I1, dz)
        C = rp * F1 / F0 - rpp
        rho_e = _trapz(r, dz) / h
        D = h * rho_e * ua + (ub - ua) * rp / F0
        return I0, I1, F0, F1, C, D, rho_e

    I0, I1, F0, F1, C, D, rho_e = coeffs(eta, rho)
    ones = np.ones((1, m))
    _, _, _, _, Cr, Dr, _ = coeffs(eta_ref[:, None] * ones, rho_ref[:, None] * ones)
    f.F0, f.F1, f.C, f.D, f.rho_e, f.C_ref, f.D_ref = F0, F1, C, D, rho_e, Cr, Dr
    f.flow_factor = C / Cr
    with np.errstate(divide="ignore", invalid="ignore"):
        f.couette_factor = np.where(np.abs(Dr) > 0.0, D / Dr, 1.0)
    du = ub - ua
    f.u = ua + du * I0 / F0[:, None] + px[:, None] * (I1 - I0 * (F1 / F0)[:, None])
    f.gamma_c = abs(du) / (eta * F0[:, None])
    f.gamma_p = px[:, None] * (z - (F1 / F0)[:, None]) / eta
    newt = abs(du) / F0
    tau = tau_e * np.arcsinh(newt / tau_e) if eyring else newt
    if limiting:
        tau = np.minimum(tau, tau_l.min(axis=1))
    f.tau_c = tau
    # Φ = τ(z) γ̇(z): the signed Couette stress plus the Poiseuille stress p_x(z − F₁/F₀),
    # times the signed shear rate du/dz. The cross terms integrate to zero across the film
    # but put the inlet's heat next to the surface whose Couette and Poiseuille shear add.
    sgn = np.sign(du)
    tau_p = px[:, None] * (z - (F1 / F0)[:, None])
    f.dissipation = (sgn * tau[:, None] + tau_p) * (sgn * f.gamma_c + f.gamma_p)
    return f

"""Checks of solver results recomputed outside the solvers, from the equations themselves.

These helpers share no code with the package's discretisation: rheology from the closed
forms (Roelands/Barus, Dowson–Higginson), deformation from the analytic log kernel
integrated over piecewise-constant pressure, flow from Reynolds' mass flux. A solver that
stops early, or returns its starting state, fails them.
"""

import math

import numpy as np


def rheology(p, oil):
    """(ρ/ρ₀, μ) at pressures p [Pa] from the closed forms of the paper's Eqs. 2–3."""
    p = np.maximum(np.asarray(p, dtype=float), 0.0)
    pg = p * 1e-9
    rho = 1.0 + 0.6 * pg / (1.0 + 1.7 * pg) if oil.compressible else np.ones_like(p)
    if oil.viscosity_model == "barus":
        mu = oil.viscosity * np.exp(oil.pressure_viscosity * p)
    else:
        ln0 = math.log(oil.viscosity) + 9.67
        z = oil.pressure_viscosity / (5.1e-9 * ln0)
        mu = oil.viscosity * np.exp(ln0 * (-1.0 + (1.0 + 5.1e-9 * p) ** z))
    return rho, mu


def mass_flux_deviation(x, p, h, ue, oil, *, where=1e-3):
    """Steady Reynolds: the mass flux m = ρ(u_e h − h³/(12μ) dp/dx) is the same at every
    section of the pressurised zone. Returns (max, 95th percentile) of |m/median(m) − 1|
    over the faces where p exceeds ``where`` × its maximum."""
    dx = np.diff(x)
    pm, hm = 0.5 * (p[1:] + p[:-1]), 0.5 * (h[1:] + h[:-1])
    rho, mu = rheology(pm, oil)
    m = rho * (ue * hm - hm**3 / (12.0 * mu) * np.diff(p) / dx)
    sel = pm > where * np.max(p)
    dev = np.abs(m[sel] / np.median(m[sel]) - 1.0)
    return float(dev.max()), float(np.percentile(dev, 95))


def log_kernel_displacement(x, q, e_prime):
    """Combined surface displacement of two half-planes under the piecewise-constant
    pressure q on the uniform grid x: u(x) = −(4/(πE')) ∫ ln|x − s| q(s) ds, with
    ∫ ln|t| dt = t ln|t| − t over each cell (defined up to a constant)."""
    dx = x[1] - x[0]

    def F(t):
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(t == 0.0, 0.0, t * np.log(np.abs(t)) - t)

    d = x[:, None] - x[None, :]
    k = F(d + 0.5 * dx) - F(d - 0.5 * dx)
    return -(4.0 / (math.pi * e_prime)) * (k @ q)


def film_equation_residual(x, h, q, R, e_prime):
    """max |h − x²/(2R) − u(q) − c| / h_min over the grid, c the median offset (the 2-D
    displacement is defined up to a constant, absorbed in the rigid approach h₀)."""
    rest = h - x**2 / (2.0 * R) - log_kernel_displacement(x, q, e_prime)
    return float(np.max(np.abs(rest - np.median(rest))) / np.min(h))


def squeeze_balance_error(profiles, dt, oil, half_width):
    """Transient Reynolds at zero entrainment, recomputed outside the solver:
    ∂/∂x(ρh³/(12μ) ∂p/∂x) = ∂(ρh)/∂t with ∂(ρh)/∂t by BDF2 from the last three steps'
    profiles, or by backward Euler from the last two (interpolated onto the newest grid).
    ``profiles`` = [(x, p, h)] × 3 or × 2 (oldest first), the newest at u_e = 0. Returns
    max |flux divergence − ∂(ρh)/∂t| over the nodes with |x| < b/2, relative to
    max |∂(ρh)/∂t| there."""
    x, p, h = profiles[-1]
    m = [rheology(np.interp(x, xs, ps), oil)[0] * np.interp(x, xs, hs) for xs, ps, hs in profiles]
    if len(m) == 3:
        dmdt = (3.0 * m[2] - 4.0 * m[1] + m[0]) / (2.0 * dt)
    else:
        dmdt = (m[1] - m[0]) / dt
    dx = np.diff(x)
    rho, mu = rheology(0.5 * (p[1:] + p[:-1]), oil)
    hm = 0.5 * (h[1:] + h[:-1])
    flux = -rho * hm**3 / (12.0 * mu) * np.diff(p) / dx  # Poiseuille mass flux at the faces
    div = np.diff(flux) / (0.5 * (dx[1:] + dx[:-1]))
    inner = np.abs(x[1:-1]) < 0.5 * half_width
    rate = dmdt[1:-1][inner]
    return float(np.max(np.abs(-div[inner] - rate)) / np.max(np.abs(rate)))

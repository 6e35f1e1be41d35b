"""Deterministic contact of a periodic rough surface: FFT boundary elements, elastic with
the pressure capped at the hardness (elastic–perfectly-plastic asperities).

A rigid rough surface with heights z(x, y) (zero mean; the composite topography of the
pair) is pressed against an elastic half-space of composite modulus E*,
1/E* = Σ(1 − ν²)/E (E* = E'/2 in the paper's convention), at a mean-plane separation ū.
On a periodic grid the normal surface displacement of the half-space under a pressure p
is, in Fourier space (Boussinesq; e.g. Johnson, Contact Mechanics, 1985; Stanley &
Kato, J. Tribol. 119 (1997) 481)::

    ũ(q) = 2 p̃(q) / (E* |q|),    q ≠ 0;    ũ(0) = 0

so the gap g = ū − z + u has mean ū exactly (the q = 0 displacement is the rigid
approach). The contact problem is the box-constrained quadratic programme

    min_p  ½ Σ p u(p) + Σ p (ū − z)    subject to 0 ≤ p ≤ H

whose Kuhn–Tucker conditions are the contact conditions: g ≥ 0 where p = 0, g = 0 where
0 < p < H, g ≤ 0 where p = H (the asperity flows plastically at the hardness H; with
H = ∞ the contact is elastic). It is solved by bound-constrained conjugate gradients on the scaled pressure
p/E* with gap and heights scaled by the RMS height σ; the Kuhn–Tucker residual is
checked after the solve and reported (``converged``, ``message``).

Outputs per unit nominal area: the mean (asperity) pressure p̄ = ⟨p⟩ and the real-contact
area fraction A/A₀ = fraction of nodes with p > 0. Swept over ū they give the
load–separation law p̄(ū) and A/A₀(ū) of the surface, the quantity Greenwood–Tripp
approximates statistically.

References checked by the tests:

* one-dimensional sinusoid z = Δ cos(2πx/ℓ) (plane strain, Westergaard 1939; Johnson,
  Greenwood & Higginson, Int. J. Mech. Sci. 27 (1985) 383): full contact at
  p* = π E* Δ/ℓ; partial contact of width 2a at p̄ = p* sin²(πa/ℓ);
* random surfaces at light load: A/A₀ = κ p̄/(E* √⟨|∇z|²⟩) with numerical κ between
  Persson's √(8/π) ≈ 1.6 and the Bush–Gibson–Thomas √(2π) ≈ 2.5 (Paggi & Ciavarella,
  Wear 268 (2010) 1020).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validation import InputError, check_positive

__all__ = ["RoughContact", "periodic_compliance", "solve_rough_contact"]


def periodic_compliance(shape: tuple[int, int], pixel_size: float) -> np.ndarray:
    """2/|q| [m] on the ``rfft2`` grid of a periodic map (divide by E* to get ũ/p̃);
    0 at q = 0."""
    nx, ny = shape
    qx = 2.0 * math.pi * np.fft.fftfreq(nx, d=pixel_size)
    qy = 2.0 * math.pi * np.fft.rfftfreq(ny, d=pixel_size)
    q = np.sqrt(qx[:, None] ** 2 + qy[None, :] ** 2)
    out = np.zeros_like(q)
    out[q > 0] = 2.0 / q[q > 0]
    return out


@dataclass
class RoughContact:
    """Solution at one mean-plane separation (SI units)."""

    separation: float  #: ū, mean gap [m]
    pressure: np.ndarray  #: contact pressure map [Pa]
    gap: np.ndarray  #: gap map g = ū − z + u [m]
    mean_pressure: float  #: p̄ = ⟨p⟩ [Pa]
    area_fraction: float  #: A/A₀ (nodes with p > 0)
    plastic_fraction: float  #: nodes at the hardness / all nodes
    residual: float  #: largest Kuhn–Tucker violation of the gap, relative to σ
    converged: bool
    message: str


def solve_rough_contact(
    heights,
    pixel_size: float,
    reduced_modulus: float,
    separation: float,
    hardness: float = math.inf,
    *,
    tol: float = 1e-4,
    max_iter: int = 5000,
    initial: np.ndarray | None = None,
) -> RoughContact:
    """Contact of a periodic rough map at mean-plane separation ū (module docstring).

    Parameters
    ----------
    heights : 2-D array z [m] (periodic; its mean is removed).
    pixel_size : grid spacing [m] (square pixels).
    reduced_modulus : E* [Pa], 1/E* = Σ(1 − ν²)/E (half the paper's E').
    separation : ū > 0 [m], the mean gap; with a finite hardness ū ≤ 0 is allowed.
    hardness : H [Pa], the cap of the contact pressure (``inf``: elastic).
    tol : accepted Kuhn–Tucker violation of the gap, as a fraction of σ.
    initial : starting pressure map [Pa] (e.g. the solution at a nearby ū).
    """
    z = np.asarray(heights, dtype=float)
    if z.ndim != 2 or min(z.shape) < 2 or not np.all(np.isfinite(z)):
        raise InputError("heights must be a finite 2-D map of at least 2 × 2 points")
    dx = check_positive("pixel_size", pixel_size, "m")
    es = check_positive("reduced_modulus", reduced_modulus, "Pa")
    hard = float(hardness)
    if not hard > 0.0:
        raise InputError(f"hardness must be > 0 Pa (got {hardness!r})")
    if not math.isfinite(float(separation)):
        raise InputError(f"separation must be finite (got {separation!r})")
    if math.isinf(hard) and separation <= 0.0:
        raise InputError(
            "an elastic contact (hardness = inf) needs a separation > 0: the mean gap of "
            f"two elastic surfaces cannot close (got {separation!r} m)"
        )
    z = z - z.mean()
    sigma = float(np.sqrt(np.mean(z**2)))
    if sigma <= 0.0:
        raise InputError("heights must not be flat (RMS height 0)")
    shape = z.shape
    comp = periodic_compliance(shape, dx) / sigma  # ũ/σ = comp · P̃, P = p/E*
    zs = z / sigma
    lin = separation / sigma - zs
    n = z.size
    upper = hard / es

    def displacement(pv):
        return np.fft.irfft2(np.fft.rfft2(pv.reshape(shape)) * comp, s=shape).ravel()

    pv = np.zeros(n) if initial is None else np.clip(np.ravel(initial) / es, 0.0, upper)
    pv, nit = _projected_cg(displacement, lin.ravel(), pv, upper, tol, max_iter)
    g = displacement(pv) + lin.ravel()
    # Kuhn–Tucker violation (units of σ): open nodes need g ≥ 0, free nodes g = 0,
    # plastic nodes g ≤ 0
    at_hard = pv >= upper * (1.0 - 1e-9) if math.isfinite(upper) else np.zeros(n, bool)
    free = (pv > 0.0) & ~at_hard
    viol = np.where(pv <= 0.0, np.maximum(-g, 0.0), 0.0)
    viol = np.maximum(viol, np.where(free, np.abs(g), 0.0))
    viol = np.maximum(viol, np.where(at_hard, np.maximum(g, 0.0), 0.0))
    resid = float(viol.max())
    ok = resid <= tol
    msg = (
        f"contact solved (Kuhn–Tucker residual {resid:.2g} σ)"
        if ok
        else f"not converged: Kuhn–Tucker residual {resid:.2g} σ > {tol:g} σ after "
        f"{nit} iterations; raise max_iter or refine the map (steep slopes converge slowly)"
    )
    p = pv.reshape(shape) * es
    return RoughContact(
        separation=float(separation),
        pressure=p,
        gap=g.reshape(shape) * sigma,
        mean_pressure=float(p.mean()),
        area_fraction=float(np.mean(pv > 0.0)),
        plastic_fraction=float(np.mean(at_hard)),
        residual=resid,
        converged=bool(ok),
        message=msg,
    )


def _projected_cg(displacement, lin, pv, upper, tol, max_iter):
    """Bound-constrained conjugate gradients for min ½ P·K P + P·lin, 0 ≤ P ≤ upper
    (gradient = gap g = K P + lin). Nodes held at a bound whose gradient pushes outward
    are frozen; conjugate directions on the others; a step that hits a bound is clipped
    and the directions restart (projected CG with restarts, as in Bugnicourt et al.,
    Tribol. Lett. 66 (2018) 29, written here from the method's description)."""
    t = np.zeros_like(pv)
    gg_old = 0.0
    nit = 0
    for nit in range(1, max_iter + 1):
        g = displacement(pv) + lin
        frozen = ((pv <= 0.0) & (g >= 0.0)) | ((pv >= upper) & (g <= 0.0))
        gf = np.where(frozen, 0.0, g)
        # Kuhn–Tucker residual of the current iterate
        if np.max(np.abs(gf)) <= tol:
            return pv, nit
        gg = float(gf @ gf)
        beta = gg / gg_old if gg_old > 0.0 else 0.0
        t = np.where(frozen, 0.0, -gf + beta * t)
        kt = displacement(t)
        tkt = float(t @ kt)
        if tkt <= 0.0:  # direction along the constant mode (no stiffness): step to a bound
            tkt = 1e-300
        tau = -float(gf @ t) / tkt
        new = pv + tau * t
        clipped = (new < 0.0) | (new > upper)
        pv = np.clip(new, 0.0, upper)
        gg_old = 0.0 if clipped.any() else gg
    return pv, nit

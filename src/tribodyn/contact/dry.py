"""Dry (frictionless, non-adhesive) line contact of a cylinder on a (coated) plane.

Find p ≥ 0 with ∫p dx = w and gap g(x) = x²/(2R) + u(x) − δ ≥ 0, p·g = 0, where the
surface displacement u = K p comes from the DC-FFT operator of
:mod:`tribodyn.physics.elasticity` (coated or not). Solved by the constrained conjugate
gradient method of Polonsky & Keer, Wear 231 (1999) 206, at fixed load; every iteration
costs two O(N log N) convolutions.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from .._threads import one_blas_thread
from .._typing import ArrayLike
from .._validation import InputError, check_int, check_positive
from ..physics.elasticity import DeformationOperator
from ..physics.hertz import HertzLineContact, hertz_line_contact
from ..physics.limits import CONTACT_RADIUS, EHL_NODES, LINE_LOAD, NEWTON_TOL
from ..physics.materials import BodyPair, as_bodies, reduced_modulus
from .ehl.validity import MAX_HALF_WIDTH_TO_RADIUS, MAX_PRESSURE

__all__ = ["DryContactResult", "solve_dry_contact", "contact_edges"]


@dataclass
class DryContactResult:
    """Result of :func:`solve_dry_contact` (SI units, per unit length)."""

    x: np.ndarray  #: node positions [m]
    pressure: np.ndarray  #: contact pressure [Pa]
    gap: np.ndarray  #: gap between deformed surfaces [m] (0 in contact)
    half_width: float  #: contact half-width (edges interpolated) [m]
    max_pressure: float  #: peak pressure [Pa]
    load: float  #: ∫p dx [N/m]
    converged: bool
    iterations: int
    message: str
    hertz: HertzLineContact = field(repr=False)  #: Hertz reference with the bulk E'
    #: conditions outside the model's validity (also appended to ``message``)
    warnings: list = field(default_factory=list)

    @property
    def contact_center(self) -> float:
        lo, hi = contact_edges(self.x, self.pressure)
        return 0.5 * (lo + hi)


def contact_edges(x: np.ndarray, p: np.ndarray) -> tuple[float, float]:
    """Contact edges located between nodes from the square-root edge behaviour.

    Near an edge p ∝ √(distance), so p² is extrapolated linearly from the last two
    loaded nodes to zero and clamped to the next grid interval.
    """
    idx = np.flatnonzero(p > 0.0)
    if idx.size == 0:
        return 0.0, 0.0
    dx = x[1] - x[0]

    def edge(k, k_in, direction):
        if k_in < 0 or k_in >= p.size or p[k_in] <= p[k]:
            return x[k] + 0.5 * direction * dx
        p2k, p2i = p[k] ** 2, p[k_in] ** 2
        s = p2k / (p2i - p2k) * dx
        return x[k] + direction * min(max(s, 0.0), dx)

    return edge(idx[0], idx[0] + 1, -1.0), edge(idx[-1], idx[-1] - 1, +1.0)


def _cgm(
    op: DeformationOperator,
    geom: np.ndarray,
    w: float,
    dx: float,
    p: np.ndarray,
    tol: float,
    max_iter: int,
):
    delta, g_old = 0.0, 1.0
    t = np.zeros_like(p)
    err = np.inf
    it = 0
    for it in range(1, max_iter + 1):
        g = op(p) + geom
        ic = p > 0.0
        if not np.any(ic):
            return p, False, it, "pressure vanished everywhere"
        g = g - g[ic].mean()
        gg = float(np.dot(g[ic], g[ic]))
        t = np.where(ic, g + delta * (gg / g_old) * t, 0.0)
        g_old = gg if gg > 0 else 1.0
        r = op(t)
        r = r - r[ic].mean()
        den = float(np.dot(r[ic], t[ic]))
        if den <= 0.0:
            tau = 0.0
        else:
            tau = float(np.dot(g[ic], t[ic])) / den
        p_old = p
        p = np.maximum(p - tau * t, 0.0)
        overlap = (p == 0.0) & (g < 0.0)
        if np.any(overlap):
            delta = 0.0
            p[overlap] -= tau * g[overlap]
        else:
            delta = 1.0
        p *= w / (p.sum() * dx)
        err = dx * np.abs(p - p_old).sum() / w
        if err < tol:
            return p, True, it, f"converged: pressure change {err:.1e} < tol"
    return p, False, it, f"not converged after {max_iter} iterations (change {err:.1e})"


@one_blas_thread
def solve_dry_contact(
    load: float,
    radius: float,
    bodies: BodyPair,
    *,
    n: int = 1024,
    domain: float = 1.6,
    tol: float = 1e-10,
    max_iter: int = 3000,
    max_domain_growth: int = 3,
    initial_pressure: Callable[[np.ndarray], ArrayLike] | None = None,
) -> DryContactResult:
    """Dry line contact of a steel or coated cylinder/plane pair.

    Parameters
    ----------
    load : w, normal load per unit length [N/m], 1e-3 … 1e9 (``limits.LINE_LOAD``).
    radius : R, reduced radius of curvature [m], 1e-6 … 1e6 (``limits.CONTACT_RADIUS``).
    bodies : pair of :class:`~tribodyn.Body`; either may carry a coating.
    n : grid nodes (uniform), >= 32.
    domain : half-length of the domain in units of the larger of the Hertz half-widths
        computed with the bulk and with the coating moduli, > 1.
    tol : convergence tolerance on the relative L1 pressure change per iteration.
    max_domain_growth : how many times the domain is enlarged (×1.5) when the contact
        reaches its edge before giving up (``converged=False``).
    initial_pressure : optional callable p₀(x) [Pa] of the node positions [m] for the
        starting pressure (scaled to the load); default: Hertz with the bulk E'.
    """
    w = LINE_LOAD.check("load", load)
    r = CONTACT_RADIUS.check("radius", radius)
    bodies = as_bodies(bodies)
    n = EHL_NODES.check("n", n)
    tol = NEWTON_TOL.check("tol", tol)
    max_iter = check_int("max_iter", max_iter)
    max_domain_growth = check_int("max_domain_growth", max_domain_growth)
    if max_iter < 1 or not 0 <= max_domain_growth <= 10:
        raise InputError(
            f"max_iter must be >= 1 and max_domain_growth in [0, 10] (got "
            f"{max_iter}, {max_domain_growth})"
        )
    domain = check_positive("domain", domain)
    if domain <= 1.0:
        raise InputError(f"domain must be > 1 half-width (got {domain:g})")
    hz = hertz_line_contact(w, r, reduced_modulus(bodies))
    # the larger of the Hertz half-widths with bulk and with surface (coating) moduli
    b_surf = hertz_line_contact(w, r, reduced_modulus(bodies, surface=True)).half_width
    b_est = max(hz.half_width, b_surf)

    for growth in range(max_domain_growth + 1):
        half = domain * b_est * 1.5**growth
        x = np.linspace(-half, half, n)
        dx = x[1] - x[0]
        op = DeformationOperator(bodies, dx, n)
        geom = x**2 / (2.0 * r)
        if initial_pressure is None:
            p0 = hz.pressure(x)
        else:
            p0 = np.maximum(np.asarray(initial_pressure(x), dtype=float), 0.0)
            if p0.shape != x.shape or not np.all(np.isfinite(p0)):
                raise InputError("initial_pressure(x) must return finite values, one per node")
        if p0.sum() <= 0.0:
            p0 = np.ones(n)
        p0 *= w / (p0.sum() * dx)
        p, ok, iters, msg = _cgm(op, geom, w, dx, p0, tol, max_iter)
        at_edge = p[0] > 0.0 or p[-1] > 0.0
        if not at_edge:
            break
    if at_edge:
        ok = False
        msg = f"contact reaches the domain edge (half-length {half:.3g} m); enlarge `domain`"

    u = op(p) + geom
    ic = p > 0.0
    gap = u - (u[ic].mean() if np.any(ic) else u.min())
    lo, hi = contact_edges(x, p)
    res = DryContactResult(
        x=x,
        pressure=p,
        gap=gap,
        half_width=0.5 * (hi - lo),
        max_pressure=float(p.max()),
        load=float(p.sum() * dx),
        converged=bool(ok),
        iterations=int(iters),
        message=msg,
        hertz=hz,
    )
    return _check_validity(res, r)


def _check_validity(res: DryContactResult, radius: float) -> DryContactResult:
    """Warn where Hertz's idealisation fails: contact not small against R, or a pressure
    beyond the elastic limit (thresholds and sources in :mod:`.ehl.validity`)."""
    size = max(res.half_width, res.hertz.half_width)
    if size > MAX_HALF_WIDTH_TO_RADIUS * radius:
        res.warnings.append(
            f"contact half-width {size / radius:.3g} R: the parabolic gap "
            "and half-space elasticity need a contact much smaller than R "
            f"(flagged above {MAX_HALF_WIDTH_TO_RADIUS:g} R)"
        )
    if res.max_pressure > MAX_PRESSURE:
        res.warnings.append(
            f"peak pressure {res.max_pressure / 1e9:.3g} GPa exceeds "
            f"{MAX_PRESSURE / 1e9:g} GPa: beyond the elastic limit of "
            "hardened steel"
        )
    res.message += "".join(f"; warning: {t}" for t in res.warnings)
    return res

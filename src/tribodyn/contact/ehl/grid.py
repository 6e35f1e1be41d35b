"""Domain and grid of the EHL line contact.

Length scale a = max(b, √(2R h_est)) (b: Hertz half-width, h_est: Moes central film), so
that elastic and rigid (inlet-dominated) contacts both get a sufficient domain. The
upstream extent is the largest of the elastic (``inlet``·b), the inlet-truncation
(R√(24μ₀|u_e|/(ε w)), see :class:`~.options.EHLOptions`) and the rigid (``inlet_rigid``·s,
s = √(2R h_est)) requirements; downstream likewise. Uniform grid (DC-FFT needs it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from ..._validation import InputError
from ...physics.elasticity import influence_coefficients
from ...physics.hertz import hertz_half_width
from ...physics.regimes import hamrock_groups, moes_central
from .march_kernels import symmetric_toeplitz
from .options import Conditions, ContactModel, EHLOptions

__all__ = ["Layout", "Grid", "layout", "N_MAX_AUTO", "N_AUTO", "N_DENSE"]

#: Largest automatic grid (a posteriori refinement of steady solves).
N_MAX_AUTO = 4096
#: Automatic grid: nodes over the physically sized domain. The discretisation error of
#: h_c and h_min falls as n⁻² and is 0.1–0.25 % at 384 nodes for every load, speed and
#: radius of the paper's cam cycle (elastic and nearly rigid alike; friction < 0.1 %),
#: see docs/convergence.md.
N_AUTO = 384
#: Grids up to this size keep the dense influence matrix (LU-based Newton solves).
N_DENSE = 1024


@dataclass(frozen=True)
class Layout:
    """Scales and extent of the grid for one operating point.

    a : length scale [m]; b : Hertz half-width [m]; h_est : film estimate [m];
    inlet, outlet : extents up- and downstream in units of a; n : nodes.
    """

    a: float
    b: float
    h_est: float
    inlet: float
    outlet: float
    n: int


def _length_scale(cond: Conditions, model: ContactModel, squeeze_film=None):
    """(a, b, h_est): a = max(b, √(2R h_est)); h_est from Moes (or the squeeze film
    when u_e ≈ 0)."""
    w, R, e = cond.load, cond.radius, model.e_bulk
    lub = model.lubricant
    b = hertz_half_width(w, R, e)  # checked conditions and model
    u = max(abs(cond.entrainment_speed), 1e-3)
    W, U, G = hamrock_groups(w, R, u, lub.viscosity, lub.pressure_viscosity, e)
    h_est = float(moes_central(W, U, G, R))
    if squeeze_film is not None:
        h_est = max(h_est, squeeze_film)
    return max(b, math.sqrt(2.0 * R * h_est)), b, h_est


def _domain(b, s, cond: Conditions, mu0, opts: EHLOptions) -> tuple[float, float]:
    """Upstream and downstream extent [m]: the largest of the elastic (b), the inlet
    truncation and the rigid (s) requirements (see :class:`EHLOptions`)."""
    x_trunc = cond.radius * math.sqrt(
        24.0 * mu0 * abs(cond.entrainment_speed) / (opts.inlet_truncation * cond.load)
    )
    return (
        max(opts.inlet * b, x_trunc, opts.inlet_rigid * s),
        max(opts.outlet * b, opts.outlet_rigid * s),
    )


def auto_nodes(length=None, s=None) -> int:
    """Default grid size (:data:`N_AUTO`; the domain, not the node count, follows the
    contact)."""
    return N_AUTO


def layout(
    cond: Conditions, model: ContactModel, opts: EHLOptions, squeeze_film=None, n=None
) -> Layout:
    """The grid :class:`Layout` for these conditions (``squeeze_film``: a film [m] the
    estimate must not fall below, for squeeze films near u_e = 0; ``n``: the node count,
    None: the options' or the automatic one)."""
    try:
        a, b, h_est = _length_scale(cond, model, squeeze_film)
        s = math.sqrt(2.0 * cond.radius * h_est)
        up, down = _domain(b, s, cond, model.lubricant.viscosity, opts)
    except (ArithmeticError, ValueError):
        a = up = down = math.nan
    if not all(math.isfinite(v) and v > 0.0 for v in (a, up, down)):
        # cannot happen inside physics.limits; said in the user's terms if it does
        raise InputError(
            f"load {cond.load:.6g} N/m, radius {cond.radius:.6g} m and entrainment_speed "
            f"{cond.entrainment_speed:.6g} m/s give no finite EHL domain for this "
            "lubricant and these bodies; use values nearer an ordinary contact"
        )
    length = up + (down if cond.entrainment_speed != 0.0 else up)
    if n is None:
        n = int(opts.n) if opts.n is not None else auto_nodes(length, s)
    return Layout(a, b, h_est, up / a, down / a, n)


def _extent(lay: Layout, direction: int) -> tuple[float, float]:
    """(lo, hi) in units of a: upstream is −x for u_e > 0, mirrored for u_e < 0,
    symmetric for pure squeeze."""
    if direction > 0:
        return -lay.inlet, lay.outlet
    if direction < 0:
        return -lay.outlet, lay.inlet
    return -lay.inlet, lay.inlet


class Grid:
    """Uniform grid in the contact frame (metres) with the physical influence coefficients.

    Holds geometry only; pressure/film scales belong to each solve, so a grid (and a
    preconditioner built on it) survives changes of load and radius in a transient.
    """

    def __init__(
        self,
        bodies,
        lay: Layout,
        direction: int,
        elastic: bool,
        n: int | None = None,
        margin: float = 1.0,
    ):
        n = lay.n if n is None else n
        self.a, self.n, self.direction = lay.a, n, direction
        lo, hi = _extent(lay, direction)
        lo, hi = lo * margin, hi * margin
        self.X = np.linspace(lo, hi, n)
        self.dX = self.X[1] - self.X[0]
        self.x = self.X * lay.a
        self.i0 = int(np.argmin(np.abs(self.X)))
        self.coef = influence_coefficients(bodies, self.dX * lay.a, n) if elastic else None
        self.elastic = bool(elastic)
        self._K = None

    @property
    def K(self):
        """Dense influence matrix [m/Pa] (built on first use: only LU paths need it)."""
        if self.elastic and self._K is None:
            assert self.coef is not None  # an elastic grid has its coefficients
            self._K = symmetric_toeplitz(self.coef, np.empty((self.n, self.n)))
        return self._K

    @cached_property
    def rigid_gap(self) -> np.ndarray:
        """X²/2 at the nodes: the undeformed parabolic gap x²/(2R) in the film scale a²/R
        of every solve on this grid (shared by them: never written)."""
        return 0.5 * self.X**2

    @cached_property
    def ones(self) -> np.ndarray:
        """Ones at the nodes, the neutral per-node factors of the solves on this grid
        (shared by them: never written)."""
        return np.ones(self.n)

    @property
    def has_dense(self) -> bool:
        """Elastic grid small enough for dense products with K (K built on demand)."""
        return self.elastic and self.n <= N_DENSE

    def covers(self, lay: Layout, direction: int, slack: float) -> bool:
        """Same node count and orientation, the required extents inside the grid and the
        grid at most ``slack`` times as long as required (spacing that much coarser)."""
        lo, hi = _extent(lay, direction)
        lo, hi = lo * lay.a, hi * lay.a
        return (
            self.n == lay.n
            and self.direction == direction
            and self.x[0] <= lo
            and self.x[-1] >= hi
            and self.x[-1] - self.x[0] <= slack * (hi - lo)
        )

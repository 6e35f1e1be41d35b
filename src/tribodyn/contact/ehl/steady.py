"""Steady mixed-EHL line contact: nested grids, load continuation, a posteriori grid check.

The solve starts on a coarse grid (cheap and robust) from a Hertz-like pressure whose
central film is the Moes estimate and refines by factors of two to the requested grid; a
coarse level that fails is retried by load continuation (light, nearly rigid first). With
the automatic grid the result is compared with the level on half the nodes and the grid
doubled (up to ``N_MAX_AUTO``) while h_c or h_min still change by more than 1 %.
"""

from __future__ import annotations

import math

import numpy as np

from ..._threads import one_blas_thread
from ..._validation import InputError
from ...physics.asperity import Roughness
from ...physics.lubricant import Lubricant
from ...physics.materials import BodyPair
from .grid import N_DENSE as _N_DENSE  # finer grids: the two-grid preconditioner
from .grid import N_MAX_AUTO, Grid, Layout, layout
from .newton import CoarseLevel, NewtonOutcome, State, newton
from .options import Conditions, ContactModel, EHLOptions, EHLResult, with_overrides
from .postprocess import postprocess
from .reynolds import ReynoldsSystem

__all__ = ["solve_ehl", "initial_state", "state_from_dimensional"]

_COARSEST = 128
#: automatic grid: refine while h_c or h_min change by more than this from n/2 to n
_GRID_REFINE_CHANGE = 0.01


def initial_state(sysm: ReynoldsSystem, b, h_est) -> State:
    """Hertz-like pressure over the Hertz width (or a narrow bump if rigid); h₀ such that
    the central film equals the film-formula estimate."""
    g = sysm.g
    bb = max(b / g.a, 4 * g.dX)
    P = np.sqrt(np.clip(1.0 - (g.X / bb) ** 2, 0.0, None))
    P /= np.sum(P) * g.dX
    H0 = h_est / sysm.h_ref
    if sysm.Kop is not None:  # elastic
        H0 -= sysm.Kop(P)[g.i0]
    return State(P, H0)


def state_from_dimensional(sysm: ReynoldsSystem, x, q, h0) -> State:
    """Scaled state on sysm's grid from a total pressure q(x) = p + p_a [Pa] and the
    rigid approach h₀ [m]."""
    Q = np.interp(sysm.g.x, x, q, left=0.0, right=0.0) / sysm.p_ref
    return State(Q, h0 / sysm.h_ref)


@one_blas_thread
def solve_ehl(
    load: float,
    radius: float,
    entrainment_speed: float,
    sliding_speed: float,
    bodies: BodyPair,
    lubricant: Lubricant,
    roughness: Roughness | None = None,
    *,
    options: EHLOptions | None = None,
    **option_overrides,
) -> EHLResult:
    """Steady mixed-EHL line contact.

    Parameters
    ----------
    load : w, load per unit length [N/m], 1e-3 … 1e9 (carried by fluid + asperities).
    radius : R, reduced radius of curvature [m], 1e-6 … 1e6.
    entrainment_speed : u_e = (u₁ + u₂)/2 relative to the contact [m/s], ≠ 0 and
        |u_e| ≤ 1000 (either sign: the inlet is on the side the flow comes from).
    sliding_speed : u_s = u₁ − u₂ [m/s], |u_s| ≤ 1000 (friction only).
    bodies : pair of :class:`~tribodyn.Body` (coating allowed on either).
    lubricant : :class:`~tribodyn.Lubricant`.
    roughness : composite :class:`~tribodyn.Roughness` or None (smooth).
    options / option_overrides : :class:`EHLOptions` fields (n, inlet, outlet, tol, …).

    Notes
    -----
    The ranges are :data:`~tribodyn.physics.limits.LINE_LOAD`, ``CONTACT_RADIUS`` and
    ``SURFACE_SPEED``; outside them :class:`~tribodyn.InputError` names the argument.
    """
    cond = Conditions.checked(load, radius, entrainment_speed, sliding_speed)
    model = ContactModel.checked(bodies, lubricant, roughness)
    opts = with_overrides(options, option_overrides)
    if cond.entrainment_speed == 0.0:
        raise InputError(
            "entrainment_speed must be non-zero for a steady film (pure squeeze needs TransientEHL)"
        )
    return _solve(cond, model, opts)


def _levels(n: int) -> list[int]:
    """Nested grid sizes, coarsest first: at least four levels (down to _COARSEST) and
    every level above the dense limit."""
    levels = [n]
    while levels[-1] // 2 >= _COARSEST and (len(levels) < 4 or levels[-1] > _N_DENSE):
        levels.append(levels[-1] // 2)
    return levels[::-1]


def _solve(cond: Conditions, model: ContactModel, opts: EHLOptions) -> EHLResult:
    lay = layout(cond, model, opts)
    direction = 1 if cond.entrainment_speed >= 0 else -1
    # nested iteration: coarse grids first (cheap, robust), then the requested grid
    levels = _levels(lay.n)
    st: State | None = None
    sysm: ReynoldsSystem | None = None
    prev: ReynoldsSystem | None = None
    coarse: CoarseLevel | None = None
    total = 0
    films: list[tuple[float, float] | None] = []
    refined = ""
    out: NewtonOutcome | None = None
    k = 0
    while k < len(levels):
        nk = levels[k]
        grid = Grid(model.bodies, lay, direction, opts.elastic, n=nk)
        prev, sysm = sysm, ReynoldsSystem(grid, cond, model)
        if st is None:
            st0 = initial_state(sysm, lay.b if opts.elastic else 0.0, lay.h_est)
        else:
            assert prev is not None
            st0 = state_from_dimensional(sysm, prev.g.x, st.Q * prev.p_ref, st.H0 * prev.h_ref)
        max_it = opts.max_iter * (2 if k == 0 and len(levels) > 1 else 1)
        out = newton(sysm, st0, opts.tol, max_it, coarse=coarse if nk > _N_DENSE else None)
        total += out.iterations
        if out.converged and nk <= _N_DENSE and nk < lay.n and levels[-1] > _N_DENSE:
            coarse = CoarseLevel(sysm, out.state)  # finest dense level preconditions the rest
        if not out.converged and k == 0:
            out = _continuation(grid, cond, model, opts, lay)
            total += out.iterations
        st = out.state
        films.append(_films(sysm, st) if out.converged else None)
        # a posteriori grid check of the automatic grid: if h_c or h_min still changed by
        # more than _GRID_REFINE_CHANGE from the previous (half as fine) level, double n
        if (
            k == len(levels) - 1
            and opts.n is None
            and out.converged
            and nk < N_MAX_AUTO
            and len(films) >= 2
            and films[-2] is not None
            and films[-1] is not None
        ):
            f_prev, f_last = films[-2], films[-1]
            change = max(abs(f1 / f0 - 1.0) for f0, f1 in zip(f_prev, f_last))
            if change > _GRID_REFINE_CHANGE:
                if coarse is None and nk <= _N_DENSE:
                    coarse = CoarseLevel(sysm, st)
                levels.append(min(N_MAX_AUTO, 2 * nk))
                refined = (
                    f"; grid refined to {levels[-1]} nodes (h changed by "
                    f"{change:.1%} from {levels[-3]} to {nk} nodes)"
                )
        k += 1
    assert out is not None and sysm is not None  # at least one level was solved
    out.iterations = total
    out.message += refined
    return postprocess(sysm, out, opts)


def _films(sysm: ReynoldsSystem, st: State) -> tuple[float, float]:
    """(h_c, h_min) [m] of a solved state."""
    h = st.H * sysm.h_ref
    return float(np.interp(0.0, sysm.g.x, h)), float(h.min())


def _continuation(
    grid: Grid, cond: Conditions, model: ContactModel, opts: EHLOptions, lay: Layout
) -> NewtonOutcome:
    """Load continuation on the same grid: start light (nearly rigid), increase to w."""
    total = 0
    st: State | None = None
    prev: ReynoldsSystem | None = None
    out: NewtonOutcome | None = None
    for frac in (0.05, 0.15, 0.35, 0.6, 0.8, 1.0):
        c = Conditions(cond.load * frac, cond.radius, cond.entrainment_speed, cond.sliding_speed)
        sysm = ReynoldsSystem(grid, c, model)
        if st is None:
            st = initial_state(sysm, lay.b * math.sqrt(frac), lay.h_est)
        else:
            assert prev is not None
            st = state_from_dimensional(sysm, grid.x, st.Q * prev.p_ref, st.H0 * prev.h_ref)
        out = newton(sysm, st, opts.tol, opts.max_iter)
        total += out.iterations
        st, prev = out.state, sysm
        if not out.converged:
            out.iterations = total
            out.message = f"load continuation stalled at {frac:.0%} of the load: {out.message}"
            return out
    assert out is not None
    out.iterations = total
    out.message += " (after load continuation)"
    return out

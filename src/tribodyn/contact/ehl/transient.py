"""Transient mixed-EHL line contact marched in time (full Eq. 1 with ∂(ρh)/∂t)."""

from __future__ import annotations

import math
from contextlib import contextmanager
from dataclasses import astuple, dataclass

import numpy as np

from ..._threads import one_blas_thread
from ..._validation import InputError, check_positive
from ...physics.asperity import Roughness
from ...physics.limits import EHL_NODES_TRANSIENT, MAX_SUBSTEPS, RangeError, unchecked
from ...physics.lubricant import Lubricant
from ...physics.materials import BodyPair
from .grid import Grid, layout
from .march_kernels import (
    bdf_history,
    committed_level,
    extrapolated_pressure,
    interp_point,
    predicted_cavitation,
    rebased_history,
)
from .newton import ROUND_OFF_PRESSURE, NewtonOutcome, State, newton
from .options import Conditions, ContactModel, EHLOptions, EHLResult, with_overrides
from .postprocess import postprocess
from .reynolds import ReynoldsSystem
from .steady import solve_ehl, state_from_dimensional

__all__ = ["TransientEHL", "GRID_SLACK", "GRID_MARGIN", "Level", "MarchState", "StepSolution"]

#: A transient keeps its grid while the required domain fits inside it and the grid is at
#: most this many times as long as required (spacing that much coarser) …
GRID_SLACK = 1.3
#: … and builds new grids this much longer than required, so that they last.
GRID_MARGIN = 1.1
#: Automatic grid: an event keeps the node count its steady start settled on.
EVENT_NODES_FROM_START = True

#: a step changing the load by more than this factor is sub-stepped from the start
_SPLIT_RATIO = 8.0


@dataclass(frozen=True)
class Level:
    """One accepted time level: the BDF history of ρh and the predictor's data."""

    x: np.ndarray  #: grid [m]
    rho_h: np.ndarray  #: ρh [kg/m²]
    q: np.ndarray  #: total pressure p + p_a [Pa]
    central_film: float  #: h(0) [m]
    dt: float | None  #: the step that reached this level [s]; None: a start
    radius: float  #: radius of curvature [m]
    p: np.ndarray  #: fluid pressure [Pa] (the predictor's cavitated nodes)


@dataclass
class MarchState:
    """Everything a step changes (restored after a failed attempt or a rollback);
    ``extra``: a variant's own state (e.g. the temperature field)."""

    grid: Grid | None
    q: np.ndarray | None
    p: np.ndarray | None
    h: np.ndarray | None
    h0: float
    levels: tuple[Level, ...]
    time: float
    lu: object | None
    result: EHLResult | None
    extra: object = None


@dataclass
class StepSolution:
    """The solve of one time level (:meth:`TransientEHL._solve`): the Newton outcome,
    the state to commit and the factorisation to keep."""

    out: NewtonOutcome
    state: State
    lu: object | None


class TransientEHL:
    """Transient mixed-EHL line contact marched in time (full Eq. 1 with ∂(ρh)/∂t).

    Each :meth:`step` advances from the current state to t + dt with the load, radius,
    entrainment and sliding speed given at t + dt (implicit, BDF2 with variable steps;
    BDF1 on the first step or after ``time_order=1``). The grid follows the contact
    (length scale from the current load/radius/speed); it is kept — together with the
    LU preconditioner of the Newton matrix — while the length scale changes by < 2 %,
    otherwise the previous ρh(x) is interpolated onto the new grid. Entrainment may change
    sign or vanish (pure squeeze): the squeeze term then carries the load.

    Start with :meth:`start_steady` (steady solution at u_e ≠ 0) or :meth:`start_film`
    (a given rigid-approach film and zero pressure, e.g. for squeeze tests).
    A step that fails to converge is retried with sub-steps (conditions interpolated
    linearly in time) from the last converged sub-step: the remaining interval is halved
    after a failure and grows again after a success, at most ``max_substeps`` (0…10)
    halvings in a row and at most 2·max_substeps + 1 failed attempts per step. A step that
    changes the load by more than a factor of 8 (never in the cam cycles studied: ≤ 4 per
    crank degree at 6000 rpm) is sub-stepped from the start, in up to 2^max_substeps
    sub-steps of equal duration: one implicit step over such a change misses the loading
    history (the squeeze film that forms as the load rises; a hundredfold step gives twice
    the central film of a finely resolved ramp) and its Newton iteration often fails. The
    effort of one step is thus bounded: with k = max_substeps, at most
    2^k + (2k + 1)(k + 2) + 1 solves of at most ``max_iter`` Newton iterations each. If it still fails the result says so
    (``converged=False``) and marching continues from the last iterate.

    A variant (e.g. :class:`~.thermal_transient.ThermalTransientEHL`) keeps this march and
    overrides only the hooks :meth:`_steady`, :meth:`_steady_on_grid` (the start),
    :meth:`_prepare`, :meth:`_solve` and :meth:`_result` (one time level).
    """

    def __init__(
        self,
        bodies: BodyPair,
        lubricant: Lubricant,
        roughness: Roughness | None = None,
        *,
        options: EHLOptions | None = None,
        max_substeps: int = 3,
        **option_overrides,
    ):
        self.model = ContactModel.checked(bodies, lubricant, roughness)
        self.bodies = self.model.bodies
        self.lub = lubricant
        self.rough = roughness
        opts = with_overrides(options, option_overrides)
        # the options checked n (an integer in the steady range): only the transient's here
        if opts.n is not None and not EHL_NODES_TRANSIENT.contains(opts.n):
            raise RangeError([("n", EHL_NODES_TRANSIENT, opts.n)])
        self.opts = opts
        self.max_substeps = MAX_SUBSTEPS.check("max_substeps", max_substeps)
        self.conditions_before: Conditions | None = None
        self.time = 0.0
        self._grid: Grid | None = None
        # total, fluid pressure [Pa], film [m] on the grid
        self._q: np.ndarray | None = None
        self._p: np.ndarray | None = None
        self._h: np.ndarray | None = None
        self._h0 = 0.0  # rigid approach [m]
        self._levels: tuple[Level, ...] = ()  # the last two time levels, newest first
        self._lu: object | None = None
        self._n_event: int | None = None  # automatic grid: the node count of the steady start
        self.result: EHLResult | None = None

    # -- starting states
    @one_blas_thread
    def start_steady(self, load, radius, entrainment_speed, sliding_speed, time=0.0) -> EHLResult:
        """Start from the steady solution at the given conditions (u_e ≠ 0), on the
        transient's own grid, with an empty history (the first step is BDF1)."""
        res = self._steady(load, radius, entrainment_speed, sliding_speed)
        cond = Conditions.checked(load, radius, entrainment_speed, sliding_speed)
        self._grid = None
        self._n_event = res.x.size if self.opts.n is None and EVENT_NODES_FROM_START else None
        grid = self._make_grid(cond, None)
        # the steady state of the transient's own grid, so that marching at constant
        # conditions stays there (the grids differ in extent and spacing)
        sysm, st, res = self._steady_on_grid(grid, cond, res)
        self._reset(grid)
        self._commit(sysm, st, None, time)
        res.time = time
        self.result = res
        return res

    @one_blas_thread
    def start_film(self, film, load, radius, entrainment_speed=0.0, sliding_speed=0.0, time=0.0):
        """Start from an unloaded film h(x) = film + x²/(2R) (no pressure yet)."""
        h0 = check_positive("film", film, "m")
        cond = Conditions.checked(load, radius, entrainment_speed, sliding_speed)
        self._grid, self._n_event = None, None
        grid = self._make_grid(cond, h0)
        sysm = ReynoldsSystem(grid, cond, self.model)
        self._reset(grid)
        self._commit(sysm, State(np.zeros(grid.n), h0 / sysm.h_ref), None, time)  # evaluated there
        self.result = None

    # -- hooks of a variant (the thermal one: :mod:`.thermal_transient`)
    def _steady(self, load, radius, entrainment_speed, sliding_speed) -> EHLResult:
        """The steady solution a march starts from."""
        return solve_ehl(
            load,
            radius,
            entrainment_speed,
            sliding_speed,
            self.bodies,
            self.lub,
            self.rough,
            options=self.opts,
        )

    def _steady_on_grid(self, grid: Grid, cond: Conditions, res: EHLResult):
        """(system, state, result): the steady solution ``res`` re-solved on ``grid``
        (kept as it is if that fails)."""
        sysm = ReynoldsSystem(grid, cond, self.model)
        st = state_from_dimensional(
            sysm, res.x, res.pressure + res.asperity_pressure, res.rigid_approach
        )
        out = newton(sysm, st, self.opts.tol, self.opts.max_iter)
        if out.converged:
            st, res = out.state, postprocess(sysm, out, self.opts)
        return sysm, st, res

    def _prepare(self, grid: Grid, cond: Conditions, time_coef: float):
        """(system, context) of a time level: the Reynolds system with the BDF
        coefficient a₀/Δt of ∂(ρh)/∂t (its old-level term f_old is set by the caller) and
        whatever :meth:`_solve` and :meth:`_result` need besides (None here)."""
        return ReynoldsSystem(grid, cond, self.model, time_coef=time_coef), None

    def _solve(self, sysm: ReynoldsSystem, ctx, st: State, dt: float, lu) -> StepSolution:
        """Solve one time level from the predicted state ``st`` (Newton; ``lu``: the
        previous factorisation when the grid is kept)."""
        out = newton(sysm, st, self.opts.tol, self.opts.max_iter, lu=lu, release_blocks=False)
        return StepSolution(out, out.state, out.lu if out.converged else None)

    def _result(self, sysm, ctx, sol: StepSolution, squeeze_velocity: float) -> EHLResult:
        """The result of a solved time level (at :attr:`time`)."""
        return postprocess(
            sysm, sol.out, self.opts, time=self.time, squeeze_velocity=squeeze_velocity
        )

    # -- internals
    def _reset(self, grid: Grid):
        """A new start on ``grid``: no history, no factorisation."""
        self._grid, self._lu, self._levels = grid, None, ()

    def _make_grid(self, cond: Conditions, film) -> Grid:
        """The current grid while it still fits the contact (see :data:`GRID_SLACK`), else
        a new one with :data:`GRID_MARGIN` (keeping a grid keeps its factorisation)."""
        lay = layout(cond, self.model, self.opts, squeeze_film=film, n=self._n_event)
        ue = cond.entrainment_speed
        direction = (ue > 0.0) - (ue < 0.0)
        g = self._grid
        if g is not None and g.covers(lay, direction, GRID_SLACK):
            return g
        return Grid(self.bodies, lay, direction, self.opts.elastic, margin=GRID_MARGIN)

    def _commit(self, sysm: ReynoldsSystem, st: State, dt, time):
        if st.P is None:
            ev = sysm.evaluate(st.Q, st.H0)
            st.P, st.H = ev.P, ev.H
        x, lub, n = sysm.g.x, sysm.lub, sysm.g.n
        self._q, self._p, self._h, rho_h = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
        if isinstance(lub, Lubricant):  # ρ(p) through the compiled law
            law = lub.rheology_law
            args = (sysm.p_ref, sysm.h_ref, x, law, lub.density, self._q, self._p, self._h)
            hc = committed_level(st.Q, st.P, st.H, *args, rho_h)
        else:  # a lubricant with per-node properties
            np.multiply(st.Q, sysm.p_ref, out=self._q)
            np.multiply(st.P, sysm.p_ref, out=self._p)
            np.multiply(st.H, sysm.h_ref, out=self._h)
            np.multiply(lub.density_at(self._p), self._h, out=rho_h)
            hc = interp_point(0.0, x, self._h)
        self._h0 = st.H0 * sysm.h_ref
        level = Level(
            x=x, rho_h=rho_h, q=self._q, central_film=hc, dt=dt, radius=sysm.cond.radius, p=self._p
        )
        self._levels = (level, *self._levels[:1])
        self._grid = sysm.g
        self.time = time

    def _old_on(self, grid: Grid, k, R_new):
        """ρh of history level k (0: last) on ``grid`` [kg/m²], re-based on the current
        radius of curvature.

        The rigid gap x²/(2R) is valid only near the contact; there the squeeze due to a
        changing R, x²Ṙ/(2R²), is negligible against the Couette term, while far upstream
        it would invent suction of metres per second on a fast-changing cam flank. The
        change of R is therefore taken quasi-statically: the old film keeps its approach
        and elastic deformation but gets the new parabola. Outside the old domain the old
        film is continued with that parabola (ambient density)."""
        lv = self._levels[k]
        x_old, R_old = lv.x, lv.radius
        # the density varies little where the parabola matters (low pressure): use ρ₀
        xe2 = (x_old[0] ** 2, x_old[-1] ** 2)
        rebase = 0.5 / R_new - 0.5 / R_old
        args = (self.lub.density, R_old, *xe2, rebase, np.empty(grid.n))
        return rebased_history(grid.x, x_old, lv.rho_h, *args)

    def _predict(self, sysm: ReynoldsSystem, dt) -> State:
        """Newton start for the next level: the total pressure extrapolated linearly from
        the last two levels and scaled to the new load (after a start: the last pressure
        scaled), and h₀ such that the central film continues linearly from the last two
        levels; else (no history) the last level as it is."""
        r = self.result
        lv = self._levels
        assert self._grid is not None and self._q is not None  # started
        last = (self._grid.x, self._q, self._h0)  # the last level (on the new grid if used)
        if r is None or not r.converged or len(lv) < 2 or lv[0].dt is None:
            return state_from_dimensional(sysm, *last)
        ratio = dt / lv[0].dt
        # the total pressure extrapolated linearly in time …
        xg = sysm.g.x
        q = extrapolated_pressure(xg, lv[0].x, lv[0].q, lv[1].x, lv[1].q, ratio, np.empty(xg.size))
        w = float(np.sum(q) * (xg[1] - xg[0]))
        # … carrying the new load (else the last pressure scaled)
        if w > 0.0:
            q *= sysm.cond.load / w
            q /= sysm.p_ref
            st = State(q, self._h0 / sysm.h_ref)
        else:
            st = state_from_dimensional(sysm, *last)
            st.Q = st.Q * (sysm.cond.load / r.load)
        if all(v.x is xg or np.array_equal(v.x, xg) for v in lv[:2]):
            # … and Newton starts from the cavitated nodes of the fluid pressure
            # extrapolated alike on the same grid (zero up to round-off of the total
            # pressure): Q − Pa(H) of the predicted Q is the small difference of two large
            # ones where the asperities carry the load, its cavitation boundary far from
            # the solution's (see docs/convergence.md)
            cav = np.empty(xg.size, dtype=np.bool_)
            st.cav = predicted_cavitation(lv[0].p, lv[1].p, lv[0].q, ratio, ROUND_OFF_PRESSURE, cav)
        hc1, hc0 = lv[0].central_film, lv[1].central_film
        hc = hc1 + ratio * (hc1 - hc0)
        if not hc > 0.0:
            return st
        if sysm.elastic:  # K Q of the predicted Q, handed to the solve's first evaluation
            st.KQ = sysm.deform(st.Q)
        H = sysm.film(st.Q, 0.0, st.KQ)
        st.H0 = hc / sysm.h_ref - interp_point(0.0, sysm.g.X, H)
        return st

    @one_blas_thread
    def step(self, dt, load, radius, entrainment_speed, sliding_speed) -> EHLResult:
        """Advance by dt [s] to the given conditions (load per unit length [N/m])."""
        dt = check_positive("dt", dt, "s")
        if self._grid is None:
            raise InputError("TransientEHL needs start_steady() or start_film() before step()")
        cond = Conditions.checked(load, radius, entrainment_speed, sliding_speed)
        saved = self.checkpoint()
        c0 = self.conditions_before if self.conditions_before is not None else cond
        marks = self._load_marks(c0.load, cond.load)
        if len(marks) > 1:  # a large load change: follow its ramp
            res = self._substep(dt, c0, cond, marks, depth=0)
            ratio = max(cond.load / c0.load, c0.load / cond.load)
            note = (
                f"the load changed by a factor {ratio:.3g} within one step, which was "
                f"split into sub-steps along a linear ramp; refine the time step to "
                "resolve the loading history"
            )
            res.warnings.append(note)
            res.message += f"; warning: {note}"
            return res
        res = self._advance(dt, cond)
        if res.converged or self.max_substeps == 0:
            return res
        self._set_state(saved)
        return self._substep(dt, c0, cond, marks, depth=1)  # the full step failed

    @contextmanager
    def _max_iter(self, n: int):
        """Temporarily cap the Newton iterations of a solve (n ≥ 1: the capped options are
        in range, not checked again)."""
        opts = self.opts
        self.opts = unchecked(EHLOptions, **{**opts.__dict__, "max_iter": min(opts.max_iter, n)})
        try:
            yield
        finally:
            self.opts = opts

    def _load_marks(self, w0: float, w1: float) -> list[float]:
        """Time fractions to pass through: [1] normally; for a load change by more than
        _SPLIT_RATIO, m sub-steps of equal duration along the step's linear ramp, enough
        for the load to change by < _SPLIT_RATIO in each after the first, at most
        2^max_substeps; a first sub-step that still fails is halved further."""
        ratio = max(w1 / w0, w0 / w1)
        if ratio <= _SPLIT_RATIO or self.max_substeps == 0:
            return [1.0]
        m = min(math.ceil((ratio - 1.0) / (_SPLIT_RATIO - 1.0)), 2**self.max_substeps)
        return [j / m for j in range(1, m + 1)]

    def _substep(self, dt, c0: Conditions, c1: Conditions, marks, depth: int) -> EHLResult:
        """March from the current state (fraction 0) through ``marks`` to fraction 1 with
        bounded adaptive sub-steps (class docstring); the first attempt spans
        1/2^depth of the way to the first mark."""

        def at(f):
            return Conditions(*(a + f * (b - a) for a, b in zip(astuple(c0), astuple(c1))))

        k = self.max_substeps
        done, failures, n_ok = 0.0, 0, 0
        mark = 0
        res: EHLResult | None = None
        while done < 1.0:
            target = marks[mark]
            span = (target - done) / 2**depth if depth else target - done
            f = target if depth == 0 else done + span
            state = self._state()
            res = self._advance(dt * (f - done), at(f))
            if res.converged:
                done, n_ok = f, n_ok + 1
                depth = max(depth - 1, 0)
                if done >= target:
                    mark += 1
                    depth = 0
                continue
            failures += 1
            self._set_state(state)
            depth += 1
            if depth > k or failures > 2 * k + 1:
                break
        if done >= 1.0:
            assert res is not None  # the interval was covered by converged sub-steps
            res.message += f" ({n_ok} sub-steps)"
            return res
        # effort exhausted: finish the interval with a short final attempt so that the
        # march stays on time, and report failure
        with self._max_iter(5):
            last = self._advance(dt * (1.0 - done), c1)
        if last.converged:
            last.message += f" (finished after {failures} failed sub-steps)"
        else:
            last.message = (
                f"no converged sub-step path: gave up after {failures} failed "
                f"sub-steps ({n_ok} converged, reached {done:.3g} of the step; "
                f"at most {k} halvings, max_substeps = {k}): "
                f"{res.message if res is not None else last.message}"
            )
        return last

    def _state(self) -> MarchState:
        """The marching state (restored by :meth:`_set_state`)."""
        return MarchState(
            grid=self._grid,
            q=self._q,
            p=self._p,
            h=self._h,
            h0=self._h0,
            levels=self._levels,
            time=self.time,
            lu=self._lu,
            result=self.result,
        )

    def _set_state(self, snap: MarchState):
        self._grid, self._q, self._p, self._h = snap.grid, snap.q, snap.p, snap.h
        self._h0, self._levels, self.time = snap.h0, snap.levels, snap.time
        self._lu, self.result = snap.lu, snap.result

    def checkpoint(self) -> MarchState:
        """An opaque copy of the marching state (for :meth:`rollback`), e.g. to redo a step
        with sub-steps when a time-error estimate is too large; the state before a step,
        remembering that step's starting conditions (``conditions_before``)."""
        r = self.result
        self.conditions_before = (
            None
            if r is None
            else Conditions(r.load, r.radius, r.entrainment_speed, r.sliding_speed)
        )
        return self._state()

    def rollback(self, checkpoint):
        """Return to a state saved by :meth:`checkpoint`."""
        self._set_state(checkpoint)

    def _advance(self, dt, cond: Conditions) -> EHLResult:
        """One implicit time level: grid, BDF coefficients, predictor, then the
        variant's hooks :meth:`_prepare`, :meth:`_solve`, :meth:`_result`."""
        assert self._grid is not None and self._levels  # started
        hc_prev = self._levels[0].central_film
        grid = self._make_grid(cond, hc_prev)
        same = grid is self._grid
        # variable-step BDF for d(ρh)/dt: (a0 f_n + a1 f_{n-1} + a2 f_{n-2})/dt
        R = cond.radius
        f1 = self._old_on(grid, 0, R)
        lv = self._levels
        bdf2 = self.opts.time_order == 2 and len(lv) == 2 and lv[0].dt is not None
        if bdf2:
            r = dt / lv[0].dt
            a0, a1, a2 = (1 + 2 * r) / (1 + r), -(1 + r), r * r / (1 + r)
        else:
            a0 = 1.0
        sysm, ctx = self._prepare(grid, cond, a0 / dt)
        scale = sysm.lub.density * sysm.h_ref  # ρh → scaled ρ̄H
        if bdf2:
            f2 = self._old_on(grid, 1, R)
            sysm.f_old = bdf_history(f1, f2, a0, a1, a2, scale, f1)
        else:
            sysm.f_old = f1 / scale
        st0 = self._predict(sysm, dt)
        sol = self._solve(sysm, ctx, st0, dt, self._lu if same else None)
        self._lu = sol.lu
        self._commit(sysm, sol.state, dt, self.time + dt)
        hc_new = self._levels[0].central_film
        res = self._result(sysm, ctx, sol, -(hc_new - hc_prev) / dt)
        self.result = res
        return res

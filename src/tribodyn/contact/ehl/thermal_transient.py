"""Transient thermal mixed-EHL line contact marched in time.

The march of :class:`~.transient.TransientEHL` (BDF1/BDF2 for ∂(ρh)/∂t on a grid that
follows the contact, the Newton predictor, sub-steps on failure), through its hooks, with
the temperature of film and solids marched by backward Euler. Each step iterates pressure (Newton, temperatures frozen) ↔ temperature
(energy equation at the new pressure) up to ``ThermalOptions.step_iter`` times, until the
temperature changes by less than ``ThermalOptions.tol``; a step that stops short of that
is flagged (``converged`` False, message). The previous step's temperatures are the
starting point, so one or two iterations usually suffice. Start with :meth:`start_steady`
(the steady thermal solution).
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from ..._validation import InputError
from ...physics.asperity import Roughness
from ...physics.heat_conduction import ThermalBody
from ...physics.materials import BodyPair
from ...physics.thermal_oil import ThermalLubricant
from .grid import Grid
from .newton import State, newton
from .options import Conditions, ContactModel, EHLOptions
from .reynolds import ReynoldsSystem
from .steady import state_from_dimensional
from .thermal import (
    FrozenTemperatureOil,
    ThermalEHLResult,
    ThermalField,
    ThermalOptions,
    apply_factors,
    checked_thermal_bodies,
    solve_thermal_ehl,
    thermal_result,
)
from .transient import MarchState, StepSolution, TransientEHL

__all__ = ["ThermalTransientEHL"]


@dataclass
class _ThermalState:
    """The thermal part of a :class:`~.transient.MarchState`."""

    tf: ThermalField | None
    theta: np.ndarray | None  #: a copy of tf.theta (tf is updated in place)
    p_T: np.ndarray | None
    rho_h_T: np.ndarray | None
    T_nodes: np.ndarray | None


@dataclass
class _Level:
    """What the energy equation of a time level needs of the previous one, on the
    level's thermal grid."""

    tf: ThermalField
    theta_old: np.ndarray  #: temperatures of the previous level
    p_old: np.ndarray  #: its pressure [Pa] (compression heating)
    rho_h_old: np.ndarray  #: its ρh [kg/m²] (film continuity)


@dataclass
class _ThermalSolution(StepSolution):
    thermal_iterations: int = 0
    change: float = float("inf")  #: the last temperature change [K]


class ThermalTransientEHL(TransientEHL):
    """Transient thermal EHL (see module docstring). ``oil`` is a
    :class:`~tribodyn.physics.thermal_oil.ThermalLubricant`, ``thermal_bodies`` the pair of
    :class:`~tribodyn.physics.heat_conduction.ThermalBody`."""

    def __init__(
        self,
        bodies: BodyPair,
        oil: ThermalLubricant,
        thermal_bodies: Sequence[ThermalBody],
        roughness: Roughness | None = None,
        *,
        options: EHLOptions | None = None,
        thermal_options: ThermalOptions | None = None,
        max_substeps: int = 3,
        **option_overrides,
    ):
        super().__init__(
            bodies,
            oil.isothermal(),
            roughness,
            options=options,
            max_substeps=max_substeps,
            **option_overrides,
        )
        self.oil = oil
        self.tbodies = checked_thermal_bodies(thermal_bodies, self.bodies)
        self.topts = thermal_options or ThermalOptions()
        self.tf: ThermalField | None = None
        self._p_T: np.ndarray | None = None  # pressure on the thermal grid (compression heating)
        self._rho_h_T: np.ndarray | None = None  # ρh on the thermal grid (film continuity)
        self._T_nodes: np.ndarray | None = None  # film-mean temperature on the EHL grid [K]

    def start_film(self, *args, **kwargs):
        raise InputError("ThermalTransientEHL starts from start_steady() (a thermal state)")

    # -- hooks of TransientEHL
    def _steady(self, load, radius, entrainment_speed, sliding_speed) -> ThermalEHLResult:
        return solve_thermal_ehl(
            load,
            radius,
            entrainment_speed,
            sliding_speed,
            self.bodies,
            self.oil,
            self.tbodies,
            self.rough,
            options=self.opts,
            thermal_options=self.topts,
        )

    def _steady_on_grid(self, grid: Grid, cond: Conditions, res):
        """The steady thermal solution's temperatures carried to ``grid``, and its
        pressure re-solved there at those temperatures."""
        steady_field = res.temperature_field
        assert isinstance(steady_field, ThermalField)  # set by solve_thermal_ehl
        tf = (
            steady_field.regridded(grid.x, cond.surface_speeds)
            if grid.x.size != res.x.size or abs(grid.x[0] / res.x[0] - 1) > 1e-12
            else steady_field
        )
        self.tf = tf
        Tm = np.interp(grid.x, tf.x, tf.mean_T())
        sysm = self._frozen_system(grid, cond, Tm)
        st = state_from_dimensional(
            sysm, res.x, res.pressure + res.asperity_pressure, res.rigid_approach
        )
        ev = sysm.evaluate(st.Q, st.H0)
        tf.refresh(
            grid.x,
            ev.P * sysm.p_ref,
            ev.H * sysm.h_ref,
            ev.pa * sysm.p_ref,
            cond,
            self.rough,
            self.opts,
        )
        apply_factors(sysm, tf, cond)
        out = newton(sysm, st, self.opts.tol, self.opts.max_iter)
        if out.converged:
            st = out.state
            res = thermal_result(
                sysm, out, self.opts, tf, cond, res.thermal_iterations, True, res.message
            )
        return sysm, st, res

    def _prepare(self, grid: Grid, cond: Conditions, time_coef: float):
        """The system at the previous level's temperatures carried to ``grid`` (frozen
        during each Newton solve), and that level's thermal data."""
        tf_old = self.tf
        assert tf_old is not None and self._p_T is not None and self._rho_h_T is not None
        tf = tf_old if grid is self._grid else tf_old.regridded(grid.x, cond.surface_speeds)
        lvl = _Level(
            tf,
            tf.theta.copy(),
            np.interp(tf.x, tf_old.x, self._p_T),
            np.interp(tf.x, tf_old.x, self._rho_h_T),
        )
        Tm = np.interp(grid.x, tf.x, tf.mean_T())
        return self._frozen_system(grid, cond, Tm, time_coef=time_coef), lvl

    def _solve(self, sysm, ctx: _Level, st: State, dt: float, lu) -> _ThermalSolution:
        """Pressure (Newton, temperatures frozen) ↔ temperature (energy equation) up to
        ``step_iter`` times, until the temperature changes by less than ``tol``."""
        o, t, tf, cond = self.opts, self.topts, ctx.tf, sysm.cond
        ev = sysm.evaluate(st.Q, st.H0)
        tf.refresh(
            sysm.g.x,
            ev.P * sysm.p_ref,
            ev.H * sysm.h_ref,
            ev.pa * sysm.p_ref,
            cond,
            self.rough,
            o,
        )
        change, k = float("inf"), 0
        out = None
        for k in range(1, t.step_iter + 1):
            apply_factors(sysm, tf, cond)
            out = newton(sysm, st, o.tol, o.max_iter, lu=lu)
            lu = out.lu if out.converged else None
            if not out.converged:
                break
            st = out.state
            change = tf.update(
                sysm.g.x,
                st.P * sysm.p_ref,
                st.H * sysm.h_ref,
                (st.Q - st.P) * sysm.p_ref,
                cond,
                self.rough,
                o,
                dt=dt,
                theta_old=ctx.theta_old,
                p_old=ctx.p_old,
                rho_h_old=ctx.rho_h_old,
                refresh=k < t.step_iter,
            )
            if not np.isfinite(change):
                break
            if k > 1 and change < t.tol:
                break
        assert out is not None  # at least one thermal iteration ran
        self.tf = tf
        # a failed Newton solve keeps the last solved pressure
        state = out.state if out.converged else st
        return _ThermalSolution(out, state, lu, thermal_iterations=k, change=change)

    def _result(self, sysm, ctx: _Level, sol, squeeze_velocity: float) -> ThermalEHLResult:
        assert isinstance(sol, _ThermalSolution)
        ok_t = bool(np.isfinite(sol.change))
        msg = sol.out.message
        if not ok_t:
            msg = "energy equation gave a non-finite temperature; " + msg
        elif self.topts.step_iter > 1:
            msg += (
                f"; last temperature change {sol.change:.2g} K after "
                f"{sol.thermal_iterations} thermal iterations"
            )
        return thermal_result(
            sysm,
            sol.out,
            self.opts,
            ctx.tf,
            sysm.cond,
            sol.thermal_iterations,
            bool(sol.out.converged and ok_t),
            msg,
            time=self.time,
            squeeze_velocity=squeeze_velocity,
        )

    # -- internals
    def _frozen_system(self, grid, cond, T_nodes, time_coef=0.0):
        oil = FrozenTemperatureOil(self.oil, T_nodes)
        self._T_nodes = T_nodes
        return ReynoldsSystem(
            grid, cond, ContactModel(self.bodies, oil, self.rough), time_coef=time_coef
        )

    def _commit(self, sysm, st, dt, time):
        super()._commit(sysm, st, dt, time)
        tf = self.tf
        assert tf is not None and self._p is not None and self._h is not None
        self._p_T = np.interp(tf.x, sysm.g.x, self._p)
        self._rho_h_T = tf.rho_h(sysm.g.x, self._p, self._h)

    def _state(self) -> MarchState:
        snap = super()._state()
        tf = self.tf
        snap.extra = _ThermalState(
            tf, None if tf is None else tf.theta.copy(), self._p_T, self._rho_h_T, self._T_nodes
        )
        return snap

    def _set_state(self, snap: MarchState):
        super()._set_state(snap)
        th = snap.extra
        assert isinstance(th, _ThermalState)
        self.tf, self._p_T, self._rho_h_T, self._T_nodes = th.tf, th.p_T, th.rho_h_T, th.T_nodes
        if self.tf is not None:
            assert th.theta is not None
            self.tf.theta = th.theta.copy()

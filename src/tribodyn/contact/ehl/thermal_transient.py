"""Transient thermal mixed-EHL line contact marched in time.

As :class:`~.transient.TransientEHL` (BDF1/BDF2 for ∂(ρh)/∂t on a grid that follows the
contact, sub-steps on failure), with the temperature of film and solids marched by
backward Euler. Each step iterates pressure (Newton, temperatures frozen) ↔ temperature
(energy equation at the new pressure) up to ``ThermalOptions.step_iter`` times, until the
temperature changes by less than ``ThermalOptions.tol``; a step that stops short of that
is flagged (``converged`` False, message). The previous step's temperatures are the
starting point, so one or two iterations usually suffice. Start with :meth:`start_steady`
(the steady thermal solution).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from ...physics.asperity import Roughness
from ...physics.heat_conduction import ThermalBody
from ...physics.materials import BodyPair
from ...physics.thermal_oil import ThermalLubricant
from .newton import newton
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
from .transient import EVENT_NODES_FROM_START, TransientEHL

__all__ = ["ThermalTransientEHL"]


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

    def start_steady(
        self, load, radius, entrainment_speed, sliding_speed, time=0.0
    ) -> ThermalEHLResult:
        res = solve_thermal_ehl(
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
        cond = Conditions.checked(load, radius, entrainment_speed, sliding_speed)
        self._grid = None
        self._n_event = res.x.size if self.opts.n is None and EVENT_NODES_FROM_START else None
        grid = self._make_grid(cond, None)
        u1 = entrainment_speed + 0.5 * sliding_speed
        speeds = (u1, u1 - sliding_speed)
        steady_field = res.temperature_field
        assert isinstance(steady_field, ThermalField)  # set by solve_thermal_ehl
        tf = (
            steady_field.regridded(grid.x, speeds)
            if grid.x.size != res.x.size or abs(grid.x[0] / res.x[0] - 1) > 1e-12
            else steady_field
        )
        self.tf = tf
        Tm = np.interp(grid.x, tf.x, tf.mean_T())
        sysm = self._system(grid, cond, Tm)
        st = state_from_dimensional(
            sysm, res.x, res.pressure + res.asperity_pressure, res.rigid_approach
        )
        # the pressure of the transient's own grid at the steady temperatures, so that
        # marching at constant conditions stays there (the grids differ)
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
        self._grid, self._lu, self._hist, self._hc_hist = grid, None, [], ()
        self._commit(sysm, st, None, time)
        assert self._p is not None and self._h is not None  # set by _commit
        self._p_T = np.interp(tf.x, grid.x, self._p)
        self._rho_h_T = tf.rho_h(grid.x, self._p, self._h)
        res.time = time
        self.result = res
        return res

    def _system(self, grid, cond, T_nodes, time_coef=0.0):
        oil = FrozenTemperatureOil(self.oil, T_nodes)
        self._T_nodes = T_nodes
        return ReynoldsSystem(
            grid, cond, ContactModel(self.bodies, oil, self.rough), time_coef=time_coef
        )

    def _commit(self, sysm, st, dt, time):
        super()._commit(sysm, st, dt, time)
        x, _, dt_, R = self._hist[0]
        self._hist[0] = (x, sysm.lub.density_at(self._p) * self._h, dt_, R)

    def _state(self):
        tf = self.tf
        return (
            super()._state(),
            (tf, None if tf is None else tf.theta.copy(), self._p_T, self._rho_h_T, self._T_nodes),
        )

    def _set_state(self, snap):
        base, thermal = snap
        super()._set_state(base)
        self.tf, theta, self._p_T, self._rho_h_T, self._T_nodes = thermal
        if self.tf is not None:
            self.tf.theta = theta.copy()

    def _advance(self, dt, cond: Conditions) -> ThermalEHLResult:
        o, t = self.opts, self.topts
        prev_grid, tf_old = self._grid, self.tf
        assert prev_grid is not None and tf_old is not None  # started
        assert self._h is not None and self._q is not None
        assert self._p_T is not None and self._rho_h_T is not None
        hc_prev = float(np.interp(0.0, prev_grid.x, self._h))
        grid = self._make_grid(cond, hc_prev)
        same = grid is prev_grid
        R = cond.radius
        f1 = self._old_on(grid, 0, R)
        if o.time_order == 2 and len(self._hist) == 2 and self._hist[0][2] is not None:
            r = dt / self._hist[0][2]
            a0, a1, a2 = (1 + 2 * r) / (1 + r), -(1 + r), r * r / (1 + r)
            f_eff = -(a1 * f1 + a2 * self._old_on(grid, 1, R)) / a0
        else:
            a0, f_eff = 1.0, f1
        u1 = cond.entrainment_speed + 0.5 * cond.sliding_speed
        speeds = (u1, u1 - cond.sliding_speed)
        tf = tf_old if same else tf_old.regridded(grid.x, speeds)
        theta_old = tf.theta.copy()
        p_old = np.interp(tf.x, tf_old.x, self._p_T)
        rho_h_old = np.interp(tf.x, tf_old.x, self._rho_h_T)
        Tm = np.interp(grid.x, tf.x, tf.mean_T())
        sysm = self._system(grid, cond, Tm, time_coef=a0 / dt)
        sysm.f_old = f_eff / (sysm.lub.density * sysm.h_ref)
        st = state_from_dimensional(sysm, prev_grid.x, self._q, self._h0)
        ev = sysm.evaluate(st.Q, st.H0)
        tf.refresh(
            grid.x, ev.P * sysm.p_ref, ev.H * sysm.h_ref, ev.pa * sysm.p_ref, cond, self.rough, o
        )
        lu = self._lu if same else None
        ok_t, change, k = False, float("inf"), 0
        out = None
        for k in range(1, t.step_iter + 1):
            apply_factors(sysm, tf, cond)
            out = newton(sysm, st, o.tol, o.max_iter, lu=lu)
            lu = out.lu if out.converged else None
            if not out.converged:
                break
            st = out.state
            p, h = st.P * sysm.p_ref, st.H * sysm.h_ref
            change = tf.update(
                grid.x,
                p,
                h,
                (st.Q - st.P) * sysm.p_ref,
                cond,
                self.rough,
                o,
                dt=dt,
                theta_old=theta_old,
                p_old=p_old,
                rho_h_old=rho_h_old,
                refresh=k < t.step_iter,
            )
            if not np.isfinite(change):
                break
            if k > 1 and change < t.tol:
                break
        assert out is not None  # at least one thermal iteration ran
        ok_t = bool(np.isfinite(change))
        self._lu = lu
        self.tf = tf
        self._commit(sysm, out.state if out.converged else st, dt, self.time + dt)
        assert self._p is not None and self._h is not None  # set by _commit
        self._p_T = np.interp(tf.x, grid.x, self._p)
        self._rho_h_T = tf.rho_h(grid.x, self._p, self._h)
        hc_new = float(np.interp(0.0, grid.x, self._h))
        msg = out.message
        if not ok_t:
            msg = "energy equation gave a non-finite temperature; " + msg
        elif t.step_iter > 1:
            msg += f"; last temperature change {change:.2g} K after {k} thermal iterations"
        ok = bool(out.converged and ok_t)
        res = thermal_result(
            sysm,
            out,
            o,
            tf,
            cond,
            k,
            ok,
            msg,
            time=self.time,
            squeeze_velocity=-(hc_new - hc_prev) / dt,
        )
        self.result = res
        return res

"""The temperature field of the thermal EHL (:mod:`.thermal`): its settings
(:class:`ThermalOptions`), the oil at a frozen film-mean temperature, the Couette shear
with the Eyring law at the local temperature, and :class:`ThermalField` (film + both
solids, :mod:`.energy`) with the generalized Reynolds factors it applies to the
pressure solve (Yang & Wen 1990; :mod:`tribodyn.physics.film_thermal`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..._validation import check_bool
from ...physics import limits as L
from ...physics.asperity import Roughness
from ...physics.film_thermal import FilmFlow, film_flow
from ...physics.friction import boundary_shear_stress
from ...physics.heat_conduction import depth_grid
from ...physics.thermal_oil import ThermalLubricant
from .energy import EnergyInputs, chain_size, solid_chain, solve_energy
from .options import Conditions, EHLOptions
from .reynolds import ReynoldsSystem


@dataclass(frozen=True)
class ThermalOptions:
    """Settings of the thermal solvers.

    x_nodes : thermal grid nodes along x (at most the EHL grid's);
    film_nodes : nodes across the film (odd, ≥ 3; first-order upwind across the film, so
        the error of h_c falls as 1/m: 7 nodes leave h_c within 0.7 % on the thermal cam
        cycle but 1.5 % / 3 % too thick at L = βμ₀u_e²/k = 0.4 / 1; 15 nodes meet 1 % to
        L ≈ 1 — docs/convergence.md); solid_nodes : depth nodes per solid;
    depth : solid depth in units of the domain length; tol : temperature change [K]
    between fixed-point iterations at convergence (plus 0.2 % of the largest rise); max_iter : fixed-point iterations
    (steady); step_iter : pressure ↔ temperature iterations per transient step (1: the
    pressure of a step is solved with the temperatures of the previous step, then the
    temperatures with the new pressure — staggered; more iterations stop early at
    ``tol``); relaxation : under-relaxation of the
    temperature (steady: of the first step, then Aitken's dynamic relaxation);
    shear_heating, compression_heating : switch the heat sources (False:
    isothermal-limit checks).
    """

    x_nodes: int = 96
    film_nodes: int = 7
    solid_nodes: int = 12
    depth: float = 1.0
    tol: float = 0.05
    max_iter: int = 60
    step_iter: int = 2
    relaxation: float = 0.7
    shear_heating: bool = True
    compression_heating: bool = True

    def __post_init__(self):
        # the case file's [numerics] thermal_* keys are checked here
        L.check_fields(self, _LIMITS)
        check_bool("shear_heating", self.shear_heating)
        check_bool("compression_heating", self.compression_heating)


#: Range of every numeric field of ThermalOptions (physics.limits).
_LIMITS = {
    "x_nodes": L.THERMAL_X_NODES,
    "film_nodes": L.THERMAL_FILM_NODES,
    "solid_nodes": L.THERMAL_SOLID_NODES,
    "depth": L.THERMAL_DEPTH,
    "tol": L.THERMAL_TOL,
    "max_iter": L.THERMAL_MAX_ITER,
    "step_iter": L.THERMAL_STEP_ITER,
    "relaxation": L.THERMAL_RELAXATION,
}


class FrozenTemperatureOil:
    """The lubricant as the Reynolds system reads it, at frozen node temperatures T [K]
    (the interface of :class:`~tribodyn.Lubricant` used by the EHL solvers)."""

    def __init__(self, oil: ThermalLubricant, T):
        self.oil = oil
        self.T = np.asarray(T, dtype=float)
        iso = oil.isothermal()
        self.viscosity = iso.viscosity  # μ₀ at Tᵢ: scales of the system
        self.pressure_viscosity = iso.pressure_viscosity
        self.density = iso.density
        self._lnmu0 = math.log(iso.viscosity)
        self.eyring_stress = iso.eyring_stress
        self.limiting_shear_coefficient = iso.limiting_shear_coefficient
        self.limiting_shear_stress = iso.limiting_shear_stress

    def density_at(self, p):
        return self.oil.density_at(p, self.T)

    def ddensity_dp(self, p):
        return self.oil.ddensity_dp(p, self.T)

    def log_viscosity_ratio(self, p):
        return self.oil.log_viscosity(p, self.T) - self._lnmu0

    def dlog_viscosity_dp(self, p):
        return self.oil.dlog_viscosity_dp(p, self.T)

    def viscosity_at(self, p):
        return self.oil.viscosity_at(p, self.T)


def couette_stress(
    pressure,
    film,
    sliding_speed,
    oil: ThermalLubricant,
    T_mean,
    fluidity,
    f_lim,
    model: str,
    limiting: bool,
):
    """Couette shear stress magnitude [Pa]: Eyring (or Newtonian) at the film-mean
    temperature with the across-film fluidity F₀ = ``fluidity``·h/μ(p, T̄), capped at
    (τ_L0 + Λp)·f_lim (f_lim: temperature factor of the hottest layer)."""
    p = np.asarray(pressure, dtype=float)
    F0 = fluidity * np.maximum(film, 1e-10) / oil.viscosity_at(p, T_mean)
    newt = abs(sliding_speed) / F0
    if model == "eyring":
        te = oil.eyring_stress_at(T_mean)
        tau = te * np.arcsinh(newt / te)
    else:
        tau = newt
    if limiting:
        tau = np.minimum(
            tau,
            (oil.limiting_shear_stress + oil.limiting_shear_coefficient * np.maximum(p, 0.0))
            * f_lim,
        )
    return tau


class ThermalField:
    """Temperature rise θ on the thermal grid (film + both solids) and the film
    quantities of the last update (see :mod:`.energy` for the chain layout)."""

    def __init__(self, x_ehl, oil: ThermalLubricant, tbodies, topts: ThermalOptions, speeds):
        n = int(min(topts.x_nodes, x_ehl.size))
        self.x = np.linspace(x_ehl[0], x_ehl[-1], n)
        self.dx = self.x[1] - self.x[0]
        self.oil, self.topts, self.tbodies = oil, topts, tbodies
        self.Ti = float(oil.inlet_temperature)
        self.m = int(topts.film_nodes) | 1  # odd
        L = self.x[-1] - self.x[0]
        u_fast = max(abs(speeds[0]), abs(speeds[1]), 0.1)
        self.grids = []
        for tb in tbodies:
            kap = tb.substrate.diffusivity
            delta = math.sqrt(kap * L / max(u_fast, 4.0 * kap / L))
            self.grids.append(
                depth_grid(tb, topts.depth * L, min(delta / 8.0, L / 40.0), topts.solid_nodes)
            )
        self.n1 = self.grids[0].s.size - 2
        self.Nz = chain_size(self.m, *self.grids)
        self.theta = np.zeros((n, self.Nz))
        self.w = np.full(self.m, 1.0 / (self.m - 1))
        self.w[0] = self.w[-1] = 0.5 / (self.m - 1)
        self.flow: FilmFlow | None = None

    # -- views
    def film_T(self):
        return self.Ti + self.theta[:, self.n1 : self.n1 + self.m]

    def mean_T(self):
        return self.film_T() @ self.w

    # -- physics on the thermal grid
    def fields(
        self,
        x,
        p,
        h,
        pa,
        cond: Conditions,
        rough: Roughness | None,
        opts: EHLOptions,
        p_old=None,
        dt=None,
    ):
        """Film flow and the energy-equation inputs for pressure p, film h, asperity
        pressure pa on the EHL grid x."""
        oil, t = self.oil, self.topts
        xs = self.x
        # averages over the thermal cells: robust to a pressure spike that moves by a
        # fraction of a cell between iterations
        pt, ht, pat = (self.cell_average(x, v) for v in (p, h, pa))
        faces = np.clip(np.r_[xs - 0.5 * self.dx, xs[-1] + 0.5 * self.dx], x[0], x[-1])
        pf = np.interp(faces, x, p)
        px = np.diff(pf) / np.diff(faces)
        T = self.film_T()
        Tm = T @ self.w
        P = pt[:, None]
        eta, rho = oil.viscosity_at(P, T), oil.density_at(P, T)
        u1, u2 = cond.surface_speeds
        ff = film_flow(
            np.maximum(ht, 1e-10),
            px,
            u1,
            u2,
            eta,
            rho,
            oil.eyring_stress_at(Tm),
            oil.limiting_shear_stress_at(P, T),
            eta_ref=oil.viscosity_at(pt, Tm),
            rho_ref=oil.density_at(pt, Tm),
            eyring=opts.viscous_model == "eyring",
            limiting=opts.limiting_shear,
        )
        self.flow = ff
        if not t.shear_heating:
            phi, q = np.zeros_like(eta), np.zeros_like(pt)
        else:
            phi = ff.dissipation
            q = np.zeros_like(pt)
            if rough is not None:
                tb = boundary_shear_stress(
                    pat,
                    rough.contact_area_fraction(ht),
                    opts.boundary_shear_coefficient,
                    opts.boundary_shear_strength,
                )
                q = tb * abs(cond.sliding_speed)
        comp = np.zeros_like(eta)
        if t.compression_heating:
            dpdt = 0.0 if p_old is None or dt is None else ((pt - p_old) / dt)[:, None]
            comp = oil.expansivity(T) * (ff.u * px[:, None] + dpdt)
        h_heat = ht * self._fill(pt, ff, cond)
        return EnergyInputs(
            self.dx,
            np.maximum(h_heat, 1e-10),
            ff.u,
            rho,
            oil.volumetric_heat_capacity(P, T),
            oil.conductivity(P, T),
            phi,
            comp,
            self.Ti,
            (u1, u2),
            tuple(self.grids),
            q,
            dt=dt,
        )

    def cell_average(self, x, v):
        """Average of v(x) (on the EHL grid x) over each thermal cell."""
        faces = np.clip(np.r_[self.x - 0.5 * self.dx, self.x[-1] + 0.5 * self.dx], x[0], x[-1])
        cum = np.r_[0.0, np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(x))]
        return np.diff(np.interp(faces, x, cum)) / np.diff(faces)

    @staticmethod
    def _fill(p, ff, cond):
        """Share of the gap filled with oil: 1, except downstream of the outlet meniscus
        where the flow of the meniscus is carried as streamers (Reynolds cavitation)."""
        fill = np.ones_like(p)
        ue = cond.entrainment_speed
        if ue == 0.0 or not np.any(p > 0):
            return fill
        ipk = int(np.argmax(p))
        idx = np.arange(ipk, p.size) if ue > 0 else np.arange(ipk, -1, -1)
        pos = np.flatnonzero(p[idx] <= 0.0)
        if pos.size:
            beyond = idx[pos[0] :]
            q_cav = ff.D[beyond[0]]
            with np.errstate(divide="ignore", invalid="ignore"):
                fill[beyond] = np.clip(q_cav / ff.D[beyond], 0.05, 1.0)
        return fill

    def factors(self, x_ehl, cond: Conditions):
        """(flow factor, Couette factor, T̄, fluidity ratio, f_lim) interpolated on the
        EHL grid from the last :meth:`fields`."""
        ff = self.flow
        assert ff is not None, "ThermalField.fields() must run before factors()"
        us, ue = cond.sliding_speed, cond.entrainment_speed
        ue_eff = math.copysign(max(abs(ue), 0.05 * abs(us), 1e-3), ue if ue != 0 else 1.0)
        cf = 1.0 + (ff.D - ff.D_ref) / (ff.rho_e * np.maximum(self._h, 1e-10) * ue_eff)
        cf = np.clip(cf, 0.5, 1.5)
        T = self.film_T()
        Tm = T @ self.w
        fl = ff.F0 * self._eta_m / np.maximum(self._h, 1e-10)
        flim = np.maximum(
            0.1, 1.0 - self.oil.limiting_shear_temperature_coefficient * (T.max(axis=1) - self.Ti)
        )
        on = lambda v: np.interp(x_ehl, self.x, v)  # noqa: E731
        return on(ff.flow_factor), on(cf), on(Tm), on(fl), on(flim)

    def update(
        self,
        x,
        p,
        h,
        pa,
        cond,
        rough,
        opts,
        *,
        dt=None,
        theta_old=None,
        p_old=None,
        rho_h_old=None,
        relax=1.0,
        refresh=True,
    ):
        """One energy solve at (p, h); θ ← θ + relax (θ_new − θ). Returns max |Δθ| [K].
        ``refresh``: recompute the film quantities (factors) at the new θ."""
        e = self.fields(x, p, h, pa, cond, rough, opts, p_old=p_old, dt=dt)
        e.theta_old, e.rho_h_old, e.theta_lag = theta_old, rho_h_old, self.theta
        new = solve_energy(e)
        if not np.all(np.isfinite(new)):
            return float("inf")
        change = float(np.max(np.abs(new - self.theta)))
        self.theta = self.theta + relax * (new - self.theta)
        if refresh:  # film quantities at the relaxed temperature (the factors)
            self.refresh(x, p, h, pa, cond, rough, opts)
        return change

    def refresh(self, x, p, h, pa, cond, rough, opts):
        """Film quantities (and so the factors) at the current θ, without a solve."""
        self.fields(x, p, h, pa, cond, rough, opts)
        self._h = self.cell_average(x, h)
        self._eta_m = self.oil.viscosity_at(self.cell_average(x, p), self.mean_T())

    def body_theta(self, body: int) -> np.ndarray:
        """θ of one solid (n_T, ns) with column 0 the surface."""
        return self.theta[:, solid_chain(body, self.n1, self.m, self.grids[body].s.size - 1)]

    def regridded(self, x_ehl, speeds) -> ThermalField:
        """A field on a new EHL grid with θ interpolated (film in x, solids in x and
        depth; zero outside the old grid)."""
        from scipy.interpolate import RegularGridInterpolator

        new = ThermalField(x_ehl, self.oil, self.tbodies, self.topts, speeds)
        if new.m != self.m:
            return new
        th = np.zeros_like(new.theta)
        xn = new.x
        for j in range(self.m):
            th[:, new.n1 + j] = np.interp(
                xn, self.x, self.theta[:, self.n1 + j], left=0.0, right=0.0
            )
        for body in (0, 1):
            old = self.body_theta(body)
            so, sn = self.grids[body].s[:-1], new.grids[body].s[:-1]
            f = RegularGridInterpolator((self.x, so), old, bounds_error=False, fill_value=0.0)
            X, S = np.meshgrid(xn, sn, indexing="ij")
            vals = f(np.stack([X, np.minimum(S, so[-1])], axis=-1))
            idx = solid_chain(body, new.n1, new.m, sn.size)
            surf = th[:, idx[0]].copy()
            th[:, idx] = vals
            th[:, idx[0]] = surf  # the surface node is the film's wall
        new.theta = th
        return new

    def rho_h(self, x_ehl, p, h):
        """ρ̄h on the thermal grid [kg/m²] (for ∂(ρh)/∂t of the film continuity)."""
        pt, ht = np.interp(self.x, x_ehl, p), np.interp(self.x, x_ehl, h)
        return self.oil.density_at(pt, self.mean_T()) * ht

    def heat(self):
        """Heat generated per unit length [W/m]: film dissipation + boundary friction."""
        return (
            0.0
            if self.flow is None
            else float(np.sum((self.flow.dissipation * self._h[:, None]) @ self.w) * self.dx)
        )


def apply_factors(sysm: ReynoldsSystem, tf: ThermalField, cond: Conditions):
    """Set the frozen temperatures and generalized-Reynolds factors on ``sysm``."""
    fp, fc, Tm, _, _ = tf.factors(sysm.g.x, cond)
    lub = sysm.lub
    assert isinstance(lub, FrozenTemperatureOil)  # set up by the thermal solvers
    lub.T = Tm
    sysm.flow_factor, sysm.couette_factor = fp, fc

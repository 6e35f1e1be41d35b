"""Thermal mixed-EHL line contact (steady): generalized Reynolds ↔ energy equation.

The pressure is solved by the isothermal Newton machinery (:mod:`.reynolds`, :mod:`.newton`)
with the temperature frozen: the lubricant seen by :class:`~.reynolds.ReynoldsSystem` is
:class:`FrozenTemperatureOil`, ρ(p, T̄ᵢ) and μ(p, T̄ᵢ) at the film-mean temperature T̄ᵢ of
each node, and the per-node factors C/C(T̄) and D/D(T̄) of the generalized Reynolds
equation (Yang & Wen 1990; :mod:`tribodyn.physics.film_thermal`) carry the variation of
viscosity and density across the film. The temperature (film + both solids,
:mod:`.energy`) is then solved for the new pressure, under-relaxed (Aitken's dynamic
relaxation factor from the last two residuals), and the two are iterated to a fixed
point: converged when the temperature changes by less than ``ThermalOptions.tol`` [K]
and the central film by less than 1e-5 (relative).

Shear: Couette stress with the Eyring law at the local temperature (τ_E ∝ T), capped by
the limiting shear stress of the hottest layer; heat from viscous dissipation (Couette +
Poiseuille), compression/expansion, and the boundary friction of the asperities (at the
surfaces). The isothermal solver is untouched: with zero heating, or very large
conductivities, the thermal solution is the isothermal one at the inlet temperature.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import cast

import numpy as np

from ..._validation import InputError, check_bool, check_int, check_positive, check_range
from ...physics.asperity import Roughness
from ...physics.film_thermal import FilmFlow, film_flow
from ...physics.friction import boundary_shear_stress
from ...physics.heat_conduction import ThermalBody, depth_grid
from ...physics.lubricant import Lubricant
from ...physics.materials import BodyPair
from ...physics.thermal_oil import ThermalLubricant
from .energy import EnergyInputs, chain_size, solve_energy
from .grid import Grid, layout
from .newton import newton
from .options import Conditions, ContactModel, EHLOptions, EHLResult, with_overrides
from .postprocess import postprocess
from .reynolds import ReynoldsSystem
from .steady import solve_ehl, state_from_dimensional

__all__ = [
    "ThermalOptions",
    "ThermalEHLResult",
    "FrozenTemperatureOil",
    "ThermalField",
    "solve_thermal_ehl",
    "couette_stress",
]


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
        for name, lo, hi in (
            ("x_nodes", 16, 4096),
            ("film_nodes", 3, 41),
            ("solid_nodes", 6, 200),
            ("max_iter", 1, 10000),
            ("step_iter", 1, 100),
        ):
            v = check_int(name, getattr(self, name))
            if not lo <= v <= hi:
                raise InputError(f"{name} must be in [{lo}, {hi}] (got {v})")
        check_bool("shear_heating", self.shear_heating)
        check_bool("compression_heating", self.compression_heating)
        check_range("depth", self.depth, 0.05, 20.0)
        check_positive("tol", self.tol, "K")
        check_range("relaxation", self.relaxation, 0.0, 1.0, lo_open=True)


@dataclass
class ThermalEHLResult(EHLResult):
    """:class:`EHLResult` with the temperatures of the thermal solution (K)."""

    inlet_temperature: float = float("nan")  #: Tᵢ [K]
    x_thermal: np.ndarray | None = field(default=None, repr=False)  #: thermal grid [m]
    film_temperature: np.ndarray | None = field(default=None, repr=False)  #: (n_T, m) [K]
    #: (2, n_T) [K], body 1 and 2
    surface_temperature: np.ndarray | None = field(default=None, repr=False)
    mid_film_temperature: np.ndarray | None = field(default=None, repr=False)  #: (n_T,) [K]
    max_temperature: float = float("nan")  #: max over film and surfaces [K]
    #: the solver's temperature field (a transient starts from it)
    temperature_field: object = field(default=None, repr=False, compare=False)
    central_mid_film_temperature: float = float("nan")  #: at x = 0 [K]
    max_surface_temperature: tuple = (float("nan"), float("nan"))  #: bodies 1, 2 [K]
    thermal_iterations: int = 0
    heat_generated: float = 0.0  #: viscous + boundary heat [W/m]


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
    @property
    def film_theta(self):
        return self.theta[:, self.n1 : self.n1 + self.m]

    def film_T(self, theta=None):
        th = self.theta if theta is None else theta
        return self.Ti + th[:, self.n1 : self.n1 + self.m]

    def mean_T(self, theta=None):
        return self.film_T(theta) @ self.w

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
        theta=None,
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
        T = self.film_T(theta)
        Tm = T @ self.w
        P = pt[:, None]
        eta, rho = oil.viscosity_at(P, T), oil.density_at(P, T)
        u1 = cond.entrainment_speed + 0.5 * cond.sliding_speed
        u2 = cond.entrainment_speed - 0.5 * cond.sliding_speed
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
        ns = self.grids[body].s.size - 1
        f0 = self.n1
        idx = [f0 - k for k in range(ns)] if body == 0 else [f0 + self.m - 1 + k for k in range(ns)]
        return self.theta[:, idx]

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
            th[:, new.n1 + j] = np.interp(xn, self.x, self.film_theta[:, j], left=0.0, right=0.0)
        for body in (0, 1):
            old = self.body_theta(body)
            so, sn = self.grids[body].s[:-1], new.grids[body].s[:-1]
            f = RegularGridInterpolator((self.x, so), old, bounds_error=False, fill_value=0.0)
            X, S = np.meshgrid(xn, sn, indexing="ij")
            vals = f(np.stack([X, np.minimum(S, so[-1])], axis=-1))
            f0 = new.n1
            idx = (
                [f0 - k for k in range(sn.size)]
                if body == 0
                else [f0 + new.m - 1 + k for k in range(sn.size)]
            )
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


def thermal_result(
    sysm, out, opts, tf: ThermalField, cond, iterations, ok, msg, time=0.0, squeeze_velocity=0.0
) -> ThermalEHLResult:
    """Post-process a thermal solution: the EHL result with the thermal Couette stress,
    and the temperatures."""
    out.converged = bool(out.converged and ok)
    out.message = msg
    r = postprocess(sysm, out, opts, time=time, squeeze_velocity=squeeze_velocity)
    _, _, Tm, fl, flim = tf.factors(sysm.g.x, cond)
    tau = couette_stress(
        r.pressure,
        r.film,
        cond.sliding_speed,
        tf.oil,
        Tm,
        fl,
        flim,
        opts.viscous_model,
        opts.limiting_shear,
    )
    r.shear_stress = np.sign(cond.sliding_speed) * tau
    r.viscous_friction = float(np.sum(tau) * (r.x[1] - r.x[0]))
    d = {k: getattr(r, k) for k in r.__dataclass_fields__}
    T = tf.film_T()
    surf = np.vstack([T[:, 0], T[:, -1]])
    mid = T[:, tf.m // 2]
    qb = r.boundary_friction * abs(cond.sliding_speed)
    res = ThermalEHLResult(
        **d,
        inlet_temperature=tf.Ti,
        x_thermal=tf.x.copy(),
        film_temperature=T.copy(),
        surface_temperature=surf,
        mid_film_temperature=mid,
        max_temperature=float(T.max()),
        central_mid_film_temperature=float(np.interp(0.0, tf.x, mid)),
        max_surface_temperature=(float(surf[0].max()), float(surf[1].max())),
        thermal_iterations=int(iterations),
        heat_generated=tf.heat() + qb,
    )
    return res


def checked_thermal_bodies(tbodies, bodies):
    tb = tuple(tbodies)
    if len(tb) != 2 or not all(isinstance(b, ThermalBody) for b in tb):
        raise InputError("thermal_bodies must be a pair (ThermalBody, ThermalBody)")
    for t, b in zip(tb, bodies):
        if (t.coating is None) != (b.coating is None):
            raise InputError("thermal_bodies must have a coating where the elastic bodies do")
        if b.coating is not None and abs(t.thickness / b.coating.thickness - 1.0) > 1e-9:
            raise InputError("thermal and elastic coating thicknesses differ")
    return tb


def solve_thermal_ehl(
    load: float,
    radius: float,
    entrainment_speed: float,
    sliding_speed: float,
    bodies: BodyPair,
    oil: ThermalLubricant,
    thermal_bodies: Sequence[ThermalBody],
    roughness: Roughness | None = None,
    *,
    options: EHLOptions | None = None,
    thermal_options: ThermalOptions | None = None,
    **option_overrides,
) -> ThermalEHLResult:
    """Steady thermal mixed-EHL line contact (arguments as :func:`~tribodyn.solve_ehl`).

    oil : :class:`~tribodyn.physics.thermal_oil.ThermalLubricant` (inlet temperature =
        temperature of the solids far from the contact);
    thermal_bodies : (ThermalBody, ThermalBody) of the two bodies (coating where the
        elastic bodies have one, same thickness).
    """
    if not isinstance(oil, ThermalLubricant):
        raise InputError(f"oil must be a ThermalLubricant (got {type(oil).__name__})")
    opts = options or EHLOptions()
    if option_overrides:
        opts = with_overrides(opts, option_overrides)
    topts = thermal_options or ThermalOptions()
    cond = Conditions.checked(load, radius, entrainment_speed, sliding_speed)
    iso_model = ContactModel.checked(bodies, oil.isothermal(), roughness)
    tb = checked_thermal_bodies(thermal_bodies, iso_model.bodies)
    iso = solve_ehl(
        load,
        radius,
        entrainment_speed,
        sliding_speed,
        iso_model.bodies,
        oil.isothermal(),
        roughness,
        options=opts,
    )
    lay = replace(layout(cond, iso_model, opts), n=iso.x.size)
    direction = 1 if cond.entrainment_speed >= 0 else -1
    grid = Grid(iso_model.bodies, lay, direction, opts.elastic)
    standin = FrozenTemperatureOil(oil, np.full(grid.n, oil.inlet_temperature))
    # the stand-in has the interface of Lubricant that the Reynolds system reads
    model = ContactModel(iso_model.bodies, cast(Lubricant, standin), roughness)
    sysm = ReynoldsSystem(grid, cond, model)
    st = state_from_dimensional(
        sysm, iso.x, iso.pressure + iso.asperity_pressure, iso.rigid_approach
    )
    ev = sysm.evaluate(st.Q, st.H0)
    st.P, st.H = ev.P, ev.H
    u1 = cond.entrainment_speed + 0.5 * cond.sliding_speed
    tf = ThermalField(grid.x, oil, tb, topts, (u1, u1 - cond.sliding_speed))
    out, ok, msg, it = None, False, "", 0
    hc_prev = iso.central_film
    relax = topts.relaxation
    last_change = float("inf")
    r_prev: np.ndarray | None = None
    lu = None
    for it in range(1, topts.max_iter + 1):
        p, h = st.P * sysm.p_ref, st.H * sysm.h_ref
        pa = (st.Q - st.P) * sysm.p_ref
        theta_prev = tf.theta.copy()
        change = tf.update(grid.x, p, h, pa, cond, roughness, opts, relax=1.0, refresh=False)
        if not math.isfinite(change):
            msg = "energy equation gave a non-finite temperature"
            break
        # Aitken's dynamic relaxation (Irons & Tuck 1969; Küttler & Wall 2008): with the
        # residuals r_k = θ_new − θ_k, ω_k = −ω_{k−1} r_{k−1}·(r_k − r_{k−1}) / |r_k −
        # r_{k−1}|², in [0.05, 1]. A fixed rule on max|r| cannot tell a slow contraction
        # under strong relaxation from a stall, and ratchets ω down to its floor.
        r = tf.theta - theta_prev
        if r_prev is not None:
            dr = r - r_prev
            den = float(np.sum(dr * dr))
            if den > 0.0:
                relax = min(1.0, max(0.05, -relax * float(np.sum(r_prev * dr)) / den))
        r_prev = r
        tf.theta = theta_prev + relax * r
        tf.refresh(grid.x, p, h, pa, cond, roughness, opts)
        last_change = change
        for _ in range(5):
            apply_factors(sysm, tf, cond)
            out = newton(sysm, st, opts.tol, opts.max_iter, lu=lu)
            lu = out.lu if out.converged else None
            if out.converged:
                break
            # too large a temperature step for Newton from here: back off halfway
            tf.theta = theta_prev + 0.5 * (tf.theta - theta_prev)
            tf.refresh(grid.x, p, h, pa, cond, roughness, opts)
            relax *= 0.5
        assert out is not None  # the loop above ran at least once
        if not out.converged:
            msg = f"Reynolds failed at thermal iteration {it}: {out.message}"
            break
        st = out.state
        hc = float(np.interp(0.0, grid.x, st.H * sysm.h_ref))
        dh = abs(hc / hc_prev - 1.0)
        hc_prev = hc
        tol_T = topts.tol + 2e-3 * float(np.max(np.abs(tf.theta)))
        if change < tol_T and dh < 1e-5:
            ok = True
            msg = (
                f"thermal fixed point in {it} iterations (ΔT {change:.2g} K, Δh_c "
                f"{dh:.1e}); {out.message}"
            )
            break
    else:
        msg = (
            f"thermal iteration not converged in {topts.max_iter} iterations (last ΔT "
            f"{last_change:.3g} K)"
        )
    if out is None:
        out = newton(sysm, st, opts.tol, opts.max_iter)
    res = thermal_result(sysm, out, opts, tf, cond, it, ok, msg)
    res.temperature_field = tf  # the temperature field (a transient starts from it)
    return res

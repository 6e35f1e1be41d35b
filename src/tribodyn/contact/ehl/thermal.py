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

import numpy as np

from ..._threads import one_blas_thread
from ..._validation import InputError
from ...physics.asperity import Roughness
from ...physics.heat_conduction import ThermalBody
from ...physics.materials import BodyPair
from ...physics.thermal_oil import ThermalLubricant
from .grid import Grid, layout
from .newton import newton
from .options import Conditions, ContactModel, EHLOptions, EHLResult, with_overrides
from .postprocess import postprocess
from .reynolds import ReynoldsSystem
from .steady import solve_ehl, state_from_dimensional
from .thermal_field import (
    FrozenTemperatureOil,
    ThermalField,
    ThermalOptions,
    apply_factors,
    couette_stress,
)

__all__ = [
    "ThermalOptions",
    "ThermalEHLResult",
    "FrozenTemperatureOil",
    "ThermalField",
    "solve_thermal_ehl",
    "couette_stress",
]


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


@one_blas_thread
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
    opts = with_overrides(options, option_overrides)
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
    # the stand-in is a LubricantModel: the lubricant as the Reynolds system reads it
    model = ContactModel(iso_model.bodies, standin, roughness)
    sysm = ReynoldsSystem(grid, cond, model)
    st = state_from_dimensional(
        sysm, iso.x, iso.pressure + iso.asperity_pressure, iso.rigid_approach
    )
    ev = sysm.evaluate(st.Q, st.H0)
    st.P, st.H = ev.P, ev.H
    tf = ThermalField(grid.x, oil, tb, topts, cond.surface_speeds)
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

"""Post-processing of an EHL solution: friction, loads, films and their positions, the
outlet meniscus, checks of the domain (inlet truncation, outlet pressure) and of the
model's validity (:mod:`.validity`).

Friction per unit length: viscous ∫|τ| dx with the Couette stress of the chosen law
(Newtonian or Eyring, capped at the limiting shear stress; paper Eq. 16 and
``physics.friction``); boundary ∫(τ₀ A_a/A + ς p_a) dx (Eqs. 17–18); both magnitudes.
Rolling (Poiseuille part ±(h/2) dp/dx of Eq. 16), signed:

    F_R = sgn(u_e) ∫ (h/2) (dp/dx) dx                                    [N/m]

With walls z = 0 and z = h the Poiseuille shear stress is τ_xz = ∓(h/2) dp/dx (the ± of
Eq. 16); each wall's outward normal points the other way, so the Poiseuille force the
film exerts is the same on both surfaces: −∫(h/2)(dp/dx) dx along x, i.e. F_R against
the entrainment direction on the cam and on the tappet alike. F_R > 0 resists rolling;
the inlet rise and the outlet fall of the pressure cancel except where the film differs,
so F_R is much smaller than ∫(h/2)|dp/dx| dx (Biboulet & Houpert 2010, Proc. IMechE J
224:765, "hydrodynamic rolling force" F_t^x, their Eq. 23). The total tangential force
on a surface is its Couette + boundary force (equal and opposite on the two surfaces,
against their relative sliding) plus F_R against the entrainment. F_R converges more
slowly with the inlet extent than the load (the integrand decays as x⁻², the pressure as
|x|⁻³), so the part beyond the cut inlet is added from the far field,
(h/2)|dp/dx| |x_in| at the inlet node.

The stresses are those of ``physics.friction``'s laws; the integrals (pairwise sums, as
NumPy's), extrema, meniscus and inlet estimates are one compiled pass over the nodes
(:func:`.post_kernels.solution_integrals`).
"""

from __future__ import annotations

import math

import numpy as np

from ...physics.friction import (
    boundary_shear_stress,
    couette_shear_stress,
    limit_shear_stress,
)
from .newton import ROUND_OFF_PRESSURE, NewtonOutcome
from .options import EHLOptions, EHLResult
from .post_kernels import solution_integrals
from .reynolds import ReynoldsSystem
from .validity import check_solution

__all__ = ["postprocess", "shear_stress"]

#: films below this [m] are taken at this value in the friction integrals
_H_FLOOR = 1e-10
#: the boundary shear stress of a contact without roughness (no nodes)
_NONE = np.empty(0)


def shear_stress(
    pressure, film, sliding_speed, lubricant, model: str, limiting_shear: bool, log_ratio=None
) -> np.ndarray:
    """Couette shear stress τ(x) [Pa] of a solution: Newtonian μu_s/h or Eyring
    τ_E asinh(μu_s/(τ_E h)) with μ = μ(p), capped at τ_L0 + Λp when ``limiting_shear``
    (``log_ratio``: ln μ/μ₀ at p where the caller has it, e.g. the solve's last
    evaluation; else from p)."""
    p = np.asarray(pressure, dtype=float)
    if log_ratio is None:
        mu = lubricant.viscosity_at(p)
    else:
        mu = lubricant.viscosity_from_log_ratio(log_ratio)
    tau = couette_shear_stress(
        mu, sliding_speed, np.maximum(film, _H_FLOOR), model, lubricant.eyring_stress
    )
    if limiting_shear:
        tau = limit_shear_stress(
            tau, p, lubricant.limiting_shear_coefficient, lubricant.limiting_shear_stress
        )
    return tau


# a non-converged last iterate may hold extreme pressures: evaluated quietly, flagged below
@np.errstate(over="ignore", invalid="ignore", under="ignore")
def postprocess(
    sysm: ReynoldsSystem, out: NewtonOutcome, opts: EHLOptions, time=0.0, squeeze_velocity=0.0
) -> EHLResult:
    """:class:`EHLResult` of a Newton outcome on ``sysm`` (friction, loads, films,
    meniscus, inlet-truncation estimate, warnings)."""
    st, ok, it, msg = out.state, out.converged, out.iterations, out.message
    w, R = sysm.cond.load, sysm.cond.radius
    ue, us = sysm.cond.entrainment_speed, sysm.cond.sliding_speed
    lub, rough = sysm.lub, sysm.rough
    g = sysm.g
    x = g.x
    p = st.P * sysm.p_ref
    h = st.H * sysm.h_ref
    pa = (st.Pa if st.Pa is not None else sysm.asperity(st.H)[0]) * sysm.p_ref
    dx = g.dX * g.a
    tau = shear_stress(p, h, us, lub, opts.viscous_model, opts.limiting_shear, st.lnmu)
    if rough is not None:
        area = rough.contact_area_fraction(h, tabulated=True)
        tau_b = boundary_shear_stress(
            pa, area, opts.boundary_shear_coefficient, opts.boundary_shear_strength
        )
    else:
        tau_b = _NONE
    direction = (g.direction > 0) - (g.direction < 0)  # the sign
    # one pass over the nodes: the sums, the extrema, the outlet meniscus (first
    # zero-pressure node, up to round-off, downstream of the peak; p ∝ (x_c − x)² near a
    # Reynolds boundary, so √p is extrapolated linearly to zero) and the inlet's shares
    s_tau, s_roll, s_p, s_pa, s_b, roll_in, i_min, ipk, x_cav, finite, deficit = solution_integrals(
        x, p, h, pa, tau, tau_b, dx, direction, ROUND_OFF_PRESSURE
    )
    f_visc = float(s_tau * dx)
    # signed: the Hertzian rise and fall cancel (not ∫(h/2)|dp/dx|, 3–11× too large)
    f_roll = float(s_roll * dx) * (-1.0 if ue < 0.0 else 1.0)
    # the cut inlet's share (roll_in): far upstream h ≈ x²/2R and p ∝ |x|⁻³, so
    # (h/2)dp/dx ∝ x⁻² and ∫ beyond x_in = (h/2)|dp/dx| |x_in| at the inlet node (8 % of
    # F_R on the rigid isoviscous cylinder at the default domain, against 0.5 % of the load)
    f_roll += roll_in
    f_b = float(s_b * dx) if rough is not None else 0.0
    if not (finite and math.isfinite(f_visc)):
        ok = False
        msg = "non-finite solution: " + msg
    # load lost to the truncated inlet (deficit): |dp/dx| x_in²/2 at the inlet node (exact
    # for the far field p ∝ |x|⁻³; on the rigid isoviscous cylinder it predicts the loss
    # within 5 %); warn at twice the tolerance the domain was sized for
    deficit /= w
    warns = []
    if ok and deficit > 2.0 * opts.inlet_truncation:
        warns.append(
            f"truncated inlet carries an estimated {deficit:.1%} of the load "
            "(lower inlet_truncation or increase inlet)"
        )
    out_end = g.n - 2 if g.direction > 0 else 1
    if ok and g.direction != 0 and p[out_end] > 1e-3 * p[ipk]:
        warns.append("pressure not negligible at the outlet (increase outlet)")
    msg += "".join(f"; warning: {t}" for t in warns)
    res = EHLResult(
        x=x,
        pressure=p,
        asperity_pressure=pa,
        film=h,
        central_film=float(np.interp(0.0, x, h)),
        min_film=float(h[i_min]),
        min_film_position=float(x[i_min]),
        cavitation_position=x_cav,
        rigid_approach=float(st.H0 * sysm.h_ref),
        load=w,
        hydrodynamic_load=float(s_p * dx),
        asperity_load=float(s_pa * dx),
        viscous_friction=f_visc,
        rolling_friction=f_roll,
        boundary_friction=f_b,
        entrainment_speed=ue,
        sliding_speed=us,
        radius=R,
        converged=bool(ok),
        iterations=int(it),
        message=msg,
        time=time,
        squeeze_velocity=squeeze_velocity,
        shear_stress=tau,
        inlet_load_deficit=deficit,
        warnings=warns,
    )
    return check_solution(res, sysm.model)  # film > 0, validity of the model

"""The cam–tappet contact that the valvetrain models share.

* the contact law δ_el(P) = C P^(1/γ) (Palmgren, γ = 1/0.9) or P/k, plus P/k_cam
  (camshaft, optional), solved with the film in series (:func:`contact_film_root`);
* the damped contact force F_c = max(0, P + c_c g(P) δ̇_kin), g the cubic step
  (:func:`smooth_step`); with the film as a state the damper acts on the elastic rate,
  F_c = P + c_c g (δ̇_kin + ḣ), ḣ = a(h) − F_c/D(h), solved for F_c in closed form; the
  contact friction F_f (tribology law or its cam-angle table,
  :class:`_FrictionTable`) and the bore friction μ_b F_f tanh(ẋ_t/v_r);
* :class:`CamContactModel`, the base of the lumped and flexible models: the contact and
  film laws, the stored contact energy, the right-hand side ẏ from ``evaluate`` and
  :meth:`CamContactModel.cam_contact`, the contact state at one instant.

Units SI (m, N, s, rad).
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

import numpy as np
from numba import njit

from .._validation import InputError, check_real
from ..physics import limits as L
from ..physics.film_state_laws import limited_growth
from .cams import CamProfile
from .kinematics import flat_follower_kinematics
from .tribology import TribologyModel

__all__ = [
    "ContactLawError",
    "smooth_step",
    "contact_film_root",
    "CamContact",
    "CamContactModel",
]

_PALMGREN_EXP = 0.9
_HUGE = float("inf")


class ContactLawError(RuntimeError):
    """The implicit contact/film law could not be solved (reported, not hidden)."""


def smooth_step(force: float, ramp: float) -> tuple[float, float]:
    """Cubic step g(F) = 3r² − 2r³, r = min(F/ramp, 1), and dg/dF."""
    if force <= 0.0:
        return 0.0, 0.0
    r = force / ramp
    if r >= 1.0:
        return 1.0, 0.0
    return r * r * (3.0 - 2.0 * r), 6.0 * r * (1.0 - r) / ramp


def joint_force(k: float, c: float, d: float, dd: float, ramp: float) -> tuple:
    """(F, E, g, dg/dE) of a compression-only joint of stiffness k [N/m] and damping c
    [N s/m] at compression d [m] and rate dd [m/s]: F = E + c g(E) ḋ, 0 where not > 0,
    E = k d⁺ [N], g the cubic step of :func:`smooth_step`."""
    E = k * d if d > 0.0 else 0.0
    g, dg = smooth_step(E, ramp)
    F = E + c * g * dd
    return (F if F > 0.0 else 0.0), E, g, dg


def joint_slopes(k: float, c: float, d: float, dd: float, F: float, g: float, dg: float):
    """(∂F/∂d, ∂F/∂ḋ) of a :func:`joint_force` joint from its force F and step g, dg/dE
    there: k (1 + c dg ḋ) where d > 0 (else 0) and c g; both 0 where F = 0."""
    if F <= 0.0:
        return 0.0, 0.0
    return (k * (1.0 + c * dg * dd) if d > 0.0 else 0.0), c * g


def coil_segment(end: bool, F0: float, k: float, c: float, d: float, dd: float) -> tuple:
    """(F, dissipation rate) of a coil segment of the lumped spring: F_el = F₀ + k Δ,
    F = F_el + c Δ̇ at compression Δ = ``d`` [m] and rate ``dd`` [m/s]; an ``end`` segment
    (seated on the valve or the head) is compression-only (both forces ≥ 0, dissipating
    (F − F_el) Δ̇), an inner one dissipates c Δ̇²."""
    fe = F0 + k * d
    f = fe + c * dd
    if not end:
        return f, c * dd * dd
    if fe < 0.0:
        fe = 0.0
    if f < 0.0:
        f = 0.0
    return f, (f - fe) * dd


def stamp_element(K, Cm, a: int, b: int, k: float, c: float) -> None:
    """Add a compressive element between bodies a and b (b = −1: ground), whose force
    pushes a in −x and b in +x, with ∂F/∂(x_a − x_b) = k and ∂F/∂(ẋ_a − ẋ_b) = c, to the
    force derivatives K = ∂(force)/∂q and Cm = ∂(force)/∂q̇ (in place)."""
    K[a, a] -= k
    Cm[a, a] -= c
    if b >= 0:
        K[a, b] += k
        K[b, a] += k
        K[b, b] -= k
        Cm[a, b] += c
        Cm[b, a] += c
        Cm[b, b] -= c


class _FrictionTable:
    """Bilinear table of F_f(θ mod 2π, F) from a periodic tribology model (fast RHS).

    Angles: a 1° grid, refined to 0.1° within ±2° of every sign change of u_e, where the
    film formulas make friction peak sharply (|u_e| → 0). Forces: 19 levels to 3 kN,
    constant friction coefficient beyond."""

    FORCES = (
        0.0,
        2.0,
        5.0,
        10.0,
        20.0,
        40.0,
        70.0,
        100.0,
        150.0,
        200.0,
        275.0,
        350.0,
        450.0,
        600.0,
        800.0,
        1100.0,
        1500.0,
        2000.0,
        3000.0,
    )

    def __init__(
        self, model: TribologyModel, cam: CamProfile, cam_speed: float, start_angle: float = 0.0
    ):
        two_pi = 2.0 * math.pi
        rb = cam.base_radius
        fine = np.linspace(0.0, two_pi, 7200, endpoint=False)  # 0.05°
        s, _, s2 = cam.derivatives(fine)
        flip = np.nonzero(np.diff(np.sign(rb + s + 2.0 * s2)))[0]
        pieces = [np.linspace(0.0, two_pi, 361)]
        for k in flip:
            pieces.append(fine[k] + np.radians(np.arange(-2.0, 2.01, 0.1)))
        th = np.unique(np.concatenate(pieces) % two_pi)
        th = np.append(th, th[0] + two_pi)  # wrap point
        self.F = np.asarray(self.FORCES)
        kin = flat_follower_kinematics(cam, cam_speed, th)
        R, ue, us = kin.radius_of_curvature, kin.entrainment_speed, kin.sliding_speed
        # simulation time of cam angle θ in the first revolution: t = (θ − θ₀)/ω mod 2π/ω
        t_of = np.mod(th - start_angle, two_pi) / cam_speed
        TT, FF = np.meshgrid(t_of, self.F, indexing="ij")
        tab = np.asarray(model.friction(TT, FF, ue[:, None], us[:, None], R[:, None]), dtype=float)
        if not np.all(np.isfinite(tab)) or np.any(tab < 0.0):
            raise InputError("tribology model returned negative or non-finite friction")
        self.th, self.tab = th, np.ascontiguousarray(tab)

    def __call__(self, theta: float, force: float) -> float:
        return table_friction(theta, force, self.th, self.tab, self.F)


@njit(cache=True, nogil=True)
def table_friction(theta, force, th, tab, fl):
    """Bilinear F_f(θ, F) [N] of a :class:`_FrictionTable` (angles ``th``, forces ``fl``,
    values ``tab``; 0 for F ≤ 0, constant coefficient beyond the largest force)."""
    if force <= 0.0:
        return 0.0
    u = (theta - th[0]) % (2.0 * math.pi) + th[0]
    i = np.searchsorted(th, u, side="right") - 1
    i = min(max(i, 0), th.size - 2)
    a = (u - th[i]) / (th[i + 1] - th[i])
    nf = fl.size
    if force >= fl[nf - 1]:
        return ((1.0 - a) * tab[i, nf - 1] + a * tab[i + 1, nf - 1]) * force / fl[nf - 1]
    lo = np.searchsorted(fl, force, side="right") - 1
    hi = lo + 1
    b = (force - fl[lo]) / (fl[hi] - fl[lo])
    return (1.0 - a) * ((1.0 - b) * tab[i, lo] + b * tab[i, hi]) + a * (
        (1.0 - b) * tab[i + 1, lo] + b * tab[i + 1, hi]
    )


def _series_film(t: float, force: float, where: tuple) -> tuple[float, float]:
    """(h [m], dh/dP [m/N]) of the film in series at time t [s] and force P [N]:
    ``where`` = (model, u_e, R), the film law of a :class:`CamContactModel`."""
    model, ue, R = where
    return model.film(t, force, ue, R)


def contact_film_root(where, t, dk, C, g, ikc, has_film) -> tuple:
    """Solve the cam contact in series with the film for P = z^g [N]:
    φ(z) = C z + P/k_cam − h(t, P) − δ_kin = 0, with (h, dh/dP) from
    ``_series_film(t, P, where)`` (the compiled kernels substitute their film table's),
    C the contact compliance coefficient, g the contact exponent and ``ikc`` = 1/k_cam;
    without a film (``has_film`` False) and with a rigid camshaft P = (δ_kin/C)^g in
    closed form.
    Safeguarded Newton from the upper bracket (monotone for convex φ) with bisection;
    returns (P [N], dP/dδ_kin [N/m], h [m], converged), (0, 0, h(t, 0), False) when 80
    steps do not converge. Shared by the lumped and flexible models and compiled (numba)
    by the lumped model's kernels."""
    if not has_film and ikc == 0.0:
        if dk <= 0.0:
            return 0.0, 0.0, 0.0, True
        z = dk / C
        return z**g, g * z ** (g - 1.0) / C, 0.0, True
    h0, _ = _series_film(t, 0.0, where)
    if dk + h0 <= 0.0:
        return 0.0, 0.0, h0, True
    lo, hi = 0.0, (dk + h0) / C  # bracket in z (see module docstring)
    z = hi
    # φ is a difference of terms of size |δ_kin| and |h|: its round-off scales with them,
    # not with the (possibly tiny) net interference δ_kin + h(0)
    tol = 1e-13 * max(dk + h0, abs(dk), abs(h0), 1e-9)
    for _ in range(80):
        P = z**g
        h, hF = _series_film(t, P, where)
        phi = C * z + P * ikc - h - dk
        if phi > 0.0:
            hi = z
        else:
            lo = z
        dPdz = g * z ** (g - 1.0) if z > 0.0 else (1.0 if g == 1.0 else 0.0)
        dphi = C + dPdz * (ikc - hF)
        if abs(phi) <= tol:
            return P, dPdz / dphi, h, True
        zn = z - phi / dphi
        z = zn if lo < zn < hi else 0.5 * (lo + hi)
        if hi - lo <= 1e-14 * hi:  # bracket collapsed onto the root
            P = z**g
            h, hF = _series_film(t, P, where)
            dPdz = g * z ** (g - 1.0) if z > 0.0 else (1.0 if g == 1.0 else 0.0)
            return P, dPdz / (C + dPdz * (ikc - hF)), h, True
    return 0.0, 0.0, h0, False


class CamContact(NamedTuple):
    """The cam–tappet contact at one instant: lobe angle θ [rad], lift s [m] and its
    derivatives s' [m/rad], s'' [m/rad²], radius of curvature R [m], entrainment and
    sliding speeds u_e, u_s [m/s], interference δ_kin [m] and its rate [m/s], elastic
    force P [N], dP/dδ_kin [N/m], film h [m], damping step g(P) and dg/dP, contact force
    F_c [N] (and whether it is positive), friction F_f [N], tanh(ẋ_t/v_r) and bore
    friction F_b [N]; with the film as a state, its rate ḣ [m/s] and ∂ḣ/∂h [1/s],
    ∂ḣ/∂F_c [m/(N s)] (``film`` is then the film state h)."""

    theta: float
    s: float
    s1: float
    s2: float
    R: float
    ue: float
    us: float
    dk: float
    dkd: float
    P: float
    dPdk: float
    film: float
    gc: float
    dgc: float
    Fc: float
    on: bool
    Ff: float
    th_v: float
    Fb: float
    hdot: float = 0.0
    dhdot_dh: float = 0.0
    dhdot_dF: float = 0.0
    kc: float = 0.0
    cc: float = 0.0
    kh: float = 0.0

    def outputs(self, **joints: Any) -> dict:
        """The ``evaluate`` dict of a model: the contact's keys, then ``joints`` (Ftv,
        Fs, Fseg, acc, cam_power, dissipation_rate)."""
        return dict(
            theta=self.theta,
            s=self.s,
            s1=self.s1,
            s2=self.s2,
            R=self.R,
            ue=self.ue,
            us=self.us,
            dk=self.dk,
            P=self.P,
            Fc=self.Fc,
            Ff=self.Ff,
            Fb=self.Fb,
            film=self.film,
            hdot=self.hdot,
            dhdot_dh=self.dhdot_dh,
            dhdot_dF=self.dhdot_dF,
            **joints,
        )


def _film_free_rate(K: float, m: float, xt: float) -> float:
    """The root x of x + m H(x) = K (H = ``limited_growth``, m ≥ 0): the film's free
    rate x = a − F_c/D where one force F_c passes through the film and the contact's
    spring and damper, F_c = P + c g (δ̇_kin + H(x)), K = a − (P + c g δ̇_kin)/D,
    m = c g/D. Closed form where the film thins (K ≤ 0: x = K/(1 + m)); else
    x + m H(x) is increasing from 0 at x = 0 to above K at x = K, and Newton's method
    from the unlimited root, kept inside the bracket, converges to round-off."""
    if K <= 0.0 or m == 0.0 or xt == math.inf:
        return K / (1.0 + m)
    if xt <= 0.0:
        return K  # no growth: H = 0
    lo, hi = 0.0, K
    x = K / (1.0 + m)
    for _ in range(60):
        H, dH, _ = limited_growth(x, xt)
        f = x + m * H - K
        if f == 0.0:
            return x
        if f > 0.0:
            hi = x
        else:
            lo = x
        step = f / (1.0 + m * dH)
        if abs(step) <= 1e-15 * K:
            return x - step
        x_new = x - step
        x = x_new if lo <= x_new <= hi else 0.5 * (lo + hi)
    return x


def damped_contact(P, dPdk, dkd, c, ramp, film_state, laws) -> tuple:
    """The damped contact force from the elastic force P [N] (dP/dδ_kin [N/m]), δ̇_kin
    [m/s], the damping c [N s/m] and its ramp [N] (:func:`smooth_step` g):
    F_c = max(0, P + c g(P) δ̇_kin); with the film as a state (``film_state``; ``laws`` =
    (a, ∂a/∂h, 1/D, ∂(1/D)/∂h, x_t, ∂x_t/∂h) of the film, else unused) one force through
    the film and the contact's spring and damper, F_c = P + c g (δ̇_kin + ḣ),
    ḣ = H(a − F_c/D) (:func:`_film_free_rate`, H = ``limited_growth``; an open contact's
    film grows at H(a)). Returns (g, dg/dP, F_c, ḣ, ∂ḣ/∂h, ∂ḣ/∂F_c, k_c, c_c, k_h) with
    k_c = ∂F_c/∂δ_kin, c_c = ∂F_c/∂δ̇_kin, k_h = ∂F_c/∂h (the forces and slopes 0 where the
    contact is open). Compiled (numba) by the lumped model's kernels too."""
    gc, dgc = smooth_step(P, ramp)
    if not film_state:
        Fc = P + c * gc * dkd
        if Fc <= 0.0:
            return gc, dgc, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
        return gc, dgc, Fc, 0.0, 0.0, 0.0, dPdk * (1.0 + c * dgc * dkd), c * gc, 0.0
    a, a_h, inv_d, inv_d_h, xt, xt_h = laws
    x = _film_free_rate(a - inv_d * (P + c * gc * dkd), c * gc * inv_d, xt)
    hd, hd_x, hd_xt = limited_growth(x, xt)
    Fc = P + c * gc * (dkd + hd)
    on_c = Fc > 0.0
    if not on_c:  # the contact is open: the film's free rate is a
        Fc = 0.0
        hd, hd_x, hd_xt = limited_growth(a, xt)
    hd_F = -hd_x * inv_d  # ∂ḣ/∂F_c and ∂ḣ/∂h at fixed F_c
    hd_h = hd_x * (a_h - inv_d_h * Fc) + hd_xt * xt_h
    if not on_c:
        return gc, dgc, 0.0, hd, hd_h, hd_F, 0.0, 0.0, 0.0
    den = 1.0 - c * gc * hd_F
    kc = dPdk * (1.0 + c * dgc * (dkd + hd)) / den
    return gc, dgc, Fc, hd, hd_h, hd_F, kc, c * gc / den, kc + c * gc * hd_h / den


class CamContactModel:
    """What the lumped and flexible valvetrain models share: the contact law (``gamma``,
    compliance ``contact_C``, camshaft compliance ``contact_ikc``), the film in series,
    the friction at the contact and in the bore, and ẏ = [q̇, q̈, P_cam, D'] from
    ``evaluate`` (a subclass sets ``cam``, ``p``, ``w``, ``trib``, ``n``, ``has_film``
    and ``friction_fn``, and implements ``evaluate``)."""

    PARAMS: type
    cam: CamProfile
    p: Any
    w: float
    trib: TribologyModel
    n: int
    has_film: bool
    friction_fn: _FrictionTable | None
    gamma: float
    contact_C: float
    contact_ikc: float

    @classmethod
    def handles(cls, params: Any) -> bool:
        """True if ``params`` is this model's parameter class (``PARAMS``)."""
        return isinstance(params, cls.PARAMS)

    def _bind(
        self, cam: CamProfile, params: Any, cam_speed: float, tribology, start_angle: float
    ) -> None:
        """Check a model's arguments (types, ``params`` of class ``PARAMS``, and the case
        file's ranges, :mod:`tribodyn.physics.limits`: :class:`InputError` naming the
        argument) and keep the cam, ω [rad/s], the tribology and θ₀ [rad]; θ₀ must lie on
        the base circle, where the models start from static equilibrium."""
        if not isinstance(cam, CamProfile):
            raise InputError(f"cam must be a CamProfile (got {type(cam).__name__})")
        if not isinstance(params, self.PARAMS):
            raise InputError(
                f"params must be a {self.PARAMS.__name__} (got {type(params).__name__})"
            )
        L.CAM_SPEED.check("cam_speed", cam_speed)
        if not isinstance(tribology, TribologyModel):
            raise InputError(f"tribology must be a TribologyModel (got {type(tribology).__name__})")
        check_real("start_angle", start_angle, "rad")
        self.cam, self.w, self.trib = cam, float(cam_speed), tribology
        self.theta0 = float(start_angle)
        s0 = cam.scalar_derivatives(self.theta0)[0]
        if abs(s0) > 1e-9:
            raise InputError(
                f"start_angle must be on the base circle (lift there is {s0 * 1e3:.4g} mm)"
            )

    def _init_contact(self, tribology: TribologyModel, cam_bending: float) -> None:
        """Contact law δ_el = C z + z^γ/k_cam, P = z^γ (``cam_bending`` = 1/k_cam [m/N]),
        the film flag and the friction table of a cam-periodic tribology."""
        p = self.p
        if p.contact_stiffness is None:
            self.gamma = 1.0 / _PALMGREN_EXP
            self.contact_C = p.contact_compliance_coefficient
        else:
            self.gamma = 1.0
            self.contact_C = 1.0 / p.contact_stiffness
        self.contact_ikc = cam_bending
        self.has_film = bool(tribology.has_film)
        # the film as a state (FilmStateTribology): y gains h at index 2n + 2
        self.film_state = bool(getattr(tribology, "has_film_state", False))
        self.h_supply = float(getattr(tribology, "supply_film", 0.0)) if self.film_state else 0.0
        self.friction_fn = (
            _FrictionTable(tribology, self.cam, self.w, self.theta0)
            if tribology.periodic_in_cam_angle
            else None
        )

    theta0: float

    def film(self, t: float, force: float, ue: float, R: float) -> tuple[float, float]:
        """Series film h [m] and dh/dP [m/N] (0, 0 without a film law)."""
        if not self.has_film:
            return 0.0, 0.0
        h, hF = self.trib.film(float(t), float(force), ue, R)
        h, hF = float(h), float(hF)
        if not (-_HUGE < h < _HUGE and -_HUGE < hF <= 0.0):  # finite, dh/dF <= 0
            raise ContactLawError(
                f"film law returned h = {h:g} m, dh/dF = {hF:g} m/N at "
                f"t = {t:.6g} s, F = {force:.6g} N (need finite, dh/dF <= 0)"
            )
        return h, hF

    def elastic_contact(
        self, t: float, dk: float, ue: float = 0.0, R: float = 1.0
    ) -> tuple[float, float, float]:
        """Elastic contact force P [N], dP/dδ_kin [N/m] and film h [m] at interference dk
        (:func:`contact_film_root`)."""
        P, dPdk, h, ok = contact_film_root(
            (self, ue, R),
            t,
            dk,
            self.contact_C,
            self.gamma,
            self.contact_ikc,
            self.has_film,
        )
        if not ok:
            raise ContactLawError(
                f"contact/film law did not converge at t = {t:.6g} s "
                f"(δ_kin = {dk:.4g} m, h(0) = {h:.4g} m)"
            )
        return P, dPdk, h

    def contact_potential(self, P):
        """Elastic energy stored in the contact at force P [J] (Palmgren/linear + camshaft;
        0 for P ≤ 0); P a float or an array."""
        P = np.maximum(P, 0.0)
        if self.gamma == 1.0:
            u = 0.5 * self.contact_C * P * P
        else:
            e = 1.0 / self.gamma  # 0.9
            u = self.contact_C * e / (1.0 + e) * P ** (1.0 + e)
        return u + 0.5 * self.contact_ikc * P * P

    def film_at_rest(self) -> float:
        """Initial film h₀ [m] of the film state on the base circle: the entraining film
        carries the force of the contact's compliance alone,
        L w'_ent(h₀; u_e = ω r_b/2, R = r_b) = P(δ_kin = 0 + h₀), found by bisection in
        ln h between 1e-10 m and the supply film h_s (where w'_ent = 0). The settled
        film is thicker, since the tappet–valve joint and the seat yield too (paper case,
        4000 rpm: 0.62 µm here, 1.48 µm settled); the run settles within about 20° of
        its first, discarded cycle."""
        rb = self.cam.base_radius
        ue, t0 = 0.5 * self.w * rb, 0.0
        hs = self.h_supply

        def excess(h: float) -> float:
            P = self.elastic_contact(t0, h, ue, rb)[0]
            rate, _, _ = self.trib.film_rate(t0, h, P, ue, rb)  # type: ignore[attr-defined]
            return rate  # ∝ L w'_ent(h) − P(h)

        lo, hi = math.log(1e-10), math.log(hs)
        if ue == 0.0 or excess(math.exp(lo)) <= 0.0:
            return 1e-10  # no entraining film, or its equilibrium lies below the floor
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            if excess(math.exp(mid)) > 0.0:
                lo = mid
            else:
                hi = mid
        return math.exp(0.5 * (lo + hi))

    def cam_contact(
        self, t: float, th: float, wl: float, x: float, v: float, hf: float = 0.0
    ) -> CamContact:
        """The contact at time t [s] for lobe angle θ [rad], lobe speed ω_l [rad/s],
        tappet-face displacement x [m] and velocity v [m/s], and (film state) film h_f [m]:
        δ_el = δ_kin + h_f. The film separates the surfaces: the kinematic interference
        δ_kin is measured from metal contact, the datum of the explicit run (zero lash)."""
        p = self.p
        s, s1, s2 = self.cam.scalar_derivatives(th)
        rb = self.cam.base_radius
        R = rb + s + s2
        ue = 0.5 * wl * (rb + s + 2.0 * s2)
        us = wl * (rb + s)
        dk = s - x
        dkd = wl * s1 - v
        if self.film_state:
            # the film in series with the contact's spring and damper (damped_contact)
            P, dPdk, _ = self.elastic_contact(t, dk + hf, ue, R)
            hfilm = hf
            trib = self.trib
            a, a_h, m_inv = trib.film_rate(t, hf, 0.0, ue, R)  # type: ignore[attr-defined]
            slope = trib.squeeze_compliance_slope(hf, ue, R)  # type: ignore[attr-defined]
            limit = trib.growth_limit(hf, ue, R)  # type: ignore[attr-defined]
            laws: tuple = (a, a_h, -m_inv, slope, *limit)
        else:
            P, dPdk, hfilm = self.elastic_contact(t, dk, ue, R)
            laws = (0.0,) * 6
        gc, dgc, Fc, hd, hd_h, hd_F, kc, cc, kh = damped_contact(
            P, dPdk, dkd, p.contact_damping, p.damping_force_ramp, self.film_state, laws
        )
        if Fc > 0.0:
            Ff = (
                self.friction_fn(th, Fc)
                if self.friction_fn is not None
                else float(self.trib.friction(t, Fc, ue, us, R))
            )
        else:
            Ff = 0.0
        th_v = math.tanh(v / p.bore_friction_velocity)
        Fb = p.bore_friction_coefficient * Ff * th_v
        return CamContact(
            th, s, s1, s2, R, ue, us, dk, dkd, P, dPdk, hfilm, gc, dgc, Fc, Fc > 0.0, Ff,
            th_v, Fb, hdot=hd, dhdot_dh=hd_h, dhdot_dF=hd_F, kc=kc, cc=cc, kh=kh,
        )  # fmt: skip

    def evaluate(self, t: float, y, jac: bool = False) -> dict:
        """Forces and kinematics at one state (see the models)."""
        raise NotImplementedError

    def rhs(self, t, y):
        """ẏ = [q̇, q̈, P_cam, D'] (+ [ḣ] with the film as a state)."""
        n = self.n
        f = self.evaluate(t, y)
        dy = np.empty(2 * n + 2 + self.film_state)
        dy[:n] = y[n : 2 * n]
        dy[n : 2 * n] = f["acc"]
        dy[2 * n] = f["cam_power"]
        dy[2 * n + 1] = f["dissipation_rate"]
        if self.film_state:
            dy[2 * n + 2] = f["hdot"]
        return dy

    def static_state(self) -> np.ndarray:
        """Static equilibrium on the base circle: all displacements (or deviations) and
        velocities zero (the film state, if any, at its rest film h₀ (``film_at_rest``))."""
        y = np.zeros(2 * self.n + 2 + self.film_state)
        if self.film_state:
            y[-1] = self.film_at_rest()
        return y

    def film_jacobian(self, J: np.ndarray, f: dict, grad: dict, Minv_g: np.ndarray) -> None:
        """Add the film state's rows and columns to the Jacobian J (size 2n + 3) from an
        ``evaluate(jac=True)`` output ``f``: ``grad`` = ∂δ_kin/∂q (index → value) and
        ``Minv_g`` = M⁻¹ times the contact force's generalised direction (−∂δ_kin/∂q).
        F_c depends on h through the elastic approach and the film's own rate
        (∂F_c/∂h = k_h, ``cam_contact``)::

            ∂q̈/∂h = M⁻¹(−g) k_h,  ∂ḣ/∂h = ∂ḣ/∂h|_F + ∂ḣ/∂F k_h,
            ∂ḣ/∂q = ∂ḣ/∂F k_c g,  ∂ḣ/∂q̇ = ∂ḣ/∂F c_c g  (g = ∂δ_kin/∂q = ∂δ̇_kin/∂q̇)
        """
        n = self.n
        k = 2 * n + 2
        kc, cc, kh = (f["kc"], f["cc"], f["kh"]) if f["Fc"] > 0.0 else (0.0, 0.0, 0.0)
        rf = f["dhdot_dF"]
        J[n : 2 * n, k] = Minv_g * kh
        J[k, k] = f["dhdot_dh"] + rf * kh
        for i, gi in grad.items():
            J[k, i] += rf * kc * gi
            J[k, n + i] += rf * cc * gi

"""Equations of motion of the single valvetrain (pure physics; no integration here).

Generalised coordinates (displacements from static equilibrium on the base circle, +x =
valve opening): q = [x_t, x_v, x_1 … x_N] (tappet, valve, coil masses). State
y = [q, q̇, W_cam, D] with two energy accumulators (cam work and dissipation).

Forces (F_c, F_tv, F_seat, F_j ≥ 0 are compressive joint forces)::

    m_t ẍ_t = F_c − F_tv − μ_b F_f tanh(ẋ_t/v_r)
    m_v ẍ_v = F_tv − F_0spr + F_seat                 m_v incl. the end half coil mass
    m_i ẍ_i = F_{i−1} − F_i                            i = 1 … N,  m_i = m_s/(N+1)

* cam–tappet: δ_kin = s(θ) − x_t, elastic law δ_el(P) = C P^0.9 (Palmgren) or P/k,
  plus P/k_cam (camshaft, optional), solved with the film in series:
  δ_el(P) = δ_kin + h(t, P)  (unique root: δ_el' > 0, h' ≤ 0);  P = 0 if δ_kin + h(t, 0) ≤ 0.
  F_c = max(0, P + c_c g(P) δ̇_kin), g the cubic step 3r² − 2r³, r = min(P/F_ramp, 1).
* tappet–valve: δ = x_t − x_v − lash, F_tv = max(0, k δ⁺ + c g δ̇).
* valve seat: δ = F₀/k_seat − x_v, F_seat = max(0, k δ⁺ + c g δ̇).
* coil segment j (node j = valve side, node j+1; node 0 = valve, node N+1 = head):
  Δ_j = x_j − x_{j+1}, F_j = F₀ + k_j Δ_j + c_j Δ̇_j; end segments include the seat
  stiffness in series and are compression-only.

Energy: kinetic T = Σ m v²/2; elastic U(q, t) from the same laws; the cam power
P_cam = F_c ω s' + F_f u_s and the dissipation rate D' = Σ (F − F_elastic) δ̇ + μ_b F_f
tanh(·) ẋ_t + F_f u_s are integrated with the motion, so W_cam = ΔT + ΔU + D checks the
force laws against each other (exact without film; with a film the film's work appears
in the residual).
"""

from __future__ import annotations

import bisect
import math

import numpy as np

from .._validation import InputError, check_real
from ..physics import limits as L
from .cams import CamProfile
from .parameters import ValvetrainParameters
from .tribology import TribologyModel

__all__ = ["ValvetrainModel", "ContactLawError", "smooth_step", "check_model_inputs"]

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
        th = [np.linspace(0.0, two_pi, 361)]
        for k in flip:
            th.append(fine[k] + np.radians(np.arange(-2.0, 2.01, 0.1)))
        th = np.unique(np.concatenate(th) % two_pi)
        th = np.append(th, th[0] + two_pi)  # wrap point
        self.F = np.asarray(self.FORCES)
        s, _, s2 = cam.derivatives(th)
        R = rb + s + s2
        ue = 0.5 * cam_speed * (rb + s + 2.0 * s2)
        us = cam_speed * (rb + s)
        # simulation time of cam angle θ in the first revolution: t = (θ − θ₀)/ω mod 2π/ω
        t_of = np.mod(th - start_angle, two_pi) / cam_speed
        TT, FF = np.meshgrid(t_of, self.F, indexing="ij")
        tab = np.asarray(model.friction(TT, FF, ue[:, None], us[:, None], R[:, None]), dtype=float)
        if not np.all(np.isfinite(tab)) or np.any(tab < 0.0):
            raise InputError("tribology model returned negative or non-finite friction")
        self.th = th.tolist()
        self.th0 = float(th[0])
        self.tab = tab.tolist()
        self.Fl = self.F.tolist()
        self.Fmax = float(self.F[-1])

    def __call__(self, theta: float, force: float) -> float:
        if force <= 0.0:
            return 0.0
        th = self.th
        u = (theta - self.th0) % (2.0 * math.pi) + self.th0
        i = min(max(bisect.bisect_right(th, u) - 1, 0), len(th) - 2)
        a = (u - th[i]) / (th[i + 1] - th[i])
        ti, tj = self.tab[i], self.tab[i + 1]
        Fl = self.Fl
        if force >= self.Fmax:  # beyond the table: constant coefficient
            return ((1.0 - a) * ti[-1] + a * tj[-1]) * force / self.Fmax
        lo = bisect.bisect_right(Fl, force) - 1
        hi = lo + 1
        b = (force - Fl[lo]) / (Fl[hi] - Fl[lo])
        return (1.0 - a) * ((1.0 - b) * ti[lo] + b * ti[hi]) + a * ((1.0 - b) * tj[lo] + b * tj[hi])


def contact_film_root(film, t, dk, ue, R, C, g, ikc) -> tuple[float, float, float]:
    """Solve the cam contact in series with the film for P = z^g [N]:
    φ(z) = C z + P/k_cam − h(t, P) − δ_kin = 0, with ``film(t, P, ue, R) -> (h, dh/dP)``,
    C the contact compliance coefficient, g the contact exponent and ``ikc`` = 1/k_cam.
    Safeguarded Newton from the upper bracket (monotone for convex φ) with bisection;
    returns (P [N], dP/dδ_kin [N/m], h [m]). Shared by the lumped and flexible models."""
    h0, _ = film(t, 0.0, ue, R)
    if dk + h0 <= 0.0:
        return 0.0, 0.0, h0
    lo, hi = 0.0, (dk + h0) / C  # bracket in z (see module docstring)
    z = hi
    # φ is a difference of terms of size |δ_kin| and |h|: its round-off scales with them,
    # not with the (possibly tiny) net interference δ_kin + h(0)
    tol = 1e-13 * max(dk + h0, abs(dk), abs(h0), 1e-9)
    for _ in range(80):
        P = z**g
        h, hF = film(t, P, ue, R)
        phi = C * z + P * ikc - h - dk
        if phi > 0.0:
            hi = z
        else:
            lo = z
        dPdz = g * z ** (g - 1.0) if z > 0.0 else (1.0 if g == 1.0 else 0.0)
        dphi = C + dPdz * (ikc - hF)
        if abs(phi) <= tol:
            return P, dPdz / dphi, h
        zn = z - phi / dphi
        z = zn if lo < zn < hi else 0.5 * (lo + hi)
        if hi - lo <= 1e-14 * hi:  # bracket collapsed onto the root
            P = z**g
            h, hF = film(t, P, ue, R)
            dPdz = g * z ** (g - 1.0) if z > 0.0 else (1.0 if g == 1.0 else 0.0)
            return P, dPdz / (C + dPdz * (ikc - hF)), h
    raise ContactLawError(
        f"contact/film law did not converge at t = {t:.6g} s "
        f"(δ_kin = {dk:.4g} m, h(0) = {h0:.4g} m)"
    )


def check_model_inputs(cam, params, params_type, cam_speed, tribology, start_angle) -> None:
    """Types and ranges of a valvetrain model's arguments (the case file's ranges,
    :mod:`tribodyn.physics.limits`): :class:`InputError` naming the argument."""
    if not isinstance(cam, CamProfile):
        raise InputError(f"cam must be a CamProfile (got {type(cam).__name__})")
    if not isinstance(params, params_type):
        raise InputError(f"params must be a {params_type.__name__} (got {type(params).__name__})")
    L.CAM_SPEED.check("cam_speed", cam_speed)
    if not isinstance(tribology, TribologyModel):
        raise InputError(f"tribology must be a TribologyModel (got {type(tribology).__name__})")
    check_real("start_angle", start_angle, "rad")


class ValvetrainModel:
    """Right-hand side, Jacobian, forces and energies of the valvetrain.

    Parameters
    ----------
    cam : the cam profile; params : :class:`ValvetrainParameters`;
    cam_speed : ω [rad/s] (constant); tribology : a :class:`TribologyModel`;
    start_angle : cam angle at t = 0 [rad] (must be on the base circle).
    """

    def __init__(
        self,
        cam: CamProfile,
        params: ValvetrainParameters,
        cam_speed: float,
        tribology: TribologyModel,
        start_angle: float = 0.0,
    ):
        check_model_inputs(cam, params, ValvetrainParameters, cam_speed, tribology, start_angle)
        self.cam, self.p, self.w, self.trib = cam, params, float(cam_speed), tribology
        self.theta0 = float(start_angle)
        p = params
        N = p.spring_masses
        self.N = N
        self.n = N + 2  # q size
        n_seg = N + 1
        self.k_seg = n_seg * p.spring_rate
        # End segments: coil segment in series with the seat stiffness.
        k_top = 1.0 / (1.0 / self.k_seg + 1.0 / p.spring_seat_stiffness)
        k_bot = 1.0 / (1.0 / self.k_seg + 1.0 / p.spring_support_stiffness)
        if N == 0:
            k_single = 1.0 / (
                1.0 / p.spring_rate
                + 1.0 / p.spring_seat_stiffness
                + 1.0 / p.spring_support_stiffness
            )
            self.kseg = np.array([k_single])
            w1 = math.pi * math.sqrt(p.spring_rate / p.spring_mass)
            m_valve = p.valve_mass + p.spring_mass / 3.0
            self.m_node = 0.0
        else:
            self.kseg = np.full(n_seg, self.k_seg)
            self.kseg[0], self.kseg[-1] = k_top, k_bot
            m_node = p.spring_mass / n_seg
            w1 = (
                2.0
                * n_seg
                * math.sqrt(p.spring_rate / p.spring_mass)
                * math.sin(math.pi / (2.0 * n_seg))
            )
            m_valve = p.valve_mass + 0.5 * m_node
            self.m_node = m_node
        self.beta = 2.0 * p.spring_damping_ratio / w1  # stiffness-proportional coil damping
        self.cseg = self.beta * self.kseg
        self.kseg_l = self.kseg.tolist()
        self.cseg_l = self.cseg.tolist()
        self.mass = np.array([p.tappet_mass, m_valve] + [self.m_node] * N)
        self.inv_mass = 1.0 / self.mass
        self.inv_mass_l = self.inv_mass.tolist()
        self.d_seat = p.spring_preload / p.seat_stiffness  # static seat compression
        # Contact law δ_el = C z + z^γ/k_cam, P = z^γ.
        if p.contact_stiffness is None:
            self.gamma = 1.0 / _PALMGREN_EXP
            self.C = p.contact_compliance_coefficient
        else:
            self.gamma = 1.0
            self.C = 1.0 / p.contact_stiffness
        self.inv_kcam = 0.0 if p.camshaft_stiffness is None else 1.0 / p.camshaft_stiffness
        self.has_film = bool(tribology.has_film)
        if tribology.periodic_in_cam_angle:
            self.friction_fn = _FrictionTable(tribology, cam, self.w, self.theta0)
            self._tab = True
        else:
            self.friction_fn = None
            self._tab = False
        s0 = cam.scalar_derivatives(self.theta0)[0]
        if abs(s0) > 1e-9:
            raise InputError(
                f"start_angle must be on the base circle (lift there is {s0 * 1e3:.4g} mm)"
            )

    #: a compiled right-hand side exists (:func:`~tribodyn.valvetrain.compiled.compiled_model`)
    compilable = True

    PARAMS = ValvetrainParameters

    @classmethod
    def handles(cls, params) -> bool:
        """True for a :class:`ValvetrainParameters`."""
        return isinstance(params, cls.PARAMS)

    def lobe_angle(self, t: float, y) -> float:
        """Cam angle at the contact [rad]: θ₀ + ωt (rigid camshaft)."""
        return self.theta0 + self.w * t

    def unresolved_clash(self, Y) -> float:
        """Coil clash the model cannot see [m]: none (the coils are lumped masses)."""
        return -math.inf

    # -- contact law ---------------------------------------------------------------------
    def film(self, t: float, force: float, ue: float, R: float) -> tuple[float, float]:
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
        """Elastic contact force P [N], dP/dδ_kin [N/m] and film h [m] at interference dk."""
        C, g, ikc = self.C, self.gamma, self.inv_kcam
        if not self.has_film and ikc == 0.0:
            if dk <= 0.0:
                return 0.0, 0.0, 0.0
            z = dk / C
            P = z**g
            return P, g * z ** (g - 1.0) / C, 0.0
        return contact_film_root(self.film, t, dk, ue, R, C, g, ikc)

    def contact_potential(self, P: float) -> float:
        """Elastic energy stored in the contact at force P [J] (Palmgren/linear + camshaft)."""
        if P <= 0.0:
            return 0.0
        if self.gamma == 1.0:
            u = 0.5 * self.C * P * P
        else:
            e = 1.0 / self.gamma  # 0.9
            u = self.C * e / (1.0 + e) * P ** (1.0 + e)
        return u + 0.5 * self.inv_kcam * P * P

    # -- forces ------------------------------------------------------------------------
    def evaluate(self, t: float, y, jac: bool = False):
        """All joint forces and accelerations at (t, y); with ``jac`` also local
        stiffness/damping needed for the Jacobian. Returns a dict of floats/lists.

        Written with Python floats (the state is small): numpy's per-call overhead would
        dominate the right-hand side."""
        p, w, n, N = self.p, self.w, self.n, self.N
        yl = y.tolist() if hasattr(y, "tolist") else list(y)
        xt, xv, vt, vv = yl[0], yl[1], yl[n], yl[n + 1]
        th = self.theta0 + w * t
        s, s1, s2 = self.cam.scalar_derivatives(th)
        rb = self.cam.base_radius
        R = rb + s + s2
        ue = 0.5 * w * (rb + s + 2.0 * s2)
        us = w * (rb + s)
        ramp = p.damping_force_ramp
        # cam–tappet contact
        dk = s - xt
        dkd = w * s1 - vt
        P, dPdk, hfilm = self.elastic_contact(t, dk, ue, R)
        gc, dgc = smooth_step(P, ramp)
        Fc = P + p.contact_damping * gc * dkd
        on_c = Fc > 0.0
        if not on_c:
            Fc = 0.0
        # friction at the contact and in the bore
        if Fc > 0.0:
            Ff = (
                self.friction_fn(th, Fc)
                if self._tab
                else float(self.trib.friction(t, Fc, ue, us, R))
            )
        else:
            Ff = 0.0
        th_v = math.tanh(vt / p.bore_friction_velocity)
        Fb = p.bore_friction_coefficient * Ff * th_v
        # tappet–valve
        dtv = xt - xv - p.lash
        dtvd = vt - vv
        Etv = p.tappet_valve_stiffness * dtv if dtv > 0.0 else 0.0
        gtv, dgtv = smooth_step(Etv, ramp)
        Ftv = Etv + p.tappet_valve_damping * gtv * dtvd
        on_tv = Ftv > 0.0
        if not on_tv:
            Ftv = 0.0
        # valve seat
        ds = self.d_seat - xv
        Es = p.seat_stiffness * ds if ds > 0.0 else 0.0
        gs, dgs = smooth_step(Es, ramp)
        Fs = Es - p.seat_damping * gs * vv
        on_s = Fs > 0.0
        if not on_s:
            Fs = 0.0
        # spring chain: segment j joins node j (0 = valve) and node j+1 (N+1 = head)
        xs = [xv] + yl[2:n] + [0.0]
        vs = [vv] + yl[n + 2 : 2 * n] + [0.0]
        F0 = p.spring_preload
        ks, cs = self.kseg_l, self.cseg_l
        Fseg = [0.0] * (N + 1)
        Fel = [0.0] * (N + 1)
        Dd = [0.0] * (N + 1)
        D = [0.0] * (N + 1)
        diss = 0.0
        for j in range(N + 1):
            d = xs[j] - xs[j + 1]
            dd = vs[j] - vs[j + 1]
            fe = F0 + ks[j] * d
            f = fe + cs[j] * dd
            if j == 0 or j == N:  # compression-only end seatings
                if fe < 0.0:
                    fe = 0.0
                if f < 0.0:
                    f = 0.0
                diss += (f - fe) * dd
            else:
                diss += cs[j] * dd * dd
            D[j], Dd[j], Fel[j], Fseg[j] = d, dd, fe, f
        im = self.inv_mass_l
        acc = [0.0] * n
        acc[0] = (Fc - Ftv - Fb) * im[0]
        acc[1] = (Ftv - Fseg[0] + Fs) * im[1]
        for i in range(1, N + 1):
            acc[i + 1] = (Fseg[i - 1] - Fseg[i]) * im[i + 1]
        out = dict(
            theta=th,
            s=s,
            s1=s1,
            s2=s2,
            R=R,
            ue=ue,
            us=us,
            dk=dk,
            P=P,
            Fc=Fc,
            Ff=Ff,
            Fb=Fb,
            Ftv=Ftv,
            Fs=Fs,
            Fseg=Fseg,
            acc=acc,
            film=hfilm,
            cam_power=Fc * w * s1 + Ff * us,
            dissipation_rate=(
                (Fc - P) * dkd + (Ftv - Etv) * dtvd + (Fs - Es) * (-vv) + diss + Fb * vt + Ff * us
            ),
        )
        if jac:
            kc = dPdk * (1.0 + p.contact_damping * dgc * dkd) if on_c else 0.0
            cc = p.contact_damping * gc if on_c else 0.0
            cb = p.bore_friction_coefficient * Ff * (1.0 - th_v * th_v) / p.bore_friction_velocity
            ktv = (
                p.tappet_valve_stiffness * (1.0 + p.tappet_valve_damping * dgtv * dtvd)
                if (on_tv and dtv > 0.0)
                else 0.0
            )
            ctv = p.tappet_valve_damping * gtv if on_tv else 0.0
            kst = (
                p.seat_stiffness * (1.0 - p.seat_damping * dgs * vv) if (on_s and ds > 0.0) else 0.0
            )
            cst = p.seat_damping * gs if on_s else 0.0
            kseg, cseg = list(ks), list(cs)
            for j in {0, N}:
                if Fseg[j] <= 0.0:
                    kseg[j] = cseg[j] = 0.0
                elif F0 + ks[j] * D[j] < 0.0:
                    kseg[j] = 0.0
            out.update(kc=kc, cc=cc, cb=cb, ktv=ktv, ctv=ctv, ks=kst, cs=cst, kseg=kseg, cseg=cseg)
        return out

    # -- ODE interface -----------------------------------------------------------------
    def rhs(self, t, y):
        n = self.n
        f = self.evaluate(t, y)
        dy = np.empty(2 * n + 2)
        dy[:n] = y[n : 2 * n]
        dy[n : 2 * n] = f["acc"]
        dy[2 * n] = f["cam_power"]
        dy[2 * n + 1] = f["dissipation_rate"]
        return dy

    def jacobian(self, t, y):
        """Analytic ∂ẏ/∂y from the local stiffness and damping of every element
        (friction's dependence on F and the accumulator rows are omitted: the friction
        effect on the motion is small and the accumulators do not feed back)."""
        n, N = self.n, self.N
        f = self.evaluate(t, y, jac=True)
        K = np.zeros((n, n))  # ∂(force)/∂q
        Cm = np.zeros((n, n))  # ∂(force)/∂q̇

        def element(a, b, k, c):
            """Compressive element between bodies a and b (b = None: ground), whose force
            pushes a in −x and b in +x, with ∂F/∂(x_a − x_b) = k, ∂F/∂(ẋ_a − ẋ_b) = c."""
            K[a, a] -= k
            Cm[a, a] -= c
            if b is not None:
                K[a, b] += k
                K[b, a] += k
                K[b, b] -= k
                Cm[a, b] += c
                Cm[b, a] += c
                Cm[b, b] -= c

        K[0, 0] -= f["kc"]  # cam contact: δ = s − x_t
        Cm[0, 0] -= f["cc"] + f["cb"]  # + bore friction
        element(1, 0, f["ktv"], f["ctv"])  # tappet–valve: δ = x_t − x_v
        element(1, None, f["ks"], f["cs"])  # valve seat (to ground)
        kseg, cseg = f["kseg"], f["cseg"]
        for j in range(N + 1):  # coil segment j: nodes j+1, j+2 (q index)
            element(j + 1, j + 2 if j < N else None, kseg[j], cseg[j])
        J = np.zeros((2 * n + 2, 2 * n + 2))
        J[:n, n : 2 * n] = np.eye(n)
        J[n : 2 * n, :n] = K * self.inv_mass[:, None]
        J[n : 2 * n, n : 2 * n] = Cm * self.inv_mass[:, None]
        return J

    # -- energy ------------------------------------------------------------------------
    def energy(self, t: float, y, evaluated: dict | None = None) -> tuple[float, float]:
        """(kinetic, elastic) energy [J] relative to the static equilibrium state
        (``evaluated``: the output of :meth:`evaluate` at (t, y), if already known)."""
        p, n, N = self.p, self.n, self.N
        v = np.asarray(y[n : 2 * n])
        T = 0.5 * float(np.sum(self.mass * v * v))
        f = self.evaluate(t, y) if evaluated is None else evaluated
        U = self.contact_potential(f["P"])
        dtv = y[0] - y[1] - p.lash
        if dtv > 0.0:
            U += 0.5 * p.tappet_valve_stiffness * dtv * dtv
        ds = self.d_seat - y[1]
        U += 0.5 * p.seat_stiffness * (max(ds, 0.0) ** 2 - self.d_seat**2)
        xs = np.concatenate([[y[1]], np.asarray(y[2:n]), [0.0]])
        D = xs[:-1] - xs[1:]
        F0 = p.spring_preload
        Useg = F0 * D + 0.5 * self.kseg * D * D
        ends = (0, N) if N > 0 else (0,)
        for j in ends:
            if F0 + self.kseg[j] * D[j] < 0.0:
                Useg[j] = -0.5 * F0 * F0 / self.kseg[j]
        return T, U + float(np.sum(Useg))

    def static_state(self) -> np.ndarray:
        """Static equilibrium on the base circle: all displacements and velocities zero."""
        return np.zeros(2 * self.n + 2)

    def surge_matrices(self) -> tuple[np.ndarray, np.ndarray]:
        """(M, K) of the coil masses with the valve held fixed (fixed–fixed spring)."""
        N = self.N
        if N == 0:
            return np.zeros((0, 0)), np.zeros((0, 0))
        K = np.zeros((N, N))
        for j in range(N + 1):  # segment j between nodes j, j+1
            a, b = j - 1, j  # coil indices (−1/N = fixed ends)
            k = self.kseg[j]
            if 0 <= a < N:
                K[a, a] += k
            if 0 <= b < N:
                K[b, b] += k
            if 0 <= a < N and 0 <= b < N:
                K[a, b] -= k
                K[b, a] -= k
        return np.eye(N) * self.m_node, K

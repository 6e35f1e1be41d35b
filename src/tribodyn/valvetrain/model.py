"""Equations of motion of the single valvetrain (pure physics; no integration here).

Generalised coordinates (displacements from static equilibrium on the base circle, +x =
valve opening): q = [x_t, x_v, x_1 … x_N] (tappet, valve, coil masses). State
y = [q, q̇, W_cam, D] with two energy accumulators (cam work and dissipation), and the
film thickness h last when the tribology has the film as a state
(:class:`~tribodyn.valvetrain.tribology.FilmStateTribology`: δ_el = δ_kin + h,
ḣ = (F_ent(h) − F_c)/D(h); the film's work −P ḣ counts as dissipation).

Forces (F_c, F_tv, F_seat, F_j ≥ 0 are compressive joint forces)::

    m_t ẍ_t = F_c − F_tv − μ_b F_f tanh(ẋ_t/v_r)
    m_v ẍ_v = F_tv − F_0spr + F_seat                 m_v incl. the end half coil mass
    m_i ẍ_i = F_{i−1} − F_i                            i = 1 … N,  m_i = m_s/(N+1)

* cam–tappet: δ_kin = s(θ) − x_t, elastic law δ_el(P) = C P^0.9 (Palmgren) or P/k,
  plus P/k_cam (camshaft, optional), solved with the film in series:
  δ_el(P) = δ_kin + h(t, P)  (unique root: δ_el' > 0, h' ≤ 0);  P = 0 if δ_kin + h(t, 0) ≤ 0.
  F_c = max(0, P + c_c g(P) δ̇_kin), g the cubic step 3r² − 2r³, r = min(P/F_ramp, 1)
  (with the film as a state: δ̇_kin + ḣ, the elastic rate).
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

import math

import numpy as np

from .cams import CamProfile
from .contact_law import (
    CamContactModel,
    ContactLawError,
    coil_segment,
    joint_force,
    joint_slopes,
    stamp_element,
)
from .parameters import ValvetrainParameters
from .tribology import TribologyModel

__all__ = ["ValvetrainModel", "lumped_energies", "ContactLawError"]


class ValvetrainModel(CamContactModel):
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
        self._bind(cam, params, cam_speed, tribology, start_angle)
        self.p = p = params
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
        self._init_contact(
            tribology, 0.0 if p.camshaft_stiffness is None else 1.0 / p.camshaft_stiffness
        )

    #: a compiled right-hand side exists (:func:`~tribodyn.valvetrain.compiled.compiled_model`)
    compilable = True

    PARAMS = ValvetrainParameters

    def lobe_angle(self, t: float, y) -> float:
        """Cam angle at the contact [rad]: θ₀ + ωt (rigid camshaft)."""
        return self.theta0 + self.w * t

    def unresolved_clash(self, Y) -> float:
        """Coil clash the model cannot see [m]: none (the coils are lumped masses)."""
        return -math.inf

    # -- forces ------------------------------------------------------------------------
    def evaluate(self, t: float, y, jac: bool = False):
        """All joint forces and accelerations at (t, y); with ``jac`` also local
        stiffness/damping needed for the Jacobian. Returns a dict of floats/lists.

        Written with Python floats (the state is small): numpy's per-call overhead would
        dominate the right-hand side."""
        p, w, n, N = self.p, self.w, self.n, self.N
        yl = y.tolist() if hasattr(y, "tolist") else list(y)
        xt, xv, vt, vv = yl[0], yl[1], yl[n], yl[n + 1]
        ramp = p.damping_force_ramp
        # cam–tappet contact, friction at the contact and in the bore
        hf = yl[2 * n + 2] if self.film_state else 0.0
        c = self.cam_contact(t, self.theta0 + w * t, w, xt, vt, hf)
        P, Fc, Ff, Fb = c.P, c.Fc, c.Ff, c.Fb
        dtv, dtvd = xt - xv - p.lash, vt - vv  # tappet–valve
        kv, cv = p.tappet_valve_stiffness, p.tappet_valve_damping
        Ftv, Etv, gtv, dgtv = joint_force(kv, cv, dtv, dtvd, ramp)
        ds = self.d_seat - xv  # valve seat
        Fs, Es, gs, dgs = joint_force(p.seat_stiffness, p.seat_damping, ds, -vv, ramp)
        # spring chain: segment j joins node j (0 = valve) and node j+1 (N+1 = head)
        xs = [xv] + yl[2:n] + [0.0]
        vs = [vv] + yl[n + 2 : 2 * n] + [0.0]
        F0 = p.spring_preload
        ks, cs = self.kseg_l, self.cseg_l
        Fseg = [0.0] * (N + 1)
        D = [0.0] * (N + 1)
        diss = 0.0
        for j in range(N + 1):
            d = xs[j] - xs[j + 1]
            dd = vs[j] - vs[j + 1]
            Fseg[j], dj = coil_segment(j == 0 or j == N, F0, ks[j], cs[j], d, dd)
            diss += dj
            D[j] = d
        im = self.inv_mass_l
        acc = [0.0] * n
        acc[0] = (Fc - Ftv - Fb) * im[0]
        acc[1] = (Ftv - Fseg[0] + Fs) * im[1]
        for i in range(1, N + 1):
            acc[i + 1] = (Fseg[i - 1] - Fseg[i]) * im[i + 1]
        us, dkd = c.us, c.dkd
        out = c.outputs(
            Ftv=Ftv,
            Fs=Fs,
            Fseg=Fseg,
            acc=acc,
            cam_power=Fc * w * c.s1 + Ff * us,
            dissipation_rate=(
                (Fc - P) * dkd
                + (Ftv - Etv) * dtvd
                + (Fs - Es) * (-vv)
                + diss
                + Fb * vt
                + Ff * us
                - P * c.hdot  # work into the film state (0 without one)
            ),
        )
        if jac:
            kc, cc = c.kc, c.cc  # ∂F_c/∂δ_kin, ∂F_c/∂δ̇_kin (0 when the contact is open)
            cb = (
                p.bore_friction_coefficient
                * Ff
                * (1.0 - c.th_v * c.th_v)
                / p.bore_friction_velocity
            )
            ktv, ctv = joint_slopes(kv, cv, dtv, dtvd, Ftv, gtv, dgtv)
            kst, cst = joint_slopes(p.seat_stiffness, p.seat_damping, ds, -vv, Fs, gs, dgs)
            kseg, cseg = list(ks), list(cs)
            for j in {0, N}:
                if Fseg[j] <= 0.0:
                    kseg[j] = cseg[j] = 0.0
                elif F0 + ks[j] * D[j] < 0.0:
                    kseg[j] = 0.0
            out.update(
                kc=kc, cc=cc, kh=c.kh, cb=cb, ktv=ktv, ctv=ctv, ks=kst, cs=cst, kseg=kseg, cseg=cseg
            )
        return out

    # -- ODE interface -----------------------------------------------------------------
    def jacobian(self, t, y):
        """Analytic ∂ẏ/∂y from the local stiffness and damping of every element
        (friction's dependence on F and the accumulator rows are omitted: the friction
        effect on the motion is small and the accumulators do not feed back)."""
        n, N = self.n, self.N
        f = self.evaluate(t, y, jac=True)
        K = np.zeros((n, n))  # ∂(force)/∂q
        Cm = np.zeros((n, n))  # ∂(force)/∂q̇
        K[0, 0] -= f["kc"]  # cam contact: δ = s − x_t
        Cm[0, 0] -= f["cc"] + f["cb"]  # + bore friction
        stamp_element(K, Cm, 1, 0, f["ktv"], f["ctv"])  # tappet–valve: δ = x_t − x_v
        stamp_element(K, Cm, 1, -1, f["ks"], f["cs"])  # valve seat (to ground)
        kseg, cseg = f["kseg"], f["cseg"]
        for j in range(N + 1):  # coil segment j: nodes j+1, j+2 (q index)
            stamp_element(K, Cm, j + 1, j + 2 if j < N else -1, kseg[j], cseg[j])
        m = 2 * n + 2 + self.film_state
        J = np.zeros((m, m))
        J[:n, n : 2 * n] = np.eye(n)
        J[n : 2 * n, :n] = K * self.inv_mass[:, None]
        J[n : 2 * n, n : 2 * n] = Cm * self.inv_mass[:, None]
        if self.film_state:
            mg = np.zeros(n)
            mg[0] = self.inv_mass[0]  # F_c pushes the tappet (+x)
            self.film_jacobian(J, f, {0: -1.0}, mg)
        return J

    # -- energy ------------------------------------------------------------------------
    def energy(self, t: float, y, evaluated: dict | None = None) -> tuple[float, float]:
        """(kinetic, elastic) energy [J] relative to the static equilibrium state
        (``evaluated``: the output of :meth:`evaluate` at (t, y), if already known), by
        :func:`lumped_energies`."""
        f = self.evaluate(t, y) if evaluated is None else evaluated
        T, U = lumped_energies(self, np.asarray(y, dtype=float)[:, None], f["P"])
        return float(T[0]), float(U[0])


def lumped_energies(model, Y, P) -> tuple[np.ndarray, np.ndarray]:
    """(kinetic, elastic) energy [J] of :class:`ValvetrainModel` ``model`` relative to
    the static equilibrium state, at the columns of Y with contact force P [N]."""
    p, n, N = model.p, model.n, model.N
    V = Y[n : 2 * n]
    T = 0.5 * np.sum(model.mass[:, None] * V * V, axis=0)
    U = model.contact_potential(np.asarray(P, float))
    dtv = Y[0] - Y[1] - p.lash
    U = U + np.where(dtv > 0.0, 0.5 * p.tappet_valve_stiffness * dtv * dtv, 0.0)
    ds = model.d_seat - Y[1]
    U = U + 0.5 * p.seat_stiffness * (np.maximum(ds, 0.0) ** 2 - model.d_seat**2)
    xs = np.vstack([Y[1:2], Y[2:n], np.zeros((1, Y.shape[1]))])
    D = xs[:-1] - xs[1:]
    F0 = p.spring_preload
    kseg = np.asarray(model.kseg, float)[:, None]
    Useg = F0 * D + 0.5 * kseg * D * D
    for j in (0, N) if N > 0 else (0,):
        Useg[j] = np.where(F0 + kseg[j] * D[j] < 0.0, -0.5 * F0 * F0 / kseg[j], Useg[j])
    return T, U + Useg.sum(axis=0)

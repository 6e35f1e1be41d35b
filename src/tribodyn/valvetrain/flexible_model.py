"""Equations of motion of the flexible valvetrain (Craig–Bampton bodies + joints).

Coordinates q (deviations from static equilibrium on the base circle, +x = valve
opening): the boundary DOFs of the reduced bodies — tappet face (index 0), valve seat
face (index 1), valve groove, spring top, clash nodes, spring bottom — then the bodies' fixed-interface modal coordinates, then the camshaft twist φ
(lobe lag) when the camshaft is flexible. State y = [q, q̇, W_cam, D] (+ the film h with
a :class:`~tribodyn.valvetrain.tribology.FilmStateTribology`) as in
:class:`~tribodyn.valvetrain.model.ValvetrainModel`, which this class mirrors (same
``evaluate`` outputs, so :func:`~tribodyn.valvetrain.simulate_valvetrain` runs either).

    M q̈ = −K q − C q̇ + Σ_joints g_j (F_j − F_j,static)

M, K, C are block-diagonal from the reduced bodies (plus J, k_t, c_t for φ). Each joint has
a deformation δ_j(q, t), a gradient g_j = −∂δ_j/∂q and a force F_j(δ, δ̇) ≥ 0:

* cam contact δ = s(θ_l) − x_face, θ_l = θ₀ + ωt − φ; elastic law δ_el = C P^0.9 (Palmgren) or
  P/k, plus P·c_bend (camshaft bending) and the film h(t, P) in series, as the lumped model;
  damping c_c g(P) δ̇; bore friction μ_b F_f tanh(ẋ/v_r) on the face;
* tappet–valve δ = x_face − x_groove − lash (stiffness: crown, shim, tip and the stem above
  the groove in series); valve seat δ = F₀/k_seat − x_seat;
* spring seat δ = x_groove − x_top + F₀/k_ss, spring support δ = x_bottom + F₀/k_sp (damping
  β k with the spring's β = 2ζ/ω₁);
* coil clash on spring elements between boundary nodes: Palmgren law of the wire overlap
  (:class:`~tribodyn.valvetrain.spring.HelicalSpring`).

Energy: T = ½q̇ᵀMq̇ (+ ½J((ω − φ̇)² − ω²)); U = ½qᵀKq + f_sᵀq + Σ[Φ_j(δ) − Φ_j(δ_s)] (+ ½k_tφ²),
f_s the static joint forces on the nodes; the drive work W_cam = ∫T_d ω dt (rigid
camshaft: ∫(F_c ω s' + F_f u_s) dt) and the dissipation are integrated with the motion.
"""

from __future__ import annotations

import math

import numpy as np

from .cams import CamProfile
from .contact_law import _PALMGREN_EXP, CamContactModel, joint_force, joint_slopes, smooth_step
from .flexible import FlexibleValvetrain
from .tribology import TribologyModel

__all__ = ["FlexibleValvetrainModel"]


class FlexibleValvetrainModel(CamContactModel):
    """Right-hand side, Jacobian, forces and energies of the flexible valvetrain."""

    def __init__(
        self,
        cam: CamProfile,
        flex: FlexibleValvetrain,
        cam_speed: float,
        tribology: TribologyModel,
        start_angle: float = 0.0,
    ):
        self._bind(cam, flex, cam_speed, tribology, start_angle)
        self.flex = flex
        self.p = p = flex.joints
        bodies = flex.reduced_bodies(cam.max_lift)
        self.bodies = bodies
        spring = flex.spring
        self.F0 = F0 = spring.preload
        st = spring.statics(spring.installed_compression)
        # ---- global numbering: boundary DOFs first, then modes, then φ ---------------
        names = ["face", "seat", "groove"]
        tb, vb, sb = bodies["tappet"], bodies["valve"], bodies["spring"]
        spring_nodes = sb.boundary
        names += [f"s{j}" for j in spring_nodes]
        idx = {nm: i for i, nm in enumerate(names)}
        nb = len(names)
        gmap = {
            "tappet": [idx["face"]],
            "valve": [idx["seat"], idx["groove"]],
            "spring": [idx[f"s{j}"] for j in spring_nodes],
        }
        k = nb
        for name, body in (("tappet", tb), ("valve", vb), ("spring", sb)):
            nm = body.n - len(body.boundary)
            gmap[name] = gmap[name] + list(range(k, k + nm))
            k += nm
        self.cs = cs = flex.camshaft
        self.iphi = k if cs is not None else None
        n = k + (1 if cs is not None else 0)
        self.n = n
        self.gmap = gmap
        M = np.zeros((n, n))
        K = np.zeros((n, n))
        C = np.zeros((n, n))
        for name, body in (("tappet", tb), ("valve", vb), ("spring", sb)):
            g = gmap[name]
            M[np.ix_(g, g)] += body.M
            K[np.ix_(g, g)] += body.K
            C[np.ix_(g, g)] += body.C
        if cs is not None:
            J = cs.inertia(cam, p.cam_width)
            kt = cs.torsional_stiffness
            M[k, k], K[k, k] = J, kt
            C[k, k] = 2.0 * cs.torsional_damping_ratio * math.sqrt(kt * J)
            self.J, self.kt, self.ct = J, kt, C[k, k]
        else:
            self.J = self.kt = self.ct = 0.0
        self.M, self.K, self.C = M, K, C
        self.Minv = np.linalg.inv(M)
        self.MinvK = self.Minv @ K
        self.MinvC = self.Minv @ C
        self.i_face, self.i_seat, self.i_groove = idx["face"], idx["seat"], idx["groove"]
        self.k_tv = flex.tappet_valve_stiffness
        self.i_top = idx[f"s{spring_nodes[0]}"]
        self.i_bot = idx[f"s{spring_nodes[-1]}"]
        # ---- joints --------------------------------------------------------------------
        self.d_seat = F0 / flex.valve.seat_stiffness
        self.d_ss = F0 / p.spring_seat_stiffness
        self.d_sp = F0 / p.spring_support_stiffness
        w1 = (
            2.0
            * math.pi
            * (
                sb.interior_frequencies[0]
                if sb.interior_frequencies.size
                else spring.surge_frequency()
            )
        )
        self.beta_s = 2.0 * spring.damping_ratio / w1
        gel = spring._elements()[2]
        self.clash = []  # elements between boundary nodes: (global a, global b, Δ_static, g, Q_s)
        self.internal_clash = []  # elements reduced into the modes: (j, Δ_static, g)
        for j in range(gel.size):
            d0, gap = float(st.compressions[j]), float(gel[j])
            if j in spring_nodes and j + 1 in spring_nodes:
                Qs = spring.clash_force(st.compressions[j] - gel[j])[0]
                self.clash.append((idx[f"s{j}"], idx[f"s{j + 1}"], d0, gap, Qs))
            else:
                self.internal_clash.append((j, d0, gap))
        fs = np.zeros(n)  # static joint forces on the nodes (seat, groove, spring ends)
        fs[[self.i_seat, self.i_groove, self.i_top, self.i_bot]] = [F0, -F0, F0, -F0]
        for a, b, _, _, Qs in self.clash:
            fs[a] -= Qs
            fs[b] += Qs
        self.f_static = fs
        # camshaft bending in series with the contact
        self._init_contact(tribology, 0.0 if cs is None else cs.bending_compliance)

    compilable = False  # no compiled right-hand side (solve_ivp path)

    PARAMS = FlexibleValvetrain

    def lobe_angle(self, t: float, y) -> float:
        """Lobe angle θ₀ + ωt − φ [rad]."""
        th = self.theta0 + self.w * t
        return th - y[self.iphi] if self.iphi is not None else th

    # -- forces --------------------------------------------------------------------------
    def evaluate(self, t: float, y, jac: bool = False) -> dict:
        p, n, w = self.p, self.n, self.w
        q = np.asarray(y[:n], dtype=float)
        v = np.asarray(y[n : 2 * n], dtype=float)
        ql, vl = q.tolist(), v.tolist()
        iphi = self.iphi
        phi = ql[iphi] if iphi is not None else 0.0
        phid = vl[iphi] if iphi is not None else 0.0
        ramp = p.damping_force_ramp
        fj = [0.0] * n
        elems = []  # (gradient dict, k, c) for the Jacobian
        diss = 0.0
        # cam contact (lobe angle θ₀ + ωt − φ, lobe speed ω − φ̇), friction there and in
        # the bore
        i_f = self.i_face
        vf = vl[i_f]
        hf = float(y[2 * n + 2]) if self.film_state else 0.0
        con = self.cam_contact(t, self.theta0 + w * t - phi, w - phid, ql[i_f], vf, hf)
        P, Fc, Ff, Fb, s1, us = con.P, con.Fc, con.Ff, con.Fb, con.s1, con.us
        fj[i_f] += Fc
        if iphi is not None:
            fj[iphi] += Fc * s1
        diss += (Fc - P) * con.dkd - P * con.hdot  # contact damping, work into the film
        if iphi is not None:
            fj[iphi] += Ff * (self.cam.base_radius + con.s)
        fj[i_f] -= Fb
        diss += Fb * vf + Ff * us
        gvec = {i_f: -1.0}  # ∂δ_kin/∂q
        if iphi is not None:
            gvec[iphi] = -s1
        kc, cc = con.kc, con.cc  # ∂F_c/∂δ_kin, ∂F_c/∂δ̇_kin (0 when the contact is open)
        if jac and con.on:
            elems.append((gvec, kc, cc))
        if jac:
            th_v = con.th_v
            cb = p.bore_friction_coefficient * Ff * (1.0 - th_v * th_v) / p.bore_friction_velocity
            elems.append(({i_f: 1.0}, 0.0, cb))

        def joint(a, b, d, dd, k, c, static):
            """Compressive joint between nodes a (pushed −x) and b (pushed +x; None:
            ground) with deformation d (total) and rate dd; returns the force."""
            nonlocal diss
            F, E, gg, dg = joint_force(k, c, d, dd, ramp)
            df = F - static
            if a is not None:
                fj[a] -= df
            if b is not None:
                fj[b] += df
            diss += (F - E) * dd
            if jac and F > 0.0:
                gv = {}
                if a is not None:
                    gv[a] = 1.0
                if b is not None:
                    gv[b] = gv.get(b, 0.0) - 1.0
                elems.append((gv, *joint_slopes(k, c, d, dd, F, gg, dg)))
            return F

        i_s, i_g = self.i_seat, self.i_groove
        Ftv = joint(  # tappet face – valve groove
            i_f,
            i_g,
            ql[i_f] - ql[i_g] - p.lash,
            vl[i_f] - vl[i_g],
            self.k_tv,
            p.tappet_valve_damping,
            0.0,
        )
        Fs = joint(
            None,
            i_s,
            self.d_seat - ql[i_s],
            -vl[i_s],
            self.flex.valve.seat_stiffness,
            p.seat_damping,
            self.F0,
        )
        kss, ksp = p.spring_seat_stiffness, p.spring_support_stiffness
        i_top, i_bot = self.i_top, self.i_bot
        Fss = joint(
            i_g,
            i_top,
            ql[i_g] - ql[i_top] + self.d_ss,
            vl[i_g] - vl[i_top],
            kss,
            self.beta_s * kss,
            self.F0,
        )
        Fsp = joint(i_bot, None, ql[i_bot] + self.d_sp, vl[i_bot], ksp, self.beta_s * ksp, self.F0)
        sp = self.flex.spring
        cdamp = sp.clash_damping
        for a, b, d0, g, Qs in self.clash:
            ov = d0 + ql[a] - ql[b] - g
            Q, dQ = sp.clash_force(ov)
            dd = vl[a] - vl[b]
            gg, dg = smooth_step(Q, ramp)
            F = Q + cdamp * gg * dd
            if F <= 0.0:
                F = 0.0
            fj[a] -= F - Qs
            fj[b] += F - Qs
            diss += (F - Q) * dd
            if jac and F > 0.0:
                elems.append(({a: 1.0, b: -1.0}, dQ * (1.0 + cdamp * dg * dd), cdamp * gg))
        fjv = np.array(fj)
        acc = self.Minv @ fjv - self.MinvK @ q - self.MinvC @ v
        diss += float(v @ (self.C @ v))
        if iphi is not None:
            Td = self.kt * phi + self.ct * phid
            cam_power = Td * w
        else:
            cam_power = Fc * w * s1 + Ff * us
        accl = acc.tolist()
        # output order: acc[0] tappet face, acc[1] valve seat face; Fseg[0] spring force on
        # the valve (spring seat), Fseg[-1] support force on the head
        out = con.outputs(
            Ftv=Ftv, Fs=Fs, Fseg=[Fss, Fsp], acc=accl, cam_power=cam_power, dissipation_rate=diss
        )
        if jac:
            out.update(elements=elems, kc=kc, cc=cc, kh=con.kh, grad=gvec)
        return out

    # -- ODE interface -----------------------------------------------------------------
    def jacobian(self, t, y):
        """∂ẏ/∂y from the bodies' K, C and each active joint's k g gᵀ, c g gᵀ (friction's
        force dependence and the accumulator rows omitted, as in the lumped model)."""
        n = self.n
        f = self.evaluate(t, y, jac=True)
        K = self.K.copy()
        C = self.C.copy()
        for gv, k, c in f["elements"]:
            items = list(gv.items())
            for i, gi in items:
                for j, gj in items:
                    K[i, j] += k * gi * gj
                    C[i, j] += c * gi * gj
        m = 2 * n + 2 + self.film_state
        J = np.zeros((m, m))
        J[:n, n : 2 * n] = np.eye(n)
        J[n : 2 * n, :n] = -self.Minv @ K
        J[n : 2 * n, n : 2 * n] = -self.Minv @ C
        if self.film_state:
            g = np.zeros(n)
            for i, gi in f["grad"].items():
                g[i] = gi
            self.film_jacobian(J, f, f["grad"], -(self.Minv @ g))
        return J

    # -- energy ------------------------------------------------------------------------
    def energy(self, t: float, y, evaluated: dict | None = None) -> tuple[float, float]:
        """(kinetic, elastic) energy [J] relative to the static equilibrium state."""
        n, p = self.n, self.p
        q = np.asarray(y[:n], dtype=float)
        v = np.asarray(y[n : 2 * n], dtype=float)
        T = 0.5 * float(v @ (self.M @ v))
        if self.iphi is not None:  # rotation of the lobe relative to ω: J(φ̇² − 2ωφ̇)/2
            T -= self.J * self.w * v[self.iphi]
        f = self.evaluate(t, y) if evaluated is None else evaluated
        U = 0.5 * float(q @ (self.K @ q)) + float(self.f_static @ q)
        U += self.contact_potential(f["P"])

        def pot(k, d, d0):
            return 0.5 * k * (max(d, 0.0) ** 2 - max(d0, 0.0) ** 2)

        U += pot(self.k_tv, q[self.i_face] - q[self.i_groove] - p.lash, -p.lash)
        U += pot(self.flex.valve.seat_stiffness, self.d_seat - q[self.i_seat], self.d_seat)
        U += pot(p.spring_seat_stiffness, q[self.i_groove] - q[self.i_top] + self.d_ss, self.d_ss)
        U += pot(p.spring_support_stiffness, q[self.i_bot] + self.d_sp, self.d_sp)
        sp = self.flex.spring
        c = sp._palmgren_c
        e = _PALMGREN_EXP

        def clash_pot(ov):  # ∫ Q dδ, Q = (δ/C)^(1/e)
            return 0.0 if ov <= 0.0 else (ov / c) ** (1.0 / e) * ov * e / (1.0 + e)

        for a, b, d0, g, _ in self.clash:
            U += clash_pot(d0 + q[a] - q[b] - g) - clash_pot(d0 - g)
        return T, U

    # -- diagnostics -----------------------------------------------------------------------
    def unresolved_clash(self, Y) -> float:
        """Largest wire overlap [m] of an element reduced into the modes (its clash is
        not modelled) over the columns of Y; ≤ 0 when none closed."""
        if not self.internal_clash:
            return -math.inf
        U = self.bodies["spring"].T @ np.asarray(Y)[self.gmap["spring"]]
        worst = -math.inf
        for j, d0, g in self.internal_clash:
            ov = d0 + U[j] - U[j + 1] - g
            worst = max(worst, float(np.max(ov)))
        return worst

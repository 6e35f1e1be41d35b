"""The discretised Reynolds system of the EHL line contact and its linearisation.

Scaled variables: P = p a/w, H = h R/a², X = x/a (a: length scale of the grid). Unknowns:
the total pressure Q = P + P_a (fluid + asperity) at the nodes and the rigid approach H₀.

* film (Eq. 9)          H = H₀ + X²/2 + K Q        (K: DC-FFT influence operator)
* asperities (Eq. 6)    P_a = k_a F_5/2(H/σ̄)       (Greenwood–Tripp, local)
* Reynolds (Eq. 1)      d/dX(ε dP/dX) − ū d(ρ̄H)/dX − c_t (ρ̄H − f_old) = 0,
                        ε = λ ρ̄ H³ μ₀/μ, λ = h_ref² p_ref/(12 μ₀ a U)
* load balance (Eq. 8)  ΔX Σ Q = 1

Finite volumes with arithmetic-mean face coefficients, second-order upwind Couette term
(first order next to the boundary), backward-difference time term (coefficient and old
level supplied by the transient driver). :meth:`ReynoldsSystem.evaluate` returns the
residuals with the banded derivatives A_P = ∂R/∂P, A_H = ∂R/∂H; :class:`Linearization`
assembles the Newton system for (δQ, δH₀) densely or applies it matrix-free.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ...physics.asperity import (
    greenwood_tripp,
    greenwood_tripp_derivative,
    greenwood_tripp_table,
)
from ...physics.elasticity import DeformationOperator
from .grid import Grid
from .options import Conditions, ContactModel

__all__ = ["ReynoldsSystem", "Evaluation", "Linearization", "band_apply"]


class ReynoldsSystem:
    """Scaled discrete system for one solve (one time level)."""

    def __init__(self, grid: Grid, cond: Conditions, model: ContactModel, time_coef=0.0,
                 f_old=None):
        w, R, ue = cond.load, cond.radius, cond.entrainment_speed
        lub, roughness = model.lubricant, model.roughness
        self.g = grid
        self.cond = cond
        self.model = model
        self.lub = lub
        self.rough = roughness
        a = grid.a
        self.p_ref = p_ref = w / a          # P = p a / w
        self.h_ref = h_ref = a * a / R      # H = h R / a²
        self.elastic = grid.elastic
        self._K = None
        if grid.elastic:
            kscale = self.kscale = p_ref / h_ref
            self.Kop = DeformationOperator.from_coefficients(grid.coef * kscale)
            self.kcoef = grid.coef * kscale
        else:
            self.Kop = None
            self.kcoef = None
        self.u_scale = max(abs(ue), 1e-3)
        self.ubar = ue / self.u_scale
        self.lam = h_ref**2 * p_ref / (12.0 * lub.viscosity * a * self.u_scale)
        self.geom = 0.5 * grid.X**2
        # time term: c_t (f − f_old) with f = ρ̄H, c_t = a/(U Δt)·α₀
        self.time_coef = time_coef * a / self.u_scale
        self.f_old = f_old
        # optional per-node factors of the generalized (thermal) Reynolds equation: the
        # Poiseuille coefficient ε and the Couette flux ū ρ̄H are multiplied by them
        # (None: isothermal Reynolds; see contact.ehl.thermal)
        self.flow_factor = None
        self.couette_factor = None
        self.h_floor = 1e-10 / h_ref
        if roughness is not None:
            self.ka = roughness.pressure_scale(model.e_surface) / p_ref
            self.sig = roughness.rms / h_ref
        n = grid.n
        # upwind second-order stencil for d/dX (ρ̄H) at node i: Σ_k c_k f[i − s k]
        s = 1 if self.ubar >= 0 else -1
        self.s = s
        idx = np.arange(n)
        self.up1 = np.clip(idx - s, 0, n - 1)
        self.up2 = np.clip(idx - 2 * s, 0, n - 1)
        second = (idx - 2 * s >= 0) & (idx - 2 * s <= n - 1)
        self.c0 = np.where(second, 1.5, 1.0)
        self.c1 = np.where(second, -2.0, -1.0)
        self.c2 = np.where(second, 0.5, 0.0)

    @property
    def K(self):
        """Scaled dense influence matrix (built on first use)."""
        if self.elastic and self._K is None:
            self._K = self.g.K * self.kscale
        return self._K

    # -- asperities and film
    def asperity(self, H):
        """Scaled Greenwood–Tripp pressure Pa(H) and D = dPa/dH."""
        if self.rough is None:
            z = np.zeros_like(H)
            return z, z
        lam = H / self.sig
        m = self.rough.method
        if m == "exact":
            f, df = greenwood_tripp_table(2.5, lam)
        else:
            f, df = greenwood_tripp(2.5, lam, m), greenwood_tripp_derivative(2.5, lam, m)
        return self.ka * f, self.ka / self.sig * df

    def film(self, Q, H0):
        """H = H0 + X²/2 + K Q: the surfaces deform under the total pressure Q = P + Pa."""
        if not self.elastic:
            return H0 + self.geom
        return H0 + self.geom + self.Kop(Q)

    # -- residual and banded derivatives
    def evaluate(self, Q, H0):
        """Residuals and banded derivatives at (Q, H0).

        Returns an :class:`Evaluation` with the Reynolds residual R (interior rows), the load
        residual ΔX ΣQ − 1, the fluid pressure P = Q − Pa(H), the film H, D = dPa/dH and
        the diagonals of A_P = ∂R/∂P, A_H = ∂R/∂H (offsets −2…2)."""
        g, lub = self.g, self.lub
        n, dX = g.n, g.dX
        H = self.film(Q, H0)
        pa, dpa = self.asperity(H)
        P = Q - pa
        p = P * self.p_ref
        rho = lub.density_at(p) / lub.density
        drho = lub.ddensity_dp(p) / lub.density * self.p_ref
        lnmu = lub.log_viscosity_ratio(p)
        dlnmu = lub.dlog_viscosity_dp(p) * self.p_ref
        Hf = np.maximum(H, self.h_floor)
        dHf = (H > self.h_floor).astype(float)
        eps = self.lam * rho * Hf**3 * np.exp(-lnmu)
        deps_dP = eps * (drho / rho - dlnmu)
        deps_dH = 3.0 * eps / Hf * dHf
        if self.flow_factor is not None:
            eps, deps_dP, deps_dH = (v * self.flow_factor for v in (eps, deps_dP, deps_dH))
        f = rho * H
        df_dP = drho * H
        df_dH = rho
        fc, dfc_dP, dfc_dH = f, df_dP, df_dH      # Couette flux ρ̄H (× factor if thermal)
        if self.couette_factor is not None:
            fc, dfc_dP, dfc_dH = (v * self.couette_factor for v in (f, df_dP, df_dH))

        R = np.zeros(n)
        ef = 0.5 * (eps[1:] + eps[:-1])           # face i+½, i = 0..n−2
        flux = ef * np.diff(P)                    # ε ∂P at faces
        R[1:-1] = (flux[1:] - flux[:-1]) / dX**2
        # upwind stencil Σ c_k f[i − s k] approximates s·df/dX, so −ū df/dX = −|ū| Σ …
        cou = -abs(self.ubar) * (self.c0 * fc + self.c1 * fc[self.up1]
                                 + self.c2 * fc[self.up2]) / dX
        R[1:-1] += cou[1:-1]
        if self.time_coef:
            R[1:-1] -= self.time_coef * (f[1:-1] - self.f_old[1:-1])
        load = dX * np.sum(Q) - 1.0

        AP = {d: np.zeros(n) for d in (-2, -1, 0, 1, 2)}
        AH = {d: np.zeros(n) for d in (-2, -1, 0, 1, 2)}
        i = np.arange(1, n - 1)
        efp, efm = ef[i], ef[i - 1]               # faces i+½, i−½
        AP[1][i] += efp / dX**2
        AP[-1][i] += efm / dX**2
        AP[0][i] += -(efp + efm) / dX**2
        cp = (P[i + 1] - P[i]) / (2 * dX**2)      # through ε at nodes i−1, i, i+1
        cm = (P[i] - P[i - 1]) / (2 * dX**2)
        AP[1][i] += cp * deps_dP[i + 1]
        AP[0][i] += (cp - cm) * deps_dP[i]
        AP[-1][i] += -cm * deps_dP[i - 1]
        AH[1][i] += cp * deps_dH[i + 1]
        AH[0][i] += (cp - cm) * deps_dH[i]
        AH[-1][i] += -cm * deps_dH[i - 1]
        s = self.s
        for ck, off in ((self.c0, 0), (self.c1, -s), (self.c2, -2 * s)):
            coef = -abs(self.ubar) * ck[i] / dX
            valid = (i + off >= 0) & (i + off <= n - 1)
            AP[off][i] += np.where(valid, coef * dfc_dP[np.clip(i + off, 0, n - 1)], 0.0)
            AH[off][i] += np.where(valid, coef * dfc_dH[np.clip(i + off, 0, n - 1)], 0.0)
        if self.time_coef:
            AP[0][i] += -self.time_coef * df_dP[i]
            AH[0][i] += -self.time_coef * df_dH[i]
        return Evaluation(R, load, P, H, pa, dpa, AP, AH)


@dataclass
class Evaluation:
    R: np.ndarray
    load: float
    P: np.ndarray
    H: np.ndarray
    pa: np.ndarray
    dpa: np.ndarray
    AP: dict
    AH: dict


def band_apply(diags, v):
    """y_i = Σ_d A_d[i] v[i+d] for a banded matrix stored by diagonals."""
    n = v.size
    y = diags[0] * v
    for d, a in diags.items():
        if d > 0:
            y[: n - d] += a[: n - d] * v[d:]
        elif d < 0:
            y[-d:] += a[-d:] * v[: n + d]
    return y


class Linearization:
    """Newton system for (δQ, δH₀) at one iterate, usable as a dense matrix (for LU) or
    matrix-free (J·z costs one DC-FFT plus banded work, for preconditioned GMRES).

    With H = H₀ + X²/2 + K Q and P = Q − Pa(H): δH = K δQ + δH₀, δP = δQ − D δH, so
    δR = A_P δQ + B (K δQ + δH₀), B = A_H − A_P D (banded). Rows: boundary nodes δQ = 0;
    cavitated nodes δP_i = −P_i, i.e. δQ_i − D_i (K δQ + δH₀)_i = −P_i; free nodes
    c_i [A_P δQ + B K δQ + B 1 δH₀] = −c_i R_i; load row ΔX Σ δQ = −(ΔX ΣQ − 1).
    """

    def __init__(self, sysm: ReynoldsSystem, c, cav, ev: Evaluation):
        g = sysm.g
        n = g.n
        self.n, self.dX, self.sysm = n, g.dX, sysm
        self.rigid = not sysm.elastic
        self.AP = ev.AP
        D = ev.dpa
        self.D = D
        self.B = {}
        for d, v in ev.AH.items():
            b = v.copy()
            lo, hi = max(0, -d), min(n, n - d)
            b[lo:hi] -= ev.AP[d][lo:hi] * D[lo + d:hi + d]
            self.B[d] = b
        self.col = sum(self.B.values())                # B·1
        self.cav = cav.copy()
        self.bnd = np.zeros(n, dtype=bool)
        self.bnd[0] = self.bnd[-1] = True
        self.cav[0] = self.cav[-1] = False
        self.free = ~(self.cav | self.bnd)
        self.c = c
        rhs = -ev.R.copy()
        rhs[self.free] *= c[self.free]
        rhs[self.cav] = -ev.P[self.cav]
        rhs[self.bnd] = -ev.P[self.bnd]
        self.rhs = np.concatenate([rhs, [-ev.load]])

    def matvec(self, z):
        n = self.n
        v, vh = z[:n], z[n]
        dh = (np.zeros_like(v) if self.rigid else self.sysm.Kop(v)) + vh      # δH
        y = band_apply(self.AP, v) + band_apply(self.B, dh - vh) + self.col * vh
        y[self.free] *= self.c[self.free]
        y[self.cav] = v[self.cav] - self.D[self.cav] * dh[self.cav]
        y[self.bnd] = v[self.bnd]
        return np.concatenate([y, [self.dX * np.sum(v)]])

    def dense(self):
        n = self.n
        J = np.zeros((n + 1, n + 1))
        idx = np.arange(n)
        for d, v in self.AP.items():
            rows = np.arange(max(0, -d), min(n, n - d))
            J[rows, rows + d] += v[rows]
        K = self.sysm.K
        if K is not None:
            for d, v in self.B.items():           # contiguous slices: no fancy-index copies
                lo, hi = max(0, -d), min(n, n - d)
                J[lo:hi, :n] += v[lo:hi, None] * K[lo + d:hi + d, :]
        J[:n, n] = self.col
        J[:n] *= np.where(self.free, self.c, 1.0)[:, None]
        ic = idx[self.cav]
        if ic.size:
            J[ic, :] = 0.0
            if K is not None:
                J[ic, :n] = -self.D[ic, None] * K[ic, :]
            J[ic, ic] += 1.0
            J[ic, n] = -self.D[ic]
        for b in (0, n - 1):
            J[b, :] = 0.0
            J[b, b] = 1.0
        J[n, :n] = self.dX
        J[n, n] = 0.0
        return J


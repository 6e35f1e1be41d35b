"""Mixed elastohydrodynamic line contact: steady and transient (paper Section 2.4, Eqs. 1–9).

Equations (x in the frame of the contact point, u_e the mean entraining speed):

* Reynolds (Eq. 1)      ∂/∂x(ρh³/(12μ) ∂p/∂x) − u_e ∂(ρh)/∂x − ∂(ρh)/∂t = 0
* cavitation            p ≥ 0, Reynolds residual ≤ 0, p·residual = 0 (complementarity;
                        the Reynolds exit condition p = dp/dx = 0, Eq. 4, emerges)
* film (Eq. 9)          h = h₀ + x²/(2R) + V(x),  V = K (p + p_a)   (DC-FFT, coated or not)
* asperities (Eq. 6)    p_a = (8√2/15)π(ηβσ)²√(σ/β) E' F_5/2(h/σ), local, load-carrying
* load balance (Eq. 8)  ∫(p + p_a) dx = w
* rheology              Roelands (or Barus) μ(p), Dowson–Higginson ρ(p)

Discretisation: uniform grid (needed by DC-FFT), finite volumes with arithmetic-mean
face coefficients, second-order upwind Couette term (first order next to the inlet),
backward-difference (BDF1/BDF2) time derivative. Unknowns p_i and h₀ are found by a
semismooth Newton method on min(p_i, −c_i R_i) = 0 with a dense Jacobian
J = A_p + A_h S, S = ∂h/∂p = (I − K D_a)⁻¹ K (D_a = dp_a/dh; Woodbury on the asperity-
active set), and an Armijo line search. Cold starts go through load continuation when
the direct Newton iteration fails.

Scaling: a = max(b, √(2R h_est)) (b: Hertz half-width; h_est: Moes central film) so
that both elastic and rigid (inlet-dominated) contacts get a sufficient domain;
P = p a/w, H = h R/a², X = x/a.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy import linalg

from .._validation import InputError, check_nonnegative, check_positive, check_real
from ..physics.asperity import (Roughness, greenwood_tripp, greenwood_tripp_derivative,
                                greenwood_tripp_table)
from ..physics.elasticity import DeformationOperator, influence_coefficients
from ..physics.friction import (BOUNDARY_SHEAR_STRENGTH, VISCOUS_MODELS,
                                boundary_shear_stress, couette_shear_stress,
                                limit_shear_stress)
from ..physics.lubricant import Lubricant
from ..physics.materials import _as_bodies, reduced_modulus
from ..physics.regimes import hamrock_groups, moes_central

__all__ = ["EHLResult", "EHLOptions", "solve_ehl", "TransientEHL"]
_NONMONOTONE = 6
_TRACE = False
_WATCHDOG = 100.0
_COARSEST = 128
_MAX_KRYLOV = 30
_MAX_KRYLOV_BEFORE_REFACTOR = 12
_MAX_KRYLOV_TWO_GRID = 200
_N_MAX_AUTO = 4096       # largest automatic grid
#: automatic grid: refine while h_c or h_min change by more than this from n/2 to n
_GRID_REFINE_CHANGE = 0.01
_N_DENSE = 1024          # finer grids are solved with the two-grid preconditioner


# ----------------------------------------------------------------------------- options
@dataclass(frozen=True)
class EHLOptions:
    """Numerical settings of the EHL solvers.

    n : grid nodes (uniform); None (default) sizes the grid so that its spacing is
        s/46, s = √(2R h_est) the rigid inlet length (h_est: Moes central film), rounded
        up to a multiple of 128 and clipped to [512, 4096]; in the elastic regime this is
        n ≈ 265 κ, κ = b/s (κ ≈ 1 light load, ≈ 6 at Moes M = 100). A steady solve then
        checks its result against the nested solution on half the nodes and doubles n
        (up to 4096) while h_c or h_min differ by more than 1 %: with the scheme's
        1.5–2nd order convergence, h_c and h_min then change by < 0.5 % when n doubles.
    inlet, outlet : domain extent upstream/downstream of the contact centre in Hertz
        half-widths b (elastic contacts) …
    inlet_truncation : … and upstream at least as far as the truncated inlet loses this
        share of the load. Far upstream p ≈ 16μ₀u_eR²/|x|³ (Reynolds with h ≈ x²/2R);
        cutting the inlet at x_in costs ≈ 24μ₀|u_e|R²/(x_in² w) of the load (the same
        estimate is reported as ``inlet_load_deficit``), so x_in = R√(24μ₀|u_e|/(ε w)).
        This sets the domain of light, hydrodynamic contacts (x_in ≈ 22√(2R h₀) for the
        rigid isoviscous cylinder at ε = 0.5 %).
    inlet_rigid, outlet_rigid : … and in rigid inlet lengths s = √(2R h_est) (squeeze
        films near u_e = 0, whose far-field pressure decays as |x|⁻⁴).
    tol : Newton tolerance on the scaled pressure/film update and residual.
    max_iter : Newton iterations per solve.
    elastic : False treats both bodies as rigid (hydrodynamic validation cases).
    viscous_model, limiting_shear : friction laws (see physics.friction).
    boundary_shear_strength, boundary_shear_coefficient : τ₀ and ς of Eq. 17.
    time_order : 1 (backward Euler) or 2 (BDF2) for the transient term.
    """

    n: int | None = None
    inlet: float = 4.0
    outlet: float = 1.75
    inlet_truncation: float = 0.005
    inlet_rigid: float = 4.0
    outlet_rigid: float = 2.0
    tol: float = 1e-9
    max_iter: int = 60
    elastic: bool = True
    viscous_model: str = "eyring"
    limiting_shear: bool = True
    boundary_shear_strength: float = BOUNDARY_SHEAR_STRENGTH
    boundary_shear_coefficient: float = 0.185
    time_order: int = 2

    def __post_init__(self):
        if self.n is not None and int(self.n) < 32:
            raise InputError(f"n must be >= 32 or None for automatic (got {self.n})")
        for name in ("inlet", "outlet", "inlet_rigid", "outlet_rigid"):
            v = check_positive(name, getattr(self, name))
            if v < 1.0:
                raise InputError(f"{name} must be >= 1 length scale (got {v:g})")
        if self.n is not None and int(self.n) > 65536:
            raise InputError(f"n must be <= 65536 (got {self.n})")
        t = check_positive("inlet_truncation", self.inlet_truncation)
        if t > 0.1:
            raise InputError(f"inlet_truncation must be in (0, 0.1] (got {t:g})")
        check_positive("tol", self.tol)
        if int(self.max_iter) < 1:
            raise InputError(f"max_iter must be >= 1 (got {self.max_iter})")
        if self.viscous_model not in VISCOUS_MODELS:
            raise InputError(f"viscous_model must be one of {VISCOUS_MODELS} "
                             f"(got {self.viscous_model!r})")
        check_nonnegative("boundary_shear_strength", self.boundary_shear_strength, "Pa")
        check_nonnegative("boundary_shear_coefficient", self.boundary_shear_coefficient)
        if self.time_order not in (1, 2):
            raise InputError(f"time_order must be 1 or 2 (got {self.time_order})")


# ----------------------------------------------------------------------------- result
@dataclass
class EHLResult:
    """Line-contact EHL solution (per unit length, SI). Friction forces are magnitudes."""

    x: np.ndarray                   #: node positions [m] (contact frame)
    pressure: np.ndarray            #: hydrodynamic pressure p [Pa]
    asperity_pressure: np.ndarray   #: Greenwood–Tripp asperity pressure p_a [Pa]
    film: np.ndarray                #: film thickness h [m]
    central_film: float             #: h at x = 0 [m]
    min_film: float                 #: min h [m]
    min_film_position: float        #: x of min h [m]
    cavitation_position: float      #: outlet meniscus (p → 0) [m]
    rigid_approach: float           #: h₀ (includes the 2-D elastic constant) [m]
    load: float                     #: imposed w [N/m]
    hydrodynamic_load: float        #: ∫p dx [N/m]
    asperity_load: float            #: ∫p_a dx [N/m]
    viscous_friction: float         #: ∫|τ_couette| dx [N/m]
    rolling_friction: float         #: ∫(h/2)|dp/dx| dx, Poiseuille part of Eq. 16 [N/m]
    boundary_friction: float        #: ∫(τ₀ A_a/A + ς p_a) dx [N/m]
    entrainment_speed: float
    sliding_speed: float
    radius: float
    converged: bool
    iterations: int
    message: str
    time: float = 0.0
    squeeze_velocity: float = 0.0   #: −dh_c/dt, approach speed of the central film [m/s]
    shear_stress: np.ndarray = field(default=None, repr=False)   #: viscous τ(x) [Pa]
    inlet_load_deficit: float = 0.0  #: estimated share of w lost to the truncated inlet

    @property
    def friction(self) -> float:
        """Viscous + boundary friction [N/m]."""
        return self.viscous_friction + self.boundary_friction

    @property
    def friction_coefficient(self) -> float:
        return self.friction / self.load

    def totals(self, width: float) -> dict:
        """Loads [N] and friction forces [N] over a contact width [m]."""
        width = check_positive("width", width, "m")
        return {k: getattr(self, k) * width for k in (
            "load", "hydrodynamic_load", "asperity_load", "viscous_friction",
            "rolling_friction", "boundary_friction", "friction")}


# ----------------------------------------------------------------------------- helpers
def _with_overrides(opts: EHLOptions, overrides: dict) -> EHLOptions:
    unknown = sorted(set(overrides) - set(opts.__dict__))
    if unknown:
        raise InputError(f"unknown EHL option(s) {', '.join(unknown)}; valid: "
                         f"{', '.join(sorted(opts.__dict__))}")
    return EHLOptions(**{**opts.__dict__, **overrides})


def _check_inputs(load, radius, entrainment_speed, sliding_speed):
    w = check_positive("load", load, "N/m")
    r = check_positive("radius", radius, "m")
    ue = check_real("entrainment_speed", entrainment_speed, "m/s")
    us = check_real("sliding_speed", sliding_speed, "m/s")
    return w, r, ue, us


def _check_models(bodies, lubricant, roughness):
    bodies = _as_bodies(bodies)
    if not isinstance(lubricant, Lubricant):
        raise InputError(f"lubricant must be a Lubricant (got {type(lubricant).__name__})")
    if roughness is not None and not isinstance(roughness, Roughness):
        raise InputError(f"roughness must be a Roughness or None (got {type(roughness).__name__})")
    return bodies


def _domain(b, s, w, R, ue, mu0, opts) -> tuple[float, float]:
    """Upstream and downstream extent [m]: the largest of the elastic (b), the inlet
    truncation and the rigid (s) requirements (see :class:`EHLOptions`)."""
    x_trunc = R * math.sqrt(24.0 * mu0 * abs(ue) / (opts.inlet_truncation * w))
    return (max(opts.inlet * b, x_trunc, opts.inlet_rigid * s),
            max(opts.outlet * b, opts.outlet_rigid * s))


def _auto_nodes(length, s) -> int:
    """Default grid size: spacing s/46, multiple of 128 in [512, _N_MAX_AUTO]."""
    return int(min(_N_MAX_AUTO, max(512, 128 * math.ceil(46.0 * length / s / 128.0))))


def _layout(w, R, ue, e_bulk, lub, opts, squeeze_film=None):
    """(a, b, h_est, inlet/a, outlet/a, n) of the grid for these conditions."""
    a, b, h_est = _length_scale(w, R, ue, e_bulk, lub, squeeze_film)
    s = math.sqrt(2.0 * R * h_est)
    up, down = _domain(b, s, w, R, ue, lub.viscosity, opts)
    length = up + (down if ue != 0.0 else up)
    n = int(opts.n) if opts.n is not None else _auto_nodes(length, s)
    return a, b, h_est, up / a, down / a, n


def _length_scale(w, R, ue, e_bulk, lub: Lubricant, squeeze_film=None):
    """a = max(b, √(2R h_est)); h_est from Moes (or the squeeze film when u_e ≈ 0)."""
    b = math.sqrt(8.0 * w * R / (math.pi * e_bulk))
    u = max(abs(ue), 1e-3)
    W, U, G = hamrock_groups(w, R, u, lub.viscosity, lub.pressure_viscosity, e_bulk)
    h_est = float(moes_central(W, U, G, R))
    if squeeze_film is not None:
        h_est = max(h_est, squeeze_film)
    return max(b, math.sqrt(2.0 * R * h_est)), b, h_est


class _Grid:
    """Uniform grid in the contact frame (metres) with the physical influence matrix.

    Holds geometry only; pressure/film scales belong to each solve, so a grid (and the LU
    preconditioner built on it) survives changes of load and radius in a transient.
    """

    def __init__(self, bodies, a, inlet, outlet, n, direction, elastic):
        self.a, self.n, self.direction = a, n, direction
        # upstream side is −x for u_e > 0; mirrored for u_e < 0; symmetric for pure squeeze
        if direction > 0:
            lo, hi = -inlet, outlet
        elif direction < 0:
            lo, hi = -outlet, inlet
        else:
            lo, hi = -inlet, inlet
        self.X = np.linspace(lo, hi, n)
        self.dX = self.X[1] - self.X[0]
        self.x = self.X * a
        self.i0 = int(np.argmin(np.abs(self.X)))
        self.coef = influence_coefficients(bodies, self.dX * a, n) if elastic else None
        self.elastic = bool(elastic)
        self._K = None

    @property
    def K(self):
        """Dense influence matrix [m/Pa] (built on first use: only LU paths need it)."""
        if self.elastic and self._K is None:
            self._K = linalg.toeplitz(self.coef)
        return self._K

    def same_as(self, a, inlet, outlet, n, direction):
        """Same node count and orientation, extents within 2 %."""
        x0, x1 = self.x[0], self.x[-1]
        lo, hi = (-inlet * a, outlet * a) if direction > 0 else (
            (-outlet * a, inlet * a) if direction < 0 else (-inlet * a, inlet * a))
        return (self.n == n and self.direction == direction
                and abs(lo / x0 - 1.0) < 0.02 and abs(hi / x1 - 1.0) < 0.02)


# ----------------------------------------------------------------------------- core
class _ReynoldsSystem:
    """Scaled discrete system for one solve (one time level)."""

    def __init__(self, grid: _Grid, w, R, ue, lub: Lubricant, roughness, e_surface,
                 time_coef=0.0, f_old=None):
        self.g = grid
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
        self.h_floor = 1e-10 / h_ref
        if roughness is not None:
            self.ka = roughness.pressure_scale(e_surface) / p_ref
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

        Returns an :class:`_Eval` with the Reynolds residual R (interior rows), the load
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
        f = rho * H
        df_dP = drho * H
        df_dH = rho

        R = np.zeros(n)
        ef = 0.5 * (eps[1:] + eps[:-1])           # face i+½, i = 0..n−2
        flux = ef * np.diff(P)                    # ε ∂P at faces
        R[1:-1] = (flux[1:] - flux[:-1]) / dX**2
        # upwind stencil Σ c_k f[i − s k] approximates s·df/dX, so −ū df/dX = −|ū| Σ …
        cou = -abs(self.ubar) * (self.c0 * f + self.c1 * f[self.up1] + self.c2 * f[self.up2]) / dX
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
            AP[off][i] += np.where(valid, coef * df_dP[np.clip(i + off, 0, n - 1)], 0.0)
            AH[off][i] += np.where(valid, coef * df_dH[np.clip(i + off, 0, n - 1)], 0.0)
        if self.time_coef:
            AP[0][i] += -self.time_coef * df_dP[i]
            AH[0][i] += -self.time_coef * df_dH[i]
        return _Eval(R, load, P, H, pa, dpa, AP, AH)


@dataclass
class _Eval:
    R: np.ndarray
    load: float
    P: np.ndarray
    H: np.ndarray
    pa: np.ndarray
    dpa: np.ndarray
    AP: dict
    AH: dict


def _band_apply(diags, v):
    """y_i = Σ_d A_d[i] v[i+d] for a banded matrix stored by diagonals."""
    n = v.size
    y = diags[0] * v
    for d, a in diags.items():
        if d > 0:
            y[: n - d] += a[: n - d] * v[d:]
        elif d < 0:
            y[-d:] += a[-d:] * v[: n + d]
    return y


class _Linearization:
    """Newton system for (δQ, δH₀) at one iterate, usable as a dense matrix (for LU) or
    matrix-free (J·z costs one DC-FFT plus banded work, for preconditioned GMRES).

    With H = H₀ + X²/2 + K Q and P = Q − Pa(H): δH = K δQ + δH₀, δP = δQ − D δH, so
    δR = A_P δQ + B (K δQ + δH₀), B = A_H − A_P D (banded). Rows: boundary nodes δQ = 0;
    cavitated nodes δP_i = −P_i, i.e. δQ_i − D_i (K δQ + δH₀)_i = −P_i; free nodes
    c_i [A_P δQ + B K δQ + B 1 δH₀] = −c_i R_i; load row ΔX Σ δQ = −(ΔX ΣQ − 1).
    """

    def __init__(self, sysm: _ReynoldsSystem, c, cav, ev: _Eval):
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
        y = _band_apply(self.AP, v) + _band_apply(self.B, dh - vh) + self.col * vh
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


def _gmres(lin: _Linearization, lu, rtol, max_it=None):
    """Right-preconditioned GMRES for lin·x = rhs with an earlier LU (or any object with
    a ``solve`` method) as preconditioner,
    started from the preconditioned solution. Returns (x, iterations) or (None, its)."""
    max_it = max_it or _MAX_KRYLOV
    b = lin.rhs
    bn = float(np.linalg.norm(b))
    if bn == 0.0:
        return np.zeros_like(b), 0
    if hasattr(lu, "solve"):              # a preconditioner object
        prec = lu.solve
    else:                                 # an LU factorisation from lu_factor
        prec = lambda v: linalg.lu_solve(lu, v, check_finite=False)  # noqa: E731
    x0 = prec(b)
    r0 = b - lin.matvec(x0)
    beta = float(np.linalg.norm(r0))
    if not np.isfinite(beta):
        return None, 0
    if beta <= rtol * bn:
        return x0, 0
    V = np.zeros((max_it + 1, b.size))
    Hm = np.zeros((max_it + 1, max_it))
    cs, sn = np.zeros(max_it), np.zeros(max_it)
    gv = np.zeros(max_it + 1)
    gv[0] = beta
    V[0] = r0 / beta
    for j in range(max_it):
        w = lin.matvec(prec(V[j]))
        for i in range(j + 1):
            Hm[i, j] = np.dot(w, V[i])
            w -= Hm[i, j] * V[i]
        Hm[j + 1, j] = np.linalg.norm(w)
        if Hm[j + 1, j] > 0.0:
            V[j + 1] = w / Hm[j + 1, j]
        for i in range(j):
            t = cs[i] * Hm[i, j] + sn[i] * Hm[i + 1, j]
            Hm[i + 1, j] = -sn[i] * Hm[i, j] + cs[i] * Hm[i + 1, j]
            Hm[i, j] = t
        den = math.hypot(Hm[j, j], Hm[j + 1, j])
        if den == 0.0:
            return None, j + 1
        cs[j], sn[j] = Hm[j, j] / den, Hm[j + 1, j] / den
        Hm[j, j] = den
        Hm[j + 1, j] = 0.0
        gv[j + 1] = -sn[j] * gv[j]
        gv[j] = cs[j] * gv[j]
        if abs(gv[j + 1]) <= rtol * bn or j == max_it - 1:
            if abs(gv[j + 1]) > rtol * bn:
                return None, j + 1
            y = linalg.solve_triangular(Hm[: j + 1, : j + 1], gv[: j + 1], check_finite=False)
            return x0 + prec(V[: j + 1].T @ y), j + 1
    return None, max_it


def _release(cav_std, prev_cav, release):
    """Free `release` cavitated nodes ahead of each node that has just left the cavitated
    set (the boundary is moving outward). The Reynolds LCP otherwise moves a free boundary
    by one node per active-set update; nodes freed too far re-cavitate together in the
    next update, so the boundary is found in O(log) iterations."""
    cav = cav_std.copy()
    if prev_cav is None or release <= 1:
        return cav
    n = cav.size
    for j in np.flatnonzero(prev_cav & ~cav_std):
        for d in (1, -1):
            if 0 < j + d < n - 1 and cav_std[j + d] and not cav_std[j - d]:
                k, cnt = j + d, 1
                while cnt < release and 0 < k < n - 1 and cav[k]:
                    cav[k] = False
                    k += d
                    cnt += 1
    return cav


@dataclass
class _State:
    """Scaled solution: total pressure Q = P + Pa (the unknown), h₀, and derived P, H."""

    Q: np.ndarray
    H0: float
    P: np.ndarray = None
    H: np.ndarray = None


def _jacobi_scale(sysm, ev):
    """c_i ≈ 1/|J_ii|, J = A_P + B K (only a scaling of the rows)."""
    n = sysm.g.n
    diag = ev.AP[0].copy()
    if sysm.kcoef is not None:
        for d, v in ev.AH.items():
            rows = np.arange(max(0, -d), min(n, n - d))
            diag[rows] += (v[rows] - ev.AP[d][rows] * ev.dpa[rows + d]) * sysm.kcoef[abs(d)]
    diag = np.abs(diag)
    diag[0], diag[-1] = diag[1], diag[-2]
    return 1.0 / np.maximum(diag, 1e-300 + 1e-14 * diag.max())


def _cavitated(ev, c):
    cav = ev.P < -c * ev.R
    cav[0] = cav[-1] = False
    return cav


class _CoarseLevel:
    """Dense LU of the Newton matrix at a coarse-grid solution, for preconditioning the
    same problem on finer grids (two-grid)."""

    def __init__(self, sysm, st: _State):
        ev = sysm.evaluate(st.Q, st.H0)
        c = _jacobi_scale(sysm, ev)
        self.lin = _Linearization(sysm, c, _cavitated(ev, c), ev)
        self.lu = linalg.lu_factor(self.lin.dense(), check_finite=False)
        self.X = sysm.g.X
        self._transfer = {}

    def transfer(self, X):
        """Prolongation P (linear interpolation) and restriction R (averaging, Pᵀ with
        unit row sums) between this grid and the fine grid X (same domain)."""
        key = (X.size, X[0], X[-1])
        if key not in self._transfer:
            from scipy import sparse
            xc = self.X
            j = np.clip(np.searchsorted(xc, X, side="right") - 1, 0, xc.size - 2)
            t = (X - xc[j]) / (xc[j + 1] - xc[j])
            rows = np.r_[np.arange(X.size), np.arange(X.size)]
            P = sparse.csr_matrix((np.r_[1 - t, t], (rows, np.r_[j, j + 1])),
                                  shape=(X.size, xc.size))
            Rt = P.T.tocsr()
            Rm = sparse.diags(1.0 / np.asarray(Rt.sum(axis=1)).ravel()) @ Rt
            self._transfer[key] = (P, Rm.tocsr())
        return self._transfer[key]


class _TwoGridPreconditioner:
    """M⁻¹ r = P J_c⁻¹ R r followed by one Jacobi sweep on the fine system.

    Residuals are moved between grids unscaled (Reynolds rows are flux densities, the
    same on every grid) and re-scaled with the coarse rows' scaling."""

    def __init__(self, coarse: _CoarseLevel, lin: _Linearization, sysm):
        self.coarse, self.lin = coarse, lin
        self.P, self.R = coarse.transfer(sysm.g.X)
        n = lin.n
        diag = lin.AP[0].copy()
        if sysm.kcoef is not None:
            for d, v in lin.B.items():
                rows = np.arange(max(0, -d), min(n, n - d))
                diag[rows] += v[rows] * sysm.kcoef[abs(d)]
        dsc = np.where(lin.free, lin.c * diag, 1.0)
        if sysm.kcoef is not None:
            dsc[lin.cav] = 1.0 - lin.D[lin.cav] * sysm.kcoef[0]
        dsc[lin.bnd] = 1.0
        self.dinv = 1.0 / np.where(np.abs(dsc) > 1e-12, dsc, 1.0)

    def solve(self, r):
        lin, cl = self.lin, self.coarse.lin
        rf = r[:-1].copy()
        rf[lin.free] /= lin.c[lin.free]
        rc = self.R @ rf
        rc[cl.free] *= cl.c[cl.free]
        rc[cl.bnd] = 0.0
        zc = linalg.lu_solve(self.coarse.lu, np.r_[rc, r[-1]], check_finite=False)
        z = np.r_[self.P @ zc[:-1], zc[-1]]
        z[:-1] += 0.8 * (r[:-1] - lin.matvec(z)[:-1]) * self.dinv
        return z


def _newton(sysm: _ReynoldsSystem, st: _State, tol, max_iter, lu=None, coarse=None):
    # trial points of the line search may overflow (e.g. exp(αp)); they are rejected by
    # their non-finite merit, and the accepted solution is checked for finiteness
    with np.errstate(over="ignore", invalid="ignore", under="ignore", divide="ignore"):
        return _newton_impl(sysm, st, tol, max_iter, lu, coarse)


def _newton_impl(sysm: _ReynoldsSystem, st: _State, tol, max_iter, lu=None, coarse=None):
    """Semismooth Newton on min(P_i, −c_i R_i) = 0 and the load balance, unknowns (Q, H₀),
    with a non-monotone Armijo line search on |Φ|² + load residual² (c frozen within a
    search) and a small budget of full steps that may raise it (watchdog). Iterates may
    dip below zero pressure; the min-function clamps them on the next iteration.
    The Newton systems are solved by LU, by GMRES preconditioned with an earlier LU, or —
    given a ``coarse`` level — by GMRES with the two-grid preconditioner (no dense matrix
    on this grid; a dense LU only as fallback)."""
    g = sysm.g

    def merit_of(ev, c=None):
        """|Φ|² + load²; the scale c is frozen within a line search (c=given)."""
        c = _jacobi_scale(sysm, ev) if c is None else c
        phi = np.minimum(ev.P, -c * ev.R)
        phi[0], phi[-1] = ev.P[0], ev.P[-1]
        return float(np.dot(phi, phi) + ev.load * ev.load), c

    Q, H0 = st.Q.copy(), st.H0
    ev = sysm.evaluate(Q, H0)
    m0, c = merit_of(ev)
    msg = "maximum iterations reached"
    ok = False
    prev_cav, release, release_cap = None, 1, 1 << 30
    history = [m0]          # non-monotone (Grippo–Lampariello–Lucidi) acceptance
    watchdog = 2            # full Newton steps allowed to raise the merit (warm starts)
    gmres_tol = 1e-6
    it = 0
    for it in range(1, max_iter + 1):
        cav_std = _cavitated(ev, c)
        accepted = False
        fresh_lu = False
        for cav in ((_release(cav_std, prev_cav, release), cav_std) if release > 1
                    else (cav_std,)):
            lin = _Linearization(sysm, c, cav, ev)
            delta = None
            fresh_lu = lu is None
            if coarse is not None and lu is None:
                delta, _ = _gmres(lin, _TwoGridPreconditioner(coarse, lin, sysm), gmres_tol,
                                  _MAX_KRYLOV_TWO_GRID)
                fresh_lu = True                 # nothing stale to refresh
            if delta is None and lu is not None:
                delta, nkry = _gmres(lin, lu, gmres_tol)
                if delta is None or nkry > _MAX_KRYLOV_BEFORE_REFACTOR:
                    lu = None
            if delta is None:
                try:
                    lu = linalg.lu_factor(lin.dense(), check_finite=False)
                except (linalg.LinAlgError, ValueError):
                    lu = None
                    continue
                delta = linalg.lu_solve(lu, lin.rhs, check_finite=False)
                fresh_lu = True
            if not np.all(np.isfinite(delta)):
                lu = None
                continue
            dQ, dH0 = delta[:-1], delta[-1]
            step = 1.0
            for _ in range(30):
                Qn = Q + step * dQ
                H0n = H0 + step * dH0
                evn = sysm.evaluate(Qn, H0n)
                mn, _ = merit_of(evn, c)
                ref = max(history[-_NONMONOTONE:])
                if np.isfinite(mn) and (mn <= (1.0 - 1e-4 * step) * ref or
                                        (step == 1.0 and watchdog > 0 and mn <= _WATCHDOG * ref)):
                    if not mn <= (1.0 - 1e-4 * step) * ref:
                        watchdog -= 1      # a full step that raised the merit: limited budget
                    accepted = True
                    break
                step *= 0.5
            if accepted:
                break
        if not accepted and lu is not None and not fresh_lu:
            lu = None                  # Krylov direction from a stale preconditioner: retry
            continue
        if not accepted:
            msg = f"line search failed (merit {m0:.2e})"
            break
        overshoot = prev_cav is not None and bool(np.any(~prev_cav & cav_std))
        moved = prev_cav is not None and bool(np.any(prev_cav & ~cav_std))
        if overshoot:
            if release > 1:
                # a released block overshot: later blocks at most half as large (no cycling)
                release_cap = max(1, release // 2)
            release = 1
        elif moved:
            release = min(2 * release, release_cap)
        else:
            release = 1
        prev_cav = cav_std
        upd = step * max(np.max(np.abs(dQ)) / max(np.max(np.abs(Qn)), 1e-30),
                         abs(dH0) / max(abs(evn.H[g.i0]), 1e-30))
        if _TRACE:
            print(f"    it {it} step {step:.3g} merit {mn:.3e} upd {upd:.2e} "
                  f"ncav {int(cav_std.sum())} rel {release}")
        m0, c = merit_of(evn)          # re-scale at the accepted point
        Q, H0, ev = Qn, H0n, evn
        history.append(m0)
        res = math.sqrt(max(m0, 0.0))
        # converged: update below tol, or residual at round-off with an update so small
        # that the next (quadratic) one would be
        if (upd < tol and res < 1e3 * tol) or (res < 1e-13 and upd < math.sqrt(tol)):
            ok = True
            msg = f"converged in {it} Newton iterations (update {upd:.1e}, residual {res:.1e})"
            break
    P = np.maximum(ev.P, 0.0) if ok else ev.P   # cavitated nodes are 0 up to round-off
    return _State(Q, H0, P, ev.H), ok, it, msg, lu


# ----------------------------------------------------------------------------- post
def _postprocess(sysm, st: _State, w, R, ue, us, opts: EHLOptions, lub, rough, ok, it, msg,
                 time=0.0, squeeze_velocity=0.0):
    # a non-converged last iterate may hold extreme pressures: evaluate quietly, flag below
    with np.errstate(over="ignore", invalid="ignore", under="ignore"):
        return _postprocess_impl(sysm, st, w, R, ue, us, opts, lub, rough, ok, it, msg, time,
                                 squeeze_velocity)


def _postprocess_impl(sysm, st, w, R, ue, us, opts, lub, rough, ok, it, msg, time,
                      squeeze_velocity):
    g = sysm.g
    x = g.x
    p = st.P * sysm.p_ref
    h = st.H * sysm.h_ref
    pa, _ = sysm.asperity(st.H)
    pa = pa * sysm.p_ref
    dx = g.dX * g.a
    mu = lub.viscosity_at(p)
    hf = np.maximum(h, 1e-10)
    tau = couette_shear_stress(mu, us, hf, opts.viscous_model, lub.eyring_stress)
    if opts.limiting_shear:
        tau = limit_shear_stress(tau, p, lub.limiting_shear_coefficient,
                                 lub.limiting_shear_stress)
    dpdx = np.gradient(p, dx)
    f_visc = float(np.sum(np.abs(tau)) * dx)
    f_roll = float(np.sum(0.5 * hf * np.abs(dpdx)) * dx)
    if rough is not None:
        area = rough.contact_area_fraction(h)
        f_b = float(np.sum(boundary_shear_stress(pa, area, opts.boundary_shear_coefficient,
                                                 opts.boundary_shear_strength)) * dx)
    else:
        f_b = 0.0
    i_min = int(np.argmin(h))
    # outlet meniscus: first zero-pressure node downstream of the peak; p ∝ (x_c − x)²
    # near a Reynolds boundary, so √p is extrapolated linearly to zero
    direction = 1 if g.direction >= 0 else -1
    ipk = int(np.argmax(p))
    x_cav = float("nan")
    idx = np.arange(ipk, g.n) if direction > 0 else np.arange(ipk, -1, -1)
    for k in range(1, idx.size):
        if p[idx[k]] <= 0.0:
            j1, j2 = idx[k - 1], idx[k - 2] if k >= 2 else idx[k - 1]
            s1, s2 = math.sqrt(p[j1]), math.sqrt(max(p[j2], 0.0))
            if s2 > s1 > 0 and j1 != j2:
                x_cav = float(x[j1] + (x[j1] - x[j2]) * s1 / (s2 - s1))
            else:
                x_cav = float(x[idx[k]])
            break
    if not (np.all(np.isfinite(p)) and np.all(np.isfinite(h)) and np.isfinite(f_visc)):
        ok = False
        msg = "non-finite solution: " + msg
    # load lost to the truncated inlet: |dp/dx| x_in²/2 at the inlet node (exact for the
    # far field p ∝ |x|⁻³; on the rigid isoviscous cylinder it predicts the loss within
    # 5 %); warn at twice the tolerance the domain was sized for
    deficit = 0.0
    ends = {1: [0], -1: [g.n - 1], 0: [0, g.n - 1]}[int(np.sign(g.direction))]
    for e in ends:
        nb = e + 1 if e == 0 else e - 1
        deficit += abs(p[nb] - p[e]) / dx * x[e] ** 2 / 2.0
    deficit /= w
    if ok and deficit > 2.0 * opts.inlet_truncation:
        msg += (f"; warning: truncated inlet carries an estimated {deficit:.1%} of the load "
                "(lower inlet_truncation or increase inlet)")
    out_end = g.n - 2 if g.direction > 0 else 1
    if ok and g.direction != 0 and p[out_end] > 1e-3 * p.max():
        msg += "; warning: pressure not negligible at the outlet (increase outlet)"
    return EHLResult(
        x=x, pressure=p, asperity_pressure=pa, film=h, central_film=float(np.interp(0.0, x, h)),
        min_film=float(h[i_min]), min_film_position=float(x[i_min]), cavitation_position=x_cav,
        rigid_approach=float(st.H0 * sysm.h_ref), load=w, hydrodynamic_load=float(np.sum(p) * dx),
        asperity_load=float(np.sum(pa) * dx), viscous_friction=f_visc, rolling_friction=f_roll,
        boundary_friction=f_b, entrainment_speed=ue, sliding_speed=us, radius=R,
        converged=bool(ok), iterations=int(it), message=msg, time=time,
        squeeze_velocity=squeeze_velocity, shear_stress=tau, inlet_load_deficit=deficit,
    )


def _initial_state(sysm: _ReynoldsSystem, b, h_est):
    """Hertz-like pressure over the Hertz width (or a narrow bump if rigid); h₀ such that
    the central film equals the film-formula estimate."""
    g = sysm.g
    bb = max(b / g.a, 4 * g.dX)
    P = np.sqrt(np.clip(1.0 - (g.X / bb) ** 2, 0.0, None))
    P /= np.sum(P) * g.dX
    H0 = h_est / sysm.h_ref
    if sysm.elastic:
        H0 -= sysm.Kop(P)[g.i0]
    return _State(P, H0)


def _state_from_dimensional(sysm: _ReynoldsSystem, x, q, h0) -> _State:
    """Scaled state on sysm's grid from a total pressure q(x) = p + p_a [Pa] and the
    rigid approach h₀ [m]."""
    Q = np.interp(sysm.g.x, x, q, left=0.0, right=0.0) / sysm.p_ref
    return _State(Q, h0 / sysm.h_ref)


def solve_ehl(load, radius, entrainment_speed, sliding_speed, bodies, lubricant: Lubricant,
              roughness: Roughness | None = None, *, options: EHLOptions | None = None,
              **option_overrides) -> EHLResult:
    """Steady mixed-EHL line contact.

    Parameters
    ----------
    load : w, load per unit length [N/m], > 0 (carried by fluid + asperities).
    radius : R, reduced radius of curvature [m], > 0.
    entrainment_speed : u_e = (u₁ + u₂)/2 relative to the contact [m/s], ≠ 0 (either
        sign: the inlet is on the side the flow comes from).
    sliding_speed : u_s = u₁ − u₂ [m/s] (friction only).
    bodies : pair of :class:`~tribodyn.Body` (coating allowed on either).
    lubricant : :class:`~tribodyn.Lubricant`.
    roughness : composite :class:`~tribodyn.Roughness` or None (smooth).
    options / option_overrides : :class:`EHLOptions` fields (n, inlet, outlet, tol, …).
    """
    w, R, ue, us = _check_inputs(load, radius, entrainment_speed, sliding_speed)
    bodies = _check_models(bodies, lubricant, roughness)
    opts = options or EHLOptions()
    if option_overrides:
        opts = _with_overrides(opts, option_overrides)
    if ue == 0.0:
        raise InputError("entrainment_speed must be non-zero for a steady film "
                         "(pure squeeze needs TransientEHL)")
    e_bulk = reduced_modulus(bodies)
    e_surf = reduced_modulus(bodies, surface=True)
    a, b, h_est, inlet, outlet, n = _layout(w, R, ue, e_bulk, lubricant, opts)
    direction = 1 if ue >= 0 else -1
    # nested iteration: coarse grids first (cheap, robust), then the requested grid
    levels = [n]
    while levels[-1] // 2 >= _COARSEST and (len(levels) < 4 or levels[-1] > _N_DENSE):
        levels.append(levels[-1] // 2)
    levels = levels[::-1]
    st, total, sysm, coarse = None, 0, None, None
    films, refined = [], ""
    k = 0
    while k < len(levels):
        nk = levels[k]
        grid = _Grid(bodies, a, inlet, outlet, nk, direction, opts.elastic)
        prev, sysm = sysm, _ReynoldsSystem(grid, w, R, ue, lubricant, roughness, e_surf)
        if st is None:
            st0 = _initial_state(sysm, b if opts.elastic else 0.0, h_est)
        else:
            st0 = _state_from_dimensional(sysm, prev.g.x, st.Q * prev.p_ref,
                                          st.H0 * prev.h_ref)
        max_it = opts.max_iter * (2 if k == 0 and len(levels) > 1 else 1)
        st, ok, it, msg, _ = _newton(sysm, st0, opts.tol, max_it,
                                     coarse=coarse if nk > _N_DENSE else None)
        total += it
        if ok and nk <= _N_DENSE and nk < n and levels[-1] > _N_DENSE:
            coarse = _CoarseLevel(sysm, st)      # finest dense level preconditions the rest
        if not ok and k == 0:
            st, ok, it2, msg = _continuation(sysm, w, R, ue, lubricant, roughness, opts, e_surf,
                                             b, h_est)
            total += it2
        films.append(_films(sysm, st) if ok else None)
        # a posteriori grid check of the automatic grid: if h_c or h_min still changed by
        # more than _GRID_REFINE_CHANGE from the previous (half as fine) level, double n
        if (k == len(levels) - 1 and opts.n is None and ok and nk < _N_MAX_AUTO
                and len(films) >= 2 and films[-2] is not None):
            change = max(abs(f1 / f0 - 1.0) for f0, f1 in zip(films[-2], films[-1]))
            if change > _GRID_REFINE_CHANGE:
                if coarse is None and nk <= _N_DENSE:
                    coarse = _CoarseLevel(sysm, st)
                levels.append(min(_N_MAX_AUTO, 2 * nk))
                refined = (f"; grid refined to {levels[-1]} nodes (h changed by "
                           f"{change:.1%} from {levels[-3]} to {nk} nodes)")
        k += 1
    return _postprocess(sysm, st, w, R, ue, us, opts, lubricant, roughness, ok, total,
                        msg + refined)


def _films(sysm, st) -> tuple[float, float]:
    """(h_c, h_min) [m] of a solved state."""
    h = st.H * sysm.h_ref
    return float(np.interp(0.0, sysm.g.x, h)), float(h.min())


def _continuation(sysm_full, w, R, ue, lub, rough, opts, e_surf, b, h_est):
    """Load continuation on the same grid: start light (nearly rigid), increase to w."""
    total, st, prev = 0, None, None
    msg = "continuation failed"
    grid = sysm_full.g
    for frac in (0.05, 0.15, 0.35, 0.6, 0.8, 1.0):
        sysm = _ReynoldsSystem(grid, w * frac, R, ue, lub, rough, e_surf)
        if st is None:
            st = _initial_state(sysm, b * math.sqrt(frac), h_est)
        else:
            st = _state_from_dimensional(sysm, grid.x, st.Q * prev.p_ref, st.H0 * prev.h_ref)
        st, ok, it, msg, _ = _newton(sysm, st, opts.tol, opts.max_iter)
        total += it
        prev = sysm
        if not ok:
            return st, False, total, f"load continuation stalled at {frac:.0%} of the load: {msg}"
    return st, True, total, msg + " (after load continuation)"


class TransientEHL:
    """Transient mixed-EHL line contact marched in time (full Eq. 1 with ∂(ρh)/∂t).

    Each :meth:`step` advances from the current state to t + dt with the load, radius,
    entrainment and sliding speed given at t + dt (implicit, BDF2 with variable steps;
    BDF1 on the first step or after ``time_order=1``). The grid follows the contact
    (length scale from the current load/radius/speed); it is kept — together with the
    LU preconditioner of the Newton matrix — while the length scale changes by < 2 %,
    otherwise the previous ρh(x) is interpolated onto the new grid. Entrainment may change
    sign or vanish (pure squeeze): the squeeze term then carries the load.

    Start with :meth:`start_steady` (steady solution at u_e ≠ 0) or :meth:`start_film`
    (a given rigid-approach film and zero pressure, e.g. for squeeze tests).
    A step that fails to converge is retried with sub-steps; if it still fails the result
    says so (``converged=False``) and marching continues from the last iterate.
    """

    def __init__(self, bodies, lubricant: Lubricant, roughness: Roughness | None = None, *,
                 options: EHLOptions | None = None, max_substeps: int = 3, **option_overrides):
        self.bodies = _check_models(bodies, lubricant, roughness)
        self.lub = lubricant
        self.rough = roughness
        opts = options or EHLOptions()
        if option_overrides:
            opts = _with_overrides(opts, option_overrides)
        self.opts = opts
        self.max_substeps = int(max_substeps)
        self.conditions_before = None
        self.e_bulk = reduced_modulus(self.bodies)
        self.e_surf = reduced_modulus(self.bodies, surface=True)
        self.time = 0.0
        self._grid = None
        self._q = self._p = self._h = None   # total, fluid pressure [Pa], film [m] on the grid
        self._h0 = 0.0                 # rigid approach [m]
        self._hist = []                # [(x, ρh, dt, R)] of the last two time levels
        self._lu = None
        self.result: EHLResult | None = None

    # -- starting states
    def start_steady(self, load, radius, entrainment_speed, sliding_speed, time=0.0) -> EHLResult:
        """Start from the steady solution at the given conditions (u_e ≠ 0)."""
        res = solve_ehl(load, radius, entrainment_speed, sliding_speed, self.bodies, self.lub,
                        self.rough, options=self.opts)
        w, R, ue, _ = _check_inputs(load, radius, entrainment_speed, sliding_speed)
        grid = self._make_grid(w, R, ue, None)
        sysm = _ReynoldsSystem(grid, w, R, ue, self.lub, self.rough, self.e_surf)
        st = _state_from_dimensional(sysm, res.x, res.pressure + res.asperity_pressure,
                                     res.rigid_approach)
        self._grid, self._lu, self._hist = grid, None, []
        self._commit(sysm, st, R, None, time)
        res.time = time
        self.result = res
        return res

    def start_film(self, film, load, radius, entrainment_speed=0.0, sliding_speed=0.0,
                   time=0.0):
        """Start from an unloaded film h(x) = film + x²/(2R) (no pressure yet)."""
        h0 = check_positive("film", film, "m")
        w, R, ue, _ = _check_inputs(load, radius, entrainment_speed, sliding_speed)
        grid = self._make_grid(w, R, ue, h0)
        sysm = _ReynoldsSystem(grid, w, R, ue, self.lub, self.rough, self.e_surf)
        st = _State(np.zeros(grid.n), h0 / sysm.h_ref)
        ev = sysm.evaluate(st.Q, st.H0)
        st.P, st.H = ev.P, ev.H
        self._grid, self._lu, self._hist = grid, None, []
        self._commit(sysm, st, R, None, time)
        self.result = None

    # -- internals
    def _make_grid(self, w, R, ue, film):
        o = self.opts
        a, b, h_est, inlet, outlet, n = _layout(w, R, ue, self.e_bulk, self.lub, o,
                                               squeeze_film=film)
        direction = int(np.sign(ue))
        g = self._grid
        if g is not None and g.same_as(a, inlet, outlet, n, direction):
            return g
        return _Grid(self.bodies, a, inlet, outlet, n, direction, o.elastic)

    def _commit(self, sysm, st: _State, R, dt, time):
        if st.P is None:
            ev = sysm.evaluate(st.Q, st.H0)
            st.P, st.H = ev.P, ev.H
        self._q = st.Q * sysm.p_ref
        self._p = st.P * sysm.p_ref
        self._h = st.H * sysm.h_ref
        self._h0 = st.H0 * sysm.h_ref
        rho_h = self.lub.density_at(self._p) * self._h
        self._hist = ([(sysm.g.x, rho_h, dt, R)] + self._hist)[:2]
        self._grid = sysm.g
        self.time = time

    def _old_on(self, grid, k, R_new):
        """ρh of history level k (0: last) on ``grid`` [kg/m²], re-based on the current
        radius of curvature.

        The rigid gap x²/(2R) is valid only near the contact; there the squeeze due to a
        changing R, x²Ṙ/(2R²), is negligible against the Couette term, while far upstream
        it would invent suction of metres per second on a fast-changing cam flank. The
        change of R is therefore taken quasi-statically: the old film keeps its approach
        and elastic deformation but gets the new parabola. Outside the old domain the old
        film is continued with that parabola (ambient density)."""
        x_old, f_old, _, R_old = self._hist[k]
        x = grid.x
        f = np.interp(x, x_old, f_old)
        rho0 = self.lub.density
        for side, idx in ((x < x_old[0], 0), (x > x_old[-1], -1)):
            if np.any(side):
                xe = x_old[idx]
                f[side] = f_old[idx] + rho0 * (x[side] ** 2 - xe**2) / (2.0 * R_old)
        # the density varies little where the parabola matters (low pressure): use ρ₀
        return f + rho0 * x**2 * (0.5 / R_new - 0.5 / R_old)

    def step(self, dt, load, radius, entrainment_speed, sliding_speed) -> EHLResult:
        """Advance by dt [s] to the given conditions (load per unit length [N/m])."""
        dt = check_positive("dt", dt, "s")
        if self._grid is None:
            raise InputError("TransientEHL needs start_steady() or start_film() before step()")
        w, R, ue, us = _check_inputs(load, radius, entrainment_speed, sliding_speed)
        saved = self._snapshot()
        res = self._advance(dt, w, R, ue, us)
        if res.converged or self.max_substeps <= 0:
            return res
        # retry with sub-steps (conditions interpolated) from the same starting state
        c0 = self.conditions_before if self.conditions_before is not None else (w, R, ue, us)
        c1 = (w, R, ue, us)
        for k in range(1, self.max_substeps + 1):
            m = 2**k
            self._restore(saved)
            ok = True
            for j in range(1, m + 1):
                f = j / m
                sub = self._advance(dt / m, *(a + f * (b - a) for a, b in zip(c0, c1)))
                ok = ok and sub.converged
            if ok:
                sub.message += f" ({m} sub-steps)"
                return sub
        return sub

    def _snapshot(self):
        r = self.result
        self.conditions_before = (None if r is None else
                                  (r.load, r.radius, r.entrainment_speed, r.sliding_speed))
        return (self._grid, self._q, self._p, self._h, self._h0, list(self._hist), self.time,
                self._lu)

    def _restore(self, snap):
        (self._grid, self._q, self._p, self._h, self._h0, hist, self.time, self._lu) = snap
        self._hist = list(hist)

    def _advance(self, dt, w, R, ue, us) -> EHLResult:
        o = self.opts
        prev_grid = self._grid
        hc_prev = float(np.interp(0.0, prev_grid.x, self._h))
        grid = self._make_grid(w, R, ue, hc_prev)
        same = grid is prev_grid
        # variable-step BDF for d(ρh)/dt: (a0 f_n + a1 f_{n-1} + a2 f_{n-2})/dt
        f1 = self._old_on(grid, 0, R)
        if o.time_order == 2 and len(self._hist) == 2 and self._hist[0][2] is not None:
            r = dt / self._hist[0][2]
            a0, a1, a2 = (1 + 2 * r) / (1 + r), -(1 + r), r * r / (1 + r)
            f_eff = -(a1 * f1 + a2 * self._old_on(grid, 1, R)) / a0
        else:
            a0, f_eff = 1.0, f1
        sysm = _ReynoldsSystem(grid, w, R, ue, self.lub, self.rough, self.e_surf,
                               time_coef=a0 / dt)
        sysm.f_old = f_eff / (self.lub.density * sysm.h_ref)
        st0 = _state_from_dimensional(sysm, prev_grid.x, self._q, self._h0)
        st, ok, it, msg, lu = _newton(sysm, st0, o.tol, o.max_iter,
                                      lu=self._lu if same else None)
        self._lu = lu if ok else None
        self._commit(sysm, st, R, dt, self.time + dt)
        hc_new = float(np.interp(0.0, grid.x, self._h))
        res = _postprocess(sysm, st, w, R, ue, us, o, self.lub, self.rough, ok, it, msg,
                           time=self.time, squeeze_velocity=-(hc_new - hc_prev) / dt)
        self.result = res
        return res

"""The discretised Reynolds system of the EHL line contact and its linearisation.

Scaled variables: P = p a/w, H = h R/a², X = x/a (a: length scale of the grid). Unknowns:
the total pressure Q = P + P_a (fluid + asperity) at the nodes and the rigid approach H₀.

* film (Eq. 9)          H = H₀ + X²/2 + K Q        (K: DC-FFT influence operator)
* asperities (Eq. 6)    P_a = k_a F(H/σ̄)           (F_5/2 of Greenwood–Tripp or a law)
* Reynolds (Eq. 1)      d/dX(ε dP/dX) − ū d(ρ̄H)/dX − c_t (ρ̄H − f_old) = 0,
                        ε = λ ρ̄ H³ μ₀/μ, λ = h_ref² p_ref/(12 μ₀ a U)
* load balance (Eq. 8)  ΔX Σ Q = 1

Finite volumes with arithmetic-mean face coefficients, second-order upwind Couette term
(first order next to the boundary), backward-difference time term (coefficient and old
level supplied by the transient driver). :meth:`ReynoldsSystem.evaluate` returns the
residuals with the banded derivatives A_P = ∂R/∂P, A_H = ∂R/∂H; :class:`Linearization`
assembles the Newton system for (δQ, δH₀) densely or applies it matrix-free. With a
:class:`~tribodyn.Lubricant` an evaluation is one compiled call after the deformation
product (:func:`.kernels.evaluate`); a lubricant with per-node properties (the thermal
solvers') is read through its methods.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np
from scipy.linalg.blas import dsymv

from ...physics.elasticity import DeformationOperator
from ...physics.lubricant import Lubricant
from . import kernels
from .gmres_kernels import GETRS, SGETRS, SYMV, gmres_lu
from .grid import Grid
from .kernels import assemble, dense_matrix_t, newton_matvec, newton_rows
from .options import Conditions, ContactModel

__all__ = ["ReynoldsSystem", "Evaluation", "Linearization"]


class ReynoldsSystem:
    """Scaled discrete system for one solve (one time level)."""

    def __init__(self, grid: Grid, cond: Conditions, model: ContactModel, time_coef=0.0):
        w, R, ue = cond.load, cond.radius, cond.entrainment_speed
        lub, roughness = model.lubricant, model.roughness
        self.g = grid
        self.cond = cond
        self.model = model
        self.lub = lub
        self.rough = roughness
        a = grid.a
        self.p_ref = p_ref = w / a  # P = p a / w
        self.h_ref = h_ref = a * a / R  # H = h R / a²
        self.elastic = grid.elastic
        self.kcoef: np.ndarray | None
        if grid.elastic:
            assert grid.coef is not None  # an elastic grid carries its influence coefficients
            kscale = self.kscale = p_ref / h_ref
            self.kcoef = grid.coef * kscale
        else:
            self.kcoef = None
        self.u_scale = max(abs(ue), 1e-3)
        self.ubar = ue / self.u_scale
        self.lam = h_ref**2 * p_ref / (12.0 * lub.viscosity * a * self.u_scale)
        self.geom = grid.rigid_gap  # X²/2, kept by the grid
        # time term: c_t (f − f_old) with f = ρ̄H, c_t = a/(U Δt)·α₀
        self.time_coef = time_coef * a / self.u_scale
        self.f_old: np.ndarray | None = None  # set by the transient driver
        # optional per-node factors of the generalized (thermal) Reynolds equation: the
        # Poiseuille coefficient ε and the Couette flux ū ρ̄H are multiplied by them
        # (None: isothermal Reynolds; see contact.ehl.thermal)
        self.flow_factor = None
        self.couette_factor = None
        self.h_floor = 1e-10 / h_ref
        if roughness is not None:
            self.ka = roughness.pressure_scale(model.e_surface) / p_ref
            self.sig = roughness.rms / h_ref
        # upwind direction of the Couette term: d/dX (ρ̄H) from nodes i, i − s, i − 2s
        self.s = 1 if self.ubar >= 0 else -1
        # compiled evaluation: the lubricant's rheology law (None: per-node lubricant,
        # read through its methods) and where the asperity pressure comes from
        self._law = lub.rheology_law if isinstance(lub, Lubricant) else None
        self._table, self._curve = kernels.NO_TABLE, kernels.NO_CURVE
        self._asperities = kernels.NO_ASPERITIES
        if roughness is not None:
            table = roughness.load_table()
            self._asperities = kernels.GIVEN_ASPERITIES  # the paper's fits
            if roughness.law is not None:
                self._curve = roughness.law.pressure_curve
                self._asperities = kernels.LAW_ASPERITIES
            elif table is not None:
                self._table, self._asperities = table, kernels.TABLE_ASPERITIES
        self._ones = grid.ones

    @cached_property
    def Kop(self) -> DeformationOperator | None:
        """DC-FFT operator of the scaled influence coefficients (None: rigid), built on
        first use (grids with the dense matrix multiply by it instead)."""
        if self.kcoef is None:
            return None
        return DeformationOperator.from_coefficients(self.kcoef)

    def deform(self, v):
        """Scaled deformation K v: a dense product on grids that keep the dense matrix
        (LU paths; BLAS symv, K symmetric: Kᵀ is its column-major view), DC-FFT
        otherwise."""
        if self.g.has_dense:
            return dsymv(self.kscale, self.g.K.T, v)
        assert self.Kop is not None  # only an elastic system deforms
        return self.Kop(v)

    # -- asperities and film
    def asperity(self, H):
        """Scaled asperity pressure Pa(H) and D = dPa/dH (Greenwood–Tripp or the
        roughness's load–separation law, through ``Roughness.load_function``)."""
        if self.rough is None:
            z = np.zeros_like(H)
            return z, z
        f, df = self.rough.load_function(H / self.sig)
        return self.ka * f, self.ka / self.sig * df

    def film(self, Q, H0, defo=None):
        """H = H0 + X²/2 + K Q: the surfaces deform under the total pressure Q = P + Pa
        (``defo``: K Q where the caller has it, else computed)."""
        if not self.elastic:
            return H0 + self.geom
        return H0 + self.geom + (self.deform(Q) if defo is None else defo)

    # -- rheology
    def rheology(self, P):
        """(ρ/ρ₀, dρ̄/dP, ln μ/μ₀, d ln μ/dP) at the nodes for the scaled pressure P, read
        elementwise through the lubricant (a lubricant with per-node fields may stand in)."""
        lub, pr = self.lub, self.p_ref
        p = P * pr
        rho0 = lub.density
        return (
            lub.density_at(p) / rho0,
            lub.ddensity_dp(p) * (pr / rho0),
            lub.log_viscosity_ratio(p),
            lub.dlog_viscosity_dp(p) * pr,
        )

    # -- residual and banded derivatives
    def evaluate(self, Q, H0, defo=None):
        """Residuals and banded derivatives at (Q, H0) (``defo``: the deformation K Q
        where the caller has it, e.g. from the predictor of the start; else computed).

        Returns an :class:`Evaluation` with the Reynolds residual R (interior rows), the load
        residual ΔX ΣQ − 1, the fluid pressure P = Q − Pa(H), the film H, D = dPa/dH,
        the diagonals of A_P = ∂R/∂P, A_H = ∂R/∂H (offsets −2…2; compiled stencil in
        :func:`.kernels.assemble`) and ln μ/μ₀ at P (a :class:`~tribodyn.Lubricant`'s
        law; None with per-node properties)."""
        if self._law is None:
            return self._evaluate_per_node(Q, H0, defo)
        n = self.g.n
        Q = np.ascontiguousarray(Q, dtype=float)
        H0 = float(H0)
        if not self.elastic:
            defo = _EMPTY
        elif defo is None:
            defo = self.deform(Q)
        pa, dpa = np.empty(n), np.empty(n)
        if self._asperities == kernels.GIVEN_ASPERITIES:  # the paper's fits
            pa, dpa = self.asperity(H0 + self.geom + defo if self.elastic else H0 + self.geom)
        H, P, lnmu, R = np.empty(n), np.empty(n), np.empty(n), np.empty(n)
        AP, AH = np.empty((5, n)), np.empty((5, n))
        rough = self.rough is not None
        load = kernels.evaluate(
            Q,
            H0,
            self.geom,
            defo,
            self._asperities,
            self._table,
            self._curve,
            self.ka if rough else 0.0,
            self.sig if rough else 1.0,
            self._law,
            self.p_ref,
            *self._stencil(),
            H,
            pa,
            dpa,
            P,
            lnmu,
            R,
            AP,
            AH,
        )
        return Evaluation(R, load, P, H, pa, dpa, AP, AH, lnmu)

    def _stencil(self):
        """The arguments of :func:`.kernels.assemble` between the rheology and the outputs:
        λ, the film floor, |ū|, the upwind direction, ΔX, the time term (c_t, f_old) and
        the per-node factors φ_f, φ_c of the generalized Reynolds equation (1: none)."""
        ff = self._ones if self.flow_factor is None else np.asarray(self.flow_factor, float)
        cf = self._ones if self.couette_factor is None else np.asarray(self.couette_factor, float)
        f_old = self.f_old if self.time_coef else _EMPTY
        return (
            self.lam,
            self.h_floor,
            abs(self.ubar),
            self.s,
            self.g.dX,
            float(self.time_coef),
            f_old,
            ff,
            cf,
        )

    def _evaluate_per_node(self, Q, H0, defo=None):
        """:meth:`evaluate` for a lubricant read through its methods (per-node
        properties): film, asperities and rheology by NumPy, then the compiled stencil."""
        n = self.g.n
        H = self.film(Q, H0, defo)
        pa, dpa = self.asperity(H)
        P = Q - pa
        R, AP, AH = np.empty(n), np.empty((5, n)), np.empty((5, n))
        assemble(P, H, *self.rheology(P), *self._stencil(), R, AP, AH)
        load = self.g.dX * float(np.sum(Q)) - 1.0
        return Evaluation(R, load, P, H, pa, dpa, AP, AH)


_EMPTY = np.zeros(0)


@dataclass
class Evaluation:
    """Residuals at one iterate; AP, AH hold the bands as (5, n) arrays (row d + 2 is
    offset d); ``lnmu``: ln μ/μ₀ at P by the lubricant's law (None: per-node lubricant)."""

    R: np.ndarray
    load: float
    P: np.ndarray
    H: np.ndarray
    pa: np.ndarray
    dpa: np.ndarray
    AP: np.ndarray
    AH: np.ndarray
    lnmu: np.ndarray | None = None


class Linearization:
    """Newton system for (δQ, δH₀) at one iterate, usable as a dense matrix (for LU) or
    matrix-free (J·z costs one deformation product plus banded work, for GMRES).

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
        self.AP, self.AH = ev.AP, ev.AH
        self.D = ev.dpa
        self.c = c
        self.B, self.col, self.cav, self.bnd, self.free, self.rhs = newton_rows(
            ev.AP, ev.AH, ev.dpa, ev.R, ev.P, ev.load, c, cav
        )

    def matvec(self, z):
        n = self.n
        v, vh = z[:n], float(z[n])
        dh = (np.zeros_like(v) if self.rigid else self.sysm.deform(v)) + vh  # δH
        out = np.empty(n + 1)
        newton_matvec(
            self.AP, self.B, self.col, self.c, self.free, self.cav, self.D, v, vh, dh, self.dX, out
        )
        return out

    def gmres_lu(self, fac, piv1, rtol, max_it):
        """Compiled GMRES (:func:`.gmres_kernels.gmres_lu`) for this system with the LU
        (``fac``, ``piv1``: ``lu_factor``'s factors and its pivots + 1, LAPACK's 1-based
        ones) of an earlier Newton matrix as preconditioner; None where the products need
        the DC-FFT operator (no dense K on this grid) or the factors are not LAPACK's
        column-major double- or single-precision ones of this system's size with 32-bit
        pivots (the kernel reads them by pointer)."""
        m = self.n + 1
        if not (
            fac.dtype in (np.float64, np.float32)
            and fac.shape == (m, m)
            and fac.flags.f_contiguous
            and piv1.dtype == np.int32
            and piv1.shape == (m,)
        ):
            return None
        if not (self.rigid or self.sysm.g.has_dense):
            return None
        K, ks = self._influence()
        system = (*self._rows(), np.ascontiguousarray(K), ks, not self.rigid, self.dX)
        getrs = GETRS if fac.dtype == np.float64 else SGETRS
        x, its, ok = gmres_lu(
            getrs,
            SYMV,
            system,
            fac,
            piv1,
            self.rhs,
            float(rtol),
            int(max_it),
        )
        return (x if ok else None), its

    def dense_column_major(self, dtype=np.float64):
        """The dense Newton matrix in ``dtype`` and column-major order, as LAPACK
        factorises it in place (:func:`.kernels.dense_matrix_t` writes its transpose).
        In single precision, entries below √(smallest normal float32) ≈ 1e-19 are zero
        (the rows are scaled to O(1)): neither they nor their products in the
        elimination are subnormal, which would make the factorisation several times
        slower, and their share of a row is below single precision's resolution."""
        K, ks = self._influence()
        out = np.empty((self.n + 1, self.n + 1), dtype=dtype)
        flush = _FLUSH if out.dtype == np.float32 else 0.0
        return dense_matrix_t(*self._rows(), K, ks, self.dX, not self.rigid, flush, out).T

    def _rows(self):
        """(A_P, B, B·1, c, free, cavitated, D): the row data of the Newton matrix."""
        return self.AP, self.B, self.col, self.c, self.free, self.cav, self.D

    def _influence(self):
        """The unscaled dense influence matrix and its scale (empty for a rigid system)."""
        if self.rigid:
            return _EMPTY2, 0.0
        return self.sysm.g.K, self.sysm.kscale


_FLUSH = float(np.sqrt(np.finfo(np.float32).tiny))


_EMPTY2 = np.zeros((0, 0))

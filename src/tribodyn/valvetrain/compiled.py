"""Compiled right-hand side, Jacobian and outputs of the lumped valvetrain (numba).

The equations are those of :class:`~tribodyn.valvetrain.model.ValvetrainModel` (see its
module docstring); this module evaluates them without Python overhead, for the model's
common case: a periodic tribology model (friction tabulated over the cam angle,
``_FrictionTable``) with no film, a :class:`FilmTableTribology` film law, or the film as
a state (:class:`FilmStateTribology`: h the last state, its entraining and squeeze laws
and growth limit from :mod:`tribodyn.physics.film_state_laws`, the correction r(t) in
the film table's place, the contact force through the film and the contact's spring and
damper in series as ``CamContactModel.cam_contact``). The cam is
tabulated over one revolution on a uniform grid of ``CAM_POINTS`` angles: s by cubic
Hermite interpolation of (s, s'), s' by cubic Hermite interpolation of (s', s''), s''
linearly; the table is checked against the cam at the cell midpoints (interpolation error
of s below 1e-10 m and of s' below 1e-9 m/rad, else the Python model is used).

The integration (:func:`integrate_compiled`) runs ODEPACK's LSODA over the whole run in
one call (``scipy.integrate.odeint``; Hindmarsh 1983, Petzold 1983), the same method as
the solve_ivp path but without its per-step Python overhead. Seat and contact events are
located from sign changes of the event functions on the output grid, each refined by a
short solve_ivp run with root finding over that output interval.
"""

from __future__ import annotations

import math
import time as _time
import types
from typing import NamedTuple

import numpy as np
from numba import njit
from scipy.integrate import odeint, solve_ivp

from ..physics import film_state_laws as laws
from .contact_law import (
    _film_free_rate,
    coil_segment,
    contact_film_root,
    damped_contact,
    joint_force,
    joint_slopes,
    smooth_step,
    stamp_element,
    table_friction,
)
from .film_kernels import entraining_film_load as _entraining
from .tribology import table_film

__all__ = [
    "CompiledLumped",
    "compiled_model",
    "integrate_compiled",
    "CAM_POINTS",
]

#: cam table points per revolution (0.0055° cam)
CAM_POINTS = 65536
_OPTS = dict(cache=True, nogil=True)
_TWO_PI = 2.0 * math.pi


class LumpedParams(NamedTuple):
    """Scalar parameters of the compiled lumped model (SI units, read by name in the
    kernels). They enter the kernels as one record of a structured array
    (:data:`_PARAMS`), which numba types at each call from Python far faster than a
    named tuple of as many fields (about 0.15 µs against 1.5 µs per call)."""

    w: float  #: cam speed ω [rad/s]
    theta0: float  #: cam angle at t = 0 [rad]
    rb: float  #: base radius [m]
    ramp: float  #: force over which contact damping phases in [N]
    cc: float  #: cam contact damping [N·s/m]
    vr: float  #: bore friction regularisation velocity [m/s]
    mub: float  #: bore friction coefficient
    lash: float  #: valve lash [m]
    ktv: float  #: tappet–valve stiffness [N/m]
    ctv: float  #: tappet–valve damping [N·s/m]
    ks: float  #: seat stiffness [N/m]
    cs: float  #: seat damping [N·s/m]
    f0: float  #: spring preload [N]
    d_seat: float  #: static seat compression [m]
    gamma: float  #: contact law exponent (P = z^γ)
    C: float  #: contact compliance coefficient
    ikc: float  #: 1/camshaft stiffness [m/N]
    has_film: float  #: 1.0 with a film law, else 0.0
    f_period: float  #: period of the film (or correction) table [s] (0: not periodic)
    film_state: float  #: 1.0 with the film as a state (h = y[2n + 2]), else 0.0
    width: float  #: cam width L [m] (film state)
    eta: float  #: viscosity η₀ [Pa s] (film state)
    alpha: float  #: pressure–viscosity coefficient α [1/Pa] (film state)
    e_prime: float  #: reduced modulus E' [Pa] (film state)
    supply: float  #: supply film h_s [m] (film state)
    sq: float  #: squeeze coefficient 3√2 π η₀ L [Pa s m] (film state)
    growth_limited: float  #: 1.0 if the film's growth is transport-limited, else 0.0


#: the record type of :class:`LumpedParams` (the kernels' entry points take a
#: one-element array of it)
_PARAMS = np.dtype([(k, float) for k in LumpedParams._fields])

#: outputs of the evaluation kernel (before the accelerations)
_OUT = (
    "theta s s1 s2 R ue us dk P Fc Ff Fb Ftv Fs F0s FNs film cam_power diss "
    "kc cc cb ktv ctv kst cst status kh hdot hdot_h hdot_F"
).split()
_NO = len(_OUT)


_step = njit(**_OPTS)(smooth_step)
_growth = njit(**_OPTS)(laws.limited_growth)


def _jit_calling(fn, **kernels):
    """``fn`` compiled, its global helpers replaced by their compiled ``kernels``."""
    scope = dict(fn.__globals__, **kernels)
    return njit(**_OPTS)(types.FunctionType(fn.__code__, scope, fn.__name__, fn.__defaults__))


_free_rate = _jit_calling(_film_free_rate, limited_growth=_growth)
_damped = _jit_calling(
    damped_contact, smooth_step=_step, _film_free_rate=_free_rate, limited_growth=_growth
)
_film_rate = _jit_calling(laws.film_rate, entraining_film_load=_entraining)
_squeeze_slope = njit(**_OPTS)(laws.squeeze_compliance_slope)
_growth_limit = njit(**_OPTS)(laws.growth_limit)
_joint = _jit_calling(joint_force, smooth_step=_step)
_element = njit(**_OPTS)(stamp_element)
_slopes = njit(**_OPTS)(joint_slopes)
_coil = njit(**_OPTS)(coil_segment)


@njit(**_OPTS)
def _cam(theta, th0, S, S1, S2):
    """(s, s', s'') from the uniform cam table (period 2π, first node at th0)."""
    m = S.size - 1
    d = _TWO_PI / m
    u = (theta - th0) % _TWO_PI
    j = int(u / d)
    if j >= m:
        j = m - 1
    x = (u - j * d) / d
    h00 = (1.0 + 2.0 * x) * (1.0 - x) ** 2
    h10 = x * (1.0 - x) ** 2
    h01 = x * x * (3.0 - 2.0 * x)
    h11 = x * x * (x - 1.0)
    s = h00 * S[j] + h10 * d * S1[j] + h01 * S[j + 1] + h11 * d * S1[j + 1]
    s1 = h00 * S1[j] + h10 * d * S2[j] + h01 * S1[j + 1] + h11 * d * S2[j + 1]
    s2 = (1.0 - x) * S2[j] + x * S2[j + 1]
    return s, s1, s2


@njit(**_OPTS)
def _table_film(t, force, where):
    """(h, dh/dF) of the film table ``where`` = (its columns, period, has_film) as the
    series film of :func:`~.contact_law.contact_film_root` (0, 0 without a film law)."""
    ft, fh, fc, ff, period, has_film = where
    if has_film == 0.0:
        return 0.0, 0.0
    return table_film(t, force, ft, fh, fc, ff, period)


_root = _jit_calling(contact_film_root, _series_film=_table_film)


@njit(**_OPTS)
def _contact(t, dk, par, ft, fh, fc, ff):
    """(P, dP/dδ_kin, h, ok) of the elastic contact with the film in series
    (``contact_film_root``, as ``CamContactModel.elastic_contact``)."""
    where = (ft, fh, fc, ff, par.f_period, par.has_film)
    return _root(where, t, dk, par.C, par.gamma, par.ikc, par.has_film != 0.0)


@njit(**_OPTS)
def _film_laws(t, h, ue, R, par, ft, fr, fz):
    """The film state's laws at film h [m] (``FilmStateTribology``): (a, ∂a/∂h, 1/D,
    ∂(1/D)/∂h, x_t, ∂x_t/∂h) with a = L w'_ent(h)/D the free rate at zero load,
    D = 3√2 π η₀ R^(3/2) L/h^(3/2) and x_t the transport limit of the growth; r(t) the
    correction table in the film table's place."""
    r, _ = table_film(t, 0.0, ft, fr, fz, fz, par.f_period)
    args = (par.eta, par.alpha, par.e_prime, par.supply, r, par.width, par.sq)
    a, a_h, m_inv = _film_rate(h, 0.0, ue, R, *args)
    xt, xt_h = _growth_limit(h, ue, R, par.supply, par.growth_limited != 0.0)
    return a, a_h, -m_inv, _squeeze_slope(h, R, par.sq), xt, xt_h


@njit(**_OPTS)
def _cam_contact(t, dk, dkd, hf, ue, R, par, ft, fh, fc, ff):
    """(P, dP/dδ, F_c, h, ḣ, ∂ḣ/∂h, ∂ḣ/∂F_c, k_c, c_c, k_h, ok) of the cam contact:
    F_c = max(0, P + c g(P) δ̇_kin) with the film law in series, or, with the film as a
    state h_f, one force through the film and the contact's spring and damper,
    F_c = P(δ_kin + h_f) + c g (δ̇_kin + ḣ), ḣ = H(a − F_c/D) (``cam_contact``)."""
    state = par.film_state != 0.0
    if state:
        P, dPdk, _, ok = _contact(t, dk + hf, par, ft, fh, fc, ff)
        h = hf
        laws = _film_laws(t, hf, ue, R, par, ft, fh, fc)
    else:
        P, dPdk, h, ok = _contact(t, dk, par, ft, fh, fc, ff)
        laws = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
    force = _damped(P, dPdk, dkd, par.cc, par.ramp, state, laws)
    Fc, hd, hd_h, hd_F, kc, cc, kh = force[2:]
    return P, dPdk, Fc, h, hd, hd_h, hd_F, kc, cc, kh, ok


@njit(**_OPTS)
def _evaluate(t, y, par, kseg, cseg, im, S, S1, S2, ft, fh, fc, ff, th, tab, fl, out, acc):
    """All forces of the model at (t, y) into ``out`` (order of ``_OUT``) and the
    accelerations into ``acc`` (see the equations in :mod:`.model`)."""
    n = im.size
    N = n - 2
    w = par.w
    ramp = par.ramp
    xt, xv, vt, vv = y[0], y[1], y[n], y[n + 1]
    theta = par.theta0 + w * t
    s, s1, s2 = _cam(theta, par.theta0, S, S1, S2)
    rb = par.rb
    R = rb + s + s2
    ue = 0.5 * w * (rb + s + 2.0 * s2)
    us = w * (rb + s)
    dk = s - xt
    dkd = w * s1 - vt
    hf = y[2 * n + 2] if par.film_state != 0.0 else 0.0
    P, _, Fc, hfilm, hd, hd_h, hd_F, kc, cc, kh, ok = _cam_contact(
        t, dk, dkd, hf, ue, R, par, ft, fh, fc, ff
    )
    Ff = table_friction(theta, Fc, th, tab, fl) if Fc > 0.0 else 0.0
    thv = math.tanh(vt / par.vr)
    Fb = par.mub * Ff * thv
    dtv, dtvd, ds = xt - xv - par.lash, vt - vv, par.d_seat - xv
    Ftv, Etv, gtv, dgtv = _joint(par.ktv, par.ctv, dtv, dtvd, ramp)
    Fs, Es, gs, dgs = _joint(par.ks, par.cs, ds, -vv, ramp)
    F0 = par.f0
    diss = 0.0
    f_prev = 0.0
    F0s = 0.0
    FNs = 0.0
    for j in range(N + 1):
        d, dd = _segment(y, n, N, j)
        f, dj = _coil(j == 0 or j == N, F0, kseg[j], cseg[j], d, dd)
        diss += dj
        if j == 0:
            F0s = f
            acc[1] = (Ftv - f + Fs) * im[1]
        else:
            acc[j + 1] = (f_prev - f) * im[j + 1]
        if j == N:
            FNs = f
        f_prev = f
    acc[0] = (Fc - Ftv - Fb) * im[0]
    out[0], out[1], out[2], out[3], out[4] = theta, s, s1, s2, R
    out[5], out[6], out[7], out[8], out[9] = ue, us, dk, P, Fc
    out[10], out[11], out[12], out[13] = Ff, Fb, Ftv, Fs
    out[14], out[15], out[16] = F0s, FNs, hfilm
    out[17] = Fc * w * s1 + Ff * us
    out[18] = (
        (Fc - P) * dkd + (Ftv - Etv) * dtvd + (Fs - Es) * (-vv) + diss + Fb * vt + Ff * us
    ) - P * hd  # work into the film state (0 without one)
    # local stiffness and damping (Jacobian)
    out[19], out[20] = kc, cc
    out[21] = par.mub * Ff * (1.0 - thv * thv) / par.vr
    out[22], out[23] = _slopes(par.ktv, par.ctv, dtv, dtvd, Ftv, gtv, dgtv)
    out[24], out[25] = _slopes(par.ks, par.cs, ds, -vv, Fs, gs, dgs)
    out[26] = 0.0 if ok else 1.0
    out[27], out[28], out[29], out[30] = kh, hd, hd_h, hd_F


@njit(**_OPTS)
def _tables(cam, film):
    """The rows of the cam table (S, S1, S2) and of the film table (ft, fh, fc, ff)."""
    return cam[0], cam[1], cam[2], film[0], film[1], film[2], film[3]


@njit(**_OPTS)
def _rhs(t, y, pa, kseg, cseg, im, cam, film, th, tab, fl, flag):
    """ẏ at (t, y). The entry points take the parameters ``pa`` as a one-element
    :data:`_PARAMS` array and the cam and film tables as rows of one array each
    (:class:`CompiledLumped`): fewer arguments for numba to type at each call."""
    par = pa[0]
    S, S1, S2, ft, fh, fc, ff = _tables(cam, film)
    n = im.size
    out = np.empty(_NO)
    acc = np.empty(n)
    _evaluate(t, y, par, kseg, cseg, im, S, S1, S2, ft, fh, fc, ff, th, tab, fl, out, acc)
    if out[26] != 0.0:
        flag[0] = 1.0
        flag[1] = t
    dy = np.empty(y.size)
    for i in range(n):
        dy[i] = y[n + i]
        dy[n + i] = acc[i]
    dy[2 * n] = out[17]
    dy[2 * n + 1] = out[18]
    if par.film_state != 0.0:
        dy[2 * n + 2] = out[28]
    return dy


@njit(**_OPTS)
def _segment(y, n, N, j):
    """Compression d and its rate of spring segment j: between coordinates j + 1 and
    j + 2, the last one (j = N) against the fixed seat."""
    xb = y[j + 2] if j < N else 0.0
    vb = y[n + j + 2] if j < N else 0.0
    return y[j + 1] - xb, y[n + j + 1] - vb


@njit(**_OPTS)
def _jac(t, y, pa, kseg, cseg, im, cam, film, th, tab, fl, flag):
    """∂ẏ/∂y as ``ValvetrainModel.jacobian`` (friction's F dependence and the
    accumulator rows omitted; the film state's rows and columns as
    ``CamContactModel.film_jacobian``, δ_kin = s − x_t); arguments as :func:`_rhs`'s
    (``flag`` unused)."""
    par = pa[0]
    S, S1, S2, ft, fh, fc, ff = _tables(cam, film)
    n = im.size
    N = n - 2
    out = np.empty(_NO)
    acc = np.empty(n)
    _evaluate(t, y, par, kseg, cseg, im, S, S1, S2, ft, fh, fc, ff, th, tab, fl, out, acc)
    K = np.zeros((n, n))
    Cm = np.zeros((n, n))
    K[0, 0] -= out[19]
    Cm[0, 0] -= out[20] + out[21]
    _element(K, Cm, 1, 0, out[22], out[23])
    _element(K, Cm, 1, -1, out[24], out[25])
    F0 = par.f0
    for j in range(N + 1):
        d, dd = _segment(y, n, N, j)
        k, c = kseg[j], cseg[j]
        if j == 0 or j == N:
            fe = F0 + kseg[j] * d
            f = max(fe, 0.0) + cseg[j] * dd
            if f <= 0.0:
                k = c = 0.0
            elif fe < 0.0:
                k = 0.0
        _element(K, Cm, j + 1, j + 2 if j < N else -1, k, c)
    J = np.zeros((y.size, y.size))
    for i in range(n):
        J[i, n + i] = 1.0
        for j in range(n):
            J[n + i, j] = K[i, j] * im[i]
            J[n + i, n + j] = Cm[i, j] * im[i]
    if par.film_state != 0.0:
        k = 2 * n + 2
        J[n, k] = im[0] * out[27]
        J[k, k] = out[29] + out[30] * out[27]
        J[k, 0] -= out[30] * out[19]
        J[k, n] -= out[30] * out[20]
    return J


@njit(**_OPTS)
def _evaluate_many(T, Y, pa, kseg, cseg, im, cam, film, th, tab, fl):
    """Outputs (rows of ``_OUT`` plus the accelerations) at the columns of Y; arguments
    as :func:`_rhs`'s."""
    par = pa[0]
    S, S1, S2, ft, fh, fc, ff = _tables(cam, film)
    n = im.size
    m = T.size
    res = np.empty((_NO + n, m))
    out = np.empty(_NO)
    acc = np.empty(n)
    for i in range(m):
        _evaluate(
            T[i], Y[:, i], par, kseg, cseg, im, S, S1, S2, ft, fh, fc, ff, th, tab, fl, out, acc
        )
        res[:_NO, i] = out
        res[_NO:, i] = acc
    return res


@njit(**_OPTS)
def _lift_many(T, pa, cam):
    """The cam lift s [m] at the times T [s], as :func:`_evaluate` has it (θ = θ₀ + ωt);
    ``pa`` and the cam table ``cam`` as in :func:`_rhs`."""
    par = pa[0]
    S, S1, S2 = cam[0], cam[1], cam[2]
    s = np.empty(T.size)
    for i in range(T.size):
        s[i] = _cam(par.theta0 + par.w * T[i], par.theta0, S, S1, S2)[0]
    return s


class CompiledLumped:
    """The compiled form of one :class:`ValvetrainModel` (same equations and tables)."""

    def __init__(self, model, film_table, cam_table):
        p = model.p
        trib = model.trib
        state = bool(model.film_state)
        has_film = film_table is not None and not state
        period = getattr(film_table, "period", None) if film_table is not None else None
        par = LumpedParams(
            w=model.w,
            theta0=model.theta0,
            rb=model.cam.base_radius,
            ramp=p.damping_force_ramp,
            cc=p.contact_damping,
            vr=p.bore_friction_velocity,
            mub=p.bore_friction_coefficient,
            lash=p.lash,
            ktv=p.tappet_valve_stiffness,
            ctv=p.tappet_valve_damping,
            ks=p.seat_stiffness,
            cs=p.seat_damping,
            f0=p.spring_preload,
            d_seat=model.d_seat,
            gamma=model.gamma,
            C=model.contact_C,
            ikc=model.contact_ikc,
            has_film=1.0 if has_film else 0.0,
            f_period=float(period or 0.0),
            film_state=1.0 if state else 0.0,
            width=trib.width if state else 0.0,
            eta=trib._eta if state else 0.0,
            alpha=trib._alpha if state else 0.0,
            e_prime=trib.e_prime if state else 0.0,
            supply=trib.supply_film if state else 0.0,
            sq=trib._sq if state else 0.0,
            growth_limited=1.0 if state and trib.growth_limited else 0.0,
        )
        par = LumpedParams(*(float(v) for v in par))
        if film_table is None:
            film = np.zeros((4, 1))
        elif state:  # the correction table r(t) in the film table's place
            film = np.zeros((4, film_table.time.size))
            film[0], film[1] = film_table.time, film_table.correction
        else:
            film = np.array([film_table.time, film_table.h, film_table.c, film_table.Fk])
        fr = model.friction_fn
        self.model = model
        self.n = model.n
        self.flag = np.zeros(2)
        self.cam_table = cam_table  # rows s, s', s''
        self.args = (
            np.array([par], dtype=_PARAMS),
            np.asarray(model.kseg, float),
            np.asarray(model.cseg, float),
            np.asarray(model.inv_mass, float),
            cam_table,
            film,
            np.asarray(fr.th, float),
            np.asarray(fr.tab, float),
            np.asarray(fr.F, float),
        )

    def rhs(self, t, y):
        return _rhs(t, y, *self.args, self.flag)

    def jac(self, t, y):
        return _jac(t, y, *self.args, self.flag)

    def lift(self, T) -> np.ndarray:
        """The cam lift s [m] at times T [s] (the output ``s`` without the rest)."""
        return _lift_many(np.asarray(T, float), self.args[0], self.cam_table)

    def outputs(self, T, Y) -> dict:
        """Named outputs at times T [s] and states Y (columns)."""
        res = _evaluate_many(np.asarray(T, float), np.ascontiguousarray(Y), *self.args)
        out = {k: res[i] for i, k in enumerate(_OUT)}
        out["acc_t"], out["acc_v"] = res[_NO], res[_NO + 1]
        return out


def _cam_table(cam, theta0: float):
    """Uniform table of (s, s', s'') (its rows) over one revolution from θ₀, or None if
    cubic Hermite interpolation cannot reproduce the cam to 1e-10 m (s) and 1e-9 m/rad
    (s')."""
    th = theta0 + np.linspace(0.0, _TWO_PI, CAM_POINTS + 1)
    table = np.empty((3, th.size))
    table[0], table[1], table[2] = cam.derivatives(th)
    S, S1, S2 = table
    S[-1], S1[-1], S2[-1] = S[0], S1[0], S2[0]
    mid = th[:-1] + 0.5 * (th[1] - th[0])
    s, s1, _ = cam.derivatives(mid)
    got = np.array([_cam(float(a), theta0, S, S1, S2)[:2] for a in mid[::97]])
    if np.max(np.abs(got[:, 0] - s[::97])) > 1e-10 or np.max(np.abs(got[:, 1] - s1[::97])) > 1e-9:
        return None
    return table


def compiled_model(model) -> CompiledLumped | None:
    """The compiled form of a :class:`ValvetrainModel`, or None where it does not apply
    (a tribology model that is not periodic in the cam angle, has a film law other than
    a :class:`FilmTableTribology` or a film state other than a
    :class:`FilmStateTribology`; a cam the table cannot reproduce)."""
    from .tribology import FilmStateTribology, FilmTableTribology

    trib = model.trib
    if model.friction_fn is None:  # the kernels need the friction tabulated over the cam angle
        return None
    film: FilmStateTribology | FilmTableTribology | None = None
    if model.film_state:
        if type(trib) is not FilmStateTribology:  # a subclass may change its laws
            return None
        film = trib
    elif model.has_film:
        if not isinstance(trib, FilmTableTribology):
            return None
        film = trib
    table = _cam_table(model.cam, model.theta0)
    if table is None:
        return None
    return CompiledLumped(model, film, table)


def integrate_compiled(cm: CompiledLumped, t_grid, rtol, atol, hmax, events, grid_events):
    """Integrate from the static state with LSODA, output at ``t_grid`` (from 0 to the
    end of the run). ``events``: the event functions (seat, contact) at (t, y);
    ``grid_events(T, Y)`` the same, vectorised over the grid (one row per event). Their
    roots are located within the output intervals where they change sign (a pair of
    roots within one interval is not seen).

    Returns (Y on t_grid, t_events, y_events, stats, message or None on success)."""
    y0 = cm.model.static_state()
    wall = _time.perf_counter()
    cm.flag[:] = 0.0
    Y, info = odeint(  # the kernels themselves: no Python call in between
        _rhs,
        y0,
        t_grid,
        args=(*cm.args, cm.flag),
        Dfun=_jac,
        rtol=rtol,
        atol=atol,
        hmax=hmax,
        mxstep=200000,
        full_output=True,
        tfirst=True,
    )
    stats = dict(
        nfev=int(info["nfe"][-1]),
        njev=int(info["nje"][-1]),
        nlu=int(info["nje"][-1]),
        method="LSODA",
    )
    if cm.flag[0] != 0.0:
        return (
            None,
            None,
            None,
            stats,
            (f"contact/film law did not converge at t = {cm.flag[1]:.6g} s"),
        )
    if info["message"] != "Integration successful." or not np.all(np.isfinite(Y)):
        return None, None, None, stats, f"LSODA failed: {info['message']}"
    Y = Y.T
    t_ev: list[list[float]] = [[] for _ in events]
    y_ev: list[list[np.ndarray]] = [[] for _ in events]
    g = np.asarray(grid_events(t_grid, Y))
    sign = np.signbit(g)
    todo = sorted({int(i) for k in range(len(events)) for i in np.nonzero(np.diff(sign[k]))[0]})
    for i in todo:
        sol = solve_ivp(
            cm.rhs,
            (t_grid[i], t_grid[i + 1]),
            Y[:, i],
            method="LSODA",
            jac=cm.jac,
            rtol=rtol,
            atol=atol,
            max_step=hmax,
            events=events,
        )
        for k in range(len(events)):
            t_ev[k].extend(sol.t_events[k].tolist())
            y_ev[k].extend(list(sol.y_events[k]))
    stats["wall_time_s"] = _time.perf_counter() - wall
    stats["event_intervals"] = len(todo)
    return Y, t_ev, y_ev, stats, None

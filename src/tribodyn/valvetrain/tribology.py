"""Tribology models seen by the valvetrain dynamics.

The dynamics asks a :class:`TribologyModel` two things about the cam–tappet contact:

* ``friction(t, force, entrainment_speed, sliding_speed, radius)`` — the friction force
  magnitude F_f ≥ 0 [N] over the whole cam width at contact force F [N], u_e, u_s [m/s],
  R [m]. It acts on the bodies as the paper's frictional damping: it loads the cam with the
  torque F_f (r_b + s), dissipates F_f u_s at the contact, and presses the tappet against
  its bore, where μ_b F_f opposes the tappet velocity.
* ``film(t, force, entrainment_speed, radius)`` → (h, dh/dF) — the lubricant film that acts
  in series with the contact stiffness (implicit coupling): the elastic approach is
  δ_el = δ_kin + h(t, F), δ_kin = s − x_tappet the kinematic interference. h is in m,
  dh/dF ≤ 0 in m/N. Explicit models (the paper's choice) return no film.

``t`` is the simulation time [s] from the start of the run (cam angle θ = θ₀ + ωt).
All methods must accept arrays (broadcast together) as well as floats.

Models here: :class:`Frictionless`, :class:`AnalyticTribology` (explicit default: film
formula + Greenwood–Tripp boundary friction + viscous friction, per unit length × width),
and :class:`FilmTableTribology`, the hook for the implicit coupling: a friction model plus
a film law linearised about reference forces, h = h_k(t) + c_k(t)(F − F_k(t)), c_k ≤ 0,
tabulated in time (what transient-EHL runs provide, iterated by waveform relaxation);
:func:`squeeze_film_load`, the rigid-cylinder squeeze film that limits how fast such a
film can thin; and :class:`FilmStateTribology`, the film thickness as a state of the
dynamics (entraining film + squeeze film, in series with the contact; see
:func:`entraining_film_load`).
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from types import MappingProxyType
from typing import Any

import numpy as np
from numba import njit

from .._typing import ArrayLike
from .._validation import InputError, check_array, check_positive
from ..physics import film_state_laws as laws
from ..physics import limits as L
from ..physics import typical, typical_engine
from ..physics.analytic_contact import analytic_contact
from ..physics.asperity import Roughness
from ..physics.film_state_laws import SUPPLY_FILM, entraining_film_load
from ..physics.lubricant import TYPICAL_OIL, Lubricant
from ..physics.materials import STEEL, Body, BodyPair
from .film_kernels import steady_films

__all__ = [
    "TribologyModel",
    "Frictionless",
    "AnalyticTribology",
    "FilmTableTribology",
    "TYPICAL_ROUGHNESS",
    "squeeze_film_load",
    "entraining_film_load",
    "FilmStateTribology",
    "SUPPLY_FILM",
]

#: Typical Greenwood–Tripp roughness of a ground cam on a ground tappet
#: (:mod:`tribodyn.physics.typical`: σ = COMPOSITE_RMS["ground"], η and β from
#: ``typical_summits``); the paper's Table 4 is stated in its case file.
_GROUND_RMS = typical.COMPOSITE_RMS["ground"].value
_GROUND_ETA, _GROUND_BETA = typical.typical_summits(_GROUND_RMS)
TYPICAL_ROUGHNESS = Roughness(
    asperity_density=_GROUND_ETA, rms=_GROUND_RMS, summit_radius=_GROUND_BETA
)


def squeeze_film_load(film, approach_speed, radius, viscosity):
    """Load per unit length [N/m] carried by squeeze of an isoviscous film between a rigid
    cylinder of radius R [m] and a plane approaching each other at V = −dh/dt [m/s], at
    minimum film h [m] and viscosity η [Pa s]::

        w' = 3√2 π η V R^(3/2) / h^(3/2)

    (Reynolds equation d/dx(h³ p'/12η) = dh/dt with h = h₀ + x²/2R, p → 0 as |x| → ∞,
    integrated twice: p = 6ηVR/h(x)², ∫ dx/h(x)² = π√(2R)/(2h₀^(3/2)); e.g. Hamrock,
    Schmid & Jacobson, *Fundamentals of Fluid Film Lubrication*, 2004, ch. 15). The
    film follows h(t) = (h_i^(−1/2) + k t/2)^(−2), k = w'/(3√2 π η R^(3/2)), under a
    constant load. Negative for separating surfaces (Sommerfeld; a real film cavitates)."""
    h = np.asarray(film, dtype=float)
    return (
        3.0
        * np.sqrt(2.0)
        * np.pi
        * viscosity
        * np.asarray(approach_speed, dtype=float)
        * np.asarray(radius, dtype=float) ** 1.5
        / h**1.5
    )


class TribologyModel(ABC):
    """Interface between the valvetrain dynamics and a contact tribology model."""

    #: friction depends on time only through the cam angle θ mod 2π (and F): the dynamics
    #: may then tabulate it over one revolution instead of calling it at every step.
    periodic_in_cam_angle: bool = True
    #: the model supplies a film law h(t, F) in series with the contact (implicit coupling).
    has_film: bool = False
    #: the model supplies the film as a state of the dynamics (``film_rate``; implicit
    #: coupling, :class:`FilmStateTribology`).
    has_film_state: bool = False
    name: str = "tribology"

    @abstractmethod
    def friction(self, t, force, entrainment_speed, sliding_speed, radius):
        """Friction force magnitude F_f ≥ 0 [N] over the cam width (vectorised)."""

    def film(self, t, force, entrainment_speed, radius):
        """(h [m], dh/dF [m/N], ≤ 0) of the film in series with the contact."""
        return 0.0, 0.0

    def report(self, t, force, entrainment_speed, sliding_speed, radius) -> dict:
        """Optional extra outputs (arrays) for the presented cycle, e.g. central film."""
        return {}


class Frictionless(TribologyModel):
    """No friction, no film (for verification against rigid-body/energy results)."""

    name = "frictionless"

    def friction(self, t, force, entrainment_speed, sliding_speed, radius):
        return np.zeros(np.broadcast(t, force, entrainment_speed, sliding_speed, radius).shape)


class AnalyticTribology(TribologyModel):
    """Explicit tribology (paper Section 2.1 "simple analytical tribology").

    Evaluates :func:`tribodyn.physics.analytic_contact.analytic_contact` at the load per
    unit length w = F/width and multiplies its friction (viscous, Eyring or Newtonian,
    plus Greenwood–Tripp boundary friction τ₀A_a + ςW_a) by the width. No film compliance
    (the paper's explicit approach).

    Parameters
    ----------
    width : cam width [m] (typical 0.014); must equal the valvetrain's cam_width.
    bodies : (cam, tappet) bodies (default steel/steel).
    lubricant : default :data:`~tribodyn.physics.lubricant.TYPICAL_OIL`.
    roughness : Greenwood–Tripp roughness or None (default :data:`TYPICAL_ROUGHNESS`).
    boundary_shear_coefficient : ς (default the typical steel/steel boundary friction
        coefficient, :func:`tribodyn.physics.typical.boundary_friction`).
    boundary_shear_strength : τ₀ [Pa] of the boundary shear τ₀ + ςp (paper Eq. 17;
        default the typical 0 that goes with a measured ς).
    viscous_model, film_formula, limiting_shear : passed to ``analytic_contact``.
    """

    name = "analytic"

    def __init__(
        self,
        width: float = typical_engine.CAM_WIDTH.value,
        *,
        bodies: BodyPair | None = None,
        lubricant: Lubricant = TYPICAL_OIL,
        roughness: Roughness | None = TYPICAL_ROUGHNESS,
        boundary_shear_coefficient: float = typical.boundary_friction("steel").value,
        boundary_shear_strength: float = typical.BOUNDARY_SHEAR_STRENGTH.value,
        viscous_model: str = "eyring",
        film_formula: str = "moes",
        limiting_shear: bool = True,
    ):
        self.width = check_positive("width", width, "m")
        self.bodies = tuple(bodies) if bodies is not None else (Body(STEEL), Body(STEEL))
        if not isinstance(lubricant, Lubricant):
            raise InputError(f"lubricant must be a Lubricant (got {type(lubricant).__name__})")
        self.lubricant = lubricant
        self.roughness = roughness
        self.boundary_shear_coefficient = boundary_shear_coefficient
        self.boundary_shear_strength = boundary_shear_strength
        self.viscous_model = viscous_model
        self.film_formula = film_formula
        self.limiting_shear = limiting_shear

    @property
    def kwargs(self) -> MappingProxyType[str, Any]:
        """The keyword arguments passed to ``analytic_contact`` (read-only)."""
        return MappingProxyType(
            {
                "boundary_shear_coefficient": self.boundary_shear_coefficient,
                "boundary_shear_strength": self.boundary_shear_strength,
                "viscous_model": self.viscous_model,
                "film_formula": self.film_formula,
                "limiting_shear": self.limiting_shear,
            }
        )

    def _contact(self, force, ue, us, R):
        w = np.maximum(np.asarray(force, dtype=float), 0.0) / self.width
        # Very light loads give films of thousands of σ: Greenwood–Tripp underflows (and
        # scipy's pbdv returns NaN for λ ≳ 10³); the asperity terms are exactly 0 there.
        with np.errstate(under="ignore", invalid="ignore"):
            c = analytic_contact(
                w,
                np.maximum(R, 1e-9),
                ue,
                us,
                self.bodies,
                self.lubricant,
                self.roughness,
                **self.kwargs,
            )
        if self.roughness is not None:
            far = np.asarray(c.central_film) > 38.0 * self.roughness.rms
            for name in ("asperity_load", "boundary_friction"):
                v = np.asarray(getattr(c, name), dtype=float)
                setattr(c, name, np.where(far, 0.0, v))
        return c

    def friction(self, t, force, entrainment_speed, sliding_speed, radius):
        c = self._contact(force, entrainment_speed, sliding_speed, radius)
        f = c.friction * self.width
        return np.where(np.asarray(force) > 0.0, f, 0.0)

    def report(self, t, force, entrainment_speed, sliding_speed, radius) -> dict:
        c = self._contact(force, entrainment_speed, sliding_speed, radius)
        on = np.asarray(force) > 0.0
        return {
            "central_film": c.central_film,
            "min_film": c.min_film,
            "viscous_friction": np.where(on, c.viscous_friction * self.width, 0.0),
            "boundary_friction": np.where(on, c.boundary_friction * self.width, 0.0),
            "asperity_load": np.where(on, c.asperity_load * self.width, 0.0),
            "regime": c.regime,
        }


def _table_times(time: ArrayLike) -> np.ndarray:
    """The sample times [s] of a table: finite, at least one, strictly increasing."""
    t = check_array("time", np.atleast_1d(time), min_size=1)
    if t.size > 1 and np.any(np.diff(t) <= 0.0):
        raise InputError("time must be strictly increasing")
    return t


def _table_column(name: str, values: ArrayLike | None, n: int, default: float) -> np.ndarray:
    """A table's column of n samples: ``values`` (finite; one value or n) as floats, or
    ``default`` everywhere."""
    if values is None:
        return np.full(n, default)
    return np.broadcast_to(check_array(name, np.atleast_1d(values), min_size=1), (n,)).astype(float)


@njit(cache=True, nogil=True)
def table_film(t, force, ft, fh, fc, ff, period):
    """(h, dh/dF) = (h_k + c_k (F − F_k), c_k) of a film table at one time t [s] and force
    F [N]: the columns h_k, c_k, F_k (``fh``, ``fc``, ``ff``) linear between the sample
    times ``ft`` (strictly increasing), the end samples outside them; with ``period``
    > 0 t is first mapped to ft[0] + (t − ft[0]) mod period."""
    n = ft.size
    if period > 0.0:
        t = ft[0] + (t - ft[0]) % period
    k = np.searchsorted(ft, t, side="right") - 1
    if k < 0:
        i, a = 0, 0.0
    elif k >= n - 1:
        i, a = n - 1, 0.0
    else:
        i, a = k, (t - ft[k]) / (ft[k + 1] - ft[k])
    j = min(i + 1, n - 1)
    hk = fh[i] + a * (fh[j] - fh[i])
    ck = fc[i] + a * (fc[j] - fc[i])
    fk = ff[i] + a * (ff[j] - ff[i])
    return hk + ck * (force - fk), ck


def _checked_friction_model(friction_model: TribologyModel) -> TribologyModel:
    """``friction_model``, the model that supplies a wrapping model's friction, checked."""
    if not isinstance(friction_model, TribologyModel):
        raise InputError(
            f"friction_model must be a TribologyModel (got {type(friction_model).__name__})"
        )
    return friction_model


class FilmTableTribology(TribologyModel):
    """Hook for the implicit coupling: friction model + tabulated, linearised film law.

    h(t, F) = h_k(t) + c_k(t) (F − F_k(t)),   dh/dF = c_k(t) ≤ 0

    with h_k, c_k, F_k given at increasing times ``time`` [s] (simulation time of the
    valvetrain run) and interpolated linearly. With ``period`` [s] (one engine cycle = one
    cam revolution, 2π/ω) the table is used periodically, t ↦ time[0] + (t − time[0])
    mod period, so a film history from the presented cycle also drives the first cycle.

    Datum: the dynamics measures the tappet from static equilibrium, where it touches the
    base circle at zero force. A film present there only shifts that datum, so give h_k
    relative to the base-circle film (a steady film formula diverges at zero load anyway);
    only changes of h along the cycle and the compliance c_k act on the motion.

    Parameters
    ----------
    friction_model : the model supplying ``friction`` (e.g. :class:`AnalyticTribology`).
    time : sample times [s], strictly increasing.
    film : h_k [m] at those times (finite; may be ≤ 0 only if the user means it).
    compliance : c_k [m/N] ≤ 0 (default 0: film independent of load).
    reference_force : F_k [N] (default 0).
    period : optional period [s] of the table.
    """

    has_film = True
    name = "film-table"

    def __init__(
        self,
        friction_model: TribologyModel,
        time: ArrayLike,
        film: ArrayLike,
        compliance: ArrayLike | None = None,
        reference_force: ArrayLike | None = None,
        *,
        period: float | None = None,
    ):
        self.friction_model = _checked_friction_model(friction_model)
        self.periodic_in_cam_angle = friction_model.periodic_in_cam_angle
        self.time = t = _table_times(time)
        self.h = _table_column("film", film, t.size, 0.0)
        self.c = _table_column("compliance", compliance, t.size, 0.0)
        if np.any(self.c > 0.0):
            raise InputError("compliance must be <= 0 (film thickness cannot grow with load)")
        self.Fk = _table_column("reference_force", reference_force, t.size, 0.0)
        self.period = None if period is None else check_positive("period", period, "s")
        self._t0 = float(t[0])

    def _wrap(self, t):
        if self.period is None:
            return t
        return self._t0 + np.mod(np.asarray(t, dtype=float) - self._t0, self.period)

    def friction(self, t, force, entrainment_speed, sliding_speed, radius):
        return self.friction_model.friction(t, force, entrainment_speed, sliding_speed, radius)

    def film(self, t, force, entrainment_speed, radius):
        # one instant (the dynamics' hot path: floats, tested first)
        if (type(t) is float and type(force) is float) or np.ndim(t) == np.ndim(force) == 0:
            columns = (self.time, self.h, self.c, self.Fk, self.period or 0.0)
            return table_film(float(t), float(force), *columns)
        tt = self._wrap(t)
        if self.time.size == 1:
            hk, ck, fk = self.h[0], self.c[0], self.Fk[0]
        else:
            hk = np.interp(tt, self.time, self.h)
            ck = np.interp(tt, self.time, self.c)
            fk = np.interp(tt, self.time, self.Fk)
        return hk + ck * (force - fk), ck * np.ones_like(np.asarray(force, dtype=float))

    def report(self, t, force, entrainment_speed, sliding_speed, radius) -> dict:
        out = dict(self.friction_model.report(t, force, entrainment_speed, sliding_speed, radius))
        out["series_film"] = self.film(t, force, entrainment_speed, radius)[0]
        return out


class FilmStateTribology(TribologyModel):
    """The film thickness h as a state of the dynamics (implicit coupling).

    The film carries the contact force F_c in series with the contact's elasticity:

        F_c = L [w'_ent(h; u_e, R, r(t)) + w'_sq(h, ḣ; R)],
        ḣ = H((L w'_ent(h) − F_c) / D(h), x_t),   D = 3√2 π η₀ R^(3/2) L / h^(3/2)

    (L the cam width; w'_ent the entraining film of :func:`entraining_film_load`, bounded
    by the oil supply h_s; w'_sq = D V/L the rigid-cylinder squeeze film of
    :func:`squeeze_film_load`, isoviscous). The elastic approach is
    δ_el = δ_kin + h: the film separates the surfaces from metal contact, the datum of
    the explicit run (zero lash); h_s only bounds the film. On the base circle the film
    lifts the tappet off metal contact, compressing the valvetrain chain in series, and
    settles where its entraining load equals that chain's force.
    Without load (F_c = 0) the film recovers towards h_s; a load squeezes it at the rate
    the squeeze film allows; with u_e = 0 only the squeeze carries the load. The film
    thickens no faster than oil reaches it from the supply: H
    (:func:`~tribodyn.physics.film_state_laws.limited_growth`)
    is a smooth minimum of the free rate and the transport limit x_t of
    :meth:`growth_limit`, which binds where u_e or R step (a ramp-less cam's step of
    acceleration; without it the film grew from 0.71 to 2.1 µm within 0.02° there and
    the force through it spiked to 2e5–7e5 N). One force F_c passes through the film and the
    contact's spring and damper in series: the damper acts on the elastic rate
    δ̇_kin + ḣ (``cam_contact`` solves for F_c: closed form where the film thins, a
    bracketed Newton iteration where it grows). The film's work −P ḣ is counted in the dynamics' dissipation, so the
    energy balance stays closed.

    ``correction`` r(t) (default 1) scales the flooded film of the entraining law,
    tabulated at ``time`` [s] and interpolated linearly (periodic with ``period``): the
    implicit coupling sets it so that the film matches the transient EHL at its samples;
    between them the laws above shape the force.

    Parameters
    ----------
    friction_model : the model supplying ``friction``.
    width : cam width L [m]; lubricant : η₀, α (a :class:`Lubricant`); e_prime : E' [Pa].
    supply_film : h_s [m] (default :data:`SUPPLY_FILM`, an assumed oil supply layer; range
        :data:`~tribodyn.physics.limits.SUPPLY_FILM_THICKNESS`).
    time, correction, period : the correction table (optional).
    growth_limited : the film thickens no faster than oil can reach it from the supply
        (:meth:`growth_limit`, :func:`~tribodyn.physics.film_state_laws.limited_growth`;
        default True).
    checked : the arguments checked where they entered (``"supply_film"``: a case file's,
        or a film state's it is copied from), not checked again.
    """

    has_film = False
    has_film_state = True
    name = "film-state"

    def __init__(
        self,
        friction_model: TribologyModel,
        *,
        width: float,
        lubricant: Lubricant,
        e_prime: float,
        supply_film: float = SUPPLY_FILM,
        time: ArrayLike | None = None,
        correction: ArrayLike | None = None,
        period: float | None = None,
        growth_limited: bool = True,
        checked: tuple[str, ...] = (),
    ):
        self.friction_model = _checked_friction_model(friction_model)
        self.growth_limited = bool(growth_limited)
        self.periodic_in_cam_angle = friction_model.periodic_in_cam_angle
        if not isinstance(lubricant, Lubricant):
            raise InputError(f"lubricant must be a Lubricant (got {type(lubricant).__name__})")
        self.width = check_positive("width", width, "m")
        self.lubricant = lubricant
        self.e_prime = check_positive("e_prime", e_prime, "Pa")
        if "supply_film" not in checked:
            supply_film = L.SUPPLY_FILM_THICKNESS.check("supply_film", supply_film)
        self.supply_film = float(supply_film)
        t = np.zeros(1) if time is None else _table_times(time)
        r = _table_column("correction", correction, t.size, 1.0)
        if np.any(r <= 0.0):
            raise InputError("correction must be > 0 (a factor on the flooded film)")
        self.time, self.correction = t, r
        self.period = None if period is None else check_positive("period", period, "s")
        self._zero = np.zeros(t.size)
        self._eta = float(lubricant.viscosity)
        self._alpha = float(lubricant.pressure_viscosity)
        # squeeze coefficient 3√2 π η₀ L = D h^1.5/R^1.5 (squeeze_film_load at h = V = R = 1)
        self._sq = float(squeeze_film_load(1.0, 1.0, 1.0, self._eta)) * self.width

    def friction(self, t, force, entrainment_speed, sliding_speed, radius):
        return self.friction_model.friction(t, force, entrainment_speed, sliding_speed, radius)

    def report(self, t, force, entrainment_speed, sliding_speed, radius) -> dict:
        return dict(self.friction_model.report(t, force, entrainment_speed, sliding_speed, radius))

    def correction_at(self, t: float) -> float:
        """r(t), linear between the table's samples (periodic with ``period``)."""
        zero, period = self._zero, self.period or 0.0
        return table_film(t, 0.0, self.time, self.correction, zero, zero, period)[0]

    def film_rate(self, t: float, h: float, force: float, ue: float, R: float):
        """(ḣ [m/s], ∂ḣ/∂h [1/s], ∂ḣ/∂F_c [m/(N s)]) of the film h [m] carrying F_c [N]
        (:func:`~tribodyn.physics.film_state_laws.film_rate`, r = r(t))."""
        args = (self._eta, self._alpha, self.e_prime, self.supply_film)
        return laws.film_rate(h, force, ue, R, *args, self.correction_at(t), self.width, self._sq)

    def squeeze_compliance_slope(self, h: float, ue: float, R: float) -> float:
        """∂(1/D)/∂h [1/(N s)] of the squeeze film at h [m] (the mixed derivative
        −∂²ḣ/∂h∂F_c of :meth:`film_rate`; :func:`~tribodyn.physics.film_state_laws.
        squeeze_compliance_slope`)."""
        return laws.squeeze_compliance_slope(h, R, self._sq)

    def growth_limit(self, h: float, ue: float, R: float) -> tuple[float, float]:
        """(x_t [m/s], ∂x_t/∂h [1/s]): the fastest the film can thicken
        (:func:`~tribodyn.physics.film_state_laws.growth_limit`; infinite with
        ``growth_limited`` False)."""
        return laws.growth_limit(h, ue, R, self.supply_film, self.growth_limited)

    def steady_film(self, t, force, entrainment_speed, radius, correction=None):
        """Film h [m] whose entraining load equals ``force`` [N] (no squeeze), by
        bisection in ln h (vectorised, compiled: :func:`~.film_kernels.steady_films`; h_s
        where the force is ≤ 0 or u_e = 0 … the film carries no steady load then)."""
        F, u, R = np.broadcast_arrays(
            *(np.asarray(v, dtype=float) for v in (force, entrainment_speed, radius))
        )
        r = (
            np.vectorize(self.correction_at)(np.asarray(t, dtype=float)) * np.ones(F.shape)
            if correction is None
            else np.broadcast_to(np.asarray(correction, dtype=float), F.shape)
        )
        args = (self._eta, self._alpha, self.e_prime, self.supply_film, self.width)
        flat = (np.ascontiguousarray(v, dtype=float).ravel() for v in (F, u, R, r))
        out = steady_films(*flat, *args).reshape(F.shape)
        return out[()] if out.ndim == 0 else out

"""Options, inputs and result of the EHL line-contact solvers.

:class:`EHLOptions` holds the numerical settings, :class:`EHLResult` the solution of one
solve or time step; :class:`Conditions` and :class:`ContactModel` bundle what every solve
needs (operating point; bodies, lubricant and roughness with their reduced moduli).
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from typing import Protocol

import numpy as np

from ..._validation import (
    InputError,
    check_bool,
    check_choice,
    check_int,
    check_positive,
)
from ...physics import limits as L
from ...physics import typical
from ...physics.asperity import Roughness
from ...physics.friction import BOUNDARY_SHEAR_STRENGTH, VISCOUS_MODELS
from ...physics.lubricant import Lubricant
from ...physics.materials import Body, as_bodies, reduced_modulus

__all__ = ["EHLOptions", "EHLResult", "Conditions", "ContactModel", "LubricantModel"]


@dataclass(frozen=True)
class EHLOptions:
    """Numerical settings of the EHL solvers.

    n : grid nodes (uniform); None (default) uses 384 nodes (``grid.N_AUTO``) over the
        domain sized from the contact (below): the discretisation error of h_c and h_min
        falls as n⁻² and is 0.1–0.25 % (friction < 0.1 %) at 384 nodes over the loads,
        speeds and radii of a cam cycle, elastic or nearly rigid (docs/convergence.md). A
        steady solve then checks its result against the nested solution on half the
        nodes and doubles n (up to 4096) while h_c or h_min differ by more than 1 %; a
        transient event keeps the node count of its steady start.
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
    boundary_shear_coefficient: float = typical.boundary_friction("steel").value
    time_order: int = 2

    def __post_init__(self):
        # the case file's [numerics] and surface sets' τ₀, ς are checked here
        L.check_fields(self, _LIMITS, optional=("n",))
        set_ = object.__setattr__
        set_(self, "elastic", check_bool("elastic", self.elastic))
        check_choice("viscous_model", self.viscous_model, VISCOUS_MODELS)
        set_(self, "limiting_shear", check_bool("limiting_shear", self.limiting_shear))
        try:
            order = check_int("time_order", self.time_order)
        except InputError:
            order = None
        if order not in (1, 2):
            raise InputError(f"time_order must be 1 or 2 (got {self.time_order!r})")
        set_(self, "time_order", order)

    def with_boundary_friction(
        self, coefficient: float, strength: float, checked: tuple[str, ...] = ()
    ) -> EHLOptions:
        """A copy with the boundary shear law τ = τ₀ + ς p_a of Eq. 17 (ς ``coefficient``
        [-], τ₀ ``strength`` [Pa]); only these two are checked again, but for the fields
        ``checked`` names (checked where they entered)."""
        new = copy.copy(self)
        object.__setattr__(new, "boundary_shear_coefficient", coefficient)
        object.__setattr__(new, "boundary_shear_strength", strength)
        L.check_fields(new, {k: _LIMITS[k] for k in _FRICTION if k not in checked})
        return new


#: the fields of the boundary shear law (Eq. 17)
_FRICTION = ("boundary_shear_coefficient", "boundary_shear_strength")
#: Range of every numeric field of EHLOptions (physics.limits).
_LIMITS = {
    "n": L.EHL_NODES,
    "inlet": L.DOMAIN_HALF_WIDTHS,
    "outlet": L.DOMAIN_HALF_WIDTHS,
    "inlet_truncation": L.INLET_TRUNCATION,
    "inlet_rigid": L.DOMAIN_RIGID_LENGTHS,
    "outlet_rigid": L.DOMAIN_RIGID_LENGTHS,
    "tol": L.NEWTON_TOL,
    "max_iter": L.NEWTON_MAX_ITER,
    "boundary_shear_strength": L.BOUNDARY_SHEAR_STRENGTH,
    "boundary_shear_coefficient": L.BOUNDARY_SHEAR_COEFFICIENT,
}


# ----------------------------------------------------------------------------- result
@dataclass
class EHLResult:
    """Line-contact EHL solution (per unit length, SI). Viscous and boundary friction are
    magnitudes (against the relative sliding, equal and opposite on the two surfaces);
    the rolling force is signed and acts alike on both surfaces (``postprocess``)."""

    x: np.ndarray  #: node positions [m] (contact frame)
    pressure: np.ndarray  #: hydrodynamic pressure p [Pa]
    asperity_pressure: np.ndarray  #: Greenwood–Tripp asperity pressure p_a [Pa]
    film: np.ndarray  #: film thickness h [m]
    central_film: float  #: h at x = 0 [m]
    min_film: float  #: min h [m]
    min_film_position: float  #: x of min h [m]
    cavitation_position: float  #: outlet meniscus (p → 0) [m]
    rigid_approach: float  #: h₀ (includes the 2-D elastic constant) [m]
    load: float  #: imposed w [N/m]
    hydrodynamic_load: float  #: ∫p dx [N/m]
    asperity_load: float  #: ∫p_a dx [N/m]
    viscous_friction: float  #: ∫|τ_couette| dx [N/m]
    #: hydrodynamic rolling force sgn(u_e)∫(h/2)(dp/dx) dx [N/m], the Poiseuille part of
    #: Eq. 16: on each surface (cam and tappet alike), > 0 against the entrainment
    rolling_friction: float
    boundary_friction: float  #: ∫(τ₀ A_a/A + ς p_a) dx [N/m]
    entrainment_speed: float
    sliding_speed: float
    radius: float
    converged: bool
    iterations: int
    message: str
    time: float = 0.0
    squeeze_velocity: float = 0.0  #: −dh_c/dt, approach speed of the central film [m/s]
    shear_stress: np.ndarray | None = field(default=None, repr=False)  #: viscous τ(x) [Pa]
    inlet_load_deficit: float = 0.0  #: estimated share of w lost to the truncated inlet
    #: conditions outside the model's validity (also appended to ``message``)
    warnings: list = field(default_factory=list)

    @property
    def friction(self) -> float:
        """Viscous + boundary friction [N/m] (the sliding friction; the rolling force
        ``rolling_friction`` acts on both surfaces alike and is not included)."""
        return self.viscous_friction + self.boundary_friction

    @property
    def friction_coefficient(self) -> float:
        return self.friction / self.load

    def surface_friction(self) -> tuple[float, float]:
        """Tangential force [N/m] the film (and asperities) exert on surface 1 (speed
        u_e + u_s/2; the cam) and surface 2 (u_e − u_s/2; the tappet), positive along the
        entrainment direction: Couette + boundary against the relative sliding, equal and
        opposite, plus the rolling force against the entrainment on both (paper Eq. 16,
        its ±(h/2)dp/dx being the shear stress on the two facing walls)::

            F₁ = −sgn(u_s)(F_v + F_b) − F_R,   F₂ = +sgn(u_s)(F_v + F_b) − F_R
        """
        s = self.friction * float(np.sign(self.sliding_speed))
        return -s - self.rolling_friction, s - self.rolling_friction

    def totals(self, width: float) -> dict:
        """Loads [N] and friction forces [N] over a contact width [m]."""
        width = check_positive("width", width, "m")
        return {
            k: getattr(self, k) * width
            for k in (
                "load",
                "hydrodynamic_load",
                "asperity_load",
                "viscous_friction",
                "rolling_friction",
                "boundary_friction",
                "friction",
            )
        }


# ----------------------------------------------------------------------------- helpers


def with_overrides(opts: EHLOptions | None, overrides: dict) -> EHLOptions:
    """``opts`` (None: the defaults) with the fields ``overrides`` names replaced (a copy);
    unknown names are an error."""
    opts = opts or EHLOptions()
    if not overrides:
        return opts
    unknown = sorted(set(overrides) - set(opts.__dict__))
    if unknown:
        raise InputError(
            f"unknown EHL option(s) {', '.join(unknown)}; valid: {', '.join(sorted(opts.__dict__))}"
        )
    return EHLOptions(**{**opts.__dict__, **overrides})


@dataclass(frozen=True)
class Conditions:
    """Operating point of one solve: w [N/m], R [m], u_e and u_s [m/s]."""

    load: float
    radius: float
    entrainment_speed: float
    sliding_speed: float

    @property
    def surface_speeds(self) -> tuple[float, float]:
        """(u₁, u₂) [m/s] of surface 1 (the cam), u₁ = u_e + u_s/2, and surface 2 (the
        tappet), u₂ = u₁ − u_s."""
        u1 = self.entrainment_speed + 0.5 * self.sliding_speed
        return u1, u1 - self.sliding_speed

    @classmethod
    def checked(cls, load, radius, entrainment_speed, sliding_speed) -> Conditions:
        """Validated conditions: load, radius and speeds inside
        :data:`~tribodyn.physics.limits.LINE_LOAD`, ``CONTACT_RADIUS`` and
        ``SURFACE_SPEED``."""
        return cls(
            L.LINE_LOAD.check("load", load),
            L.CONTACT_RADIUS.check("radius", radius),
            L.SURFACE_SPEED.check("entrainment_speed", entrainment_speed),
            L.SURFACE_SPEED.check("sliding_speed", sliding_speed),
        )


class LubricantModel(Protocol):
    """The lubricant as the EHL solvers read it: a :class:`~tribodyn.Lubricant`, or the
    thermal solver's oil at frozen node temperatures
    (:class:`~tribodyn.contact.ehl.thermal_field.FrozenTemperatureOil`). Scales: μ₀
    [Pa·s], α [1/Pa], ρ₀ [kg/m³], Eyring stress τ₀ [Pa], limiting-shear coefficient
    [-] and stress [Pa]; functions of the pressure p [Pa]: ρ(p), dρ/dp, ln(μ(p)/μ₀),
    d ln μ/dp [1/Pa] and μ(p)."""

    @property
    def viscosity(self) -> float: ...

    @property
    def pressure_viscosity(self) -> float: ...

    @property
    def density(self) -> float: ...

    @property
    def eyring_stress(self) -> float: ...

    @property
    def limiting_shear_coefficient(self) -> float: ...

    @property
    def limiting_shear_stress(self) -> float: ...

    def density_at(self, p): ...

    def ddensity_dp(self, p): ...

    def log_viscosity_ratio(self, p): ...

    def dlog_viscosity_dp(self, p): ...

    def viscosity_at(self, p): ...


@dataclass(frozen=True)
class ContactModel:
    """The physical model of a contact: bodies, lubricant, composite roughness (or None)
    and the reduced moduli E' of the bulk (sizes the contact) and of the surface layer
    (scales the asperity pressure)."""

    bodies: tuple[Body, Body]
    lubricant: LubricantModel
    roughness: Roughness | None
    e_bulk: float = field(init=False)
    e_surface: float = field(init=False)

    def __post_init__(self):
        object.__setattr__(self, "e_bulk", reduced_modulus(self.bodies))
        object.__setattr__(self, "e_surface", reduced_modulus(self.bodies, surface=True))

    @classmethod
    def checked(cls, bodies, lubricant, roughness) -> ContactModel:
        """Validated model: two bodies, a Lubricant, a Roughness or None."""
        bodies = as_bodies(bodies)
        if not isinstance(lubricant, Lubricant):
            raise InputError(f"lubricant must be a Lubricant (got {type(lubricant).__name__})")
        if roughness is not None and not isinstance(roughness, Roughness):
            raise InputError(
                f"roughness must be a Roughness or None (got {type(roughness).__name__})"
            )
        return cls(bodies, lubricant, roughness)

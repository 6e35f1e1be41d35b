"""Parameters of the single direct-acting valvetrain (paper Section 2.3, Tables 2, 3, 7).

Bodies (one translational DOF each along the valve axis, +x = valve opening):
cam (rotation prescribed), flat tappet, valve (+ retainer), valve spring as N lumped
masses, cylinder head (ground). Joints (paper Table 3), each a stiffness and a damping:

=====================  =======================  ===========================================
joint                  bodies                   law
=====================  =======================  ===========================================
cam–follower contact   cam, tappet              nonlinear line contact (Palmgren) + damping,
                                                unilateral; optional film in series
push contact           tappet, valve tip        linear + damping, unilateral, optional lash
spring seat            valve (retainer), spring linear, unilateral, in series with the
                                                first coil segment
spring support         head, spring             linear, unilateral, in series with the last
                                                coil segment
valve seat             head, valve              linear + damping, unilateral
=====================  =======================  ===========================================

Defaults: the masses, spring rate and preload, which decide the contact force, are the
typical values of :data:`tribodyn.physics.typical_engine.VALVETRAIN` (with their sources); a case
file that leaves them out runs on them with a warning naming each one. The paper's values
(Table 7) are stated in its case, ``cases/andreou2023.toml``. Everything else is assumed
(docs/conventions.md) and documented per field below.
Unilateral joints phase their damping in over the first ``damping_force_ramp`` newtons of
elastic force (a cubic step, as the IMPACT force of MSC Adams), so contact forces are
continuous at closure and never tensile.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, fields
from typing import ClassVar

import numpy as np

from .._validation import InputError
from ..physics import limits as L
from ..physics import typical_engine

__all__ = ["ValvetrainParameters", "STEEL_REDUCED_MODULUS", "PALMGREN_COEFFICIENT"]

#: E' of the steel/steel pair, 1/E' = ½Σ(1−ν²)/E with the typical E = 210 GPa, ν = 0.3
#: (:data:`tribodyn.physics.typical_engine.STEEL_MODULUS`, docs/conventions.md).
STEEL_REDUCED_MODULUS = typical_engine.STEEL_MODULUS.value / (
    1.0 - typical_engine.STEEL_POISSON.value**2
)

#: Palmgren's line-contact approach for steel, δ = 3.84e-5 Q^0.9 / l^0.8 with δ, l in mm and
#: Q in N (Palmgren, Ball and Roller Bearing Engineering, 3rd ed., 1959; Harris & Kotzalas,
#: Rolling Bearing Analysis, 5th ed., 2007). In SI: δ = 3.84e-8 · 1000^(−0.8) Q^0.9 l^(−0.8).
PALMGREN_COEFFICIENT = 3.84e-8 * 1000.0**-0.8


@dataclass(frozen=True)
class ValvetrainParameters:
    """Validated parameters of the single valvetrain (SI units).

    Masses and spring (typical values, :data:`tribodyn.physics.typical_engine.VALVETRAIN`)
    ------------------------------------------------------------------------------
    valve_mass : valve + retainer + collets [kg] (0.060).
    tappet_mass : flat (bucket) tappet [kg] (0.040).
    spring_mass : active valve-spring mass m_s [kg] (0.030).
    spring_rate : k [N/m] (35 000).
    spring_preload : installed load F₀ with the valve closed [N] (250).
    spring_masses : N, number of lumped coil masses (≥ 0). N ≥ 1: N masses of m_s/(N+1)
        joined by N+1 coil segments of stiffness (N+1)k, the end half-masses m_s/(2(N+1))
        assigned to the valve and the head, so the fixed–fixed surge frequency is
        f₁ = (N+1)/π √(k/m_s) sin(π/(2(N+1))) → ½√(k/m_s) (error ≈ π²/(24(N+1)²)) and
        the quasi-static effective mass m_s(2n²+1)/(6n²), n = N+1 → m_s/3.
        N = 0: massless spring with m_s/3 lumped on the valve. Default 8 (f₁ 0.5 % low).
    spring_damping_ratio : ζ of the first surge mode (stiffness-proportional coil damping,
        ζ_j = ζ f_j/f₁) [-] (*assumed* 0.02; valve springs show ~1–3 %).

    Joints (all *assumed*: plausible direct-acting-bucket magnitudes; change per engine)
    ----------------------------------------------------------------------------------
    contact_stiffness : None → Palmgren steel line contact over ``cam_width`` scaled by
        STEEL_REDUCED_MODULUS/``contact_modulus`` (≈ 3.9e8 N/m tangent at 500 N,
        12 mm); a number → linear contact law of that stiffness [N/m].
    contact_modulus : E' of the cam/tappet pair for the Palmgren law [Pa].
    contact_damping : cam–tappet damping [N·s/m] (500: ζ ≈ 0.06 of the tappet on the
        contact stiffness at 500 N).
    camshaft_stiffness : optional camshaft/bearing support stiffness in series with the
        contact [N/m] (None = rigid camshaft, as the paper's model does not give it).
    tappet_valve_stiffness, tappet_valve_damping : bucket crown + shim + valve tip [N/m],
        [N·s/m] (1e8, 300).
    lash : clearance between tappet and valve tip on the base circle [m] (0: zero lash).
    seat_stiffness, seat_damping : valve stem + seat insert [N/m], [N·s/m]
        (stem EA/L ≈ 5e7 for a 5.5 mm, 100 mm steel stem; damping 400).
    spring_seat_stiffness, spring_support_stiffness : retainer–spring and head–spring
        seatings [N/m] (5e8 each; in series with the end coil segments).
    damping_force_ramp : elastic force over which unilateral damping is phased in [N] (5).

    Tappet bore and geometry
    ------------------------
    bore_friction_coefficient : μ_b of the tappet in its bore [-] (*assumed* 0.1). The
        contact friction force F_f presses the tappet laterally against the bore; the bore
        reaction μ_b F_f opposes the tappet velocity (sign regularised by
        tanh(v/``bore_friction_velocity``)).
    bore_friction_velocity : regularisation velocity [m/s] (0.01).
    tappet_radius : radius of the tappet face [m] (*assumed* 16.5 mm, a 33 mm bucket);
        the cam's maximum contact offset must stay below it.
    cam_width : axial contact length [m] (typical 0.014).
    """

    valve_mass: float = typical_engine.VALVE_MASS.value
    tappet_mass: float = typical_engine.TAPPET_MASS.value
    spring_mass: float = typical_engine.SPRING_MASS.value
    spring_rate: float = typical_engine.SPRING_RATE.value
    spring_preload: float = typical_engine.SPRING_PRELOAD.value
    spring_masses: int = 8
    spring_damping_ratio: float = 0.02
    contact_stiffness: float | None = None
    contact_modulus: float = STEEL_REDUCED_MODULUS
    contact_damping: float = 500.0
    camshaft_stiffness: float | None = None
    tappet_valve_stiffness: float = 1e8
    tappet_valve_damping: float = 300.0
    lash: float = 0.0
    seat_stiffness: float = 5e7
    seat_damping: float = 400.0
    spring_seat_stiffness: float = 5e8
    spring_support_stiffness: float = 5e8
    damping_force_ramp: float = 5.0
    bore_friction_coefficient: float = 0.1
    bore_friction_velocity: float = 0.01
    tappet_radius: float = 0.0165
    cam_width: float = typical_engine.CAM_WIDTH.value

    def __post_init__(self):
        # the case file's [valvetrain] and cam width are checked here (physics.limits)
        L.check_fields(self, _LIMITS, optional=("contact_stiffness", "camshaft_stiffness"))

    # -- derived ------------------------------------------------------------------------
    @property
    def effective_mass(self) -> float:
        """Quasi-static m_eff = m_valve + m_tappet + m_spring/3 [kg] (continuous spring)."""
        return self.valve_mass + self.tappet_mass + self.spring_mass / 3.0

    @property
    def contact_compliance_coefficient(self) -> float:
        """C of the Palmgren law δ = C F^0.9 [m/N^0.9] for this width and modulus."""
        return (
            PALMGREN_COEFFICIENT
            * self.cam_width**-0.8
            * STEEL_REDUCED_MODULUS
            / self.contact_modulus
        )

    # -- what the variants differ in (FlexibleValvetrain has the same members) ----------
    #: a lumped companion other than itself to compare with
    has_lumped_companion: ClassVar[bool] = False

    def lumped_equivalent(self) -> ValvetrainParameters:
        """The lumped model: itself."""
        return self

    def surge_frequencies(self, modes: int = 3) -> np.ndarray:
        """The first ``modes`` surge frequencies f_k = (k/2)√(k_s/m_s) [Hz] of the continuous
        fixed–fixed spring (Wahl, *Mechanical Springs*, 1963, ch. 25)."""
        return 0.5 * math.sqrt(self.spring_rate / self.spring_mass) * np.arange(1, modes + 1)

    def spring_advice(self) -> str:
        """The case keys that set the spring's preload and rate, with their values."""
        return (
            f"valvetrain.spring_preload ({self.spring_preload:g} N) or valvetrain.spring_rate "
            f"({self.spring_rate:g} N/m)"
        )

    def replace(self, **changes) -> ValvetrainParameters:
        """A copy with some fields changed (validated again)."""
        unknown = set(changes) - {f.name for f in fields(self)}
        if unknown:
            raise InputError(f"unknown ValvetrainParameters field(s): {sorted(unknown)}")
        d = asdict(self)
        d.update(changes)
        return ValvetrainParameters(**d)


#: Range of every field (the case file's [valvetrain] uses the same limits).
_LIMITS = {
    "valve_mass": L.MASS,
    "tappet_mass": L.MASS,
    "spring_mass": L.MASS,
    "spring_rate": L.SPRING_RATE,
    "spring_preload": L.SPRING_PRELOAD,
    "spring_masses": L.SPRING_MASSES,
    "spring_damping_ratio": L.SPRING_DAMPING_RATIO,
    "contact_stiffness": L.STIFFNESS,
    "contact_modulus": L.CONTACT_MODULUS,
    "contact_damping": L.DAMPING,
    "camshaft_stiffness": L.STIFFNESS,
    "tappet_valve_stiffness": L.STIFFNESS,
    "tappet_valve_damping": L.DAMPING,
    "lash": L.LASH,
    "seat_stiffness": L.STIFFNESS,
    "seat_damping": L.DAMPING,
    "spring_seat_stiffness": L.STIFFNESS,
    "spring_support_stiffness": L.STIFFNESS,
    "damping_force_ramp": L.DAMPING_FORCE_RAMP,
    "bore_friction_coefficient": L.BORE_FRICTION_COEFFICIENT,
    "bore_friction_velocity": L.BORE_FRICTION_VELOCITY,
    "tappet_radius": L.LENGTH_BELOW_1M,
    "cam_width": L.LENGTH_BELOW_1M,
}

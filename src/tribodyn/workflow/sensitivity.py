"""Single-contact studies at the cycle's nose condition, for the report's claims.

At the cam nose (the most loaded, smallest-radius sample with a sizeable entraining
speed) the reference surface set is solved steadily with variants that show what the
friction and film depend on: the case roughness; the other viscous law (Newtonian Eq. 16
or Eyring); the same σ and β with a summit density giving ηβσ = 0.04, typical of measured
Gaussian surfaces (isotropic Gaussian surfaces have ηβσ ≥ 0.025; the paper's Table 4
gives 2e-4 … 2.3e-3); and the case roughness without the limiting-shear cap.
:func:`surface_sets_at_nose` solves every surface set of the case at the same condition.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..config.build import BuiltCase, as_built, options_for
from ..contact.ehl import solve_ehl
from ..cycle.driver import CycleInputs
from ..physics.asperity import Roughness

__all__ = [
    "NoseCondition",
    "SensitivityCase",
    "RoughnessSensitivity",
    "nose_condition",
    "roughness_sensitivity",
    "surface_sets_at_nose",
    "GAUSSIAN_ETA_BETA_SIGMA",
]

#: ηβσ of the "typical measured Gaussian surface" variant.
GAUSSIAN_ETA_BETA_SIGMA = 0.04


@dataclass(frozen=True)
class NoseCondition:
    """The cam-nose sample of the cycle: index into the cycle inputs, crank angle [deg],
    contact force [N] (total), R [m], u_e and u_s [m/s]."""

    index: int
    crank_deg: float
    force: float
    radius: float
    entrainment_speed: float
    sliding_speed: float


@dataclass
class SensitivityCase:
    """One steady solve of the sensitivity study (totals over the cam width)."""

    label: str
    eta_beta_sigma: float
    viscous_model: str
    limiting_shear: bool
    central_film_m: float
    min_film_m: float
    asperity_load_share: float
    boundary_friction_N: float
    viscous_friction_N: float
    friction_coefficient: float
    converged: bool


@dataclass
class RoughnessSensitivity:
    """The variants at the nose for one surface set, by label."""

    conditions: NoseCondition
    surface_set: str
    cases: dict[str, SensitivityCase] = field(default_factory=dict)

    def to_dict(self) -> dict:
        return {
            "conditions": vars(self.conditions),
            "surface_set": self.surface_set,
            "cases": {k: vars(v) for k, v in self.cases.items()},
        }


def nose_condition(inputs: CycleInputs) -> NoseCondition | None:
    """Among samples with F > F_max/2 and |u_e| > 0.5 m/s, the one with the smallest
    radius of curvature R (None if there is none)."""
    F = inputs.contact_force
    ok = (np.abs(inputs.entrainment_speed) > 0.5) & (F > 0.5 * F.max())
    if not ok.any():
        return None
    i = int(np.flatnonzero(ok)[np.argmin(inputs.radius[ok])])
    return NoseCondition(
        i,
        float(inputs.crank_angle[i]),
        float(F[i]),
        float(inputs.radius[i]),
        float(inputs.entrainment_speed[i]),
        float(inputs.sliding_speed[i]),
    )


def roughness_sensitivity(case, surface_set, nose: NoseCondition) -> RoughnessSensitivity:
    """Steady EHL of ``surface_set`` of a case (Case or BuiltCase) at the ``nose``
    condition with the variants of the module docstring."""
    s, built = surface_set, as_built(case)
    r0 = s.roughness
    alt = Roughness(
        asperity_density=GAUSSIAN_ETA_BETA_SIGMA / (r0.rms * r0.summit_radius),
        rms=r0.rms,
        summit_radius=r0.summit_radius,
        method=r0.method,
    )
    opts = options_for(built, s)
    other = "newtonian" if opts.viscous_model == "eyring" else "eyring"
    variants: tuple[tuple[str, Roughness, dict[str, object]], ...] = (
        ("case roughness", r0, {}),
        (f"{other} viscous law", r0, {"viscous_model": other}),
        (f"Gaussian ηβσ = {GAUSSIAN_ETA_BETA_SIGMA:g}", alt, {}),
        ("no limiting-shear cap", r0, {"limiting_shear": False}),
    )
    out = RoughnessSensitivity(nose, s.name)
    for label, rough, over in variants:
        out.cases[label] = _steady(built, s, nose, rough, label, opts, over)
    return out


def surface_sets_at_nose(case, nose: NoseCondition) -> RoughnessSensitivity:
    """Steady EHL of every surface set of ``case`` (Case or BuiltCase) at its own
    ``nose`` condition (its roughness, coating and options), keyed by the sets' labels;
    ``surface_set`` is ``"*"``."""
    built = as_built(case)
    out = RoughnessSensitivity(nose, "*")
    for own in built.sets.values():
        s = own.surface
        out.cases[s.coating_label] = _steady(
            built, s, nose, s.roughness, s.coating_label, own.options, {}
        )
    return out


def _steady(built: BuiltCase, s, nose, rough, label, opts, over) -> SensitivityCase:
    width = built.case.width
    w = nose.force / width
    r = solve_ehl(
        w,
        nose.radius,
        nose.entrainment_speed,
        nose.sliding_speed,
        s.bodies,
        built.lubricant,
        rough,
        options=opts,
        **over,
    )
    return SensitivityCase(
        label=label,
        eta_beta_sigma=rough.roughness_parameter,
        viscous_model=over.get("viscous_model", opts.viscous_model),
        limiting_shear=bool(over.get("limiting_shear", opts.limiting_shear)),
        central_film_m=r.central_film,
        min_film_m=r.min_film,
        asperity_load_share=r.asperity_load / w,
        boundary_friction_N=r.boundary_friction * width,
        viscous_friction_N=r.viscous_friction * width,
        friction_coefficient=r.friction_coefficient,
        converged=r.converged,
    )

"""The inputs of a cycle study as used, taken once from the built case
(:func:`tribodyn.config.build.build`) and kept on the study, so that the report reads
them instead of building the case's objects again: per surface set its coating,
roughness, asperity model and boundary-shear coefficient ς; the cam's base radius; the
thermal oil at the inlet (a thermal case).

The Greenwood–Tripp roughness factor of a set is (ηβσ)²√(σ/β), that of the asperity
pressure p_a = (8√2/15)π(ηβσ)²√(σ/β) E' F_5/2(h/σ) (DESIGN.md, Greenwood–Tripp): its
ratio between two sets compares their asperity load at the same film and E'.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from ..cycle.methods import study_variant

__all__ = ["InputsAsUsed", "inputs_as_used", "surface_as_used"]


@dataclass(frozen=True)
class InputsAsUsed:
    """``surfaces``: {set name: :func:`surface_as_used`} in case order;
    ``cam_base_radius`` [m]; ``thermal_oil``: {name, inlet viscosity μ [Pa s],
    pressure–viscosity α [1/Pa] and temperature–viscosity β [1/K] at the inlet} or None
    (an isothermal study)."""

    surfaces: dict = field(default_factory=dict)
    cam_base_radius: float = math.nan
    thermal_oil: dict | None = None


def surface_as_used(s) -> dict:
    """One :class:`~tribodyn.config.SurfaceSet` as used: label, coating material and
    thickness [m] (None: uncoated), σ [m], β [m], η [1/m²], ηβσ, whether Greenwood–Tripp
    carries the asperities (else the set's load–separation law), the text of that law,
    ς and the roughness factor (ηβσ)²√(σ/β) (module docstring)."""
    r = s.roughness
    return {
        "label": s.coating_label,
        "coating_material": s.coating_material,
        "coating_thickness_m": s.coating.thickness if s.coating is not None else None,
        "rms_m": r.rms,
        "summit_radius_m": r.summit_radius,
        "asperity_density_per_m2": r.asperity_density,
        "roughness_parameter": r.roughness_parameter,
        "greenwood_tripp": r.law is None,
        "asperity_law": s.asperity_law,
        "boundary_shear_coefficient": s.boundary_shear_coefficient,
        "roughness_factor": r.roughness_parameter**2 * math.sqrt(r.rms / r.summit_radius),
    }


def inputs_as_used(built) -> InputsAsUsed:
    """The :class:`InputsAsUsed` of a :class:`~tribodyn.config.build.BuiltCase`."""
    oil = study_variant(built).oil(built)  # the thermal passes' oil (None: isothermal)
    return InputsAsUsed(
        surfaces={s.name: surface_as_used(s) for s in built.surface_sets},
        cam_base_radius=float(built.cam.base_radius),
        thermal_oil=None
        if oil is None
        else {
            "name": oil.name,
            "viscosity_Pa_s": float(oil.inlet_viscosity),
            "pressure_viscosity_1_Pa": float(oil.inlet_pressure_viscosity),
            "temperature_viscosity_1_K": float(oil.temperature_viscosity_coefficient()),
        },
    )

"""One line contact at one operating point: the computation behind ``tribodyn contact``.

:func:`point_surfaces` builds the surfaces (a named surface set of a case, or a steel cam
on a steel tappet with an optional coating and roughness); :func:`solve_point` solves the
dry or lubricated contact and returns a JSON-ready dict in SI units with the unit in each
key (``central_film_m``, ``friction_N``, …), with the Hertz values, the film formulas and
the Greenwood-chart regime beside the numerical solution. Loads and friction forces are
totals over ``width``.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .._validation import InputError, check_positive, check_real
from ..config import SurfaceSet
from ..config.build import BuiltCase, as_built, options_for
from ..contact.dry import solve_dry_contact
from ..contact.ehl import EHLOptions, EHLResult, solve_ehl
from ..physics.asperity import Roughness
from ..physics.hertz import hertz_line_contact
from ..physics.lubricant import Lubricant
from ..physics.materials import Body, Coating, reduced_modulus
from ..physics.regimes import (
    greenwood_chart_groups,
    hamrock_groups,
    lubrication_regime,
    moes_central,
    pan_hamrock,
)
from ..physics.thermal_oil import ThermalLubricant

if TYPE_CHECKING:
    from ..contact.ehl.thermal import ThermalEHLResult

__all__ = ["point_surfaces", "solve_point"]


def point_surfaces(
    case,
    *,
    surface_set: str | None = None,
    coating: Coating | None = None,
    coating_material: str | None = None,
    coating_thickness: float | None = None,
    roughness: Roughness | None = None,
    shear_coefficient: float | None = None,
) -> SurfaceSet:
    """The surfaces of one contact.

    ``case``: a Case or its BuiltCase. ``surface_set``: a set of ``case`` by name
    (exclusive with the other arguments). Otherwise a steel tappet (``[materials.steel]``
    of the case, or the cam's material) under the case's cam, coated with ``coating``
    (E, ν, thickness) or with the material ``coating_material`` of the case
    ``coating_thickness`` thick, rough with ``roughness`` (None: smooth). ς is
    ``shear_coefficient``, else the coating material's, else the substrate's (an error if
    the case gives none, as for a surface set); τ₀ is the case's first surface set's.
    """
    built = as_built(case)
    case = built.case
    if surface_set is not None:
        clash = [
            k
            for k, v in (
                ("coating", coating),
                ("coating_material", coating_material),
                ("coating_thickness", coating_thickness),
                ("roughness", roughness),
            )
            if v is not None
        ]
        if clash:
            raise InputError(
                f"surface_set takes the coating and roughness from the case; "
                f"drop {', '.join(clash)}"
            )
        try:
            s = built.set(surface_set).surface
        except InputError as exc:
            raise InputError(f"surface_set: {exc}") from None
        if shear_coefficient is not None:
            from dataclasses import replace

            s = replace(s, boundary_shear_coefficient=_shear(shear_coefficient))
        return s
    if coating is not None and coating_material is not None:
        raise InputError("give either coating (E, nu, thickness) or coating_material (not both)")
    if coating_thickness is not None and coating_material is None:
        raise InputError("coating_thickness needs coating_material")
    cam = Body(built.materials[case.cam_config.material])
    substrate_key = "steel" if "steel" in case.materials else case.cam_config.material
    substrate = built.materials[substrate_key]
    sigma = case.materials[substrate_key].boundary_shear_coefficient
    label, key = "uncoated", None
    if coating is not None:
        if not isinstance(coating, Coating):
            raise InputError(f"coating must be a Coating (got {type(coating).__name__})")
        label = (
            f"coating E = {coating.E / 1e9:.4g} GPa, ν = {coating.nu:g}, "
            f"{coating.thickness * 1e6:.3g} µm"
        )
    elif coating_material is not None:
        key = coating_material.strip().lower().replace("-", "")
        if key not in case.materials:
            raise InputError(
                f"coating_material must be one of {', '.join(case.materials)} "
                f"(got {coating_material!r})"
            )
        m = case.materials[key]
        if coating_thickness is None and key != "steel":
            raise InputError("coating_material needs coating_thickness [m]")
        if coating_thickness is not None:
            coating = Coating(E=m.E, nu=m.nu, thickness=coating_thickness)
            label = f"{m.label or key} {coating_thickness * 1e6:.3g} µm"
        if m.boundary_shear_coefficient is not None:
            sigma = m.boundary_shear_coefficient
    if roughness is not None and not isinstance(roughness, Roughness):
        raise InputError(f"roughness must be a Roughness (got {type(roughness).__name__})")
    if shear_coefficient is not None:
        sigma = _shear(shear_coefficient)
    if sigma is None:
        raise InputError(
            f"shear_coefficient: required, material {substrate_key!r} of the case has no "
            "boundary_shear_coefficient"
        )
    return SurfaceSet(
        name="",
        bodies=(cam, Body(substrate, coating)),
        roughness=roughness,
        boundary_shear_coefficient=float(sigma),
        coating_label=label,
        boundary_shear_strength=case.surface_set_configs[0].boundary_shear_strength,
        coating_material=key if coating is not None else None,
    )


def _shear(v) -> float:
    v = check_real("shear_coefficient", v)
    if v < 0.0:
        raise InputError(f"shear_coefficient must be a finite number >= 0 (got {v:g})")
    return v


def solve_point(
    case,
    surfaces: SurfaceSet,
    *,
    load_per_length,
    radius,
    width,
    entrainment_speed=None,
    sliding_speed=None,
    dry=False,
    lubricant: Lubricant | ThermalLubricant | None = None,
    options: EHLOptions | None = None,
    n: int | None = None,
    thermal_oil: ThermalLubricant | None = None,
    stress: bool = False,
) -> dict:
    """Solve one contact (see the module docstring) of ``case`` (a Case or BuiltCase).
    ``lubricant`` and ``options`` default to the case's; ``n`` is the dry grid (default:
    :func:`solve_dry_contact`'s). ``sliding_speed`` defaults to 0 for EHL; a dry contact
    takes no speeds. ``lubricant`` may be a datasheet oil
    (:class:`~tribodyn.physics.thermal_oil.ThermalLubricant`): the isothermal solve then
    uses it at its inlet temperature (μ₀, α, ρ₀ as the thermal solver derives them,
    ``ThermalLubricant.isothermal``) and the output names it (``oil``,
    ``inlet_temperature_K``).

    ``warnings`` lists conditions outside the model's validity (film ≫ R, inertia, …; see
    :mod:`tribodyn.contact.ehl.validity`). A solution whose film is not positive and finite
    is not converged, and its solution fields (films, pressure, loads, friction) are
    ``None``: there is no meaningful value to print. ``thermal_oil``
    (:class:`~tribodyn.physics.thermal_oil.ThermalLubricant`): solve the thermal EHL
    with the case's material thermal properties; the isothermal solution at the inlet
    temperature is reported beside it (keys ``isothermal_*``).

    ``stress``: also the subsurface stresses of the cam and the tappet at the (isothermal)
    EHL solution (EHL pressure with the mean asperity pressure, viscous and boundary
    shear; :func:`~tribodyn.contact.stress.ehl_stresses`): the six peaks of each body
    (``stress_<body>_<peak>_Pa`` with ``_x_m``, ``_z_m``), the safety factors against
    the case's strengths (``safety_factor_<body>_<mode>``: strength / peak; inf where
    the mode is not loaded, None without a strength) and ``stress_closest_failure``."""
    built = as_built(case)
    case = built.case
    w = check_positive("load_per_length", load_per_length, "N/m")
    radius = check_positive("radius", radius, "m")
    width = check_positive("width", width, "m")
    bodies = surfaces.bodies
    e_bulk = reduced_modulus(bodies)
    hz = hertz_line_contact(w, radius, e_bulk)
    tappet = bodies[1]
    out: dict = {
        "mode": "dry" if dry else "ehl",
        "case": None if case.source is None else str(case.source),
        "surface_set": surfaces.name or None,
        "surfaces": surfaces.coating_label,
        "load_N": w * width,
        "width_m": width,
        "load_per_length_N_per_m": w,
        "radius_m": radius,
        "cam_E_Pa": bodies[0].material.E,
        "cam_nu": bodies[0].material.nu,
        "tappet_E_Pa": tappet.material.E,
        "tappet_nu": tappet.material.nu,
        "coating_E_Pa": tappet.coating.E if tappet.coating else None,
        "coating_nu": tappet.coating.nu if tappet.coating else None,
        "coating_thickness_m": tappet.coating.thickness if tappet.coating else None,
        "reduced_modulus_Pa": e_bulk,
        "surface_reduced_modulus_Pa": reduced_modulus(bodies, surface=True),
        "hertz_half_width_m": hz.half_width,
        "hertz_max_pressure_Pa": hz.max_pressure,
    }
    if dry:
        if stress:
            raise InputError(
                "stress: the subsurface stresses are computed at an EHL solution "
                "(drop --dry, give --ue and --us)"
            )
        if entrainment_speed is not None or sliding_speed is not None:
            raise InputError(
                "a dry contact takes no entrainment or sliding speed "
                "(drop --ue/--us, or drop --dry for an EHL solution)"
            )
        d = (
            solve_dry_contact(w, radius, bodies)  # its default grid
            if n is None
            else solve_dry_contact(w, radius, bodies, n=n)
        )
        out.update(
            {
                "half_width_m": d.half_width,
                "max_pressure_Pa": d.max_pressure,
                "contact_center_m": d.contact_center,
                "grid_points": d.x.size,
                "converged": bool(d.converged),
                "iterations": int(d.iterations),
                "message": d.message,
                "warnings": list(d.warnings),
            }
        )
        return out

    if entrainment_speed is None:
        raise InputError(
            "entrainment_speed (--ue) [m/s] is required for an EHL solution (or use --dry)"
        )
    ue = check_real("entrainment_speed", entrainment_speed, "m/s")
    if ue == 0.0:
        raise InputError(
            "entrainment_speed (--ue) must be non-zero [m/s]: a steady film needs entrainment"
        )
    us = check_real("sliding_speed", 0.0 if sliding_speed is None else sliding_speed, "m/s")
    if thermal_oil is not None and lubricant is not None:
        raise InputError("give either lubricant or thermal_oil (the thermal solve's oil)")
    oil = thermal_oil if thermal_oil is not None else lubricant
    lub: Lubricant
    if isinstance(oil, ThermalLubricant):
        lub = oil.isothermal()  # the datasheet oil at its inlet temperature
    else:
        oil = None
        if lubricant is None:
            lub = built.lubricant
        elif isinstance(lubricant, Lubricant):
            lub = lubricant
        else:
            raise InputError(
                "lubricant must be a Lubricant or a ThermalLubricant "
                f"(got {type(lubricant).__name__})"
            )
    opts = options or options_for(built, surfaces)
    rough = surfaces.roughness
    iso = solve_ehl(w, radius, ue, us, bodies, lub, rough, options=opts)
    res: EHLResult = iso  # the thermal solution replaces it when thermal_oil is given
    th: ThermalEHLResult | None = None
    if thermal_oil is not None:
        from ..contact.ehl.thermal import solve_thermal_ehl

        if surfaces.coating is not None and surfaces.coating_material is None:
            raise InputError(
                "thermal: the coating needs a material with thermal properties "
                "(give coating_material, not E, nu, thickness)"
            )
        th = res = solve_thermal_ehl(
            w,
            radius,
            ue,
            us,
            bodies,
            thermal_oil,
            built.thermal_bodies_of(surfaces),
            rough,
            options=opts,
            thermal_options=built.thermal_solver_options(),
        )
    W, U, G = hamrock_groups(w, radius, ue, lub.viscosity, lub.pressure_viscosity, e_bulk)
    gV, gE = greenwood_chart_groups(W, U, G)
    ph_c, ph_min = pan_hamrock(W, U, G, radius)
    tot = res.totals(width)
    out.update(
        {
            "entrainment_speed_m_per_s": ue,
            "sliding_speed_m_per_s": us,
            "asperity_density_per_m2": rough.asperity_density if rough else None,
            "roughness_rms_m": rough.rms if rough else None,
            "summit_radius_m": rough.summit_radius if rough else None,
            "greenwood_tripp": rough.method if rough else None,
            "asperity_model": rough.asperity_model if rough else None,
            "asperity_law": (rough.law.source if rough.law is not None else "Greenwood–Tripp")
            if rough
            else None,
            "boundary_shear_coefficient": opts.boundary_shear_coefficient,
            "boundary_shear_strength_Pa": opts.boundary_shear_strength,
            "viscosity_Pa_s": lub.viscosity,
            "pressure_viscosity_per_Pa": lub.pressure_viscosity,
            "density_kg_per_m3": lub.density,
            "eyring_stress_Pa": lub.eyring_stress,
            "limiting_shear_coefficient": lub.limiting_shear_coefficient,
            "viscosity_model": lub.viscosity_model,
            "viscous_model": opts.viscous_model,
            "limiting_shear": opts.limiting_shear,
            "grid_points": int(res.x.size),
            "central_film_m": res.central_film,
            "min_film_m": res.min_film,
            "min_film_position_m": res.min_film_position,
            "film_parameter_lambda": res.min_film / rough.rms if rough else None,
            "max_pressure_Pa": float(res.pressure.max()),
            "pan_hamrock_central_film_m": float(ph_c),
            "pan_hamrock_min_film_m": float(ph_min),
            "moes_central_film_m": float(moes_central(W, U, G, radius)),
            "hydrodynamic_load_N": tot["hydrodynamic_load"],
            "asperity_load_N": tot["asperity_load"],
            "asperity_load_share": res.asperity_load / res.load,
            "viscous_friction_N": tot["viscous_friction"],
            "boundary_friction_N": tot["boundary_friction"],
            "rolling_friction_N": tot["rolling_friction"],
            # film + asperity force on each surface along the entrainment (Eq. 16 per surface)
            "surface_friction_cam_N": res.surface_friction()[0] * width,
            "surface_friction_tappet_N": res.surface_friction()[1] * width,
            "friction_N": tot["friction"],
            "friction_coefficient": res.friction_coefficient,
            "hamrock_W": float(W),
            "hamrock_U": float(U),
            "hamrock_G": float(G),
            "greenwood_gV": float(gV),
            "greenwood_gE": float(gE),
            "regime": str(lubrication_regime(gV, gE)),
            "converged": bool(res.converged),
            "iterations": int(res.iterations),
            "message": res.message,
            "warnings": list(res.warnings),
        }
    )
    out["thermal"] = thermal_oil is not None
    out["oil"] = None if oil is None else (oil.name or None)  # None: the case's oil
    out["inlet_temperature_K"] = None if oil is None else oil.inlet_temperature
    if th is not None:
        itot = iso.totals(width)
        out.update(
            {
                "max_temperature_K": th.max_temperature,
                "max_surface_temperature_cam_K": th.max_surface_temperature[0],
                "max_surface_temperature_tappet_K": th.max_surface_temperature[1],
                "central_mid_film_temperature_K": th.central_mid_film_temperature,
                "thermal_iterations": int(th.thermal_iterations),
                "isothermal_central_film_m": iso.central_film,
                "isothermal_min_film_m": iso.min_film,
                "isothermal_viscous_friction_N": itot["viscous_friction"],
                "isothermal_friction_N": itot["friction"],
                "isothermal_converged": bool(iso.converged),
            }
        )
    solved = res.min_film > 0.0 and np.isfinite(res.min_film) and np.all(np.isfinite(res.pressure))
    if not solved:
        out.update({k: None for k in _SOLUTION_KEYS})  # no lubricated solution
    if stress:
        out["stress"] = _point_stresses(built, surfaces, iso, lub, opts) if solved else None
    return out


def _point_stresses(built: BuiltCase, surfaces: SurfaceSet, result, lubricant, options) -> dict:
    """The stress keys of :func:`solve_point` (see there)."""
    import math

    from ..contact.stress import ehl_stresses
    from ..physics.strength import safety_factors
    from .stress_study import closest_failure

    cam, tappet, _ = ehl_stresses(
        result, surfaces.bodies, lubricant, surfaces.roughness, options=options
    )
    by_material = built.material_strengths
    if surfaces.name in built.sets:
        strengths = built.set(surfaces.name).strengths
    else:  # an ad-hoc pair: the cam's material, a steel tappet, the named coating
        cam_s = by_material[built.case.cam_config.material]
        sub = by_material["steel"] if "steel" in by_material else cam_s
        coat = (
            by_material[surfaces.coating_material]
            if surfaces.coating_material is not None
            else None
        )
        strengths = {"cam": (cam_s, None), "tappet": (sub, coat)}
    out: dict = {"note": "isothermal EHL solution; elastic stresses, typical or case strengths"}
    factors, maxima = {}, {}  # as a CycleStress's, at no crank angle
    for name, st, body in (("cam", cam, surfaces.cam), ("tappet", tappet, surfaces.tappet)):
        peaks = st.peaks()
        maxima[name] = {
            k: {"value": pk.value, "crank_angle": math.nan, "x": pk.x, "z": pk.z}
            for k, pk in peaks.items()
        }
        for k, pk in peaks.items():
            fin = math.isfinite(pk.value)
            out[f"{name}_{k}_Pa"] = pk.value if fin else None
            out[f"{name}_{k}_x_m"] = pk.x if fin else None
            out[f"{name}_{k}_z_m"] = pk.z if fin else None
        sub, coat = strengths[name]
        if sub is None:
            continue
        factors[name] = safety_factors(st, sub, coat if body.is_coated else None)
        for mode, v in factors[name].items():
            out[f"safety_factor_{name}_{mode}"] = None if math.isnan(v) else v
    worst = closest_failure(factors, maxima)
    if worst is not None:
        del worst["crank_deg"]  # one contact: no crank angle
    out["closest_failure"] = worst
    return out


#: Fields of an EHL solution; None when the film is not positive and finite.
_SOLUTION_KEYS = (
    "central_film_m",
    "min_film_m",
    "min_film_position_m",
    "film_parameter_lambda",
    "max_pressure_Pa",
    "hydrodynamic_load_N",
    "asperity_load_N",
    "asperity_load_share",
    "viscous_friction_N",
    "boundary_friction_N",
    "rolling_friction_N",
    "surface_friction_cam_N",
    "surface_friction_tappet_N",
    "friction_N",
    "friction_coefficient",
)

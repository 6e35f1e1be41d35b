"""Cycle-study results as one xarray Dataset.

Dimensions: ``crank_angle`` (dynamics output, deg), ``ehl_crank`` (transient-EHL samples,
deg), ``surface_set``, ``k`` (profile samples), ``point`` (the six representative points
of the paper's Fig. 13), and for the single-contact studies ``dry_ratio``/``dry_x``
(Fig. 5), ``ehl_ratio``/``ehl_pair``/``ehl_x`` (Fig. 6). Every variable carries ``units``
and ``long_name``. EHL quantities are NaN where the contact carries no load (``loaded``
false: cam on the base circle) — by definition, not as a failure; steps that did not
converge keep their last iterate and are flagged by ``converged`` false and listed in the
``ehl_failures`` attribute. Attributes: the case as run (``case_toml``), the roles of the
surface sets (``reference_set``, ``surface_roles``), the coupling, warnings, and the
single-contact studies' conditions.
"""

from __future__ import annotations

import json
from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

if TYPE_CHECKING:
    from ..workflow.cycle import CycleStudy

__all__ = ["study_to_dataset"]

_DYNAMICS = {
    "contact_force": ("N", "cam–tappet contact force (total over the width)"),
    "tappet_displacement": ("m", "tappet displacement"),
    "tappet_velocity": ("m/s", "tappet velocity"),
    "tappet_acceleration": ("m/s²", "tappet acceleration"),
    "valve_lift": ("m", "valve lift"),
    "seat_force": ("N", "valve seat force"),
    "cam_lift": ("m", "cam lift s"),
    "cam_torque": ("N·m", "camshaft drive torque"),
    "friction_power": ("W", "contact friction power (analytic tribology of the dynamics)"),
    "entrainment_speed": ("m/s", "entraining speed u_e"),
    "sliding_speed": ("m/s", "sliding speed u_s"),
    "radius_of_curvature": ("m", "radius of curvature R of the cam at the contact"),
    "contact_offset": ("m", "contact offset e on the tappet face"),
}
_EHL = {
    "central_film": ("m", "central film thickness h_c (x = 0)"),
    "min_film": ("m", "minimum film thickness h_min"),
    "max_pressure": ("Pa", "maximum hydrodynamic pressure"),
    "hydrodynamic_load": ("N", "load carried by the fluid (total over the width)"),
    "asperity_load": ("N", "load carried by the asperities (total over the width)"),
    "viscous_friction": ("N", "viscous (Couette) friction force"),
    "viscous_friction_newtonian": (
        "N",
        "viscous friction with the Newtonian law (Eq. 16), same film and pressure",
    ),
    "viscous_friction_eyring": (
        "N",
        "viscous friction with the Eyring law, same film and pressure",
    ),
    "boundary_friction": ("N", "boundary friction force"),
    "rolling_friction": (
        "N",
        "hydrodynamic rolling force (Poiseuille part of Eq. 16) on each surface, cam and "
        "tappet alike, > 0 against the entrainment; not in the friction total",
    ),
    "friction_power": ("W", "friction power (viscous + boundary) × u_s"),
    "lambda_ratio": ("1", "λ = h_min/σ"),
}


def _var(dims, data, units=None, long_name=None, **attrs) -> xr.Variable:
    a = {k: v for k, v in (("units", units), ("long_name", long_name)) if v is not None}
    return xr.Variable(dims, np.asarray(data), {**a, **attrs})


def study_to_dataset(study: CycleStudy) -> xr.Dataset:
    """All results of a :class:`~tribodyn.workflow.cycle.CycleStudy` in one Dataset."""
    from .. import __version__

    an = study.analyse()
    case, dyn, inp, sets = study.case, study.dynamics, study.inputs, study.sets
    ds = xr.Dataset()
    ds.coords["crank_angle"] = _var("crank_angle", dyn.crank_angle, "deg", "crank angle")
    for k, (units, name) in _DYNAMICS.items():
        ds["analytic_friction_power" if k == "friction_power" else k] = _var(
            "crank_angle", getattr(dyn, k), units, name
        )
    imp = study.implicit
    if imp is not None:
        for k in ("contact_force", "tappet_velocity", "tappet_acceleration", "valve_lift"):
            units, name = _DYNAMICS[k]
            ds[k + "_implicit"] = _var(
                "crank_angle",
                np.interp(dyn.crank_angle, imp.crank_angle, getattr(imp, k)),
                units,
                name + " (implicit: numerical EHL in the dynamics)",
            )

    ds.coords["ehl_crank"] = _var(
        "ehl_crank", inp.crank_angle, "deg", "crank angle of the transient-EHL samples"
    )
    ds.coords["surface_set"] = xr.Variable("surface_set", [s.name for s in sets])
    ds["surface_label"] = _var(
        "surface_set", [study.labels[s.name] for s in sets], long_name="tappet surface"
    )
    cfg = {s.name: s for s in case.surface_sets()}
    ds["coating_material"] = _var(
        "surface_set",
        [cfg[s.name].coating_material or "" for s in sets],
        long_name="coating material key ('' = uncoated)",
    )
    ds["coating_thickness"] = _var(
        "surface_set",
        [c.thickness if (c := cfg[s.name].coating) is not None else 0.0 for s in sets],
        "m",
        "coating thickness (0 = uncoated)",
    )
    for name, v, units, long in (
        ("ehl_contact_force", inp.contact_force, "N", "contact force at the EHL samples"),
        ("ehl_entrainment_speed", inp.entrainment_speed, "m/s", "u_e at the EHL samples"),
        ("ehl_sliding_speed", inp.sliding_speed, "m/s", "u_s at the EHL samples"),
        ("ehl_radius", inp.radius, "m", "R at the EHL samples"),
    ):
        ds[name] = _var("ehl_crank", v, units, long)
    ds["gV"] = _var("ehl_crank", an.gV, "1", "Greenwood-chart viscosity group g_V")
    ds["gE"] = _var("ehl_crank", an.gE, "1", "Greenwood-chart elasticity group g_E")
    from ..physics.regimes import REGIMES

    ds["regime"] = _var(
        "ehl_crank",
        an.regime,
        long_name="lubrication regime",
        flag_values="-1 0 1 2 3",
        flag_meanings="unloaded " + " ".join(REGIMES),
    )
    ds["in_event"] = _var(
        "ehl_crank",
        an.in_event.astype(np.int8),
        long_name="inside the cam lift event (lift > 10 µm)",
    )
    two = ("surface_set", "ehl_crank")
    ds["loaded"] = _var(
        two,
        np.array([s.loaded for s in sets]).astype(np.int8),
        long_name="contact loaded (EHL solved)",
    )
    ds["converged"] = _var(
        two, np.array([s.converged for s in sets]).astype(np.int8), long_name="EHL step converged"
    )
    ds["iterations"] = _var(
        two, np.array([s.iterations for s in sets]).astype(np.int32), long_name="Newton iterations"
    )
    for k, (units, name) in _EHL.items():
        ds[k] = _var(two, np.array([getattr(s, k) for s in sets]), units, name)
    three = ("surface_set", "ehl_crank", "k")
    ds.coords["k"] = _var(
        "k",
        np.arange(sets[0].x.shape[1]),
        long_name=("profile sample index (each step's whole solver domain, uniform)"),
    )
    ds["profile_x"] = _var(
        three,
        np.array([s.x for s in sets]),
        "m",
        "position along the contact (positive in the direction of positive u_e)",
    )
    ds["pressure"] = _var(
        three, np.array([s.pressure for s in sets]), "Pa", "hydrodynamic pressure p(x)"
    )
    ds["film"] = _var(three, np.array([s.film for s in sets]), "m", "film thickness h(x)")
    ds.coords["point"] = xr.Variable("point", np.arange(1, an.point_crank.size + 1))
    ds["point_crank"] = _var(
        "point", an.point_crank, "deg", "crank angle of the representative points (Fig. 13)"
    )
    _coating_studies(ds, study)
    _engineering(ds, study)
    from .thermal import add_thermal

    add_thermal(ds, study)
    failures = {s.name: [[c, m] for c, m in s.failures] for s in sets}
    ds.attrs.update(
        {
            "title": f"tribodyn cam-cycle study: {case.name}",
            "tribodyn_version": __version__,
            "case_toml": case.to_toml(),
            "engine_speed_rpm": float(case.engine_speed),
            "cam_width_m": float(case.width),
            "runtime_s": float(study.runtime_s),
            "reference_set": an.roles["reference"],
            "surface_roles": json.dumps(an.roles),
            "coupling": json.dumps(study.coupling.to_dict()),
            "warnings": json.dumps(study.warnings),
            "ehl_failures": json.dumps(failures),
            "conventions": "SI; EHL NaN where unloaded (loaded = 0)",
            "roughness_sensitivity": json.dumps(
                study.sensitivity.to_dict() if study.sensitivity is not None else {}
            ),
            "surface_sets_at_nose": json.dumps(
                ns.to_dict() if (ns := getattr(study, "nose_sets", None)) is not None else {}
            ),
        }
    )
    return ds


def _engineering(ds, study):
    """Camshaft torque and contact pressure per set, the cam kinematics as used (with the
    table's points and fit residual), the surge spectrum and the oil as used
    (:mod:`tribodyn.workflow.engineering`)."""
    from ..workflow.engineering import oil_as_used

    two = ("surface_set", "ehl_crank")
    eng = study.engineering_outputs() if hasattr(study, "engineering_outputs") else None
    if eng is not None:
        ds["camshaft_friction_torque"] = _var(
            two,
            eng.friction_torque,
            "N m",
            "camshaft friction torque T_f = F_f (r_b + s), F_f = viscous + boundary "
            "friction of the EHL signed by the sliding direction (0 where unloaded)",
        )
        ds["camshaft_drive_torque"] = _var(
            two,
            eng.drive_torque,
            "N m",
            "camshaft drive torque T = W s' + F_f (r_b + s) (W contact force, s' = ds/dθ "
            "the contact offset on the tappet)",
        )
        ds["hertz_pressure"] = _var(
            two, eng.hertz_pressure, "Pa", "Hertz maximum pressure p_h = √(w E'/(2πR))"
        )
        ds["ehl_lift"] = _var("ehl_crank", eng.lift, "m", "cam lift s at the EHL samples")
        ds["ehl_contact_offset"] = _var(
            "ehl_crank", eng.lift_velocity, "m", "contact offset e = s' at the EHL samples"
        )
        ds.coords["cam_angle_deg"] = _var(
            "cam_angle_deg", eng.cam_angle_deg, "deg", "cam angle (kinematics grid)"
        )
        k = eng.kinematics
        for name, key, units, long in (
            ("kinematic_lift", "lift", "m", "cam lift s(θ) of the fitted profile"),
            ("kinematic_velocity", "velocity", "m/s", "tappet velocity s'ω (rigid)"),
            ("kinematic_acceleration", "acceleration", "m/s²", "tappet acceleration s''ω²"),
            ("kinematic_radius", "radius", "m", "radius of curvature r_b + s + s''"),
        ):
            ds[name] = _var("cam_angle_deg", k[key], units, long)
        if eng.table is not None:
            ds.coords["table_angle_deg"] = _var(
                "table_angle_deg", eng.table["angle_deg"], "deg", "cam angle of the table points"
            )
            ds["table_lift"] = _var("table_angle_deg", eng.table["lift"], "m", "lift table")
            ds["table_fit_residual"] = _var(
                "table_angle_deg",
                eng.table["residual"],
                "m",
                "table lift minus the fitted profile at the table points",
            )
        sg = eng.surge
        ds.coords["harmonic"] = _var(
            "harmonic", np.arange(1, sg["harmonic_amplitude_m"].size + 1), "1"
        )
        ds["harmonic_frequency"] = _var(
            "harmonic", sg["harmonic_frequency_Hz"], "Hz", "cam excitation harmonic n f_cam"
        )
        ds["harmonic_amplitude"] = _var(
            "harmonic", sg["harmonic_amplitude_m"], "m", "amplitude of the lift's harmonic n"
        )
        ds.coords["surge_mode"] = _var(
            "surge_mode", np.arange(1, sg["surge_frequency_Hz"].size + 1), "1"
        )
        ds["surge_frequency"] = _var(
            "surge_mode",
            sg["surge_frequency_Hz"],
            "Hz",
            "valve-spring surge frequency (k/2)√(k_s/m_s), both ends fixed",
        )
    oil = oil_as_used(study.case)
    for name, key, units, long in (
        ("oil_viscosity", "viscosity_Pa_s", "Pa s", "oil dynamic viscosity μ₀ at the inlet"),
        ("oil_pressure_viscosity", "pressure_viscosity_1_Pa", "1/Pa", "oil α (inlet)"),
        ("oil_density", "density_kg_m3", "kg/m³", "oil density ρ₀ at the inlet"),
    ):
        ds[name] = _var((), oil[key], units, long)
    t_in = oil["inlet_temperature_C"]
    ds["oil_inlet_temperature"] = _var(
        (),
        np.nan if t_in is None else t_in,
        "degC",
        "oil inlet temperature (NaN: not given; the viscosity was given directly)",
    )
    ds.attrs["lubricant_as_used"] = json.dumps(oil)
    ds.attrs["compare_paper"] = int(bool(getattr(study, "compare_paper", False)))


def _coating_studies(ds, study):
    from .. import paper

    if study.dry:
        ds.attrs["dry_coating_conditions"] = json.dumps(
            {k: v for k, v in paper.FIG5.items() if k != "ratios"}
        )
        half = max(1.3 * c.result.half_width for c in study.dry)
        xd = np.linspace(-half, half, 401)
        ds.coords["dry_x"] = _var("dry_x", xd, "m")
        ds.coords["dry_ratio"] = _var(
            "dry_ratio", [c.ratio for c in study.dry], long_name="coating/steel modulus ratio"
        )
        ds["dry_pressure"] = _var(
            ("dry_ratio", "dry_x"),
            np.array(
                [np.interp(xd, c.result.x, c.result.pressure, left=0, right=0) for c in study.dry]
            ),
            "Pa",
            "dry contact pressure (Fig. 5)",
        )
        ds["dry_half_width"] = _var("dry_ratio", [c.result.half_width for c in study.dry], "m")
        ds["dry_max_pressure"] = _var("dry_ratio", [c.result.max_pressure for c in study.dry], "Pa")
    e = study.ehl_coating
    if e is not None and e.results:
        lo = max(r.x[0] for r in e.results)
        hi = min(r.x[-1] for r in e.results)
        xe = np.linspace(lo, hi, 601)
        ds.coords["ehl_x"] = _var("ehl_x", xe, "m")
        ds.coords["ehl_ratio"] = xr.Variable("ehl_ratio", [c.ratio for c in e.ratios])
        ds.coords["ehl_pair"] = xr.Variable("ehl_pair", [c.label for c in e.pairs])
        for dim, items in (
            ("ehl_ratio", [c.result for c in e.ratios]),
            ("ehl_pair", [c.result for c in e.pairs]),
        ):
            ds[f"{dim}_pressure"] = _var(
                (dim, "ehl_x"),
                np.array([np.interp(xe, r.x, r.pressure) for r in items]),
                "Pa",
                "EHL pressure (Fig. 6)",
            )
            ds[f"{dim}_film"] = _var(
                (dim, "ehl_x"),
                np.array([np.interp(xe, r.x, r.film) for r in items]),
                "m",
                "EHL film (Fig. 6)",
            )
            ds[f"{dim}_central_film"] = _var(dim, [r.central_film for r in items], "m")
            ds[f"{dim}_min_film"] = _var(dim, [r.min_film for r in items], "m")
            ds[f"{dim}_converged"] = _var(
                dim, np.array([r.converged for r in items], dtype=np.int8)
            )
        ds.attrs["ehl_coating_conditions"] = json.dumps(e.conditions)

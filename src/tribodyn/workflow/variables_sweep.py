"""The variables of a sweep point's Dataset and of the combined ``sweep.nc``: the tables of
:mod:`~tribodyn.workflow.variables`.

A point has scalars (:data:`POINT_SCALARS`: names of ``summary.json``), per-set scalars
(:data:`SET_SCALARS`, engine mode :data:`ENGINE_SCALARS`), the surface sets' description
as coordinates, and on request cycle traces. The traces are the study Dataset's variables
(:mod:`~tribodyn.workflow.variables_study`), over crank angles counted in the presented
cycle (``crank_angle`` and ``ehl_crank`` start at 0).
"""

from __future__ import annotations

import numpy as np

from .variables import Group, Variable, number, var
from .variables_study import (
    CONVERGED,
    DYNAMICS,
    EHL,
    LOADED,
    SET_DESCRIPTION,
    SURFACE_SET,
    StudySource,
)

__all__ = [
    "COMPARISON_SCALARS",
    "POINT_SCALARS",
    "SET_SCALARS",
    "ENGINE_SCALARS",
    "ENGINE_SETS",
    "SET_COORDS",
    "DYNAMICS_TRACES",
    "EHL_TRACES",
    "SWEEP_STATUS",
    "ALL",
]


def _scalar(name):
    return lambda values: number(values[name])


def _scalars(rows) -> dict[str, Variable]:
    return {k: var(k, (), u, d, _scalar(k)) for k, u, d in rows}


#: The implicit-vs-explicit comparison of a study point (``summary.json``'s
#: ``implicit_vs_explicit``; NaN without implicit coupling).
_COMPARISON_ROWS = (
    (
        "max_contact_force_diff_pct",
        "%",
        "implicit vs explicit dynamics: largest contact-force difference, % of its peak",
    ),
    (
        "rms_contact_force_diff_pct",
        "%",
        "implicit vs explicit dynamics: RMS contact-force difference over the cam event, "
        "% of its peak",
    ),
    (
        "peak_contact_force_diff_pct",
        "%",
        "implicit vs explicit dynamics: difference of the peak contact forces, % of the peak",
    ),
    (
        "valve_opening_shift_deg",
        "deg",
        "implicit vs explicit dynamics: shift of the valve opening (lift leaves zero)",
    ),
    (
        "valve_closing_shift_deg",
        "deg",
        "implicit vs explicit dynamics: shift of the valve closing (lift returns to zero)",
    ),
    (
        "max_velocity_diff_pct",
        "%",
        "implicit vs explicit dynamics: largest tappet-velocity difference, % of its peak",
    ),
    ("coupling_iterations", "1", "implicit coupling iterations"),
    ("coupling_converged", "1", "implicit coupling converged (1 yes, 0 no)"),
)
#: Their names, in the order of the rows.
COMPARISON_SCALARS = tuple(r[0] for r in _COMPARISON_ROWS)


#: Point scalars (values from a mapping of name → value; booleans stored as 0/1).
POINT_SCALARS = _scalars(
    (
        ("peak_contact_force_N", "N", "peak cam–tappet contact force"),
        (
            "peak_contact_force_crank_deg",
            "deg",
            "crank angle of the peak contact force within the presented cycle, 0–720°",
        ),
        ("min_contact_force_in_event_N", "N", "minimum contact force in the cam event"),
        ("min_radius_of_curvature_m", "m", "minimum radius of curvature of the cam"),
        ("entrainment_speed_min_m_s", "m/s", "lowest entraining speed u_e"),
        ("entrainment_speed_max_m_s", "m/s", "highest entraining speed u_e"),
        ("max_valve_lift_m", "m", "maximum valve lift"),
        ("max_seat_force_N", "N", "maximum valve-seat force"),
        ("peak_cam_torque_Nm", "N·m", "peak camshaft drive torque"),
        (
            "dynamics_friction_energy_per_cycle_J",
            "J",
            "friction energy per cycle of the dynamics' explicit (analytic) tribology",
        ),
        ("jump", "1", "cam contact lost while the cam lifts (1 yes, 0 no)"),
        (
            "jump_onset_crank_deg",
            "deg",
            "crank angle where the first jump starts, within the presented cycle, 0–720° "
            "(NaN: none)",
        ),
        ("max_separation_m", "m", "maximum separation tappet lift − cam lift (valve jump)"),
        ("valve_bounce", "1", "valve lifts off its seat after closing (1 yes, 0 no)"),
        ("seating_velocity_m_s", "m/s", "valve velocity at the first closing seat impact"),
        ("energy_residual_rel", "1", "relative residual of the cycle energy balance"),
        *_COMPARISON_ROWS,
        ("n_warnings", "1", "warnings of the study (non-converged EHL steps, jumps, coupling)"),
        ("runtime_s", "s", "run time (wall clock) of the point on its worker"),
        ("cpu_s", "s", "CPU time of the point on its worker (one thread)"),
    )
)


def _set_scalar(k):
    """Per-set values from ``summary.json``'s ``surface_sets`` entries."""

    def extract(s: StudySource):
        sets = s.analysis.summary["surface_sets"]
        return np.array([number(sets[r.name].get(k)) for r in s.sets])

    return extract


#: Surface-set scalars of the study (keys of summary.json's ``surface_sets`` entries).
SET_SCALARS: dict[str, Variable] = {
    k: var(k, "surface_set", u, d, _set_scalar(k))
    for k, u, d in (
        ("min_film_m", "m", "minimum film thickness h_min in the cam event"),
        ("max_central_film_m", "m", "largest central film thickness h_c in the cam event"),
        ("min_lambda", "1", "minimum λ = h_min/σ in the cam event"),
        ("max_film_gain_vs_uncoated_pct", "%", "robust maximum film gain over the reference set"),
        ("median_abs_film_gain_vs_uncoated_pct", "%", "median |film gain| over the reference"),
        ("p95_abs_film_gain_vs_uncoated_pct", "%", "95th percentile of |film gain|"),
        ("max_boundary_friction_N", "N", "peak boundary friction force in the cam event"),
        ("max_viscous_friction_N", "N", "peak viscous friction force in the cam event"),
        (
            "boundary_friction_cycle_integral_change_pct",
            "%",
            "change of ∫F_b dt over the cam event against the reference set (negative = less)",
        ),
        (
            "max_boundary_friction_change_pct",
            "%",
            "change of the maximum boundary friction against the reference set (negative = less)",
        ),
        (
            "friction_energy_change_pct",
            "%",
            "change of the friction energy per cycle against the reference set (negative = less)",
        ),
        ("friction_energy_per_cycle_J", "J", "friction energy per engine cycle"),
        (
            "friction_energy_per_cycle_newtonian_J",
            "J",
            "friction energy per cycle, Newtonian viscous law",
        ),
        (
            "friction_energy_per_cycle_eyring_J",
            "J",
            "friction energy per cycle, Eyring viscous law",
        ),
        ("mean_friction_power_W", "W", "mean friction power over the engine cycle"),
        ("failed_steps", "1", "transient-EHL steps that did not converge"),
        ("min_safety_factor", "1", "smallest safety factor of the cam and tappet stresses"),
        ("safety_factor_substrate_yield", "1", "tappet: substrate yield / von Mises maximum"),
        ("safety_factor_surface_tension", "1", "tappet: surface tensile strength / max tension"),
        ("safety_factor_coating_tension", "1", "tappet: coating tensile strength / max tension"),
        ("safety_factor_coating_yield", "1", "tappet: coating yield / von Mises maximum"),
        ("safety_factor_interface_shear", "1", "tappet: adhesion (shear) / interface shear"),
        ("safety_factor_interface_tension", "1", "tappet: adhesion (tension) / interface tension"),
        ("wear_depth_per_cycle_m", "m", "Archard wear depth of the tappet surface per cycle"),
        ("hours_to_wear_through", "h", "running hours until the coating is worn through"),
    )
}


def _engine(key, part=None):
    """Per-set values of an engine summary (source: ``{"sets": …, "names": […]}``)."""

    def extract(e):
        sets = (e["sets"][n][key] for n in e["names"])
        return [number(v if part is None else v[part]) for v in sets]

    return extract


#: Per-set scalars of an engine point (``mode = "engine"``), with their summary keys.
ENGINE_SCALARS: dict[str, Variable] = {
    k: var(k, "surface_set", u, d, _engine(key, part))
    for k, key, part, u, d in (
        ("engine_friction_energy_per_cycle_J", "engine_friction_energy_per_cycle_J", None,
         "J", "valvetrain friction energy per engine cycle"),
        ("valvetrain_friction_mep_Pa", "valvetrain_friction_mep_Pa", None,
         "Pa", "valvetrain friction mean effective pressure"),
        ("engine_friction_power_W", "mean_friction_power_W", None,
         "W", "mean valvetrain friction power"),
        ("engine_friction_torque_Nm", "mean_friction_torque_Nm", None,
         "N·m", "mean camshaft friction torque, all camshafts"),
        ("engine_friction_energy_change_pct", "friction_energy_change_pct", None,
         "%", "change of the engine friction energy per cycle (and FMEP) against the "
         "reference set (negative = less)"),
        ("cam_tappet_energy_J", "friction_energy_per_cycle_J", "cam_tappet",
         "J", "cam–tappet contacts' friction energy per cycle"),
        ("tappet_bore_energy_J", "friction_energy_per_cycle_J", "tappet_bore",
         "J", "tappet bores' friction energy per cycle"),
        ("valve_guide_energy_J", "friction_energy_per_cycle_J", "valve_guide",
         "J", "valve guides' friction energy per cycle"),
        ("camshaft_journal_energy_J", "friction_energy_per_cycle_J", "camshaft_journal",
         "J", "camshaft journals' friction energy per cycle"),
    )
}  # fmt: skip

#: the surface sets of an engine point (source as for ENGINE_SCALARS)
ENGINE_SETS = var(
    "surface_set",
    "surface_set",
    SURFACE_SET.units,
    SURFACE_SET.description,
    lambda e: list(e["names"]),
    coord=True,
)

#: the surface sets and their description, as coordinates of a point
SET_COORDS = Group((SURFACE_SET, *SET_DESCRIPTION), coords=True)


def _presented(s: StudySource, crank) -> np.ndarray:
    return crank - float(s.dynamics.crank_angle[0])


#: dynamics traces (``[sweep] traces = true``): the study's variables, crank angle from 0
DYNAMICS_TRACES = Group(
    (
        var("crank_angle", "crank_angle", "deg",
            "crank angle within the presented engine cycle, 0–720°",
            lambda s: _presented(s, s.dynamics.crank_angle), coord=True),
        *(
            DYNAMICS[k]
            for k in (
                "contact_force", "tappet_velocity", "tappet_acceleration", "valve_lift",
                "cam_lift", "seat_force", "cam_torque", "entrainment_speed", "sliding_speed",
                "radius_of_curvature",
            )
        ),
        var("dynamics_friction_power", "crank_angle", "W",
            "friction power of the dynamics' explicit tribology",
            lambda s: np.asarray(s.dynamics.friction_power, float)),
    )
)  # fmt: skip

#: transient-EHL traces of a study point
EHL_TRACES = Group(
    (
        var("ehl_crank", "ehl_crank", "deg",
            "crank angle of the transient-EHL samples within the presented cycle, 0–720°",
            lambda s: _presented(s, s.inputs.crank_angle), coord=True),
        var("ehl_contact_force", "ehl_crank", "N", "contact force at the EHL samples",
            lambda s: s.inputs.contact_force),
        *(
            EHL[k]
            for k in (
                "central_film", "min_film", "hydrodynamic_load", "asperity_load",
                "viscous_friction", "boundary_friction", "friction_power", "lambda_ratio",
            )
        ),
        LOADED,
        CONVERGED,
    )
)  # fmt: skip


def _item(k):
    return lambda values: values[k]


#: the combined sweep's per-point bookkeeping over the sweep's axes (dims given when built)
SWEEP_STATUS: dict[str, Variable] = {
    k: var(k, None, u, d, _item(k))
    for k, u, d in (
        ("status", "1", "point finished (1) or failed (0)"),
        ("error", None, "why the point failed ('' if it did not)"),
        ("warnings", None, "warnings of the point's study ('' if none)"),
        ("point_key", None, "point file points/<key>.nc"),
    )
}

ALL: tuple[Variable, ...] = (
    *POINT_SCALARS.values(),
    *SET_SCALARS.values(),
    *ENGINE_SCALARS.values(),
    ENGINE_SETS,
    *SET_COORDS,
    *DYNAMICS_TRACES,
    *EHL_TRACES,
    *SWEEP_STATUS.values(),
)

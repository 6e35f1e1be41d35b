"""One point of a design sweep: the study (or the dynamics alone) of one case, reduced to
an xarray Dataset of summary scalars and, on request, cycle traces.

:func:`run_point` is the task a sweep sends to a Dask worker (it runs in any process
where tribodyn is installed). It never raises for a point's own failure: an invalid case,
a failed valvetrain integration or a study that cannot proceed returns a Dataset with
``status = "failed"`` and the error in its attributes, so that one point cannot stop the
sweep. Units are SI and given in every variable's ``units`` attribute; the names of the
scalars are those of ``summary.json`` (:func:`tribodyn.workflow.postprocess.summary`).

Variables (study mode; dynamics mode has the point scalars and dynamics traces only):

* per point — the dynamics of the reference set's explicit tribology: peak contact force,
  minimum contact force in the cam event, jump (contact loss while the cam lifts) and its
  onset crank angle, valve bounce, seating velocity, peak cam torque, …;
* per ``surface_set`` — minimum film and λ, maximum central film, film gain over the
  reference, peak boundary and viscous friction, friction energy per cycle and mean
  friction power, failed EHL steps;
* engine mode (a case with ``[engine] cylinders``): per ``surface_set`` the engine's
  valvetrain friction energy per cycle, FMEP, mean power and torque, the reduction below
  the reference set and the parts (cam–tappet, bores, guides, journals);
* traces (``[sweep] traces = true``) — dynamics over ``crank_angle`` (crank angle in the
  presented cycle, 0–720°) and transient-EHL quantities over ``(surface_set,
  ehl_crank)``.
"""

from __future__ import annotations

import json
import math
import socket
import time
import traceback

import numpy as np
import xarray as xr

__all__ = ["run_point", "failed_point", "POINT_SCALARS", "SET_SCALARS", "ENGINE_SCALARS"]

#: Point scalars: name → (units, long name). Booleans are stored as 0/1.
POINT_SCALARS = {
    "peak_contact_force_N": ("N", "peak cam–tappet contact force"),
    "peak_contact_force_crank_deg": (
        "deg",
        "crank angle of the peak contact force (presented cycle)",
    ),
    "min_contact_force_in_event_N": ("N", "minimum contact force in the cam event"),
    "min_radius_of_curvature_m": ("m", "minimum radius of curvature of the cam"),
    "entrainment_speed_min_m_s": ("m/s", "lowest entraining speed u_e"),
    "entrainment_speed_max_m_s": ("m/s", "highest entraining speed u_e"),
    "max_valve_lift_m": ("m", "maximum valve lift"),
    "max_seat_force_N": ("N", "maximum valve-seat force"),
    "peak_cam_torque_Nm": ("N·m", "peak camshaft drive torque"),
    "dynamics_friction_energy_per_cycle_J": (
        "J",
        "friction energy per cycle of the dynamics' explicit (analytic) tribology",
    ),
    "jump": ("1", "cam contact lost while the cam lifts (1 yes, 0 no)"),
    "jump_onset_crank_deg": ("deg", "crank angle where the first jump starts (NaN: none)"),
    "valve_bounce": ("1", "valve lifts off its seat after closing (1 yes, 0 no)"),
    "seating_velocity_m_s": ("m/s", "valve velocity at the first closing seat impact"),
    "energy_residual_rel": ("1", "relative residual of the cycle energy balance"),
    "max_contact_force_diff_pct": (
        "%",
        "implicit vs explicit dynamics: largest contact-force difference, % of its peak",
    ),
    "max_velocity_diff_pct": (
        "%",
        "implicit vs explicit dynamics: largest tappet-velocity difference, % of its peak",
    ),
    "coupling_converged": ("1", "implicit coupling converged (1 yes, 0 no)"),
    "n_warnings": ("1", "warnings of the study (non-converged EHL steps, jumps, coupling)"),
    "runtime_s": ("s", "run time (wall clock) of the point on its worker"),
    "cpu_s": ("s", "CPU time of the point on its worker (one thread)"),
}

#: Surface-set scalars of the study (keys of summary.json's ``surface_sets`` entries).
SET_SCALARS = {
    "min_film_m": ("m", "minimum film thickness h_min in the cam event"),
    "max_central_film_m": ("m", "largest central film thickness h_c in the cam event"),
    "min_lambda": ("1", "minimum λ = h_min/σ in the cam event"),
    "max_film_gain_vs_uncoated_pct": ("%", "robust maximum film gain over the reference set"),
    "median_abs_film_gain_vs_uncoated_pct": ("%", "median |film gain| over the reference"),
    "p95_abs_film_gain_vs_uncoated_pct": ("%", "95th percentile of |film gain|"),
    "max_boundary_friction_N": ("N", "peak boundary friction force in the cam event"),
    "max_viscous_friction_N": ("N", "peak viscous friction force in the cam event"),
    "boundary_friction_reduction_vs_uncoated_pct": (
        "%",
        "boundary friction impulse below the reference set's",
    ),
    "friction_energy_per_cycle_J": ("J", "friction energy per engine cycle"),
    "friction_energy_per_cycle_newtonian_J": (
        "J",
        "friction energy per cycle, Newtonian viscous law",
    ),
    "friction_energy_per_cycle_eyring_J": ("J", "friction energy per cycle, Eyring viscous law"),
    "mean_friction_power_W": ("W", "mean friction power over the engine cycle"),
    "failed_steps": ("1", "transient-EHL steps that did not converge"),
    "min_safety_factor": ("1", "smallest safety factor of the cam and tappet stresses"),
    "safety_factor_substrate_yield": ("1", "tappet: substrate yield / von Mises maximum"),
    "safety_factor_surface_tension": ("1", "tappet: surface tensile strength / max tension"),
    "safety_factor_coating_tension": ("1", "tappet: coating tensile strength / max tension"),
    "safety_factor_coating_yield": ("1", "tappet: coating yield / von Mises maximum"),
    "safety_factor_interface_shear": ("1", "tappet: adhesion (shear) / interface shear"),
    "safety_factor_interface_tension": ("1", "tappet: adhesion (tension) / interface tension"),
    "wear_depth_per_cycle_m": ("m", "Archard wear depth of the tappet surface per cycle"),
    "hours_to_wear_through": ("h", "running hours until the coating is worn through"),
}

_DYN_TRACES = {
    "contact_force": ("N", "cam–tappet contact force"),
    "tappet_velocity": ("m/s", "tappet velocity"),
    "tappet_acceleration": ("m/s²", "tappet acceleration"),
    "valve_lift": ("m", "valve lift"),
    "cam_lift": ("m", "cam lift"),
    "seat_force": ("N", "valve-seat force"),
    "cam_torque": ("N·m", "camshaft drive torque"),
    "entrainment_speed": ("m/s", "entraining speed u_e"),
    "sliding_speed": ("m/s", "sliding speed u_s"),
    "radius_of_curvature": ("m", "radius of curvature R"),
    "friction_power": ("W", "friction power of the dynamics' explicit tribology"),
}
_EHL_TRACES = {
    "central_film": ("m", "central film thickness h_c"),
    "min_film": ("m", "minimum film thickness h_min"),
    "hydrodynamic_load": ("N", "load carried by the fluid"),
    "asperity_load": ("N", "load carried by the asperities"),
    "viscous_friction": ("N", "viscous friction force"),
    "boundary_friction": ("N", "boundary friction force"),
    "friction_power": ("W", "friction power (viscous + boundary) × u_s"),
    "lambda_ratio": ("1", "λ = h_min/σ"),
}


def _num(v) -> float:
    if v is None:
        return math.nan
    if isinstance(v, bool):
        return float(v)
    v = float(v)
    return v if math.isfinite(v) else math.nan


def _scalar(name, value, table=POINT_SCALARS) -> xr.Variable:
    units, long = table[name]
    return xr.Variable((), _num(value), {"units": units, "long_name": long})


def _where() -> dict:
    """Host and Dask worker address of this process ('' outside a worker)."""
    try:
        from distributed import get_worker

        worker = get_worker().address
    except (ImportError, ValueError):
        worker = ""
    return {"worker_host": socket.gethostname(), "worker": worker}


def failed_point(error: str, runtime_s: float = 0.0) -> xr.Dataset:
    """The Dataset of a point that failed: no variables, the error in the attributes."""
    return xr.Dataset(
        attrs={
            "status": "failed",
            "error": error,
            "runtime_s": float(runtime_s),
            "warnings": "[]",
            **_where(),
        }
    )


def _dynamics_scalars(dyn) -> dict:
    s = dyn.summary()
    ue = s["entrainment_speed_range_m_s"]
    return {
        "peak_contact_force_N": s["peak_contact_force_N"],
        "peak_contact_force_crank_deg": s["peak_contact_force_crank_deg"]
        - float(dyn.crank_angle[0]),
        "min_contact_force_in_event_N": s["min_contact_force_in_event_N"],
        "min_radius_of_curvature_m": s["min_radius_of_curvature_m"],
        "entrainment_speed_min_m_s": ue[0],
        "entrainment_speed_max_m_s": ue[1],
        "max_valve_lift_m": s["max_valve_lift_m"],
        "max_seat_force_N": s["max_seat_force_N"],
        "peak_cam_torque_Nm": s["peak_cam_torque_Nm"],
        "dynamics_friction_energy_per_cycle_J": s["friction_energy_per_cycle_J"],
        "jump": s["jump"],
        "jump_onset_crank_deg": (
            dyn.jumps[0][0] - float(dyn.crank_angle[0]) if dyn.jumps else math.nan
        ),
        "valve_bounce": s["valve_bounce"],
        "seating_velocity_m_s": s["seating_velocity_m_s"],
        "energy_residual_rel": s["energy_residual_rel"],
    }


def _dynamics_traces(ds: xr.Dataset, dyn):
    c0 = float(dyn.crank_angle[0])
    ds.coords["crank_angle"] = xr.Variable(
        "crank_angle",
        dyn.crank_angle - c0,
        {"units": "deg", "long_name": "crank angle in the presented engine cycle"},
    )
    for k, (units, long) in _DYN_TRACES.items():
        name = "dynamics_friction_power" if k == "friction_power" else k
        ds[name] = xr.Variable(
            "crank_angle", np.asarray(getattr(dyn, k), float), {"units": units, "long_name": long}
        )


def point_dynamics(case):
    from ..valvetrain.dynamics import simulate_valvetrain
    from .postprocess import surface_roles

    ref = case.surface_set(surface_roles(case)["reference"])
    return simulate_valvetrain(
        case.cam(),
        case.valvetrain_parameters(),
        tribology=case.analytic_tribology(ref),
        **case.dynamics_options(),
    )


def _dynamics_point(case, traces: bool) -> tuple[xr.Dataset, list]:
    dyn = point_dynamics(case)
    if not dyn.converged:
        raise _PointFailure(f"valvetrain dynamics failed: {dyn.message}")
    ds = xr.Dataset()
    for k, v in _dynamics_scalars(dyn).items():
        ds[k] = _scalar(k, v)
    ds["n_warnings"] = _scalar("n_warnings", int(dyn.jump))
    warnings = [f"contact loss (jump) during the event at {dyn.jumps}"] if dyn.jump else []
    if traces:
        _dynamics_traces(ds, dyn)
    return ds, warnings


def _study_point(case, traces: bool) -> tuple[xr.Dataset, list]:
    from .cycle import run_cycle_study

    study = run_cycle_study(case, workers=1)
    summ = study.analyse().summary
    ds = xr.Dataset()
    for k, v in _dynamics_scalars(study.dynamics).items():
        ds[k] = _scalar(k, v)
    ie = summ["implicit_vs_explicit"]
    ds["max_contact_force_diff_pct"] = _scalar(
        "max_contact_force_diff_pct", ie.get("max_contact_force_diff_pct")
    )
    ds["max_velocity_diff_pct"] = _scalar("max_velocity_diff_pct", ie.get("max_velocity_diff_pct"))
    ds["coupling_converged"] = _scalar("coupling_converged", ie.get("coupling_converged"))
    ds["n_warnings"] = _scalar("n_warnings", len(study.warnings))
    names = [s.name for s in study.sets]
    ds.coords["surface_set"] = xr.Variable("surface_set", names)
    ds.coords["surface_label"] = xr.Variable(
        "surface_set", [study.labels[n] for n in names], {"long_name": "tappet surface"}
    )
    sets = {s.name: s for s in case.surface_sets()}
    ds.coords["coating_material"] = xr.Variable(
        "surface_set",
        [sets[n].coating_material or "" for n in names],
        {"long_name": "coating material key ('' = uncoated)"},
    )
    ds.coords["coating_thickness"] = xr.Variable(
        "surface_set",
        [sets[n].coating.thickness if sets[n].coating else 0.0 for n in names],
        {"units": "m", "long_name": "coating thickness (0 = uncoated)"},
    )
    for k, (units, long) in SET_SCALARS.items():
        ds[k] = xr.Variable(
            "surface_set",
            np.array([_num(summ["surface_sets"][n].get(k)) for n in names]),
            {"units": units, "long_name": long},
        )
    ds.attrs["reference_set"] = summ["reference_set"]
    if traces:
        _dynamics_traces(ds, study.dynamics)
        inp = study.inputs
        ds.coords["ehl_crank"] = xr.Variable(
            "ehl_crank",
            inp.crank_angle - float(study.dynamics.crank_angle[0]),
            {
                "units": "deg",
                "long_name": "crank angle of the transient-EHL samples in the presented cycle",
            },
        )
        ds["ehl_contact_force"] = xr.Variable(
            "ehl_crank",
            inp.contact_force,
            {"units": "N", "long_name": "contact force at the EHL samples"},
        )
        two = ("surface_set", "ehl_crank")
        for k, (units, long) in _EHL_TRACES.items():
            ds[k] = xr.Variable(
                two,
                np.array([getattr(s, k) for s in study.sets], float),
                {"units": units, "long_name": long},
            )
        ds["loaded"] = xr.Variable(
            two,
            np.array([s.loaded for s in study.sets], np.int8),
            {"long_name": "contact loaded (EHL solved)"},
        )
        ds["converged"] = xr.Variable(
            two,
            np.array([s.converged for s in study.sets], np.int8),
            {"long_name": "EHL step converged"},
        )
    return ds, list(study.warnings)


#: Per-set scalars of an engine point (``mode = "engine"``): name → (units, long name).
ENGINE_SCALARS = {
    "engine_friction_energy_per_cycle_J": ("J", "valvetrain friction energy per engine cycle"),
    "valvetrain_friction_mep_Pa": ("Pa", "valvetrain friction mean effective pressure"),
    "engine_friction_power_W": ("W", "mean valvetrain friction power"),
    "engine_friction_torque_Nm": ("N·m", "mean camshaft friction torque, all camshafts"),
    "engine_friction_reduction_vs_uncoated_pct": ("%", "engine friction below the reference"),
    "cam_tappet_energy_J": ("J", "cam–tappet contacts' friction energy per cycle"),
    "tappet_bore_energy_J": ("J", "tappet bores' friction energy per cycle"),
    "valve_guide_energy_J": ("J", "valve guides' friction energy per cycle"),
    "camshaft_journal_energy_J": ("J", "camshaft journals' friction energy per cycle"),
}


def _engine_point(case) -> tuple[xr.Dataset, list]:
    """A whole engine (:func:`~tribodyn.workflow.engine.run_engine_study`; the coatings
    share each lobe's dynamics) reduced to per-set scalars."""
    from .engine import run_engine_study

    study = run_engine_study(case, workers=1)
    summ = study.summary()
    ds = xr.Dataset()
    for k, v in _dynamics_scalars(study.lobes["intake"].study.dynamics).items():
        ds[k] = _scalar(k, v)
    names = study.set_names
    ds.coords["surface_set"] = xr.Variable("surface_set", names)
    sets = summ["surface_sets"]
    parts = sets[names[0]]["friction_energy_per_cycle_J"]
    values = {
        "engine_friction_energy_per_cycle_J": "engine_friction_energy_per_cycle_J",
        "valvetrain_friction_mep_Pa": "valvetrain_friction_mep_Pa",
        "engine_friction_power_W": "mean_friction_power_W",
        "engine_friction_torque_Nm": "mean_friction_torque_Nm",
        "engine_friction_reduction_vs_uncoated_pct": "friction_reduction_vs_uncoated_pct",
    }
    for k, src in values.items():
        units, long = ENGINE_SCALARS[k]
        ds[k] = xr.Variable(
            "surface_set", [_num(sets[n][src]) for n in names], {"units": units, "long_name": long}
        )
    for part in parts:
        k = f"{part}_energy_J"
        units, long = ENGINE_SCALARS[k]
        ds[k] = xr.Variable(
            "surface_set",
            [_num(sets[n]["friction_energy_per_cycle_J"][part]) for n in names],
            {"units": units, "long_name": long},
        )
    ds.attrs["reference_set"] = summ["reference_set"]
    return ds, list(study.warnings)


class _PointFailure(RuntimeError):
    """A point whose run cannot give results (the message says why)."""


def run_point(case, mode: str = "study", traces: bool = False) -> xr.Dataset:
    """Run one sweep point: the full cam-cycle study of ``case`` (``mode="study"``) or the
    valvetrain dynamics alone (``mode="dynamics"``); return its Dataset.

    The study runs serially in this process (one BLAS thread): a sweep's parallelism is
    over points. Failures are returned as :func:`failed_point`, never raised."""
    from threadpoolctl import threadpool_limits

    from .cycle import StudyError

    t0, c0 = time.perf_counter(), time.process_time()
    try:
        with threadpool_limits(1):
            if mode == "dynamics":
                ds, warnings = _dynamics_point(case, traces)
            elif mode == "study":
                ds, warnings = _study_point(case, traces)
            elif mode == "engine":
                ds, warnings = _engine_point(case)
            else:
                raise ValueError(f"mode must be 'study', 'dynamics' or 'engine' (got {mode!r})")
    except (_PointFailure, StudyError) as exc:
        return failed_point(str(exc), time.perf_counter() - t0)
    except Exception as exc:  # any other error of this point is recorded, not fatal
        tb = traceback.extract_tb(exc.__traceback__)
        where = f" (at {tb[-1].filename.rsplit('/', 1)[-1]}:{tb[-1].lineno})" if tb else ""
        return failed_point(f"{type(exc).__name__}: {exc}{where}", time.perf_counter() - t0)
    runtime, cpu = time.perf_counter() - t0, time.process_time() - c0
    ds["runtime_s"] = _scalar("runtime_s", runtime)
    ds["cpu_s"] = _scalar("cpu_s", cpu)
    ds.attrs.update(
        {
            "status": "ok",
            "error": "",
            "runtime_s": runtime,
            "cpu_s": cpu,
            "warnings": json.dumps(warnings),
            **_where(),
        }
    )
    return ds

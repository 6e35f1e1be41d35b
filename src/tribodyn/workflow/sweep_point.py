"""One point of a design sweep: the study (or the dynamics alone) of one case, reduced to
an xarray Dataset of summary scalars and, on request, cycle traces.

:func:`run_point` is the task a sweep sends to a Dask worker (it runs in any process
where tribodyn is installed). It never raises for a point's own failure: an invalid case,
a failed valvetrain integration or a study that cannot proceed returns a Dataset with
``status = "failed"`` and the error in its attributes, so that one point cannot stop the
sweep. Units are SI and given in every variable's ``units`` attribute; the names of the
scalars are those of ``summary.json`` (:func:`tribodyn.workflow.postprocess.summary`).
The variables are the tables of :mod:`tribodyn.workflow.variables_sweep`.

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

import math
import socket
import time
import traceback

import xarray as xr

from .. import _json
from .._threads import single_blas_thread
from ..config.build import BuiltCase, as_built
from .variables import Group, build
from .variables_study import StudySource
from .variables_sweep import (
    COMPARISON_SCALARS,
    DYNAMICS_TRACES,
    EHL_TRACES,
    ENGINE_SCALARS,
    ENGINE_SETS,
    POINT_SCALARS,
    SET_COORDS,
    SET_SCALARS,
)

__all__ = ["run_point", "failed_point", "POINT_SCALARS", "SET_SCALARS", "ENGINE_SCALARS"]


def _scalars(ds: xr.Dataset, values: dict) -> xr.Dataset:
    """Point scalars (:data:`POINT_SCALARS`) from a mapping of name → value."""
    for k in values:
        ds[k] = POINT_SCALARS[k].make(values)
    return ds


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
    """The point scalars of the dynamics: the summary's, crank angles within the
    presented cycle."""
    s, t0 = dyn.summary(), float(dyn.crank_angle[0])
    own = {
        "peak_contact_force_crank_deg": s["peak_contact_force_crank_deg"] - t0,
        "entrainment_speed_min_m_s": s["entrainment_speed_range_m_s"][0],
        "entrainment_speed_max_m_s": s["entrainment_speed_range_m_s"][1],
        "dynamics_friction_energy_per_cycle_J": s["friction_energy_per_cycle_J"],
        "jump_onset_crank_deg": dyn.jumps[0][0] - t0 if dyn.jumps else math.nan,
    }
    return {k: own[k] if k in own else s[k] for k in POINT_SCALARS if k in own or k in s}


def _dynamics_point(built: BuiltCase, traces: bool) -> tuple[xr.Dataset, list]:
    from .cycle import study_dynamics

    dyn = study_dynamics(built)
    if not dyn.converged:
        raise _PointFailure(f"valvetrain dynamics failed: {dyn.message}")
    ds = _scalars(xr.Dataset(), {**_dynamics_scalars(dyn), "n_warnings": int(dyn.jump)})
    warnings = [f"contact loss (jump) during the event at {dyn.jumps}"] if dyn.jump else []
    if traces:
        build(ds, [DYNAMICS_TRACES], StudySource(dynamics=dyn))
    return ds, warnings


def _study_point(built: BuiltCase, traces: bool) -> tuple[xr.Dataset, list]:
    from .cycle import run_cycle_study

    study = run_cycle_study(built, workers=1)
    source = StudySource(study)
    summ = source.analysis.summary
    ie = summ["implicit_vs_explicit"]
    ds = _scalars(
        xr.Dataset(),
        {
            **_dynamics_scalars(study.dynamics),
            **{k: ie.get(k) for k in COMPARISON_SCALARS},
            "n_warnings": len(study.warnings),
        },
    )
    build(ds, [SET_COORDS, Group(tuple(SET_SCALARS.values()))], source)
    ds.attrs["reference_set"] = summ["reference_set"]
    if traces:
        build(ds, [DYNAMICS_TRACES, EHL_TRACES], source)
    return ds, list(study.warnings)


def _engine_point(built: BuiltCase) -> tuple[xr.Dataset, list]:
    """A whole engine (:func:`~tribodyn.workflow.engine.run_engine_study`; the coatings
    share each lobe's dynamics) reduced to per-set scalars."""
    from .engine import run_engine_study

    study = run_engine_study(built.case, workers=1)
    summ = study.summary()
    ds = _scalars(xr.Dataset(), _dynamics_scalars(study.lobes["intake"].study.dynamics))
    source = {"sets": summ["surface_sets"], "names": study.set_names}
    ds.coords["surface_set"] = ENGINE_SETS.make(source)
    for k, v in ENGINE_SCALARS.items():
        ds[k] = v.make(source)
    ds.attrs["reference_set"] = summ["reference_set"]
    return ds, list(study.warnings)


class _PointFailure(RuntimeError):
    """A point whose run cannot give results (the message says why)."""


def run_point(case, mode: str = "study", traces: bool = False) -> xr.Dataset:
    """Run one sweep point: the full cam-cycle study of ``case`` (``mode="study"``) or the
    valvetrain dynamics alone (``mode="dynamics"``); return its Dataset. ``case`` (the
    point's case, or its BuiltCase) is built once for the point.

    The study runs serially in this process (one BLAS thread): a sweep's parallelism is
    over points. Failures are returned as :func:`failed_point`, never raised."""
    from .cycle import StudyError

    t0, c0 = time.perf_counter(), time.process_time()
    try:
        with single_blas_thread():
            built = as_built(case)
            if mode == "dynamics":
                ds, warnings = _dynamics_point(built, traces)
            elif mode == "study":
                ds, warnings = _study_point(built, traces)
            elif mode == "engine":
                ds, warnings = _engine_point(built)
            else:
                raise ValueError(f"mode must be 'study', 'dynamics' or 'engine' (got {mode!r})")
    except (_PointFailure, StudyError) as exc:
        return failed_point(str(exc), time.perf_counter() - t0)
    except Exception as exc:  # any other error of this point is recorded, not fatal
        tb = traceback.extract_tb(exc.__traceback__)
        where = f" (at {tb[-1].filename.rsplit('/', 1)[-1]}:{tb[-1].lineno})" if tb else ""
        return failed_point(f"{type(exc).__name__}: {exc}{where}", time.perf_counter() - t0)
    runtime, cpu = time.perf_counter() - t0, time.process_time() - c0
    _scalars(ds, {"runtime_s": runtime, "cpu_s": cpu})
    ds.attrs.update(
        {
            "status": "ok",
            "error": "",
            "runtime_s": runtime,
            "cpu_s": cpu,
            "warnings": _json.dumps(warnings),
            **_where(),
        }
    )
    return ds

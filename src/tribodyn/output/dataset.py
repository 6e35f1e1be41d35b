"""Cycle-study results as one xarray Dataset.

Dimensions: ``crank_angle`` (dynamics output, deg), ``ehl_crank`` (transient-EHL samples,
deg), ``surface_set``, ``k`` (profile samples), ``point`` (the six representative points
of the paper's Fig. 13), and for the single-contact studies ``dry_ratio``/``dry_x``
(Fig. 5), ``ehl_ratio``/``ehl_pair``/``ehl_x`` (Fig. 6), ``chart_gV``/``chart_gE`` (the
regime map of Fig. 12). Every variable carries ``units`` and ``long_name``. EHL
quantities are NaN where the contact carries no load (``loaded`` false: cam on the base
circle) — by definition, not as a failure; steps that did not
converge keep their last iterate and are flagged by ``converged`` false and listed in the
``ehl_failures`` attribute. Attributes: the case as run (``case_toml``), the roles of the
surface sets (``reference_set``, ``surface_roles``), the coupling, warnings, the
single-contact studies' conditions, and ``thermal`` (1 in a thermal study, with
``inlet_temperature_K``; 0 else).

The variables, their units and descriptions are the table of
:mod:`tribodyn.workflow.variables_study`; this module writes them and the attributes.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import xarray as xr

from .. import _json
from .._typing import PathLike
from .._validation import InputError
from ..workflow.coating_study import DRY_CONDITIONS
from ..workflow.variables import build
from ..workflow.variables_study import STUDY, THERMAL_GROUP, StudySource

if TYPE_CHECKING:
    from ..workflow.cycle import CycleStudy

__all__ = ["RUN_VARIABLES", "load_run_results", "study_to_dataset", "write_netcdf"]

#: Variables every cycle study's results.nc holds (what tells it from other netCDF files).
RUN_VARIABLES = ("ehl_crank", "crank_angle", "surface_set")


def load_run_results(nc: PathLike) -> xr.Dataset:
    """The results.nc ``nc`` of a cycle study, loaded into memory; an InputError (under
    RESULTS) if it cannot be read or is not a cycle study's (:data:`RUN_VARIABLES`)."""
    try:
        with xr.open_dataset(nc, engine="h5netcdf") as ds:
            ds.load()
    except (OSError, ValueError) as exc:
        raise InputError(f"RESULTS: cannot read {nc}: {exc}") from exc
    missing = [v for v in RUN_VARIABLES if v not in ds.variables]
    if missing:
        raise InputError(
            f"RESULTS: {nc} is not a tribodyn results file of a cam-cycle study "
            f"(it has no {', '.join(missing)})"
        )
    return ds


def write_netcdf(ds: xr.Dataset, path: PathLike, encoding: dict | None = None) -> None:
    """Write ``ds``, held in memory (no dask chunks, as a study's Dataset), to the
    netCDF-4 file ``path`` with h5netcdf: the file of ``ds.to_netcdf(path,
    engine="h5netcdf", encoding=encoding)``, straight through xarray's h5netcdf store
    under the HDF5 library's lock: ``to_netcdf`` first asks dask for its scheduler (for
    its choice of file closing and write lock), which imports ``dask.distributed`` (about
    a second), a choice that only matters for chunked data."""
    from xarray.backends import H5NetCDFStore
    from xarray.backends.locks import HDF5_LOCK

    # the lock given: else the store asks dask's scheduler for a write lock too
    store = H5NetCDFStore.open(path, mode="w", lock=HDF5_LOCK)
    try:
        ds.dump_to_store(store, encoding=encoding or {})
    finally:
        store.close()


def study_to_dataset(study: CycleStudy) -> xr.Dataset:
    """All results of a :class:`~tribodyn.workflow.cycle.CycleStudy` in one Dataset."""
    from .. import __version__

    source = StudySource(study)
    an = study.analyse()
    case, sets = study.case, study.sets
    ds = build(xr.Dataset(), STUDY, source)
    if study.dry:
        ds.attrs["dry_coating_conditions"] = _json.dumps(DRY_CONDITIONS)
    if (e := study.ehl_coating) is not None and e.results:
        ds.attrs["ehl_coating_conditions"] = _json.dumps(e.conditions)
    ds.attrs["lubricant_as_used"] = _json.dumps(source.oil)
    ds.attrs["compare_paper"] = int(bool(getattr(study, "compare_paper", False)))
    # a thermal study (numerics.thermal): the temperatures along the cycle [K] and the
    # isothermal run's film and friction (suffix _isothermal) on (surface_set, ehl_crank)
    thermal = source.isothermal_sets is not None
    ds.attrs["thermal"] = int(thermal)
    if thermal:
        build(ds, [THERMAL_GROUP], source)
        ds.attrs["inlet_temperature_K"] = float(source.study.sets[0].inlet_temperature)
    failures = {s.name: [[c, m] for c, m in s.failures] for s in sets}
    ds.attrs.update(
        {
            "title": f"tribodyn cam-cycle study: {case.name}",
            "tribodyn_version": __version__,
            # files by absolute path: the case can be read again from results.nc alone
            "case_toml": case.to_toml(resolve_paths=True),
            "engine_speed_rpm": float(case.engine_speed),
            "cam_width_m": float(case.width),
            "runtime_s": float(study.runtime_s),
            "reference_set": an.roles["reference"],
            "surface_roles": _json.dumps(an.roles),
            "coupling": _json.dumps(study.coupling.to_dict()),
            "warnings": _json.dumps(study.warnings),
            "valve_jump": _json.dumps(study.dynamics.jump_summary()),
            "ehl_failures": _json.dumps(failures),
            "conventions": "SI; EHL NaN where unloaded (loaded = 0)",
            "roughness_sensitivity": _json.dumps(
                study.sensitivity.to_dict() if study.sensitivity is not None else {}
            ),
            "surface_sets_at_nose": _json.dumps(
                ns.to_dict() if (ns := getattr(study, "nose_sets", None)) is not None else {}
            ),
        }
    )
    return ds

"""Thermal results of a cycle study (``numerics.thermal``) in the results Dataset.

Adds, on (surface_set, ehl_crank): the temperatures along the cycle [K] and the
isothermal run's film and friction (suffix ``_isothermal``) beside the thermal ones (the
variables without suffix are the thermal model's in a thermal study); attributes
``thermal`` (1) and ``inlet_temperature_K``. The variables are the table
``THERMAL`` of :mod:`tribodyn.workflow.variables_study`.
"""

from __future__ import annotations

import xarray as xr

from ..workflow.variables import build
from ..workflow.variables_study import THERMAL_GROUP, StudySource

__all__ = ["add_thermal"]


def add_thermal(ds: xr.Dataset, study) -> xr.Dataset:
    """Add the thermal variables (no-op for an isothermal study)."""
    if getattr(study, "isothermal_sets", None) is None:
        ds.attrs["thermal"] = 0
        return ds
    build(ds, [THERMAL_GROUP], StudySource(study))
    ds.attrs["thermal"] = 1
    ds.attrs["inlet_temperature_K"] = float(study.sets[0].inlet_temperature)
    return ds

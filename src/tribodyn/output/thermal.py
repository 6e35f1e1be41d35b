"""Thermal results of a cycle study (``numerics.thermal``) in the results Dataset.

Adds, on (surface_set, ehl_crank): the temperatures along the cycle [K] and the
isothermal run's film and friction (suffix ``_isothermal``) beside the thermal ones (the
variables without suffix are the thermal model's in a thermal study); attributes
``thermal`` (1) and ``inlet_temperature_K``.
"""

from __future__ import annotations

import numpy as np
import xarray as xr

__all__ = ["add_thermal"]

_TEMPERATURES = {
    "max_temperature": "maximum temperature of film and surfaces",
    "mid_film_temperature": "mid-film temperature at the contact centre",
    "surface_temperature_cam": "maximum surface temperature of the cam",
    "surface_temperature_tappet": "maximum surface temperature of the tappet (coating)",
    "mean_film_temperature": "film-mean temperature at the contact centre",
}
_ISO = {
    "central_film": ("m", "central film, isothermal model at the inlet temperature"),
    "min_film": ("m", "minimum film, isothermal model"),
    "viscous_friction": ("N", "viscous friction, isothermal model"),
    "boundary_friction": ("N", "boundary friction, isothermal model"),
    "friction_power": ("W", "friction power, isothermal model"),
    "asperity_load": ("N", "asperity load, isothermal model"),
}


def add_thermal(ds: xr.Dataset, study) -> xr.Dataset:
    """Add the thermal variables (no-op for an isothermal study)."""
    iso = getattr(study, "isothermal_sets", None)
    if iso is None:
        ds.attrs["thermal"] = 0
        return ds
    two = ("surface_set", "ehl_crank")
    for k, name in _TEMPERATURES.items():
        ds[k] = xr.Variable(
            two, np.array([getattr(s, k) for s in study.sets]), {"units": "K", "long_name": name}
        )
    for k, (units, name) in _ISO.items():
        ds[k + "_isothermal"] = xr.Variable(
            two, np.array([getattr(s, k) for s in iso]), {"units": units, "long_name": name}
        )
    ds["converged_isothermal"] = xr.Variable(
        two,
        np.array([s.converged for s in iso]).astype(np.int8),
        {"long_name": "isothermal EHL step converged"},
    )
    ds.attrs["thermal"] = 1
    ds.attrs["inlet_temperature_K"] = float(study.sets[0].inlet_temperature)
    return ds

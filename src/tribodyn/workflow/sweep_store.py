"""The points of a sweep on disk, and the combined Dataset.

:class:`PointStore` keeps one small netCDF file per finished point in ``OUT/points/``,
named by the point's key (a hash of its complete case, the mode, the traces flag and the
tribodyn version), written to a temporary file and renamed into place, so a file either is
complete or does not exist. A resumed sweep skips the points whose file says
``status = "ok"``; a changed sweep file reuses every point whose case is unchanged.

:func:`combine_points` puts the points of a plan into one xarray Dataset indexed by the
sweep's dimensions (failed points are NaN, with ``status`` 0 and their ``error``).
"""

from __future__ import annotations

import json
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from .. import _json
from .._safe_write import TOKEN_CHARS, atomic_write_with, make_dirs
from .variables_study import SET_DESCRIPTION
from .variables_sweep import SWEEP_STATUS

__all__ = ["PointStore", "combine_points", "POINTS_FOLDER"]

POINTS_FOLDER = "points"
#: Temporary name of a point file being written (:mod:`tribodyn._safe_write`).
_TMP_POINT = re.compile(rf"\.[0-9a-f]+(?:\.nc)?\.[0-9a-f]{{{TOKEN_CHARS}}}\.tmp")
#: Coordinates along ``surface_set`` kept in the combined Dataset when all points agree.
SET_COORDS = tuple(v.name for v in SET_DESCRIPTION)


class PointStore:
    """One netCDF file per point in ``folder/points`` (see the module docstring)."""

    def __init__(self, folder):
        self.folder = Path(folder)
        self.dir = self.folder / POINTS_FOLDER

    def path(self, key: str) -> Path:
        return self.dir / f"{key}.nc"

    def keys(self) -> list[str]:
        """Keys of all point files present (finished or failed)."""
        if not self.dir.is_dir():
            return []
        return sorted(p.stem for p in self.dir.glob("*.nc") if not p.name.startswith("."))

    def _read(self, key: str, read: Callable[[xr.Dataset], Any]) -> Any:
        """``read`` of the point's open Dataset; None without a readable file."""
        p = self.path(key)
        if not p.is_file():
            return None
        try:
            with xr.open_dataset(p, engine="h5netcdf") as ds:
                return read(ds)
        except (OSError, ValueError):
            return None

    def status(self, key: str) -> str | None:
        """``"ok"``, ``"failed"`` or None (no readable file)."""
        return self._read(key, lambda ds: str(ds.attrs.get("status", "failed")))

    def load(self, key: str) -> xr.Dataset | None:
        return self._read(key, lambda ds: ds.load())

    def write(self, point, ds: xr.Dataset) -> Path:
        """Write a point's Dataset atomically, with the point's identity in its
        attributes."""
        make_dirs(self.dir)
        ds = ds.copy()
        ds.attrs.update(
            {
                "point_index": int(point.index),
                "point_key": point.key,
                "point_values": _json.dumps(point.values),
                "point_changes": _json.dumps(point.changes),
                "point_label": point.label,
            }
        )
        if point.case is not None:
            ds.attrs["case_toml"] = point.case.to_toml()
        return atomic_write_with(
            self.path(point.key), lambda tmp: ds.to_netcdf(tmp, engine="h5netcdf")
        )

    def clean(self) -> None:
        """Remove temporary files left by an interrupted write (``.KEY.XXXXXXXX.tmp``
        of a point file's key; nothing else)."""
        if self.dir.is_dir() and not self.dir.is_symlink():
            for p in self.dir.glob(".*.tmp"):
                if _TMP_POINT.fullmatch(p.name) and p.is_file() and not p.is_symlink():
                    p.unlink(missing_ok=True)


def _ordered_union(values_lists) -> np.ndarray:
    """Union of coordinate values: numeric sorted, text in order of first appearance."""
    arrays = [np.asarray(v) for v in values_lists]
    if all(a.dtype.kind in "iuf" for a in arrays):
        return np.unique(np.concatenate(arrays))
    return np.array(list(dict.fromkeys(v for a in arrays for v in a.tolist())), dtype=object)


def combine_points(spec, plan, results: dict) -> xr.Dataset:
    """One Dataset of all points of ``plan`` (``results``: point index → its Dataset),
    indexed by the sweep dimensions; variables of failed or missing points are NaN."""
    from .. import __version__

    shape = spec.shape
    dims = [d for d, _ in spec.dims]
    ok = {i: ds for i, ds in results.items() if ds.attrs.get("status") == "ok"}
    inner: dict[str, np.ndarray] = {}
    for d in ("surface_set", "crank_angle", "ehl_crank"):
        have = [ds[d].values for ds in ok.values() if d in ds.dims]
        if have:
            inner[d] = _ordered_union(have)
    aligned = {
        i: ds.reindex({d: v for d, v in inner.items() if d in ds.dims}) for i, ds in ok.items()
    }
    out = xr.Dataset()
    names = list(dict.fromkeys(v for ds in aligned.values() for v in ds.data_vars))
    n = len(plan)
    for name in names:
        first = next(ds[name] for ds in aligned.values() if name in ds)
        idims = first.dims
        data = np.full((n, *(len(inner[d]) for d in idims)), np.nan)
        for i, ds in aligned.items():
            if name in ds:
                data[i] = ds[name].values.astype(float)
        out[name] = xr.Variable(
            (*dims, *idims), data.reshape(*shape, *data.shape[1:]), dict(first.attrs)
        )
    for d, v in inner.items():
        first = next(ds for ds in aligned.values() if d in ds.dims)
        out.coords[d] = xr.Variable(
            d, v.astype(str) if v.dtype == object else v, dict(first[d].attrs)
        )
    for name in SET_COORDS:  # per-set descriptions, where all points agree
        vals = {tuple(ds[name].values.tolist()) for ds in aligned.values() if name in ds.coords}
        if len(vals) == 1 and "surface_set" in inner:
            first = next(ds[name] for ds in aligned.values() if name in ds.coords)
            v = np.asarray(first.values)
            out.coords[name] = xr.Variable(
                "surface_set", v.astype(str) if v.dtype == object else v, dict(first.attrs)
            )
    for dim, axes in spec.dims:
        idx_axis = next((a for a in axes if a.name == dim), None)
        if idx_axis is None:
            out.coords[dim] = xr.Variable(
                dim, np.arange(len(axes[0].values)), {"long_name": f"position along {dim}"}
            )
        for a in axes:
            out.coords[a.name] = xr.Variable(
                dim,
                np.array(a.values),
                {"units": a.unit, "long_name": a.path, "description": a.description},
            )
    status = np.zeros(n, np.int8)
    error = np.full(n, "", dtype=object)
    warnings = np.full(n, "", dtype=object)
    keys = np.array([p.key for p in plan], dtype=object)
    for p in plan:
        ds = results.get(p.index)
        if ds is None:
            error[p.index] = "not run"
        elif ds.attrs.get("status") == "ok":
            status[p.index] = 1
            warnings[p.index] = "; ".join(json.loads(ds.attrs.get("warnings", "[]")))
        else:
            error[p.index] = str(ds.attrs.get("error", "failed"))
    bookkeeping = {
        "status": status.reshape(shape),
        "error": error.astype(str).reshape(shape),
        "warnings": warnings.astype(str).reshape(shape),
        "point_key": keys.astype(str).reshape(shape),
    }
    for name, row in SWEEP_STATUS.items():
        out[name] = row.make(bookkeeping, tuple(dims))
    refs = {ds.attrs.get("reference_set") for ds in ok.values()} - {None}
    out.attrs.update(
        {
            "title": f"tribodyn sweep: {spec.name}",
            "tribodyn_version": __version__,
            "mode": spec.mode,
            "traces": int(spec.traces),
            "n_points": int(n),
            "n_failed": int(n - status.sum()),
            "axes": _json.dumps(
                [
                    {
                        "path": a.path,
                        "name": a.name,
                        "dim": a.dim,
                        "unit": a.unit,
                        "values": list(a.values),
                    }
                    for a in spec.axes
                ]
            ),
            "sweep_toml": spec.to_toml(),
            "base_case_toml": spec.base.to_toml(resolve_paths=True),
            "conventions": "SI; NaN where a point failed (status = 0)",
        }
    )
    if len(refs) == 1:
        out.attrs["reference_set"] = refs.pop()
    return out

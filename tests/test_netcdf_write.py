"""results.nc is written by output.dataset.write_netcdf: the file of xarray's
to_netcdf(engine="h5netcdf"), without importing dask.distributed."""

from __future__ import annotations

import subprocess
import sys

import numpy as np
import xarray as xr

from tribodyn.output.dataset import write_netcdf


def _dataset() -> xr.Dataset:
    rng = np.random.default_rng(3)
    return xr.Dataset(
        {
            "pressure": (("s", "k"), rng.random((3, 64)).astype(np.float32), {"units": "Pa"}),
            "loaded": (("s",), np.array([1, 0, 1], dtype=np.int8)),
            "force": (("t",), np.r_[rng.random(9), np.nan], {"units": "N"}),
        },
        coords={"s": ["a", "b", "c"], "t": np.arange(10.0)},
        attrs={"case": "demo", "warnings": "[]"},
    )


def test_the_same_file_as_to_netcdf(tmp_path):
    ds = _dataset()
    enc = {"pressure": {"compression": "gzip", "compression_opts": 4}}
    ds.to_netcdf(tmp_path / "a.nc", engine="h5netcdf", encoding=enc)
    write_netcdf(ds, tmp_path / "b.nc", enc)
    with (
        xr.open_dataset(tmp_path / "a.nc", engine="h5netcdf") as a,
        xr.open_dataset(tmp_path / "b.nc", engine="h5netcdf") as b,
    ):
        assert a.load().identical(b.load())
        for name in a.variables:
            ea, eb = dict(a[name].encoding), dict(b[name].encoding)
            ea.pop("source", None), eb.pop("source", None)
            assert repr(ea) == repr(eb), name  # repr: _FillValue NaN
        assert b["pressure"].encoding["zlib"] and b["pressure"].encoding["complevel"] == 4


def test_no_dask_distributed(tmp_path):
    code = (
        "import sys, xarray as xr\n"
        "from tribodyn.output.dataset import write_netcdf\n"
        f"write_netcdf(xr.Dataset({{'x': ('t', [1.0, 2.0])}}), {str(tmp_path / 'x.nc')!r})\n"
        "print('distributed' in sys.modules)\n"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"
    with xr.open_dataset(tmp_path / "x.nc", engine="h5netcdf") as ds:
        assert ds["x"].values.tolist() == [1.0, 2.0]

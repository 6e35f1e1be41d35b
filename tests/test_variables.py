"""The registry of output variables (tribodyn.workflow.variables): one name has one unit
in every table, and every variable written to results.nc, a sweep point's file or
sweep.nc carries the units and description of its registry row."""

from collections import defaultdict

import numpy as np
import xarray as xr

from test_sweep_run import STUDY_FIXED
from tribodyn.config import load_case
from tribodyn.config.sweep import load_sweep
from tribodyn.workflow.sweep_point import run_point
from tribodyn.workflow.sweep_store import combine_points
from tribodyn.workflow.variables_registry import registry


def assert_registered(ds: xr.Dataset, exempt=()) -> int:
    """Every variable and coordinate of ``ds`` (except ``exempt``) is a registry row: its
    ``long_name`` is the row's description and its ``units`` the row's units. Numbers
    always have units; text has none. Returns the number of variables checked."""
    rows = defaultdict(list)
    for v in registry():
        rows[v.name].append(v)
    bad: list[tuple] = []
    names = [n for n in ds.variables if n not in exempt]
    for name in names:
        a = ds[name].attrs
        match = [
            v
            for v in rows.get(str(name), [])
            if a.get("long_name") == v.description and a.get("units") == v.units
        ]
        if not match:
            bad.append((name, dict(a)))
        elif ds[name].dtype.kind in "biuf" and "units" not in a:
            bad.append((name, "a number without units"))
        elif ds[name].dtype.kind in "USO" and "units" in a:
            bad.append((name, "text with units"))
    assert not bad, bad
    return len(names)


def test_one_name_has_one_unit_and_every_row_is_described():
    units, rows = defaultdict(set), registry()
    for v in rows:
        units[v.name].add(v.units)
        assert v.description.strip(), v.name
    conflicts = {k: u for k, u in units.items() if len(u) > 1}
    assert not conflicts, conflicts
    assert len(rows) > 200  # the study, thermal, stress, engineering and sweep tables


def test_results_nc_variables_come_from_the_registry(reduced_results):
    with xr.open_dataset(reduced_results / "results.nc", engine="h5netcdf") as ds:
        n = assert_registered(ds)
        # the groups of the paper case: implicit coupling, coating studies, stresses,
        # engineering outputs
        for name in ("contact_force_implicit", "dry_pressure", "ehl_pair_film", "surge_mode"):
            assert name in ds
    assert n > 100


SWEEP = f"""
[sweep]
name = "registry_check"
mode = "study"
traces = true
{STUDY_FIXED}
[[axes]]
path = "engine.speed_rpm"
values = [3000.0]
"""


def test_sweep_point_and_sweep_nc_variables_come_from_the_registry(tmp_path):
    p = tmp_path / "s.toml"
    p.write_text(SWEEP, encoding="utf-8")
    spec = load_sweep(p)
    plan = spec.points()
    point = run_point(plan[0].case, spec.mode, spec.traces)
    assert point.attrs["status"] == "ok", point.attrs
    assert assert_registered(point) > 50
    # the traces are the study Dataset's variables: same name, same description
    assert "contact_force" in point and "min_film" in point and "surface_label" in point.coords
    combined = combine_points(spec, plan, {plan[0].index: point})
    # the sweep's axis coordinates describe the case parameter swept (its own units)
    axes = {a.name for _, axs in spec.dims for a in axs} | {d for d, _ in spec.dims}
    assert assert_registered(combined, exempt=axes) > 50
    for a in axes:
        assert "long_name" in combined[a].attrs
    assert np.all(combined["status"].values == 1)


def test_dynamics_point_variables_come_from_the_registry():
    case = load_case().updated(
        {"numerics.cycles": 1, "numerics.output_step_deg": 2.0, "numerics.max_step_deg": 2.0}
    )
    ds = run_point(case, "dynamics", True)
    assert ds.attrs["status"] == "ok", ds.attrs
    assert assert_registered(ds) > 25

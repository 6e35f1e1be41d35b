"""Sweeps on real Dask clusters: a LocalCluster of two process workers, a ``dask
scheduler`` with two ``dask worker`` processes driven through ``--scheduler``, a sweep
killed mid-way and resumed, and a failing point. Every cluster result is compared with
the same points run one by one in this process.

The sweeps are tiny so that the suite stays fast: dynamics-only points of one engine
cycle on a 2° output grid, and study points of a reduced case (one or two surface sets,
5° EHL steps, 128 nodes); the physics is the full model at coarse resolution.
"""

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from tribodyn.cli import app
from tribodyn.config import load_case
from tribodyn.config.sweep import load_sweep
from tribodyn.workflow.cycle import run_cycle_study
from tribodyn.workflow.sweep import run_sweep
from tribodyn.workflow.sweep_point import run_point
from tribodyn.workflow.sweep_store import PointStore, combine_points

runner = CliRunner()


def text(result) -> str:
    """Command output with line wrapping undone."""
    return " ".join(result.output.split())


BIN = Path(sys.executable).parent

COARSE = {"numerics.cycles": 1, "numerics.output_step_deg": 2.0, "numerics.max_step_deg": 2.0}
DYNAMICS_SWEEP = """
[sweep]
name = "tiny_dynamics"
mode = "dynamics"
traces = true

[fixed]
"numerics.cycles" = 1
"numerics.output_step_deg" = 2.0
"numerics.max_step_deg" = 2.0

[[axes]]
path = "engine.speed_rpm"
values = [2000.0, 5000.0, 8000.0]

[[axes]]
path = "valvetrain.spring_rate"
values = [30000.0, 45000.0]
"""

STUDY_FIXED = """
[fixed]
"numerics.cycles" = 1
"numerics.output_step_deg" = 2.0
"numerics.max_step_deg" = 2.0
"numerics.crank_step_deg" = 5.0
"numerics.n" = 128
"numerics.implicit_coupling" = false
"surface_sets" = [{ name = "uncoated", roughness = { asperity_density = 8.3e9, rms = 0.408e-6, summit_radius = 0.669e-6 } }]
"""


@pytest.fixture(scope="module")
def dyn_file(tmp_path_factory):
    p = tmp_path_factory.mktemp("sweep") / "tiny.toml"
    p.write_text(DYNAMICS_SWEEP, encoding="utf-8")
    return p


@pytest.fixture(scope="module")
def reference(dyn_file):
    """The points run one by one in this process, combined."""
    spec = load_sweep(dyn_file)
    plan = spec.points()
    results = {p.index: run_point(p.case, spec.mode, spec.traces) for p in plan}
    return combine_points(spec, plan, results)


def assert_same_numbers(ds, ref):
    """Identical variables and coordinates; every number equal (runtimes excepted)."""
    skip = {"runtime_s", "cpu_s"}
    assert set(ds.data_vars) == set(ref.data_vars)
    for name in ref.coords:
        np.testing.assert_array_equal(ds[name].values, ref[name].values)
    for name in set(ref.data_vars) - skip:
        a, b = ds[name].values, ref[name].values
        if b.dtype.kind in "fc":
            np.testing.assert_allclose(a, b, rtol=1e-12, atol=0.0, equal_nan=True, err_msg=name)
        else:
            np.testing.assert_array_equal(a, b, err_msg=name)


def test_reference_is_physical(reference):
    """The tiny sweep is a real one: the peak force grows with speed, the follower jumps
    at 8000 rpm on the soft spring only, and a trace is there."""
    ds = reference
    assert int(ds["status"].sum()) == 6
    pk = ds["peak_contact_force_N"].values
    assert np.all(np.diff(pk, axis=0) > 0)
    assert ds["jump"].sel(speed_rpm=8000.0, spring_rate=30000.0) == 1
    assert ds["jump"].sel(speed_rpm=2000.0).sum() == 0
    cf = ds["contact_force"].sel(speed_rpm=5000.0, spring_rate=45000.0)
    assert float(cf.max()) == pytest.approx(
        float(ds["peak_contact_force_N"].sel(speed_rpm=5000.0, spring_rate=45000.0))
    )
    assert ds["crank_angle"].values[0] == 0.0 and ds["crank_angle"].values[-1] == 720.0


def test_local_cluster_with_two_process_workers(dyn_file, reference, tmp_path):
    from distributed import Client, LocalCluster

    spec = load_sweep(dyn_file)
    with (
        LocalCluster(
            n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0"
        ) as cluster,
        Client(cluster) as client,
    ):
        pids = set(client.run(os.getpid).values())
        assert len(pids) == 2 and os.getpid() not in pids
        res = run_sweep(spec, client, out_dir=tmp_path)
    assert (res.ran, res.skipped, res.failed) == (6, 0, [])
    assert_same_numbers(res.dataset, reference)
    store = PointStore(tmp_path)
    assert sorted(store.keys()) == sorted(p.key for p in res.points)
    workers = {store.load(k).attrs["worker"] for k in store.keys()}
    assert all(w.startswith("tcp://") for w in workers)


# ----------------------------------------------------------------------------- scheduler
@pytest.fixture(scope="module")
def scheduler(tmp_path_factory):
    """``dask scheduler`` and two ``dask worker`` processes on localhost."""
    d = tmp_path_factory.mktemp("dask")
    sfile = d / "scheduler.json"
    log = open(d / "log.txt", "w")
    procs = [
        subprocess.Popen(
            [
                BIN / "dask",
                "scheduler",
                "--host",
                "127.0.0.1",
                "--port",
                "0",
                "--no-dashboard",
                "--scheduler-file",
                sfile,
            ],
            stdout=log,
            stderr=subprocess.STDOUT,
            cwd=d,
        )
    ]
    try:
        t0 = time.monotonic()
        while not sfile.exists() or not sfile.read_text().strip():
            assert time.monotonic() - t0 < 120, "dask scheduler did not start"
            assert procs[0].poll() is None, (d / "log.txt").read_text()
            time.sleep(0.1)
        address = json.loads(sfile.read_text())["address"]
        for _ in range(2):
            procs.append(
                subprocess.Popen(
                    [
                        BIN / "dask",
                        "worker",
                        address,
                        "--nthreads",
                        "1",
                        "--nworkers",
                        "1",
                        "--no-dashboard",
                    ],
                    stdout=log,
                    stderr=subprocess.STDOUT,
                    cwd=d,
                )
            )
        yield address
    finally:
        for p in reversed(procs):
            p.terminate()
        for p in procs:
            try:
                p.wait(timeout=30)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
        log.close()


def test_sweep_through_scheduler_address(dyn_file, reference, scheduler, tmp_path):
    out = tmp_path / "out"
    r = runner.invoke(
        app,
        ["sweep", str(dyn_file), "-o", str(out), "--scheduler", scheduler, "--workers", "2", "-q"],
    )
    assert r.exit_code == 0, r.output
    assert "6 of 6 points finished" in text(r)
    with xr.open_dataset(out / "sweep.nc", engine="h5netcdf") as ds:
        assert_same_numbers(ds.load(), reference)
        assert ds["peak_contact_force_N"].attrs["units"] == "N"
        assert ds["speed_rpm"].attrs["units"] == "rpm"
        assert "tribodyn case" in ds.attrs["base_case_toml"]
    report = (out / "sweep_report.md").read_text()
    assert f"Dask scheduler {scheduler}" in report
    for fig in ("sweep_dynamics.png", "sweep_heatmap.png"):
        assert (out / fig).stat().st_size > 10_000 and f"]({fig})" in report


def test_run_study_on_scheduler_matches_local(scheduler, tmp_path):
    """``tribodyn run --scheduler``: the surface sets, the reference set's task chain and
    the single-contact studies run on the cluster and give the numbers of the in-process
    study (implicit coupling off to keep the test short; its task is the same)."""
    case = load_case().updated(
        {
            **COARSE,
            "numerics.crank_step_deg": 5.0,
            "numerics.n": 128,
            "numerics.implicit_coupling": False,
            "numerics.min_load": 350.0,
            "numerics.workers": 1,
        }
    )
    d = case.to_dict()
    d["surface_sets"] = [s for s in d["surface_sets"] if s["name"] in ("uncoated", "wcc_4um")]
    case = type(case).from_dict(d)
    path = tmp_path / "case.toml"
    case.write_toml(path)
    r = runner.invoke(
        app, ["run", str(path), "-o", str(tmp_path / "out"), "--scheduler", scheduler, "-q"]
    )
    assert r.exit_code == 0, r.output
    remote = json.loads((tmp_path / "out" / "summary.json").read_text())
    local = run_cycle_study(case, workers=1).analyse().summary
    for name in ("uncoated", "wcc_4um"):
        for k in ("friction_energy_per_cycle_J", "min_film_m", "max_boundary_friction_N"):
            assert remote["surface_sets"][name][k] == pytest.approx(
                local["surface_sets"][name][k], rel=1e-10
            ), (name, k)
    assert remote["surface_sets"]["wcc_4um"]["boundary_friction_cycle_integral_change_pct"] < -80


def test_unreachable_scheduler_is_an_input_error():
    from tribodyn import InputError
    from tribodyn.workflow.sweep import connect

    with pytest.raises(
        InputError,
        match=r"--scheduler: cannot connect to "
        r"'tcp://127.0.0.1:9' within 2 s",
    ):
        connect("tcp://127.0.0.1:9", timeout=2)


# ----------------------------------------------------------------------------- resume
def test_killed_sweep_resumes_only_the_missing_points(dyn_file, reference, tmp_path):
    out = tmp_path / "out"
    points = out / "points"
    proc = subprocess.Popen(
        [BIN / "tribodyn", "sweep", dyn_file, "-o", out, "-j", "1", "-q"],
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        start_new_session=True,
    )
    try:
        t0 = time.monotonic()
        while len(list(points.glob("*.nc"))) < 2:
            assert proc.poll() is None, "the sweep ended before it could be killed"
            assert time.monotonic() - t0 < 300, "no point finished"
            time.sleep(0.02)
    finally:
        os.killpg(proc.pid, signal.SIGKILL)  # the client and its local workers
        proc.wait()
    before = {p.name: p.stat().st_mtime_ns for p in points.glob("*.nc")}
    assert 2 <= len(before) < 6
    assert not (out / "sweep.nc").exists()
    # without --resume the folder is refused: no finished point is overwritten
    r = runner.invoke(app, ["sweep", str(dyn_file), "-o", str(out), "-q"])
    assert r.exit_code == 2 and "already holds points" in text(r)
    r = runner.invoke(app, ["sweep", str(dyn_file), "-o", str(out), "--resume", "-q", "-j", "2"])
    assert r.exit_code == 0, r.output
    n = len(before)
    assert f"({6 - n} run now, {n} resumed)" in text(r)
    after = {p.name: p.stat().st_mtime_ns for p in points.glob("*.nc")}
    assert len(after) == 6
    assert all(after[k] == v for k, v in before.items())  # finished points not rerun
    assert not list(points.glob(".*.tmp"))
    with xr.open_dataset(out / "sweep.nc", engine="h5netcdf") as ds:
        assert_same_numbers(ds.load(), reference)
        assert ds.attrs["points_resumed"] == n


# ----------------------------------------------------------------------------- failures
def test_failing_point_is_reported_and_the_rest_complete(tmp_path):
    """A point whose study cannot run (no EHL sample above numerics.min_load) and an
    invalid combination are recorded with their errors; the other point completes with
    the numbers of the in-process run."""
    f = tmp_path / "s.toml"
    f.write_text(
        '[sweep]\nname = "fail"\n'
        + STUDY_FIXED
        + '[[axes]]\npath = "numerics.min_load"\nvalues = [350.0, 5000.0]\n'
        + '[[axes]]\npath = "cam.max_lift"\nvalues = [0.0093, 0.0099]\ngroup = "g"\n'
        + '[[axes]]\npath = "valvetrain.tappet_radius"\nvalues = [0.0165, 0.0145]\n'
        + 'group = "g"\n',
        encoding="utf-8",
    )
    spec = load_sweep(f)
    assert spec.shape == (2, 2)
    res = run_sweep(spec, workers=2, out_dir=tmp_path / "out")
    errors = {p.label: e for p, e in res.failed}
    assert len(errors) == 3 and res.n_ok == 1
    assert (
        "no EHL sample carries numerics.min_load = 5000 N"
        in errors["min_load = 5000, max_lift = 0.0093, tappet_radius = 0.0165"]
    )
    assert errors["min_load = 350, max_lift = 0.0099, tappet_radius = 0.0145"].startswith(
        "invalid combination: cam: "
    )
    ds = res.dataset
    assert ds["status"].values.tolist() == [[1, 0], [0, 0]]
    ok = ds.isel(min_load=0, g=0, surface_set=0)
    assert 1e-9 < float(ok["min_film_m"]) < float(ok["max_central_film_m"]) < 1e-5
    # magnitude: flat-tappet friction loss of 2–4 J per cam revolution was measured
    # (Winer et al., J. Tribol. 1986); this rough set (σ 0.41 µm) under the default
    # surface law lies in it
    assert 0.5 < float(ok["friction_energy_per_cycle_J"]) < 5
    assert int(ok["failed_steps"]) == 0
    # the implicit-vs-explicit comparison is stored in full, NaN without the coupling
    for k in (
        "max_contact_force_diff_pct",
        "rms_contact_force_diff_pct",
        "peak_contact_force_diff_pct",
        "valve_opening_shift_deg",
        "valve_closing_shift_deg",
        "coupling_iterations",
    ):
        assert np.isnan(float(ok[k])), k
    assert np.isnan(ds["friction_energy_per_cycle_J"].isel(min_load=1, g=0)).all()
    from tribodyn.output.sweep import write_sweep

    files = write_sweep(res, tmp_path / "out")
    report = files["report"].read_text()
    assert "## Failed points" in report and "no EHL sample carries" in report
    assert "invalid combination" in report
    # the CLI says so with exit code 1 after writing everything (resume reruns the
    # failed points, keeps the finished one)
    r = runner.invoke(
        app, ["sweep", str(f), "-o", str(tmp_path / "out"), "--resume", "-q", "-j", "1"]
    )
    assert r.exit_code == 1, r.output
    assert "1 of 4 points finished (1 run now, 1 resumed), 3 failed" in text(r)


def test_points_are_submitted_fastest_engine_first(dyn_file):
    """The points are submitted, with Dask priorities, by engine speed (fastest, i.e.
    costliest, first; equal speeds in plan order), so the longest points do not finish
    last; the futures come back in plan order."""
    from tribodyn.workflow.sweep import _submit

    spec = load_sweep(dyn_file)
    plan = spec.points()
    seen = []  # (plan index, engine speed, priority) in the order of submission

    class Recorder:
        def submit(self, fn, case, *args, key, priority, **kwargs):
            seen.append((int(key.split("-")[2]), case.engine_speed, priority))
            return key

    keys = _submit(Recorder(), spec, plan)
    assert [int(k.split("-")[2]) for k in keys] == [p.index for p in plan]
    expected = sorted(plan, key=lambda p: (-p.case.engine_speed, p.index))
    assert [i for i, _, _ in seen] == [p.index for p in expected]
    assert [r for _, _, r in seen] == sorted((r for _, _, r in seen), reverse=True)

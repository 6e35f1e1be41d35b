"""Benchmark: design sweeps on a local Dask cluster. Prints JSON. Not a timed test.

    python benchmarks/bench_sweep.py [--points 8] [--cheap-points 200]

1. Throughput: a dynamics-only sweep of the bundled paper case at full resolution (two
   engine cycles, 0.25° output) over ``--points`` engine speeds, on 1 and on 2 local
   process workers. The cluster is started and its workers import tribodyn before the
   clock starts; the time covers planning, scheduling, the points, their files and the
   combined Dataset. Reported: wall time, points per minute, the sum of the points' CPU
   times and the speed-up of 2 workers over 1.
2. Scheduling overhead: a sweep of ``--cheap-points`` trivially cheap points (each task
   returns a one-variable Dataset at once) on 2 workers, through the same machinery
   (plan with its case validation, submission, results, point files, combination).
   Reported: wall time per point, and the planning share of it.
"""

from __future__ import annotations

import argparse
import json
import statistics
import tempfile
import time

import xarray as xr

from tribodyn.config import SweepSpec
from tribodyn.workflow import sweep as sweep_module
from tribodyn.workflow.sweep import local_cluster, machine_workers, run_sweep


def _spec(n: int) -> SweepSpec:
    return SweepSpec.from_toml_string(
        '[sweep]\nname = "bench"\nmode = "dynamics"\n[[axes]]\npath = "engine.speed_rpm"\n'
        f"start = 1500.0\nstop = 6000.0\nnum = {n}\n"
    )


def _warm(client):
    client.run(lambda: __import__("tribodyn.workflow.sweep_point"))


def throughput(n_points: int, workers: int) -> dict:
    from distributed import Client

    spec = _spec(n_points)
    t0 = time.perf_counter()
    with local_cluster(workers) as cluster, Client(cluster) as client:
        _warm(client)
        start = time.perf_counter() - t0
        with tempfile.TemporaryDirectory() as out:
            t0 = time.perf_counter()
            res = run_sweep(spec, client, out_dir=out)
            wall = time.perf_counter() - t0
    cpu = [float(v) for v in res.dataset["cpu_s"].values.ravel()]
    return {
        "workers": workers,
        "points": n_points,
        "failed": len(res.failed),
        "cluster_start_s": start,
        "wall_s": wall,
        "points_per_min": 60.0 * n_points / wall,
        "sum_point_cpu_s": sum(cpu),
        "median_point_cpu_s": statistics.median(cpu),
    }


def _cheap_point(case, mode="study", traces=False):
    """A point that costs nothing: the scheduling, transfer and file cost stay."""
    return xr.Dataset(
        {"x": ((), float(case.engine_speed))},
        attrs={"status": "ok", "error": "", "runtime_s": 0.0, "warnings": "[]", "worker": ""},
    )


def overhead(n_points: int, workers: int = 2) -> dict:
    from distributed import Client

    spec = _spec(n_points)
    t0 = time.perf_counter()
    spec.points()
    plan_s = time.perf_counter() - t0
    real = sweep_module.run_point
    sweep_module.run_point = _cheap_point
    try:
        with local_cluster(workers) as cluster, Client(cluster) as client:
            _warm(client)
            with tempfile.TemporaryDirectory() as out:
                t0 = time.perf_counter()
                res = run_sweep(spec, client, out_dir=out)
                wall = time.perf_counter() - t0
    finally:
        sweep_module.run_point = real
    assert not res.failed
    return {
        "workers": workers,
        "points": n_points,
        "wall_s": wall,
        "per_point_ms": 1e3 * wall / n_points,
        "planning_per_point_ms": 1e3 * plan_s / n_points,
    }


def main() -> dict:
    ap = argparse.ArgumentParser()
    ap.add_argument("--points", type=int, default=8)
    ap.add_argument("--cheap-points", type=int, default=200)
    a = ap.parse_args()
    one = throughput(a.points, 1)
    two = throughput(a.points, 2)
    return {
        "case": "andreou2023 (bundled), dynamics only, 2 engine cycles per point",
        "machine_cores": machine_workers(),
        "workers_1": one,
        "workers_2": two,
        "speedup_2_over_1": one["wall_s"] / two["wall_s"],
        "overhead": overhead(a.cheap_points),
    }


if __name__ == "__main__":
    print(json.dumps(main(), indent=2, default=float))

"""Benchmark: the bundled engine map (``engine_dohc16_map``: 7 engine speeds × 3 oil
sump temperatures × the case's 3 tappet surfaces, each point the whole 16-valve engine)
on a local Dask cluster. Prints JSON. Not a timed test.

    python benchmarks/bench_engine_map.py [--workers 2]

Each point runs one lobe study (valvetrain dynamics once; the surfaces' transient EHL on
the same dynamics), phase-shifted to the 16 valves (intake and exhaust lobes are the same
here, so one study serves both). Reported: wall time (cluster start included), the sum
of the points' CPU times, failed points, and the FMEP and its change against the
reference set (negative = less) of each surface at the map's corners.
"""

from __future__ import annotations

import argparse
import json
import time

import numpy as np

from tribodyn.config import load_sweep
from tribodyn.workflow.sweep import run_sweep


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--workers", type=int, default=2)
    args = ap.parse_args()
    spec = load_sweep("engine_dohc16_map")
    t0 = time.perf_counter()
    res = run_sweep(spec, workers=args.workers)
    wall = time.perf_counter() - t0
    ds = res.dataset
    out = {
        "sweep": spec.name,
        "points": len(res.points),
        "failed": len(res.failed),
        "workers": args.workers,
        "wall_s": round(wall, 1),
        "points_cpu_s": round(float(np.nansum(ds["cpu_s"].values)), 1),
        "limit_s": 900,
    }
    fmep = ds["valvetrain_friction_mep_Pa"]
    change = ds["engine_friction_energy_change_pct"]  # negative = less
    dims = [d for d in fmep.dims if d != "surface_set"]
    corners = {}
    for sel_i in ((0, 0), (0, -1), (-1, 0), (-1, -1)):
        sel = dict(zip(dims, sel_i))
        f = fmep.isel(sel)
        label = ", ".join(f"{d}={f[d].values!s}" for d in dims)
        corners[label] = {
            str(s): {
                "fmep_kPa": round(float(f.sel(surface_set=s)) / 1e3, 3),
                "friction_energy_change_pct": round(float(change.isel(sel).sel(surface_set=s)), 2),
            }
            for s in f["surface_set"].values
        }
    out["corners"] = corners
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()

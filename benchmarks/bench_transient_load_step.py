"""Effort of one transient EHL step through a large load change.

Starts the steady paper-roughness contact at 4e4 N/m (R = 10 mm, u_e = 2 m/s,
u_s = 3 m/s) and takes one 0.1 ms step to 4e6 N/m (a hundredfold load, p_h ≈ 3.8 GPa),
then one back. Prints JSON: wall time, the number of solves (sub-step attempts), whether
the step converged and its film. ``--n N`` sets the grid (default 256; 0: automatic,
which refines to ≈ 2000 nodes at 4e6 N/m and takes minutes).

Run: ``python benchmarks/bench_transient_load_step.py [--n 256]``.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import time
from pathlib import Path

os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

from tribodyn import TransientEHL

# the contact and the solve counter of tests/test_validity.py
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from ehl_cases import OIL_055, PAIR, ROUGH, counted_advances


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--n", type=int, default=256)
    args = ap.parse_args()
    kw = {"n": args.n} if args.n else {}
    tr = TransientEHL(PAIR, OIL_055, ROUGH, **kw)
    tr.start_steady(4e4, 0.01, 2.0, 3.0)
    out = {
        "benchmark": "transient_load_step",
        "grid": args.n or "automatic",
        "max_substeps": tr.max_substeps,
    }
    for label, w in (("up", 4e6), ("down", 4e4)):
        t0 = time.perf_counter()
        with counted_advances() as solves:
            r = tr.step(1e-4, w, 0.01, 2.0, 3.0)
        out[label] = {
            "load_N_per_m": w,
            "wall_s": round(time.perf_counter() - t0, 2),
            "solves": len(solves),
            "failed_solves": solves.count(False),
            "converged": bool(r.converged),
            "central_film_m": r.central_film,
            "min_film_m": r.min_film,
        }
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()

"""Mixed-EHL solver timings (prints JSON). Not a timed test.

    python benchmarks/bench_ehl.py

* steady solve at Moes M = 20, L = 10 (Roelands + Dowson–Higginson) on the default grid;
* one warm-started transient step (conditions changed by 1 %);
* steady-solve time versus grid size N = 256 … 4096 (fixed N, same case).
BLAS is limited to one thread (the solver's matrices are small; that is also how the
cycle study runs its workers). Times are the best of several runs, wall clock and CPU
(``*_cpu_s``: the process's CPU time, steadier than the wall on a shared machine). The
script uses only the public API, so it times other versions of tribodyn alike.
"""

import json
import math
import platform
import time

import numpy as np
from threadpoolctl import threadpool_limits

from tribodyn import Body, Lubricant, Material, Roughness, TransientEHL, solve_ehl

STEEL = Material(210e9, 0.3)
PAIR = (Body(STEEL), Body(STEEL))
E_PRIME = 210e9 / 0.91
R, MU0, G = 0.01, 0.04, 5000.0


def conditions(M, L):
    U = (L / G) ** 4 / 2
    W = M * math.sqrt(2 * U)
    return W * E_PRIME * R, U * E_PRIME * R / MU0


CPU = {}


def best_of(fn, repeat, key=None):
    times, cpus = [], []
    for _ in range(repeat):
        t0, c0 = time.perf_counter(), time.process_time()
        out = fn()
        times.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
    if key:
        CPU[key] = min(cpus)
    return min(times), out


def main():
    threadpool_limits(1)
    oil = Lubricant(MU0, G / E_PRIME)
    w, u = conditions(20, 10)
    out = {"python": platform.python_version(), "numpy": np.__version__, "blas_threads": 1}
    t, r = best_of(
        lambda: solve_ehl(w, R, u, 1.0, PAIR, oil), 5, "steady_M20_L10_default_grid_cpu_s"
    )
    out["steady_M20_L10_default_grid_s"] = t
    out["steady_M20_L10_default_grid_n"] = len(r.x)
    out["steady_M20_L10_newton_iterations"] = r.iterations
    rough = Roughness(8.3e9, 0.408e-6, 0.669e-6)
    t, r = best_of(
        lambda: solve_ehl(w, R, u, 1.0, PAIR, oil, rough), 3, "steady_M20_L10_with_roughness_cpu_s"
    )
    out["steady_M20_L10_with_roughness_s"] = t

    tr = TransientEHL(PAIR, oil)
    tr.start_steady(w, R, u, 1.0)
    b = math.sqrt(8 * w * R / (math.pi * E_PRIME))
    dt = b / u
    for _ in range(5):  # settle the history (BDF2)
        tr.step(dt, w, R, u, 1.0)
    steps, cpus = [], []
    for k in range(20):
        t0, c0 = time.perf_counter(), time.process_time()
        r = tr.step(dt, w * (1 + 0.01 * math.sin(0.3 * k)), R, u, 1.0)
        steps.append(time.perf_counter() - t0)
        cpus.append(time.process_time() - c0)
    out["transient_warm_step_median_cpu_s"] = float(np.median(cpus))
    out["transient_warm_step_median_s"] = float(np.median(steps))
    out["transient_warm_step_min_s"] = float(np.min(steps))
    out["transient_warm_step_iterations_last"] = r.iterations

    scaling = {}
    for n in (256, 512, 1024, 2048, 4096):
        t, r = best_of(lambda: solve_ehl(w, R, u, 1.0, PAIR, oil, n=n), 2 if n < 4096 else 1, "n")
        scaling[str(n)] = {
            "seconds": t,
            "cpu_seconds": CPU["n"],
            "iterations": r.iterations,
            "central_film_m": r.central_film,
        }
    out["steady_time_vs_n"] = scaling
    ns = np.array([int(k) for k in scaling])
    ts = np.array([v["seconds"] for v in scaling.values()])
    out["steady_time_growth_exponent_1024_4096"] = float(
        np.log(ts[-1] / ts[2]) / np.log(ns[-1] / ns[2])
    )
    CPU.pop("n", None)
    out.update(CPU)
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()

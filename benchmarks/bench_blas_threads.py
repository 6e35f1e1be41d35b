"""One steady EHL solve under three BLAS thread settings (prints one line per run).

    python benchmarks/bench_blas_threads.py [--repeat 7] [--rounds 2]

The paper case's uncoated set at w = 40 kN/m, R = 10 mm, u_e = 2 m/s, u_s = 0.5 m/s
(automatic grid), timed ``--repeat`` times after a warm-up solve, in a fresh interpreter
per setting:

- ``env1``: ``OPENBLAS_NUM_THREADS=1`` (and OpenMP/MKL) set before numpy loads;
- ``default``: as many threads as CPUs (the variables set to the CPU count);
- ``limit``: as ``default``, with a runtime limit of one thread
  (``threadpoolctl.threadpool_limits(1)``) around the solves.

Also the cost of entering and leaving the runtime limit once.
"""

import argparse
import os
import subprocess
import sys
import time

VARS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def child(mode: str, repeat: int) -> None:
    from threadpoolctl import threadpool_info, threadpool_limits

    from tribodyn import solve_ehl
    from tribodyn.config import Case

    case = Case()
    s = case.surface_sets()[0]
    lub, opts = case.lubricant(), case.ehl_options(s)

    def solve():
        return solve_ehl(4e4, 0.01, 2.0, 0.5, s.bodies, lub, s.roughness, options=opts)

    solve()  # compiles the kernels
    times = []
    with threadpool_limits(1 if mode == "limit" else None):
        threads = [i.get("num_threads") for i in threadpool_info()]
        for _ in range(repeat):
            t = time.perf_counter()
            r = solve()
            times.append(time.perf_counter() - t)
    times.sort()
    print(
        f"{mode:8s} threads={threads} min={times[0]:.3f} s median={times[len(times) // 2]:.3f} s "
        f"converged={r.converged} h_c={r.central_film:.6e} m"
    )
    if mode == "limit":
        t = time.perf_counter()
        for _ in range(100):
            with threadpool_limits(1):
                pass
        print(f"threadpool_limits enter/exit: {(time.perf_counter() - t) * 10:.2f} ms")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--rounds", type=int, default=2)
    ap.add_argument("--child", default=None)
    a = ap.parse_args()
    if a.child:
        child(a.child, a.repeat)
        return
    ncpu = str(os.cpu_count() or 1)
    for _ in range(a.rounds):
        for mode in ("env1", "default", "limit"):
            env = dict(os.environ)
            env.update({v: "1" if mode == "env1" else ncpu for v in VARS})
            cmd = [sys.executable, __file__, "--child", mode, "--repeat", str(a.repeat)]
            subprocess.run(cmd, env=env, check=True)


if __name__ == "__main__":
    main()

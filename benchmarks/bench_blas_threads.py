"""One steady EHL solve under three BLAS thread settings (prints one line per run).

    python benchmarks/bench_blas_threads.py [--repeat 7] [--rounds 2]

The paper case's uncoated set at w = 40 kN/m, R = 10 mm, u_e = 2 m/s, u_s = 0.5 m/s
(automatic grid), timed ``--repeat`` times after a warm-up solve, in a fresh interpreter
per setting:

- ``env1``: ``OPENBLAS_NUM_THREADS=1`` (and OpenMP/MKL) set before numpy loads;
- ``default``: as many threads as CPUs (the variables set to the CPU count);
- ``untouched``: the variables removed, as in a plain Python script (BLAS picks its own
  thread count);
- ``limit``: as ``default``, with a runtime limit of one thread
  (``threadpoolctl.threadpool_limits(1)``) around the solves.

``solve_ehl`` limits itself to one thread inside the call, so ``default`` and
``untouched`` should take the ``env1`` time. Each line also gives the ratio of its median
to the ``env1`` median of the same round.

Also the cost of entering and leaving the runtime limit once.
"""

import argparse
import json
import os
import subprocess
import sys
import time

VARS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def child(mode: str, repeat: int) -> None:
    from threadpoolctl import threadpool_info, threadpool_limits

    from tribodyn import solve_ehl
    from tribodyn.config import load_case
    from tribodyn.config.build import build

    built = build(load_case("andreou2023"))  # the paper case, as named (not the defaults)
    s = built.surface_sets[0]
    lub, opts = built.lubricant, built.set(s.name).options

    def solve():
        return solve_ehl(4e4, 0.01, 2.0, 0.5, s.bodies, lub, s.roughness, options=opts)

    solve()  # compiles the kernels
    times = []
    with threadpool_limits(1 if mode == "limit" else None):  # None: as the environment says
        threads = [i.get("num_threads") for i in threadpool_info()]
        for _ in range(repeat):
            t = time.perf_counter()
            r = solve()
            times.append(time.perf_counter() - t)
    times.sort()
    print(
        json.dumps(
            {
                "mode": mode,
                "threads_outside_solve": threads,
                "min_s": round(times[0], 5),
                "median_s": round(times[len(times) // 2], 5),
                "converged": bool(r.converged),
                "h_c_m": r.central_film,
            }
        )
    )
    if mode == "limit":
        t = time.perf_counter()
        for _ in range(100):
            with threadpool_limits(1):
                pass
        print(json.dumps({"threadpool_limits_enter_exit_ms": (time.perf_counter() - t) * 10}))


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
        medians = {}
        for mode in ("env1", "default", "untouched", "limit"):
            env = dict(os.environ)
            for v in VARS:
                env.pop(v, None)
            if mode != "untouched":
                env.update({v: "1" if mode == "env1" else ncpu for v in VARS})
            cmd = [sys.executable, __file__, "--child", mode, "--repeat", str(a.repeat)]
            out = subprocess.run(cmd, env=env, check=True, capture_output=True, text=True)
            for line in out.stdout.splitlines():
                rec = json.loads(line)
                if "median_s" in rec:
                    medians[mode] = rec["median_s"]
                    rec["ratio_to_env1"] = round(rec["median_s"] / medians["env1"], 3)
                print(json.dumps(rec))


if __name__ == "__main__":
    main()

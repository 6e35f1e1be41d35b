"""Dry coated line contact and DC-FFT timings (prints JSON). Not a timed test.

python benchmarks/bench_dry_contact.py
"""

import json
import platform
import time

import numpy as np

from tribodyn import Body, Coating, DeformationOperator, Material, solve_dry_contact


def best_of(fn, repeat):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main():
    steel = Material(210e9, 0.3)
    bodies = (Body(steel), Body(steel, Coating(175e9, 0.3, 4e-6)))
    t0 = time.perf_counter()
    solve_dry_contact(1e5, 0.01, bodies, n=64)  # builds the coating kernel table
    out = {
        "python": platform.python_version(),
        "numpy": np.__version__,
        "coated_kernel_table_build_s": time.perf_counter() - t0,
    }
    for n in (1024, 4096):
        res = solve_dry_contact(1e5, 0.01, bodies, n=n)
        out[f"dry_solve_N{n}_s"] = best_of(lambda: solve_dry_contact(1e5, 0.01, bodies, n=n), 5)
        out[f"dry_solve_N{n}_iterations"] = res.iterations
    rng = np.random.default_rng(0)
    for n in (4096, 65536):
        op = DeformationOperator(bodies, 1e-7, n)
        p = rng.random(n)
        out[f"dcfft_deformation_N{n}_s"] = best_of(lambda: op(p), 50)
        out[f"influence_coefficients_N{n}_s"] = best_of(
            lambda: DeformationOperator(bodies, 1e-7, n), 5
        )
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()

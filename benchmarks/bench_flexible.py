"""Benchmark: flexible (Craig–Bampton bodies, camshaft compliance) vs lumped valvetrain
dynamics, two engine cycles at 3000 rpm, explicit tribology of the bundled
andreou2023_flexible case and its lumped companion (same masses, rate, preload and static
compliances). Runs alternate; prints JSON with the medians, their ratio and the key
numbers of both models. Not a timed test.

    python benchmarks/bench_flexible.py [repeats]
"""

from __future__ import annotations

import json
import statistics
import sys
import time

from threadpoolctl import threadpool_limits

from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.valvetrain import simulate_valvetrain


def main(repeats: int = 3) -> dict:
    threadpool_limits(1)
    case = load_case("andreou2023_flexible")
    built = build(case)
    trib = built.analytic_tribology(built.surface_sets[0].name)
    models = {"lumped": built.lumped, "flexible": built.valvetrain}
    kw = dict(tribology=trib, **built.dynamics_options)
    times = {k: [] for k in models}
    res = {}
    for _ in range(repeats):
        for name, p in models.items():
            t0 = time.perf_counter()
            res[name] = simulate_valvetrain(built.cam, p, **kw)
            times[name].append(time.perf_counter() - t0)
    med = {k: statistics.median(v) for k, v in times.items()}
    keys = (
        "peak_contact_force_N",
        "min_contact_force_in_event_N",
        "seating_velocity_m_s",
        "friction_energy_per_cycle_J",
        "energy_residual_rel",
    )
    return {
        "case": "andreou2023_flexible (bundled), 3000 rpm, 2 engine cycles, explicit",
        "repeats": repeats,
        "times_s": times,
        "median_s": med,
        "ratio_flexible_to_lumped": med["flexible"] / med["lumped"],
        "nfev": {k: r.stats.get("nfev") for k, r in res.items()},
        "summary": {k: {q: r.summary().get(q) for q in keys} for k, r in res.items()},
    }


if __name__ == "__main__":
    print(json.dumps(main(int(sys.argv[1]) if len(sys.argv) > 1 else 3), indent=2, default=float))

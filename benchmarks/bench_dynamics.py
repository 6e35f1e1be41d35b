"""Benchmark: two engine cycles of the single valvetrain at 3000 rpm (paper case), explicit
and implicit. Prints JSON. Not a timed test.

    python benchmarks/bench_dynamics.py

Explicit: the analytic tribology of the case (film formula + Greenwood–Tripp + viscous
friction), no film compliance. Implicit: the numerical transient EHL of the first surface
set along the cycle, its film in series with the contact stiffness and its friction,
coupled to the dynamics by under-relaxed waveform iteration
(:mod:`tribodyn.cycle.coupling`); the timing includes the EHL runs.
"""

from __future__ import annotations

import json
import time

import numpy as np
from threadpoolctl import threadpool_limits

from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.cycle.driver import CycleInputs
from tribodyn.valvetrain import compare_results, simulate_valvetrain
from tribodyn.workflow.cycle import _coupling_task


def main() -> dict:
    threadpool_limits(1)
    case = load_case("andreou2023")
    built = build(case)
    ref = built.surface_sets[0]
    args = (built.cam, built.valvetrain)
    kw = dict(tribology=built.analytic_tribology(ref.name), **built.dynamics_options)
    simulate_valvetrain(*args, **kw)  # warm-up
    t0 = time.perf_counter()
    ex = simulate_valvetrain(*args, **kw)
    out = {
        "case": "andreou2023 (bundled), 3000 rpm, 2 engine cycles",
        "explicit_s": time.perf_counter() - t0,
        "explicit_solver_s": ex.stats.get("wall_time_s"),
        "explicit_nfev": ex.stats.get("nfev"),
        "explicit_summary": ex.summary(),
    }
    inputs = CycleInputs.from_dynamics(ex, case.numerics.crank_step_deg, case.width)
    t0 = time.perf_counter()
    _first, coupling, _stress = _coupling_task(built, ref.name, ex, inputs)
    out["implicit_s"] = time.perf_counter() - t0
    out["implicit_converged"] = coupling.converged
    out["implicit_message"] = coupling.message
    out["implicit_history"] = [vars(h) for h in coupling.history]
    im = coupling.implicit
    if im is not None:
        out["implicit_vs_explicit"] = compare_results(ex, im)
        d = np.abs(np.interp(ex.crank_angle, im.crank_angle, im.contact_force) - ex.contact_force)
        out["max_contact_force_diff_pct_of_peak"] = float(d.max() / ex.contact_force.max() * 100)
    return out


if __name__ == "__main__":
    print(json.dumps(main(), indent=2, default=float))

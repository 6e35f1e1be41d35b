"""Benchmark: time response of the flexible valvetrain vs the number k of fixed-interface
modes kept in every body (Craig–Bampton), bundled andreou2023_flexible case (its final
ASSUMED geometry, camshaft compliance, explicit tribology), 3000 rpm, two engine cycles.
The reference keeps all modes of the FE meshes. Prints JSON: per k the model size, the
kept spring modes [Hz], the contact force's difference to the reference (max and RMS over
the presented cycle, % of the peak), peak and minimum contact force, seating velocity and
the solver time (one run each). Not a timed test.

    python benchmarks/bench_flexible_modes.py [k ...]
"""

from __future__ import annotations

import json
import sys
import time
from dataclasses import replace

import numpy as np
from threadpoolctl import threadpool_limits

from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.valvetrain import simulate_valvetrain
from tribodyn.valvetrain.flexible_model import FlexibleValvetrainModel


def with_modes(flex, k):
    """The same valvetrain with k fixed-interface modes in every FE body (None: all)."""
    return replace(
        flex,
        valve=replace(flex.valve, modes=k, cutoff=None),
        tappet=replace(flex.tappet, modes=k, cutoff=None),
        spring=replace(flex.spring, modes=k, cutoff=None),
    )


def main(ks=(0, 1, 2, 3, 4, 6, None)) -> dict:
    threadpool_limits(1)
    case = load_case("andreou2023_flexible")
    built = build(case)
    cam = built.cam
    trib = built.analytic_tribology(built.surface_sets[0].name)
    opts = built.dynamics_options
    base = built.valvetrain
    runs = {"case (5 kHz cut-off)": base} | {
        ("all" if k is None else str(k)): with_modes(base, k) for k in ks
    }
    res, rows = {}, {}
    for name, flex in runs.items():
        t0 = time.perf_counter()
        r = simulate_valvetrain(cam, flex, tribology=trib, **opts)
        wall = time.perf_counter() - t0
        model = FlexibleValvetrainModel(cam, flex, r.cam_speed, trib)
        res[name] = r
        s = r.summary()
        rows[name] = {
            "dofs": model.n,
            "spring_modes_Hz": model.bodies["spring"].modal_frequencies.round(0).tolist(),
            "peak_contact_force_N": s.get("peak_contact_force_N"),
            "min_contact_force_in_event_N": s.get("min_contact_force_in_event_N"),
            "seating_velocity_m_s": s.get("seating_velocity_m_s"),
            "time_s": wall,
            "converged": r.converged,
        }
    ref = res["all"].contact_force
    peak = float(ref.max())
    for name, r in res.items():
        d = r.contact_force - ref
        rows[name]["max_diff_pct_of_peak"] = float(100 * np.abs(d).max() / peak)
        rows[name]["rms_diff_pct_of_peak"] = float(100 * np.sqrt(np.mean(d * d)) / peak)
    return {
        "case": "andreou2023_flexible (bundled), 3000 rpm, 2 engine cycles, explicit",
        "modes_per_body": rows,
    }


if __name__ == "__main__":
    ks = tuple(None if a == "all" else int(a) for a in sys.argv[1:]) or (0, 1, 2, 3, 4, 6, None)
    print(json.dumps(main(ks), indent=2, default=float))

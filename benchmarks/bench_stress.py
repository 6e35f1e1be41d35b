"""Cost of the subsurface stresses along a cycle against the set's EHL pass (prints JSON).
Not a timed test.

    python benchmarks/bench_stress.py [CASE.toml] [--set NAME] [--crank-step DEG] [--repeat N]

Runs the explicit valvetrain dynamics, one transient-EHL pass along the cycle for the
surface set (default: the first coated set), then the stresses of the cam and the tappet
at every loaded sample as the study computes them (``stress_for_set`` with the set's
strengths, as ``workflow.cycle`` calls it), and reports CPU seconds of both, their ratio
(target ≤ 0.20), the cycle maxima with crank angles, and the safety factors. With
``--repeat N`` the stresses are computed N times on the same pass: the first call's
times (which include loading the compiled kernels) and the median CPU of all N.
Run it with one BLAS thread per process (importing tribodyn first sets it).
"""

import argparse
import json
import statistics
import time

import tribodyn  # noqa: F401  (one BLAS thread, before numpy loads)
from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.cycle.driver import CycleInputs, ehl_for_set
from tribodyn.valvetrain.dynamics import simulate_valvetrain
from tribodyn.workflow.postprocess import surface_roles
from tribodyn.workflow.stress_study import stress_for_set


def timed(fn):
    w, c = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - w, time.process_time() - c


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case", nargs="?", default=None)
    ap.add_argument("--set", default=None)
    ap.add_argument("--crank-step", type=float, default=None)
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args()
    case = load_case(args.case)
    built = build(case)
    sets = built.surface_sets
    if args.set:
        s = built.set(args.set).surface
    else:
        s = next((x for x in sets if x.coating is not None), sets[0])
    ref = built.set(surface_roles(case)["reference"]).surface
    dyn = simulate_valvetrain(
        built.cam,
        built.valvetrain,
        tribology=built.analytic_tribology(ref.name),
        **built.dynamics_options,
    )
    step = args.crank_step or case.numerics.crank_step_deg
    # the EHL's speeds as the study uses them (workflow.cycle)
    inputs = CycleInputs.from_dynamics(dyn, step, case.width).with_rotation(built.tappet_rotation)
    r, w_ehl, c_ehl = timed(lambda: ehl_for_set(case, s, inputs))
    strengths = built.set(s.name).strengths
    runs = [
        timed(lambda: stress_for_set(built, s, r, inputs, strengths=strengths))
        for _ in range(max(1, args.repeat))
    ]
    st, w_st, c_st = runs[0]
    out = {
        "set": s.name,
        "crank_step_deg": step,
        "loaded_samples": int(r.loaded.sum()),
        "stress_samples": st.evaluated,
        "ehl_pass": {"wall_s": w_ehl, "cpu_s": c_ehl},
        "stress": {"wall_s": w_st, "cpu_s": c_st},
        "stress_repeats": len(runs),
        "stress_cpu_s_median": statistics.median(c for _, _, c in runs),
        "cpu_ratio_stress_to_ehl": c_st / c_ehl,
        "target_ratio": 0.20,
        "maxima": st.maxima,
        "safety_factors": st.safety_factors,
    }
    print(json.dumps(out, indent=2, default=float))


if __name__ == "__main__":
    main()

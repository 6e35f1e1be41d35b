"""One transient-EHL pass along the cam cycle, with the solver's work counted (prints JSON).

    python benchmarks/bench_ehl_pass.py [--set NAME] [--repeat N] [--case CASE.toml]

The explicit valvetrain dynamics of the case are computed once; then one surface set's
EHL pass (``ehl_for_set``, default settings) is run once to warm the compiled kernels
and ``--repeat`` times timed, under one BLAS thread. Reported per pass: CPU and wall
seconds, loaded samples, the Newton iterations of every solve (steady starts, rejected
and sub-steps included; the results' ``iterations`` count only the last solve of each
sample), dense LU factorisations, GMRES calls (a fresh factorisation's own Newton step
included where the solver solves it by GMRES) and their Krylov iterations, and residual
evaluations. The counters wrap public functions only, so the script times other
versions of tribodyn alike. On a shared machine compare CPU seconds, alternating the
versions (see docs/convergence.md).
"""

import argparse
import json
import time

import numpy as np

import tribodyn  # noqa: F401  (one BLAS thread, before numpy loads)
from tribodyn._threads import single_blas_thread
from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.contact.ehl import reynolds, steady, transient
from tribodyn.cycle.driver import CycleInputs, ehl_for_set
from tribodyn.valvetrain.dynamics import simulate_valvetrain
from tribodyn.workflow.postprocess import surface_roles

COUNTS = {"newton_iterations": 0, "lu": 0, "gmres": 0, "krylov": 0, "evaluations": 0}


def count_work():
    """Wrap the solver's entry points with counters (COUNTS)."""
    from scipy import linalg

    lu_factor = linalg.lu_factor

    def counted_lu(*a, **k):
        COUNTS["lu"] += 1
        return lu_factor(*a, **k)

    linalg.lu_factor = counted_lu
    gmres_lu = reynolds.Linearization.gmres_lu

    def counted_gmres(self, *a):
        out = gmres_lu(self, *a)
        if out is not None:
            COUNTS["gmres"] += 1
            COUNTS["krylov"] += out[1]
        return out

    reynolds.Linearization.gmres_lu = counted_gmres
    evaluate = reynolds.ReynoldsSystem.evaluate

    def counted_evaluate(self, *a):
        COUNTS["evaluations"] += 1
        return evaluate(self, *a)

    reynolds.ReynoldsSystem.evaluate = counted_evaluate
    for module in (transient, steady):
        newton = module.newton

        def counted_newton(*a, _newton=newton, **k):
            out = _newton(*a, **k)
            COUNTS["newton_iterations"] += out.iterations
            return out

        module.newton = counted_newton


def pass_setup(case_arg, set_name):
    """(case, built case, the surface set to march, explicit dynamics, cycle inputs): the
    case's dynamics with the reference set's tribology, once (call under one BLAS
    thread)."""
    case = load_case(case_arg)
    built = build(case)
    ref = built.set(surface_roles(case)["reference"]).surface
    s = built.set(set_name).surface if set_name else ref
    dyn = simulate_valvetrain(
        built.cam,
        built.valvetrain,
        tribology=built.analytic_tribology(ref.name),
        **built.dynamics_options,
    )
    inputs = CycleInputs.from_dynamics(dyn, case.numerics.crank_step_deg, case.width)
    return case, built, s, dyn, inputs


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--case", default=None)
    ap.add_argument("--set", default=None, help="surface set (default: the reference set)")
    ap.add_argument("--repeat", type=int, default=1)
    args = ap.parse_args()
    with single_blas_thread():
        case, _, s, _, inputs = pass_setup(args.case, args.set)
        count_work()
        ehl_for_set(case, s, inputs)  # compile and warm
        runs = []
        for _ in range(args.repeat):
            for k in COUNTS:
                COUNTS[k] = 0
            w, c = time.perf_counter(), time.process_time()
            r = ehl_for_set(case, s, inputs)
            runs.append(
                {
                    "cpu_s": time.process_time() - c,
                    "wall_s": time.perf_counter() - w,
                    "loaded_samples": int(r.loaded.sum()),
                    "failed_steps": len(r.failures),
                    **COUNTS,
                }
            )
    out = {
        "set": s.name,
        "cpu_s_median": float(np.median([x["cpu_s"] for x in runs])),
        "runs": runs,
    }
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()

"""Bounds on the cost of one transient-EHL pass (prints JSON). An analysis, not a timed
test: what the grid's node count and the Newton start can still save.

    python benchmarks/ehl_pass_bounds.py [--case CASE.toml] [--set NAME]
                                         [--nodes 192 256 320 384 768] [--companion NAME]

1. ``nodes``: the pass on grids of each node count (``numerics.n``), CPU seconds (median
   of two after a warm-up) with the solver's counts (as ``bench_ehl_pass.py``), and its
   friction energy per cycle and h_c, h_min at the six representative points relative to
   the largest node count given.
2. ``perfect_start``: the default pass run once recording every time level's converged
   solution (total pressure and h₀), then again with each level started from the
   recorded solution of the same time and step (where the grid's nodes agree to 1e-8):
   the cost left when the Newton start is exact, a bound on what any predictor can save.
3. ``companion_start`` (``--companion NAME``): that set's pass, each level started from
   its own linear predictor plus the reference set's prediction error at the same level
   (q̂ + q_ref − q̂_ref): sharing work between sets that see the same dynamics.

Steps 2 and 3 hook the march's private ``_predict`` and ``_solve``; they measure the
solver, they are not an option of it. Outputs of the hooked passes differ from the
default's only by the Newton tolerance (relative differences of h_c, h_min and friction
power are reported).
"""

import argparse
import json
import time

import numpy as np

import tribodyn  # noqa: F401  (one BLAS thread, before numpy loads)
from bench_ehl_pass import COUNTS, count_work, pass_setup
from tribodyn._threads import single_blas_thread
from tribodyn.contact.ehl import transient
from tribodyn.cycle.driver import ehl_for_set
from tribodyn.workflow.postprocess import representative_points


class StartHook:
    """Records each time level's prediction and solution (dimensional), or replaces the
    prediction from a record (``mode``: None, "record", "perfect", "companion")."""

    def __init__(self):
        self.mode, self.record, self.guide, self.hits = None, {}, {}, 0
        self._predict, self._solve = transient.TransientEHL._predict, transient.TransientEHL._solve
        hook = self

        def predict(stepper, sysm, dt):
            st = hook._predict(stepper, sysm, dt)
            key = (round((stepper.time + dt) * 1e9), round(dt * 1e12))
            stepper._bound_key = (key, sysm.g.x, st.Q * sysm.p_ref, st.H0 * sysm.h_ref)
            g = hook.guide.get(key) if hook.mode in ("perfect", "companion") else None
            if g is None or g[0].shape != sysm.g.x.shape:
                return st
            if not np.allclose(g[0], sysm.g.x, rtol=1e-8, atol=0.0):
                return st
            q, h0 = g[2], g[4]  # the recorded solution …
            if hook.mode == "companion":  # … or this set's prediction corrected by it
                q, h0 = st.Q * sysm.p_ref + (g[2] - g[1]), st.H0 * sysm.h_ref + (g[4] - g[3])
            st.Q, st.H0, st.cav = q / sysm.p_ref, h0 / sysm.h_ref, None
            st.KQ = sysm.deform(st.Q) if sysm.elastic else None
            hook.hits += 1
            return st

        def solve(stepper, sysm, ctx, st, dt, lu):
            sol = hook._solve(stepper, sysm, ctx, st, dt, lu)
            if hook.mode == "record":
                key, x, q_pred, h0_pred = stepper._bound_key
                s = sol.state
                hook.record[key] = (x, q_pred, s.Q * sysm.p_ref, h0_pred, s.H0 * sysm.h_ref)
            return sol

        transient.TransientEHL._predict = predict
        transient.TransientEHL._solve = solve


#: timed passes per row (after a warm-up)
REPEAT = 2


def timed_pass(case, s, inputs, repeat=REPEAT):
    """(result of the last run, median CPU seconds, counts of the last run)."""
    cpu = []
    for _ in range(repeat):
        for k in COUNTS:
            COUNTS[k] = 0
        c = time.process_time()
        r = ehl_for_set(case, s, inputs)
        cpu.append(time.process_time() - c)
    return r, float(np.median(cpu)), dict(COUNTS)


def outputs(r, points):
    """Friction energy per cycle [J] and h_c, h_min at the points [m]."""
    dtheta = np.gradient(r.crank_angle)
    e = float(np.nansum(np.where(r.loaded, r.friction_power, 0.0) * dtheta))
    return e, r.central_film[points], r.min_film[points]


def rel(a, b):
    return float(np.max(np.abs(np.asarray(a) / np.asarray(b) - 1.0)))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--case", default=None)
    ap.add_argument("--set", default=None, help="surface set (default: the reference set)")
    ap.add_argument("--nodes", type=int, nargs="*", default=[192, 256, 320, 384, 768])
    ap.add_argument("--companion", default=None, help="a second set started from the first")
    args = ap.parse_args()
    with single_blas_thread():
        case, built, s, dyn, inputs = pass_setup(args.case, args.set)
        out = {"set": s.name, "nodes": [], "perfect_start": None, "companion_start": None}
        count_work()
        rows = []
        for n in sorted(args.nodes):
            c_n = case.updated({"numerics.n": n})
            ehl_for_set(c_n, s, inputs)  # warm
            r, cpu, counts = timed_pass(c_n, s, inputs)
            rows.append((n, r, cpu, counts))
        finest = rows[-1][1]
        points = representative_points(inputs, dyn, finest.loaded)
        e_f, hc_f, hm_f = outputs(finest, points)
        for n, r, cpu, counts in rows:
            e, hc, hm = outputs(r, points)
            out["nodes"].append(
                {
                    "n": n,
                    "cpu_s": cpu,
                    **counts,
                    "failed_steps": len(r.failures),
                    "friction_energy_rel": e / e_f - 1.0,
                    "h_c_points_max_rel": rel(hc, hc_f),
                    "h_min_points_max_rel": rel(hm, hm_f),
                }
            )
        hook = StartHook()
        hook.mode = "record"
        ehl_for_set(case, s, inputs)  # warm and record
        hook.mode, hook.guide = None, dict(hook.record)
        base, cpu0, counts0 = timed_pass(case, s, inputs)
        out["default"] = {"cpu_s": cpu0, **counts0}
        hook.mode, hook.hits = "perfect", 0
        r, cpu, counts = timed_pass(case, s, inputs)
        out["perfect_start"] = {
            "cpu_s": cpu,
            "cpu_ratio": cpu / cpu0,
            **counts,
            "levels_started_exactly": hook.hits // REPEAT,
            "levels": len(hook.guide),
            **_moved(r, base),
        }
        if args.companion:
            other = built.set(args.companion).surface
            hook.mode = None
            plain, cpu_p, counts_p = timed_pass(case, other, inputs)
            hook.mode, hook.hits = "companion", 0
            r, cpu, counts = timed_pass(case, other, inputs)
            out["companion_start"] = {
                "set": other.name,
                "own_start": {"cpu_s": cpu_p, **counts_p},
                "cpu_s": cpu,
                "cpu_ratio": cpu / cpu_p,
                **counts,
                "levels_corrected": hook.hits // REPEAT,
                **_moved(r, plain),
            }
    print(json.dumps(out, indent=2))


def _moved(r, base) -> dict:
    """The largest relative changes of a hooked pass's outputs from the default's."""
    m = base.loaded & r.loaded
    return {
        f"{k}_moved_max_rel": rel(getattr(r, k)[m], getattr(base, k)[m])
        for k in ("central_film", "min_film", "friction_power")
    }


if __name__ == "__main__":
    main()

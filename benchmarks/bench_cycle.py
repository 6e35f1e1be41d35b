"""Cycle-study timings and accuracy (prints JSON). Not a timed test.

    python benchmarks/bench_cycle.py [CASE.toml] [--legacy] [--reference DIR ...]
                                     [--skip-study] [--workers N]

Phases, each with wall and CPU seconds: the explicit valvetrain dynamics; one transient-EHL
pass along the cycle per surface set (loaded steps, Newton iterations, failed steps); the
coupling chain of the reference set (implicit dynamics runs, EHL re-passes, iterations);
the whole study (``run_cycle_study`` with its default process pool). The implicit
dynamics run once with the compiled lumped model and once with the Python right-hand
side under solve_ivp (``implicit_dynamics``).

``--legacy`` repeats the reference set's EHL pass in the same process with the grid
settings of tribodyn 0.1 (spacing s/46 over the domain, 512 to 4096 nodes, a new grid
whenever the domain changes by 2 %) and reports the speed-up of the default settings.

``--reference DIR`` compares the whole study with the results folder of another run
(``results.nc`` and ``summary.json`` as written by ``tribodyn run``: a fine-step run, or
another version's): friction energy per cycle, h_c and h_min at the six representative
points, the event-mean h_c, the boundary-friction reductions and the implicit-vs-explicit
metrics, each as a relative difference (reductions in percentage points).

Run it with one BLAS thread per process (``OPENBLAS_NUM_THREADS=1``; importing tribodyn
before numpy sets it). On a shared machine compare CPU seconds and ratios, not walls.
"""

import argparse
import json
import math
import os
import sys
import time
from pathlib import Path

import numpy as np

import tribodyn  # noqa: F401  (one BLAS thread, before numpy loads)
from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.cycle.coupling import run_coupling
from tribodyn.cycle.driver import CycleInputs, ehl_for_set
from tribodyn.physics.materials import reduced_modulus
from tribodyn.valvetrain import dynamics as dynamics_module
from tribodyn.valvetrain.dynamics import simulate_valvetrain
from tribodyn.workflow.cycle import run_cycle_study
from tribodyn.workflow.postprocess import surface_roles

# the earlier linearised film-table law, kept beside the tests
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from film_table_law import ehl_tribology


def _boundary_change(d):
    """Change of ∫F_b dt against the reference set [%] (negative = less); a summary
    written before the key was renamed stores the reduction (positive = less)."""
    if d.get("boundary_friction_cycle_integral_change_pct") is not None:
        return d["boundary_friction_cycle_integral_change_pct"]
    old = d.get("boundary_friction_reduction_vs_uncoated_pct")
    return None if old is None else -old


def timed(fn):
    w, c = time.perf_counter(), time.process_time()
    out = fn()
    return out, time.perf_counter() - w, time.process_time() - c


def pass_stats(r, wall, cpu):
    return {
        "wall_s": wall,
        "cpu_s": cpu,
        "loaded_steps": int(r.loaded.sum()),
        "newton_iterations": int(r.iterations.sum()),
        "failed_steps": len(r.failures),
        "friction_energy_proxy_J": None,
    }


def legacy_grid():
    """Context: tribodyn 0.1's automatic grid (s/46, 512…4096 nodes, multiples of 128) and
    its transient grid rule (new grid when the domain changes by 2 %)."""
    import contextlib

    import tribodyn.contact.ehl.grid as grid
    import tribodyn.contact.ehl.transient as tr

    def nodes_01(length, s):
        n = 128 * math.ceil(46.0 * length / s / 128.0)
        return int(min(4096, max(512, n)))

    def same_as(g, lay, direction, slack):
        """0.1's rule: same node count and orientation, extents within 2 %."""
        lo, hi = grid._extent(lay, direction)
        return (
            g.n == lay.n
            and g.direction == direction
            and abs(lo * lay.a / g.x[0] - 1.0) < 0.02
            and abs(hi * lay.a / g.x[-1] - 1.0) < 0.02
        )

    @contextlib.contextmanager
    def ctx():
        saved = (
            grid.auto_nodes,
            tr.GRID_SLACK,
            tr.GRID_MARGIN,
            grid.Grid.covers,
            tr.EVENT_NODES_FROM_START,
        )
        grid.auto_nodes = nodes_01
        tr.GRID_SLACK, tr.GRID_MARGIN, tr.EVENT_NODES_FROM_START = 1.0, 1.0, False
        grid.Grid.covers = same_as
        try:
            yield
        finally:
            (
                grid.auto_nodes,
                tr.GRID_SLACK,
                tr.GRID_MARGIN,
                grid.Grid.covers,
                tr.EVENT_NODES_FROM_START,
            ) = saved

    return ctx()


def energy(time_s, loaded, power):
    dt = np.gradient(time_s)
    return float(np.nansum(np.where(loaded, power, 0.0) * dt))


def accuracy(study, ref_dir: Path) -> dict:
    """Relative differences of the study's key outputs from a results folder."""
    import xarray as xr

    s_new = study.analysis.summary
    s_ref = json.loads((ref_dir / "summary.json").read_text())
    out = {"reference": ref_dir.name, "sets": {}}
    with xr.open_dataset(ref_dir / "results.nc", engine="h5netcdf") as ds:
        crank_ref = ds["ehl_crank"].values
        names = [str(v) for v in ds["surface_set"].values]
        hc_ref = ds["central_film"].values
        hm_ref = ds["min_film"].values
        ev_ref = ds["in_event"].values.astype(bool)
    crank = study.inputs.crank_angle
    common = np.intersect1d(np.round(crank, 6), np.round(crank_ref, 6))
    i_new = np.searchsorted(np.round(crank, 6), common)
    i_ref = np.searchsorted(np.round(crank_ref, 6), common)
    an = study.analysis
    pts = an.point_crank
    for s in study.sets:
        k = names.index(s.name)
        a, b = s_new["surface_sets"][s.name], s_ref["surface_sets"][s.name]
        row = {
            "friction_energy_pct": 100
            * (a["friction_energy_per_cycle_J"] / b["friction_energy_per_cycle_J"] - 1)
        }
        ch_a, ch_b = _boundary_change(a), _boundary_change(b)
        if ch_a is not None and ch_b is not None:
            row["boundary_friction_change_pp"] = ch_a - ch_b
        hc_pts, hm_pts = [], []
        for c in pts:
            j = int(np.argmin(np.abs(crank - c)))
            jr = int(np.argmin(np.abs(crank_ref - c)))
            if abs(crank_ref[jr] - c) > 1e-6:
                continue
            hc_pts.append(100 * (s.central_film[j] / hc_ref[k, jr] - 1))
            hm_pts.append(100 * (s.min_film[j] / hm_ref[k, jr] - 1))
        row["central_film_at_points_pct"] = hc_pts
        row["min_film_at_points_pct"] = hm_pts
        ev = an.in_event[i_new] & ev_ref[i_ref] & s.loaded[i_new]
        mean_new = np.nanmean(s.central_film[i_new][ev])
        mean_ref = np.nanmean(hc_ref[k, i_ref][ev])
        row["event_mean_central_film_pct"] = 100 * (mean_new / mean_ref - 1)
        out["sets"][s.name] = row
    ie_a, ie_b = s_new["implicit_vs_explicit"], s_ref["implicit_vs_explicit"]
    out["implicit_vs_explicit_pct"] = {
        key: 100 * (ie_a[key] / ie_b[key] - 1)
        for key in ("max_contact_force_diff_pct", "max_velocity_diff_pct")
        if ie_a.get(key) and ie_b.get(key)
    }
    out["coupling_converged"] = bool(ie_a.get("coupling_converged"))
    out["failed_steps"] = {n: v["failed_steps"] for n, v in s_new["surface_sets"].items()}
    return out


def implicit_dynamics(case, ref, inputs, first) -> dict:
    """One implicit dynamics run (the first coupling iteration's film law) with the
    compiled lumped model and with the Python right-hand side under solve_ivp (the path
    of tribodyn 0.1 and of non-tabulated tribology models): CPU times and the largest
    difference of the contact force."""
    built = build(case)
    lub = built.lubricant
    period = 2.0 * math.pi / case.cam_speed
    table = ehl_tribology(inputs, first, lub, reduced_modulus(ref.bodies), period)

    def run():
        return simulate_valvetrain(
            built.cam, built.valvetrain, tribology=table, **built.dynamics_options
        )

    fast, wf, cf = timed(run)
    saved = dynamics_module.compiled_model
    dynamics_module.compiled_model = lambda model: None
    try:
        slow, ws, cs = timed(run)
    finally:
        dynamics_module.compiled_model = saved
    peak = float(slow.contact_force.max())
    return {
        "compiled": {"wall_s": wf, "cpu_s": cf, **fast.stats},
        "python_solve_ivp": {"wall_s": ws, "cpu_s": cs, **slow.stats},
        "cpu_speedup": cs / cf,
        "max_force_difference_pct_of_peak": float(
            100.0 * np.abs(fast.contact_force - slow.contact_force).max() / peak
        ),
        "seating_velocity_m_s": [fast.seating_velocity, slow.seating_velocity],
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("case", nargs="?", default=None)
    ap.add_argument("--legacy", action="store_true")
    ap.add_argument("--reference", action="append", default=[])
    ap.add_argument("--skip-study", action="store_true")
    ap.add_argument("--workers", type=int, default=None)
    args = ap.parse_args()
    case = load_case(args.case)
    out = {
        "python": sys.version.split()[0],
        "cpus": os.cpu_count(),
        "blas_threads_env": os.environ.get("OPENBLAS_NUM_THREADS"),
    }
    ref_name = surface_roles(case)["reference"]
    built = build(case)
    ref = built.set(ref_name).surface

    dyn, w, c = timed(
        lambda: simulate_valvetrain(
            built.cam,
            built.valvetrain,
            tribology=built.analytic_tribology(ref.name),
            **built.dynamics_options,
        )
    )
    out["dynamics_explicit"] = {"wall_s": w, "cpu_s": c, **dyn.stats}
    inputs = CycleInputs.from_dynamics(dyn, case.numerics.crank_step_deg, case.width)

    passes, first = {}, None
    for s in built.surface_sets:
        r, w, c = timed(lambda: ehl_for_set(case, s, inputs))
        passes[s.name] = pass_stats(r, w, c)
        passes[s.name]["friction_energy_proxy_J"] = energy(inputs.time, r.loaded, r.friction_power)
        if s.name == ref_name:
            first = r
    out["ehl_pass"] = passes

    if args.legacy:
        with legacy_grid():
            r, w, c = timed(lambda: ehl_for_set(case, ref, inputs))
        leg = pass_stats(r, w, c)
        leg["friction_energy_proxy_J"] = energy(inputs.time, r.loaded, r.friction_power)
        leg["cpu_speedup_of_default"] = c / passes[ref_name]["cpu_s"]
        out["ehl_pass_legacy_grid"] = leg

    if case.numerics.implicit_coupling:
        out["implicit_dynamics"] = implicit_dynamics(case, ref, inputs, first)
        cp, w, c = timed(lambda: run_coupling(case, ref, dyn, inputs, first))
        out["coupling_chain"] = {
            "wall_s": w,
            "cpu_s": c,
            "converged": cp.converged,
            "iterations": len(cp.history),
            "message": cp.message,
            "history": [vars(h) for h in cp.history],
        }

    if not args.skip_study:
        t0 = time.perf_counter()
        study = run_cycle_study(case, workers=args.workers)
        out["study"] = {
            "wall_s": time.perf_counter() - t0,
            "runtime_s": study.runtime_s,
            "timings": study.timings,
            "set_runtime_s": {s.name: s.runtime_s for s in study.sets},
            "coupling_runtime_s": study.coupling.runtime_s,
            "warnings": study.warnings,
        }
        out["accuracy"] = [accuracy(study, Path(d)) for d in args.reference]
    print(json.dumps(out, indent=2, default=float))


if __name__ == "__main__":
    main()

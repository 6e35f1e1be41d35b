"""The default asperity law (the surface law with the typical spectrum) on the bundled
flat-tappet rig (``flat_tappet_rig``, no asperity keys) against the published checks of
docs/validation-friction.md, its sensitivity to the spectrum parameters over their
sourced ranges, and its cost against Greenwood–Tripp. Prints JSON.

    python benchmarks/default_surface_law.py checks       # before (GT) / after (default)
    python benchmarks/default_surface_law.py sensitivity  # H, λ_s, λ_L over their ranges
    python benchmarks/default_surface_law.py timing       # default vs GT, back to back

Metrics (as on the validation page): friction energy per cam revolution (summary
``friction_energy_per_cycle_J``); μ at the nose = friction/contact force averaged over
±5 crank degrees around maximum cam lift; the DLC change = energy(DLC)/energy(steel) − 1.
Nothing here is fitted: the case's inputs and the typical values are used as they are.
"""

from __future__ import annotations

import json
import sys
import time

import numpy as np

from tribodyn.config import load_case
from tribodyn.physics import typical
from tribodyn.workflow.cycle import run_cycle_study
from tribodyn.workflow.postprocess import analyse

CASE = "flat_tappet_rig"
GT = {"surface_sets[*].asperity_model": "greenwood_tripp"}


def _nose_mu(study, name: str) -> float:
    dyn, inp = study.dynamics, study.inputs
    s = study.set(name)
    nose = float(dyn.crank_angle[int(np.argmax(dyn.cam_lift))])
    # the samples' crank angles run over the simulated cycles: take the one nearest
    period = 720.0
    k = np.round((inp.crank_angle - nose) / period)
    d = inp.crank_angle - (nose + k * period)
    m = (np.abs(d) <= 5.0) & s.loaded & s.converged & (inp.contact_force > 0)
    return float(np.mean(s.friction[m] / inp.contact_force[m]))


def metrics(changes: dict | None = None) -> dict:
    """Energy per cam revolution and μ at the nose of both sets of the rig."""
    case = load_case(CASE)
    if changes:
        case = case.updated(changes)
    t0 = time.perf_counter()
    study = run_cycle_study(case, workers=1, compare_paper=False)
    wall = time.perf_counter() - t0
    summ = analyse(study).summary
    out: dict = {"wall_s": wall}
    for name, v in summ["surface_sets"].items():
        out[name] = {
            "energy_J": v["friction_energy_per_cycle_J"],
            "mu_nose": _nose_mu(study, name),
            "min_lambda": v["min_lambda"],
            "failed_steps": v["failed_steps"],
        }
    e = {n: out[n]["energy_J"] for n in ("steel", "dlc_2um")}
    out["dlc_change_pct"] = 100.0 * (e["dlc_2um"] / e["steel"] - 1.0)
    return out


def checks() -> dict:
    res: dict = {}
    for label, base in (("before_greenwood_tripp", GT), ("after_default", {})):
        r = {"cam_1000rpm_90C": metrics(base)}
        for temp in (60.0, 90.0, 120.0):
            r[f"cam_500rpm_{temp:.0f}C"] = metrics(
                {**base, "engine.speed_rpm": 1000.0, "lubricant.inlet_temperature_c": temp}
            )
        res[label] = r
    return res


def sensitivity() -> dict:
    """Each spectrum parameter at the ends of its sourced range, the others typical."""
    base = {
        "hurst": typical.SURFACE_HURST.value,
        "short_cutoff": typical.SURFACE_SHORT_CUTOFF.value,
        "long_cutoff": typical.SURFACE_LONG_CUTOFF.value,
    }
    ranges = {
        "hurst": typical.SURFACE_HURST,
        "short_cutoff": typical.SURFACE_SHORT_CUTOFF,
        "long_cutoff": typical.SURFACE_LONG_CUTOFF,
    }
    rows = [{"changed": "none (typical)", **base, **_row(base)}]
    for key, tv in ranges.items():
        for v in (tv.low, tv.high):
            spec = {**base, key: v}
            rows.append({"changed": key, **spec, **_row(spec)})
    return {"case": CASE, "conditions": "cam 1000 rpm, 90 °C", "rows": rows}


def _row(spec: dict) -> dict:
    from tribodyn.topography.synthetic import synthetic_moments

    m = metrics({"surface_sets[*].measured_surface": dict(spec)})
    mom = synthetic_moments(0.2e-6, spec["hurst"], spec["short_cutoff"], spec["long_cutoff"])
    return {
        "rms_profile_slope": float(np.sqrt(mom.m2)),
        "steel_energy_J": m["steel"]["energy_J"],
        "steel_mu_nose": m["steel"]["mu_nose"],
        "dlc_energy_J": m["dlc_2um"]["energy_J"],
        "dlc_mu_nose": m["dlc_2um"]["mu_nose"],
        "dlc_change_pct": m["dlc_change_pct"],
    }


def timing(repeats: int = 3) -> dict:
    """Wall and CPU time of the study (imports, case, dynamics, EHL of both sets,
    post-processing; no figures), default law against Greenwood–Tripp, alternating, in
    fresh single-threaded processes; with the EHL's Newton iterations. CPU time is the
    steadier measure on a shared machine."""
    import os
    import subprocess

    code = (
        "import time, json, sys\n"
        "t0, c0 = time.perf_counter(), time.process_time()\n"
        "from tribodyn.config import load_case\n"
        "from tribodyn.workflow.cycle import run_cycle_study\n"
        "from tribodyn.workflow.postprocess import analyse\n"
        "c = load_case('flat_tappet_rig')\n"
        "c = c.updated(json.loads(sys.argv[1])) if sys.argv[1] != '{}' else c\n"
        "st = run_cycle_study(c, workers=1, compare_paper=False)\n"
        "analyse(st)\n"
        "it = sum(int(s.iterations[s.loaded].sum()) for s in st.sets)\n"
        "print(json.dumps([time.perf_counter() - t0, time.process_time() - c0, it]))\n"
    )
    env = {**os.environ, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    runs: dict[str, list[list[float]]] = {"greenwood_tripp": [], "default": []}
    for _ in range(repeats):
        for label, ch in (("greenwood_tripp", GT), ("default", {})):
            r = subprocess.run(
                [sys.executable, "-c", code, json.dumps(ch)],
                capture_output=True,
                text=True,
                check=True,
                env=env,
            )
            runs[label].append(json.loads(r.stdout.strip().splitlines()[-1]))
    med = {k: np.median(np.array(v), axis=0).tolist() for k, v in runs.items()}
    gt, de = med["greenwood_tripp"], med["default"]
    return {
        "runs_wall_cpu_iterations": runs,
        "median_wall_s": {"greenwood_tripp": gt[0], "default": de[0]},
        "median_cpu_s": {"greenwood_tripp": gt[1], "default": de[1]},
        "newton_iterations": {"greenwood_tripp": gt[2], "default": de[2]},
        "ratio_wall": de[0] / gt[0],
        "ratio_cpu": de[1] / gt[1],
    }


if __name__ == "__main__":
    what = sys.argv[1] if len(sys.argv) > 1 else "checks"
    fn = {"checks": checks, "sensitivity": sensitivity, "timing": timing}[what]
    print(json.dumps(fn(), indent=1))

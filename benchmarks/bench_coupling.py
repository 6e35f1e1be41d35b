"""Implicit coupling at default settings over the cases users run (prints JSON lines).

    python benchmarks/bench_coupling.py [--only NAME ...] [--out DIR]

Cases: the paper's case at 1000–7000 rpm (step 1000), the bundled flexible case, and three
tabulated cams built here (written to ``--out``, default a temporary folder):

- ``poly``: lift L(1 − u²)³, u = 2φ/Φ − 1 over a Φ = 160° event, L = 6 mm (zero lift,
  velocity and acceleration at both ends; nose radius of curvature r_b + L − 24L/Φ² = 2.5 mm);
- ``three_arc``: base circle r_b = 15 mm, flank arcs 45 mm, nose arc 6 mm, 8 mm lift;
  the flat follower's lift is the cam's support function h(ψ) − r_b (nose: N·e + ρ_n,
  flanks: F·e + ρ_f, base: r_b), exact on tangent arcs, with steps of acceleration where
  the arcs meet (event 139°);
- ``ramps``: the acceleration-designed cam with long ramps (0.35 mm over 30°), a 180° event
  and 8 mm lift, tabulated;
- ``poly9``: lift L(1 − u²)²(1 + u²/2), L = 9 mm over a Φ = 140° event, no ramp: zero
  lift and velocity at the ends, but a step of acceleration (12 L/(Φ/2)², from the base
  circle's 15 mm the contact radius steps to 87 mm); nose radius r_b + L − 3L/(Φ/2)² =
  5.9 mm; also at 6000 rpm (``table_poly9_6000``).

For each: iterations, last change of the contact force (RMS, max), converged, the message,
the implicit-vs-explicit metrics and the wall and CPU time of the coupling chain.
"""

import argparse
import json
import math
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import tribodyn  # noqa: F401  (one BLAS thread, before numpy loads)
from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.cycle.coupling import implicit_vs_explicit_metrics, run_coupling
from tribodyn.cycle.driver import CycleInputs, ehl_for_set
from tribodyn.valvetrain.cams import AccelerationCam
from tribodyn.valvetrain.dynamics import simulate_valvetrain

R_B = 15e-3
ANGLES = np.arange(0.0, 360.0, 0.5)  # cam degrees


def poly_lift(phi_deg, lift=6e-3, event=160.0, nose=180.0):
    u = (phi_deg - nose) / (event / 2.0)
    return np.where(np.abs(u) < 1.0, lift * (1.0 - u**2) ** 3, 0.0)


def three_arc_lift(phi_deg, lift=8e-3, flank=45e-3, nose_r=6e-3, nose=180.0):
    d = R_B + lift - nose_r  # nose-arc centre on the cam axis
    # flank centre F: |F| = flank − r_b, |F − N| = flank − nose_r (internal tangency)
    a, b = flank - R_B, flank - nose_r
    x = (a**2 - b**2 + d**2) / (2.0 * d)
    y = math.sqrt(a**2 - x**2)
    psi1 = math.atan2(y, d - x)  # normal direction where flank meets nose
    psi2 = math.atan2(y, -x)  # … where flank meets base circle
    psi = np.radians(np.abs(phi_deg - nose))
    h = np.full_like(psi, R_B)
    on_nose = psi <= psi1
    on_flank = (psi > psi1) & (psi < psi2)
    h[on_nose] = d * np.cos(psi[on_nose]) + nose_r
    h[on_flank] = x * np.cos(psi[on_flank]) - y * np.sin(psi[on_flank]) + flank
    return h - R_B


def poly9_lift(phi_deg, lift=9e-3, event=140.0, nose=180.0):
    u = np.clip((phi_deg - nose) / (event / 2.0), -1.0, 1.0)
    return lift * (1.0 - u**2) ** 2 * (1.0 + 0.5 * u**2)


def ramps_lift(phi_deg):
    cam = AccelerationCam(
        max_lift=8e-3,
        event_angle=math.radians(180.0),
        ramp_height=0.35e-3,
        ramp_angle=math.radians(30.0),
    )
    return cam.lift(np.radians(phi_deg))


TABLES = {
    "poly": poly_lift,
    "three_arc": three_arc_lift,
    "ramps": ramps_lift,
    "poly9": poly9_lift,
}


def table_case(name, folder: Path):
    path = folder / f"{name}.csv"
    lift_mm = TABLES[name](ANGLES) * 1e3
    rows = "\n".join(f"{a!r},{float(v):.9f}" for a, v in zip(ANGLES.tolist(), lift_mm))
    path.write_text("angle_deg,lift_mm\n" + rows + "\n")
    return load_case("example_table_cam").updated(
        {"cam.path": str(path), "cam.max_lift": float(lift_mm.max()) * 1e-3}
    )


def cases(folder):
    for rpm in range(1000, 8000, 1000):
        yield f"paper_{rpm}", lambda rpm=rpm: load_case().updated({"engine.speed_rpm": float(rpm)})
    yield "flexible", lambda: load_case("andreou2023_flexible")
    for name in TABLES:
        yield f"table_{name}", lambda name=name: table_case(name, folder)
    yield (
        "table_poly9_6000",
        lambda: table_case("poly9", folder).updated({"engine.speed_rpm": 6000.0}),
    )


def run(case):
    built = build(case)
    s = built.set(built.surface_sets[0].name).surface
    dyn = simulate_valvetrain(
        built.cam,
        built.valvetrain,
        tribology=built.analytic_tribology(s.name),
        **built.dynamics_options,
    )
    inputs = CycleInputs.from_dynamics(dyn, case.numerics.crank_step_deg, case.width)
    first = ehl_for_set(case, s, inputs)
    w, c = time.perf_counter(), time.process_time()
    cp = run_coupling(case, s, dyn, inputs, first)
    out = {
        "peak_force_N": float(dyn.contact_force.max()),
        "iterations": len(cp.history),
        "last_rms_N": cp.history[-1].rms_force_change_N if cp.history else None,
        "last_max_N": cp.history[-1].max_force_change_N if cp.history else None,
        "converged": cp.converged,
        "history": [[h.rms_force_change_N, h.max_force_change_N] for h in cp.history],
        "message": cp.message,
        "coupling_wall_s": time.perf_counter() - w,
        "coupling_cpu_s": time.process_time() - c,
    }
    if cp.implicit is not None:
        out["metrics"] = implicit_vs_explicit_metrics(dyn, cp.implicit)
    return out


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--only", nargs="*")
    ap.add_argument("--out", type=Path)
    a = ap.parse_args(argv)
    folder = a.out or Path(tempfile.mkdtemp(prefix="bench_coupling_"))
    folder.mkdir(parents=True, exist_ok=True)
    for name, make in cases(folder):
        if a.only and name not in a.only:
            continue
        try:
            res = run(make())
        except Exception as exc:  # report and go on with the next case
            res = {"error": f"{type(exc).__name__}: {exc}"}
        print(json.dumps({"case": name, **res}), flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())

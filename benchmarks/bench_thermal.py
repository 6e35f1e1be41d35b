"""Thermal EHL timings (prints JSON). Not a timed test.

    python benchmarks/bench_thermal.py [--set wcc_4um] [--repeat 1] [--only steady|cycle]
        [--model isothermal|thermal]

* steady thermal solve beside the isothermal one (SAE 5W-30 at 40 °C, steel on steel,
  w = 200 kN/m, R = 20 mm, u_e = 2 m/s, u_s = 1 m/s), best of 3;
* the cam cycle of the bundled thermal case (``andreou2023_thermal``) for one surface
  set: the isothermal transient EHL and the thermal one over the same samples, with the
  ratio of their run times (the design bound: ≤ 5).
BLAS is limited to one thread (as in the cycle study's workers).
"""

import argparse
import json
import platform

import numpy as np
from threadpoolctl import threadpool_limits

from timing import best_of, steel_5w30
from tribodyn import solve_ehl
from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.contact.ehl.thermal import solve_thermal_ehl
from tribodyn.cycle.driver import CycleInputs, ehl_for_set, march_for_set
from tribodyn.cycle.thermal import ThermalCycle
from tribodyn.valvetrain import simulate_valvetrain


def steady():
    oil, pair, tb = steel_5w30()
    args = (2e5, 0.02, 2.0, 1.0, pair)
    t_iso, iso = best_of(lambda: solve_ehl(*args, oil.isothermal()), 3)
    t_th, th = best_of(lambda: solve_thermal_ehl(*args, oil, tb), 3)
    return {
        "isothermal_s": t_iso,
        "thermal_s": t_th,
        "ratio": t_th / t_iso,
        "isothermal_central_film_m": iso.central_film,
        "thermal_central_film_m": th.central_film,
        "thermal_max_temperature_rise_K": th.max_temperature - th.inlet_temperature,
        "thermal_iterations": th.thermal_iterations,
        "converged": bool(th.converged),
    }


def cycle(set_name, repeat, model=None):
    case = load_case("andreou2023_thermal")
    built = build(case)
    s = built.set(set_name).surface
    dyn = simulate_valvetrain(
        built.cam,
        built.valvetrain,
        tribology=built.analytic_tribology(built.surface_sets[0].name),
        **built.dynamics_options,
    )
    inp = CycleInputs.from_dynamics(dyn, case.numerics.crank_step_deg, case.width)

    def thermal_for_set(case, s, inp):
        return march_for_set(case, s, inp, ThermalCycle.for_set(case, s))

    if model == "isothermal":
        t, r = best_of(lambda: ehl_for_set(case, s, inp), repeat)
        return {"isothermal_s": t, "loaded_steps": int(r.loaded.sum())}
    if model == "thermal":
        t, r = best_of(lambda: thermal_for_set(case, s, inp), repeat)
        return {"thermal_s": t, "loaded_steps": int(r.loaded.sum())}
    t_iso, iso = best_of(lambda: ehl_for_set(case, s, inp), repeat)
    t_th, th = best_of(lambda: thermal_for_set(case, s, inp), repeat)
    L = iso.loaded
    steps = int(L.sum())

    def e(r):
        return float(np.nansum(np.where(L, r.friction_power, 0.0) * np.gradient(inp.time)))

    return {
        "case": case.name,
        "surface_set": set_name,
        "loaded_steps": steps,
        "isothermal_s": t_iso,
        "thermal_s": t_th,
        "ratio": t_th / t_iso,
        "isothermal_ms_per_step": 1e3 * t_iso / steps,
        "thermal_ms_per_step": 1e3 * t_th / steps,
        "failed_steps_isothermal": len(iso.failures),
        "failed_steps_thermal": len(th.failures),
        "friction_energy_isothermal_J": e(iso),
        "friction_energy_thermal_J": e(th),
        "max_tappet_surface_temperature_K": float(np.nanmax(th.surface_temperature_tappet)),
        "max_temperature_K": float(np.nanmax(th.max_temperature)),
        "inlet_temperature_K": th.inlet_temperature,
    }


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--set", default="wcc_4um")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--only", choices=("steady", "cycle"), default=None)
    ap.add_argument(
        "--model",
        choices=("isothermal", "thermal"),
        default=None,
        help="cycle of one model only (to time whole processes A/B)",
    )
    a = ap.parse_args()
    threadpool_limits(1)
    out = {"python": platform.python_version(), "numpy": np.__version__, "blas_threads": 1}
    if a.only in (None, "steady"):
        out["steady"] = steady()
    if a.only in (None, "cycle"):
        out["cycle"] = cycle(a.set, a.repeat, a.model)
    print(json.dumps(out, indent=2))


if __name__ == "__main__":
    main()

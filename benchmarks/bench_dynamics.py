"""Benchmark: two engine cycles of the single valvetrain at 3000 rpm, explicit and implicit.

Explicit: the default analytic tribology (film formula + Greenwood–Tripp + viscous
friction), no film compliance. Implicit: the same friction plus a film in series with the
contact stiffness, h(t, F) = h_k(t) + c_k(t)(F − F_k(t)), linearised about the previous
run's contact force and iterated twice (waveform relaxation). Here h_k, c_k come from the
Moes central-film formula, a stand-in for the transient numerical EHL that supplies them in
the real coupling: the timing measures the dynamics with the implicit contact law, not an
EHL solve. Two variants: compliance only (h_k = 0) and full film. Prints JSON.
"""

from __future__ import annotations

import json
import time

import numpy as np

from tribodyn.physics.analytic_contact import analytic_contact
from tribodyn.valvetrain import (AccelerationCam, AnalyticTribology, FilmTableTribology,
                                 ValvetrainParameters, compare_results, simulate_valvetrain)


def moes_film_table(result, tribology: AnalyticTribology, *, thickness: bool = True,
                    force_floor: float = 10.0):
    """Film table linearised about ``result``'s contact force F_k: Moes h_c and dh/dF (1 %
    finite difference), both at max(F_k, force_floor) because the steady film formula
    diverges at zero load. ``thickness=False`` keeps only the compliance, h = c_k (F − F_k);
    otherwise h_k is the film measured from its base-circle value (first sample), which
    only shifts the tappet datum, so static equilibrium is unchanged."""
    Fe = np.maximum(result.contact_force, force_floor)
    args = (result.radius_of_curvature, result.entrainment_speed, result.sliding_speed,
            tribology.bodies, tribology.lubricant)
    w = tribology.width
    h1 = analytic_contact(Fe / w, *args).central_film
    h2 = analytic_contact(1.01 * Fe / w, *args).central_film
    c = np.minimum((h2 - h1) / (0.01 * Fe), 0.0)
    h_k = (h1 - h1[0] + c * (result.contact_force - Fe)) if thickness else 0.0 * h1
    keep = np.append(np.diff(result.time) > 0.0, True)
    return FilmTableTribology(tribology, result.time[keep], h_k[keep], c[keep],
                              result.contact_force[keep],
                              period=2.0 * np.pi / result.cam_speed)


def implicit(cam, params, trib, explicit, thickness: bool, passes: int = 2):
    ref, log = explicit, []
    for k in range(passes):                           # waveform relaxation
        film = moes_film_table(ref, trib, thickness=thickness)
        t0 = time.perf_counter()
        im = simulate_valvetrain(cam, params, engine_speed=3000.0, tribology=film)
        wall = time.perf_counter() - t0
        if not im.converged:
            log.append({"pass": k + 1, "converged": False, "message": im.message})
            return ref, log
        change = np.max(np.abs(np.interp(ref.crank_angle, im.crank_angle, im.contact_force)
                               - ref.contact_force))
        log.append({"pass": k + 1, "wall_s": wall, "nfev": im.stats["nfev"],
                    "max_force_change_N": float(change)})
        ref = im
    return ref, log


def main() -> dict:
    cam = AccelerationCam()
    params = ValvetrainParameters()
    trib = AnalyticTribology(width=params.cam_width)
    out = {"case": "AccelerationCam default, ValvetrainParameters default, 3000 rpm, 2 cycles"}
    simulate_valvetrain(cam, params, engine_speed=3000.0, tribology=trib)       # warm-up
    t0 = time.perf_counter()
    ex = simulate_valvetrain(cam, params, engine_speed=3000.0, tribology=trib)
    out["explicit_s"] = time.perf_counter() - t0
    out["explicit_solver_s"] = ex.stats["wall_time_s"]
    out["explicit_nfev"] = ex.stats["nfev"]
    out["explicit_summary"] = ex.summary()
    for label, thick in (("implicit_compliance_only", False), ("implicit_full_film", True)):
        im, log = implicit(cam, params, trib, ex, thick)
        out[label] = {"passes": log, "wall_s": log[-1].get("wall_s"),
                      "series_film_range_um": [float(im.series_film.min() * 1e6),
                                               float(im.series_film.max() * 1e6)],
                      "summary": im.summary(),
                      "difference_to_explicit": compare_results(ex, im)}
    return out


if __name__ == "__main__":
    print(json.dumps(main(), indent=2, default=float))

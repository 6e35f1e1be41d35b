"""The cam-cycle study of a case (paper Section 3): the main job of ``tribodyn run``.

1. Valvetrain dynamics, explicit tribology (analytic film + friction, the paper's choice),
   two engine cycles from static equilibrium; the second cycle is presented. It is run
   with the first surface set's friction and its kinematics and loads drive every set.
2. Transient mixed-EHL along the presented cycle for each surface set (coatings,
   roughness, boundary shear coefficient) at a fixed crank step — in parallel processes.
3. Implicit dynamics for the comparison (paper Figs. 8–10): the numerical EHL film in
   series with the contact stiffness and the EHL friction, coupled by under-relaxed
   waveform iteration (:mod:`tribodyn.workflow.coupling`) for the first surface set.
4. The single-contact coating studies of the paper's Figs. 5 and 6.

Everything returned is in memory; writing results is :mod:`tribodyn.results_io`.
"""

from __future__ import annotations

import math
import os
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field

import numpy as np

from ..physics.materials import reduced_modulus
from ..valvetrain.dynamics import ValvetrainResult, simulate_valvetrain
from ..valvetrain.tribology import FilmTableTribology
from .coating_study import dry_coating_study, ehl_coating_study
from .coupling import FrictionCoefficientTable, ehl_tribology
from .cycle_ehl import CycleInputs, SetCycleResult, ehl_along_cycle

__all__ = ["CycleStudy", "StudyError", "run_cycle_study", "roughness_sensitivity",
           "RELAXATION"]

#: Under-relaxation of the film/friction tables between coupling iterations.
RELAXATION = 0.5
#: Coupling converged: change of the contact force between iterations, relative to its
#: peak, below these in RMS over the cam event and in maximum (the maximum sits at the
#: valve-closing impact, whose timing is the last to settle).
COUPLING_RMS_TOL = 5e-3
COUPLING_MAX_TOL = 5e-2


class StudyError(RuntimeError):
    """The study cannot proceed (e.g. the valvetrain dynamics failed)."""


@dataclass
class CycleStudy:
    """Everything the cycle study computed (see module docstring)."""

    case: object
    dynamics: ValvetrainResult
    inputs: CycleInputs
    sets: list                                  #: [SetCycleResult] in case order
    labels: dict                                #: set name → label
    implicit: ValvetrainResult | None = None
    coupling: dict = field(default_factory=dict)
    dry: list = field(default_factory=list)     #: Fig. 5 cases
    ehl_coating: dict = field(default_factory=dict)   #: Fig. 6 results
    sensitivity: dict = field(default_factory=dict)   #: roughness sensitivity at the nose
    runtime_s: float = 0.0
    timings: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)

    def set(self, name: str) -> SetCycleResult:
        for s in self.sets:
            if s.name == name:
                return s
        raise KeyError(name)


# ----------------------------------------------------------------------------- workers
def _limit_threads():
    """One BLAS thread per process: the solvers' matrices are small, and oversubscribed
    BLAS threads are much slower than one."""
    try:
        from threadpoolctl import threadpool_limits
        threadpool_limits(1)
    except ImportError:  # pragma: no cover - threadpoolctl is a dependency
        pass


def _set_task(case, name, inputs, progress_queue=None):
    _limit_threads()
    s = case.surface_set(name)
    cb = None
    if progress_queue is not None:
        def cb(i, n):
            if i % 10 == 0 or i == n:
                progress_queue.put((name, i, n))
    return ehl_along_cycle(inputs, s.name, s.coating_label, s.bodies, case.lubricant(),
                           s.roughness, case.ehl_options(s),
                           min_load=case.numerics.min_load, progress=cb)


def _relax(new: FilmTableTribology, old: FilmTableTribology | None, theta: float, period):
    if old is None:
        return new
    t = new.time

    def mix(a, b_time, b):
        return theta * a + (1.0 - theta) * np.interp(t, b_time, b)

    mu = mix(new.friction_model.mu, old.time, old.friction_model.mu)
    return FilmTableTribology(FrictionCoefficientTable(t, mu, period), t,
                              mix(new.h, old.time, old.h), mix(new.c, old.time, old.c),
                              mix(new.Fk, old.time, old.Fk), period=period)


def _coupling_task(case, name, dynamics, inputs, progress_queue=None, first=None):
    """Reference set: its EHL on the explicit dynamics (unless given as ``first``), then
    the implicit coupling iterations."""
    _limit_threads()
    t0 = time.perf_counter()
    if first is None:
        first = _set_task(case, name, inputs, progress_queue)
    out = {"first": first, "implicit": None, "history": [], "converged": False,
           "message": "implicit coupling disabled", "runtime_s": 0.0}
    n = case.numerics
    if not n.implicit_coupling:
        return out
    s = case.surface_set(name)
    lub = case.lubricant()
    e_prime = reduced_modulus(s.bodies)
    period = 2.0 * math.pi / case.cam_speed
    ev = dynamics.event_mask()
    f_peak = float(dynamics.contact_force.max())
    prev, table, ehl, inp = dynamics, None, first, inputs
    msg = f"not converged in {n.coupling_iterations} iterations"
    for k in range(1, n.coupling_iterations + 1):
        table = _relax(ehl_tribology(inp, ehl, lub, e_prime, period), table, RELAXATION,
                       period)
        new = simulate_valvetrain(case.cam(), case.valvetrain_parameters(), tribology=table,
                                  **case.dynamics_options())
        if not new.converged:
            msg = f"implicit dynamics failed at iteration {k}: {new.message}"
            break
        d = new.contact_force - prev.contact_force
        rms = float(np.sqrt(np.mean(d[ev] ** 2))) if ev.any() else float(np.abs(d).max())
        out["history"].append({"iteration": k, "rms_force_change_N": rms,
                               "max_force_change_N": float(np.abs(d).max())})
        out["implicit"] = new
        prev = new
        mx = float(np.abs(d).max())
        if rms < COUPLING_RMS_TOL * f_peak and mx < COUPLING_MAX_TOL * f_peak:
            out["converged"] = True
            msg = (f"converged in {k} iterations (last change of the contact force: RMS "
                   f"{rms:.2f} N, max {mx:.1f} N)")
            break
        if k < n.coupling_iterations:
            inp = CycleInputs.from_dynamics(new, n.crank_step_deg, case.width)
            label = f"implicit coupling {k + 1}"
            cb = None
            if progress_queue is not None:
                def cb(i, m, label=label):
                    if i % 10 == 0 or i == m:
                        progress_queue.put((label, i, m))
            ehl = ehl_along_cycle(inp, s.name, s.coating_label, s.bodies, lub, s.roughness,
                                  case.ehl_options(s), min_load=n.min_load, progress=cb)
    if not out["converged"] and out["history"]:
        last = out["history"][-1]
        msg += (f" (last change of the contact force: RMS {last['rms_force_change_N']:.2f} N, "
                f"max {last['max_force_change_N']:.1f} N)")
    out["message"] = msg
    out["runtime_s"] = time.perf_counter() - t0
    return out


def _coating_studies_task(case, nose=None):
    _limit_threads()
    lub = case.lubricant()
    dry = dry_coating_study()
    ehl = ehl_coating_study(lub, case)
    sens = roughness_sensitivity(case, nose) if nose is not None else {}
    return dry, ehl, sens


def roughness_sensitivity(case, nose: dict) -> dict:
    """Steady EHL at the nose condition of the cycle (see :func:`_nose_condition`) for the
    first surface set with (a) its case roughness, (b) the same σ, β but a summit density
    giving ηβσ = 0.04, typical of measured Gaussian surfaces (isotropic Gaussian surfaces
    have ηβσ ≥ 0.025; the paper's Table 4 gives 2e-4…2.3e-3), and (c) the case roughness
    without the limiting-shear cap (how much of the viscous friction the cap removes)."""
    from ..contact.ehl import solve_ehl
    from ..physics.asperity import Roughness
    s = case.surface_sets()[0]
    w = nose["force"] / case.width
    out = {"conditions": nose, "cases": {}}
    r0 = s.roughness
    alt = Roughness(asperity_density=0.04 / (r0.rms * r0.summit_radius), rms=r0.rms,
                    summit_radius=r0.summit_radius, method=r0.method)
    opts = case.ehl_options(s)
    variants = (("case roughness", r0, {}), ("Gaussian ηβσ = 0.04", alt, {}),
                ("no limiting-shear cap", r0, {"limiting_shear": False}))
    for label, rough, over in variants:
        r = solve_ehl(w, nose["radius"], nose["entrainment_speed"], nose["sliding_speed"],
                      s.bodies, case.lubricant(), rough, options=opts, **over)
        out["cases"][label] = {
            "eta_beta_sigma": rough.roughness_parameter,
            "limiting_shear": bool(over.get("limiting_shear", opts.limiting_shear)),
            "central_film_m": r.central_film, "min_film_m": r.min_film,
            "asperity_load_share": r.asperity_load / w,
            "boundary_friction_N": r.boundary_friction * case.width,
            "viscous_friction_N": r.viscous_friction * case.width,
            "friction_coefficient": r.friction_coefficient, "converged": r.converged}
    return out


def _nose_condition(inputs) -> dict:
    """The cam-nose sample: among samples with F > F_max/2 and |u_e| > 0.5 m/s, the one
    with the smallest radius of curvature R (``None`` if there is none)."""
    F = inputs.contact_force
    ok = (np.abs(inputs.entrainment_speed) > 0.5) & (F > 0.5 * F.max())
    if not ok.any():
        return None
    i = np.flatnonzero(ok)[np.argmin(inputs.radius[ok])]
    return {"crank_deg": float(inputs.crank_angle[i]), "force": float(F[i]),
            "radius": float(inputs.radius[i]),
            "entrainment_speed": float(inputs.entrainment_speed[i]),
            "sliding_speed": float(inputs.sliding_speed[i])}


# ----------------------------------------------------------------------------- driver
def run_cycle_study(case, *, workers: int | None = None, progress=None) -> CycleStudy:
    """Run the whole study for a validated :class:`~tribodyn.config.Case`.

    ``progress(event, **info)`` receives ``("dynamics", …)``, ``("set", name=, done=,
    total=)`` and ``("done", …)`` events (the CLI drives a progress bar with them).
    """
    t_start = time.perf_counter()
    _limit_threads()
    n = case.numerics
    report = progress or (lambda *a, **k: None)
    timings = {}
    sets = case.surface_sets()
    ref = sets[0]

    t0 = time.perf_counter()
    report("dynamics")
    dyn = simulate_valvetrain(case.cam(), case.valvetrain_parameters(),
                              tribology=case.analytic_tribology(ref), **case.dynamics_options())
    timings["dynamics_explicit_s"] = time.perf_counter() - t0
    if not dyn.converged:
        raise StudyError(f"valvetrain dynamics failed: {dyn.message}")
    inputs = CycleInputs.from_dynamics(dyn, n.crank_step_deg, case.width)
    if not np.any(inputs.contact_force >= n.min_load):
        raise StudyError(
            f"no EHL sample carries numerics.min_load = {n.min_load:g} N: the peak contact "
            f"force is {inputs.contact_force.max():.1f} N (lower numerics.min_load)")

    if workers is None:
        workers = n.workers or os.cpu_count() or 1
    workers = max(1, min(int(workers), len(sets) + 1))
    t0 = time.perf_counter()
    results, coupling, coating = {}, None, None
    if workers == 1:
        def cb_for(name):
            return lambda i, m: report("set", name=name, done=i, total=m)
        # serial: in-process, with per-step progress
        first = ehl_along_cycle(inputs, ref.name, ref.coating_label, ref.bodies,
                                case.lubricant(), ref.roughness, case.ehl_options(ref),
                                min_load=n.min_load, progress=cb_for(ref.name))
        results[ref.name] = first
        for s in sets[1:]:
            results[s.name] = ehl_along_cycle(inputs, s.name, s.coating_label, s.bodies,
                                              case.lubricant(), s.roughness,
                                              case.ehl_options(s), min_load=n.min_load,
                                              progress=cb_for(s.name))
        coupling = _coupling_task(case, ref.name, dyn, inputs, first=first)
        coating = _coating_studies_task(case, _nose_condition(inputs))
    else:
        import multiprocessing as mp
        ctx = mp.get_context("fork" if "fork" in mp.get_all_start_methods() else "spawn")
        manager = ctx.Manager()
        queue = manager.Queue()          # progress messages from the workers
        with manager, ProcessPoolExecutor(max_workers=workers, mp_context=ctx) as pool:
            fut_c = pool.submit(_coupling_task, case, ref.name, dyn, inputs, queue)
            futs = {s.name: pool.submit(_set_task, case, s.name, inputs, queue)
                    for s in sets[1:]}
            fut_coat = pool.submit(_coating_studies_task, case, _nose_condition(inputs))
            pending = [fut_c, fut_coat, *futs.values()]
            while any(not f.done() for f in pending):
                _drain(queue, report)
                time.sleep(0.05)
            _drain(queue, report)
            coupling = fut_c.result()
            results[ref.name] = coupling["first"]
            for name, f in futs.items():
                results[name] = f.result()
            coating = fut_coat.result()
    timings["ehl_and_coupling_s"] = time.perf_counter() - t0

    study = CycleStudy(case=case, dynamics=dyn, inputs=inputs,
                       sets=[results[s.name] for s in sets],
                       labels={s.name: s.coating_label for s in sets},
                       implicit=coupling.get("implicit"),
                       coupling={k: v for k, v in coupling.items()
                                 if k not in ("first", "implicit")},
                       dry=coating[0], ehl_coating=coating[1], sensitivity=coating[2],
                       timings=timings)
    for s in study.sets:
        if s.failures:
            study.warnings.append(f"{s.name}: {len(s.failures)} EHL step(s) did not converge "
                                  f"(first at {s.failures[0][0]:.0f}°: {s.failures[0][1]})")
    if n.implicit_coupling and not coupling.get("converged"):
        study.warnings.append(f"implicit coupling: {coupling.get('message')}")
    if dyn.jump:
        study.warnings.append(f"contact loss (jump) during the event at {dyn.jumps}")
    study.runtime_s = time.perf_counter() - t_start
    report("done", runtime_s=study.runtime_s)
    return study


def _drain(queue, report):
    while True:
        try:
            name, i, m = queue.get_nowait()
        except Exception:
            return
        report("set", name=name, done=i, total=m)

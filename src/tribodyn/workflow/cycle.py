"""The cam-cycle study of a case (paper Section 3): the main job of ``tribodyn run``.

1. Valvetrain dynamics, explicit tribology (analytic film + friction, the paper's choice),
   two engine cycles from static equilibrium; the second cycle is presented. It is run
   with the reference surface set's friction and its kinematics and loads drive every set.
2. Transient mixed-EHL along the presented cycle for each surface set (coatings,
   roughness, boundary shear coefficient) at a fixed crank step — in parallel processes.
3. Implicit dynamics for the comparison (paper Figs. 8–10): the numerical EHL film in
   series with the contact stiffness and the EHL friction, coupled by under-relaxed
   waveform iteration (:mod:`tribodyn.workflow.coupling`) for the reference set.
4. The single-contact coating studies of the paper's Figs. 5 and 6 and the sensitivity
   study at the cam nose (:mod:`tribodyn.workflow.sensitivity`).
5. The analysis (:mod:`tribodyn.workflow.postprocess`): roles, event, representative
   points, regimes, film-gain statistics, the summary.

Everything returned is in memory; writing results is :mod:`tribodyn.output`.
"""

from __future__ import annotations

import os
import queue as queue_module
import time
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass, field

import numpy as np

from ..valvetrain.dynamics import ValvetrainResult, simulate_valvetrain
from .coating_study import (
    DryCoatingCase,
    EHLCoatingStudy,
    dry_coating_study,
    ehl_coating_study,
)
from .coupling import CouplingResult, run_coupling
from .cycle_ehl import CycleInputs, SetCycleResult, ehl_for_set
from .postprocess import Analysis, analyse, surface_roles
from .sensitivity import RoughnessSensitivity, nose_condition, roughness_sensitivity

__all__ = ["CycleStudy", "StudyError", "run_cycle_study"]


class StudyError(RuntimeError):
    """The study cannot proceed (e.g. the valvetrain dynamics failed)."""


@dataclass
class CycleStudy:
    """Everything the cycle study computed (see module docstring)."""

    case: object                                #: the validated Case
    dynamics: ValvetrainResult                  #: explicit dynamics
    inputs: CycleInputs                         #: EHL samples of the presented cycle
    sets: list[SetCycleResult]                  #: in case order
    labels: dict[str, str]                      #: set name → label
    coupling: CouplingResult = field(default_factory=CouplingResult)
    dry: list[DryCoatingCase] = field(default_factory=list)       #: Fig. 5 cases
    ehl_coating: EHLCoatingStudy | None = None                     #: Fig. 6 results
    sensitivity: RoughnessSensitivity | None = None                #: at the cam nose
    analysis: Analysis | None = None
    runtime_s: float = 0.0
    timings: dict = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)

    @property
    def implicit(self) -> ValvetrainResult | None:
        """Implicit dynamics of the coupling (None if disabled or failed)."""
        return self.coupling.implicit

    @property
    def reference(self) -> SetCycleResult:
        """The reference surface set (first uncoated set)."""
        return self.set(surface_roles(self.case)["reference"])

    def set(self, name: str) -> SetCycleResult:
        for s in self.sets:
            if s.name == name:
                return s
        raise KeyError(name)

    def analyse(self) -> Analysis:
        """Compute (once) and return the :class:`Analysis` of the study."""
        if self.analysis is None:
            self.analysis = analyse(self)
        return self.analysis


# ----------------------------------------------------------------------------- workers
def _limit_threads():
    """One BLAS thread per process: the solvers' matrices are small, and oversubscribed
    BLAS threads are much slower than one."""
    from threadpoolctl import threadpool_limits
    threadpool_limits(1)


def _queue_progress(queue, name):
    """Progress callback of a worker: every tenth sample to the parent's queue."""
    if queue is None:
        return None

    def cb(i, n, name=name):
        if i % 10 == 0 or i == n:
            queue.put((name, i, n))
    return cb


def _set_task(case, name, inputs, queue=None) -> SetCycleResult:
    _limit_threads()
    return ehl_for_set(case, case.surface_set(name), inputs, _queue_progress(queue, name))


def _coupling_task(case, name, dynamics, inputs, queue=None, first=None):
    """Reference set: its EHL on the explicit dynamics (unless given as ``first``), then
    the implicit coupling iterations. Returns (first, CouplingResult)."""
    _limit_threads()
    s = case.surface_set(name)
    if first is None:
        first = ehl_for_set(case, s, inputs, _queue_progress(queue, name))
    progress = None if queue is None else (
        lambda label, i, m: (i % 10 == 0 or i == m) and queue.put((label, i, m)))
    return first, run_coupling(case, s, dynamics, inputs, first, progress)


def _coating_studies_task(case, reference: str, nose):
    _limit_threads()
    dry = dry_coating_study()
    ehl = ehl_coating_study(case.lubricant(), case)
    sens = (roughness_sensitivity(case, case.surface_set(reference), nose)
            if nose is not None else None)
    return dry, ehl, sens


# ----------------------------------------------------------------------------- driver
def run_cycle_study(case, *, workers: int | None = None, progress=None,
                    executor=None) -> CycleStudy:
    """Run the whole study for a validated :class:`~tribodyn.config.Case`.

    ``progress(event, **info)`` receives ``("dynamics", …)``, ``("set", name=, done=,
    total=)`` and ``("done", …)`` events (the CLI drives a progress bar with them).
    ``executor``: any :class:`concurrent.futures.Executor` (e.g. a Dask client's
    ``client.get_executor()``) runs the surface sets, the coupling chain and the
    single-contact studies instead of a local process pool; progress is then reported
    per finished task (``done = total = 1``), as remote workers cannot reach the queue.
    """
    t_start = time.perf_counter()
    _limit_threads()
    n = case.numerics
    report = progress or (lambda *a, **k: None)
    timings = {}
    sets = case.surface_sets()
    ref_name = surface_roles(case)["reference"]
    ref = case.surface_set(ref_name)

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
    nose = nose_condition(inputs)

    if workers is None:
        workers = n.workers or os.cpu_count() or 1
    workers = max(1, min(int(workers), len(sets) + 1))
    t0 = time.perf_counter()
    results = {}
    if executor is not None:
        results, coupling, coating = _run_on_executor(executor, case, sets, ref_name, dyn,
                                                      inputs, nose, report)
    elif workers == 1:
        def cb_for(name):
            return lambda i, m: report("set", name=name, done=i, total=m)
        # serial: in-process, with per-step progress
        for s in sets:
            results[s.name] = ehl_for_set(case, s, inputs, cb_for(s.name))
        _, coupling = _coupling_task(case, ref_name, dyn, inputs, first=results[ref_name])
        coating = _coating_studies_task(case, ref_name, nose)
    else:
        import multiprocessing as mp
        ctx = mp.get_context("fork" if "fork" in mp.get_all_start_methods() else "spawn")
        manager = ctx.Manager()
        queue = manager.Queue()          # progress messages from the workers
        with manager, ProcessPoolExecutor(max_workers=workers, mp_context=ctx) as pool:
            fut_c = pool.submit(_coupling_task, case, ref_name, dyn, inputs, queue)
            futs = {s.name: pool.submit(_set_task, case, s.name, inputs, queue)
                    for s in sets if s.name != ref_name}
            fut_coat = pool.submit(_coating_studies_task, case, ref_name, nose)
            pending = [fut_c, fut_coat, *futs.values()]
            while any(not f.done() for f in pending):
                _drain(queue, report)
                time.sleep(0.05)
            _drain(queue, report)
            results[ref_name], coupling = fut_c.result()
            for name, f in futs.items():
                results[name] = f.result()
            coating = fut_coat.result()
    timings["ehl_and_coupling_s"] = time.perf_counter() - t0

    study = CycleStudy(case=case, dynamics=dyn, inputs=inputs,
                       sets=[results[s.name] for s in sets],
                       labels={s.name: s.coating_label for s in sets}, coupling=coupling,
                       dry=coating[0], ehl_coating=coating[1], sensitivity=coating[2],
                       timings=timings)
    for s in study.sets:
        if s.failures:
            study.warnings.append(f"{s.name}: {len(s.failures)} EHL step(s) did not converge "
                                  f"(first at {s.failures[0][0]:.0f}°: {s.failures[0][1]})")
    if n.implicit_coupling and not coupling.converged:
        study.warnings.append(f"implicit coupling: {coupling.message}")
    if dyn.jump:
        study.warnings.append(f"contact loss (jump) during the event at {dyn.jumps}")
    study.runtime_s = time.perf_counter() - t_start
    study.analyse()
    report("done", runtime_s=study.runtime_s)
    return study


def _run_on_executor(executor, case, sets, ref_name, dyn, inputs, nose, report):
    """The parallel part of the study on a given executor, one task per surface set."""
    from concurrent.futures import as_completed
    fut_c = executor.submit(_coupling_task, case, ref_name, dyn, inputs)
    futs = {executor.submit(_set_task, case, s.name, inputs): s.name
            for s in sets if s.name != ref_name}
    fut_coat = executor.submit(_coating_studies_task, case, ref_name, nose)
    names = {fut_c: ref_name, **futs}
    for name in names.values():
        report("set", name=name, done=0, total=1)
    results = {}
    for f in as_completed([fut_c, fut_coat, *futs]):
        if f in names:
            report("set", name=names[f], done=1, total=1)
    results[ref_name], coupling = fut_c.result()
    for f, name in futs.items():
        results[name] = f.result()
    return results, coupling, fut_coat.result()


def _drain(queue, report):
    while True:
        try:
            name, i, m = queue.get_nowait()
        except queue_module.Empty:
            return
        report("set", name=name, done=i, total=m)

"""The cam-cycle study of a case (paper Section 3): the main job of ``tribodyn run``.

1. Valvetrain dynamics, explicit tribology (analytic film + friction, the paper's choice),
   two engine cycles from static equilibrium; the second cycle is presented. It is run
   with the reference surface set's friction and its kinematics and loads drive every set.
2. Transient mixed-EHL along the presented cycle for each surface set (coatings,
   roughness, boundary shear coefficient) at a fixed crank step — in parallel processes.
3. Implicit dynamics for the comparison (paper Figs. 8–10): the numerical EHL film in
   series with the contact stiffness and the EHL friction, coupled by under-relaxed
   waveform iteration (:mod:`tribodyn.workflow.coupling`) for the reference set.
4. The sensitivity study at the case's own cam nose with its reference set
   (:mod:`tribodyn.workflow.sensitivity`); the single-contact coating studies of the
   paper's Figs. 5 and 6 (the paper's conditions) only for the paper's case or with
   ``compare_paper`` (:func:`tribodyn.workflow.engineering.compares_paper`).
5. The analysis (:mod:`tribodyn.workflow.postprocess`): roles, event, representative
   points, regimes, film-gain statistics, the summary.

Everything returned is in memory; writing results is :mod:`tribodyn.output`.
"""

from __future__ import annotations

import os
import time
from collections.abc import Callable
from concurrent.futures import Executor, ProcessPoolExecutor, as_completed
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from .._system import exit_with_parent
from ..valvetrain.dynamics import ValvetrainResult, simulate_valvetrain
from .coating_study import (
    DryCoatingCase,
    EHLCoatingStudy,
    dry_coating_study,
    ehl_coating_study,
)
from .coupling import CouplingResult, run_coupling
from .cycle_ehl import CycleInputs, SetCycleResult, ehl_for_set
from .engineering import (
    Engineering,
    compares_paper,
    engineering_outputs,
    plausibility_warnings,
)
from .model_comparison import ModelComparison, compare_lumped_flexible
from .postprocess import Analysis, analyse, surface_roles
from .sensitivity import (
    RoughnessSensitivity,
    nose_condition,
    roughness_sensitivity,
    surface_sets_at_nose,
)

if TYPE_CHECKING:
    from ..config.case import Case

__all__ = ["CycleStudy", "StudyError", "run_cycle_study"]


class StudyError(RuntimeError):
    """The study cannot proceed (e.g. the valvetrain dynamics failed)."""


@dataclass
class CycleStudy:
    """Everything the cycle study computed (see module docstring)."""

    case: Case  #: the validated Case
    dynamics: ValvetrainResult  #: explicit dynamics
    inputs: CycleInputs  #: EHL samples of the presented cycle
    sets: list[SetCycleResult]  #: in case order
    labels: dict[str, str]  #: set name → label
    coupling: CouplingResult = field(default_factory=CouplingResult)
    dry: list[DryCoatingCase] = field(default_factory=list)  #: Fig. 5 cases
    ehl_coating: EHLCoatingStudy | None = None  #: Fig. 6 results
    sensitivity: RoughnessSensitivity | None = None  #: at the cam nose
    #: every surface set at the case's own nose (a case other than the paper's)
    nose_sets: RoughnessSensitivity | None = None
    model_comparison: ModelComparison | None = None  #: lumped vs flexible (flexible cases)
    analysis: Analysis | None = None
    runtime_s: float = 0.0
    timings: dict = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)
    #: with ``numerics.thermal``: ``sets`` are the thermal results and these the
    #: isothermal ones at the same inlet temperature (None for an isothermal study)
    isothermal_sets: list[SetCycleResult] | None = None
    #: the report carries the paper's comparison (claims, Figs. 5/6 at its conditions)
    compare_paper: bool = False
    engineering: Engineering | None = None  #: torque, pressure, kinematics, surge

    def engineering_outputs(self) -> Engineering:
        """Compute (once) and return the :class:`Engineering` outputs of the study."""
        if self.engineering is None:
            self.engineering = engineering_outputs(self)
        return self.engineering

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
#: BLAS/OpenMP thread settings of worker processes: the solvers' dense matrices are small,
#: and multi-threaded BLAS on them costs several times the single-threaded time.
_THREAD_ENV = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")


def _limit_threads():
    """One BLAS thread per process (a runtime limit; see :func:`_pool_context` for the
    start-up setting that also avoids the threads' start-up costs)."""
    from threadpoolctl import threadpool_limits

    threadpool_limits(1)


def _blas_single_threaded() -> bool:
    from threadpoolctl import threadpool_info

    return all(i.get("num_threads", 1) <= 1 for i in threadpool_info())


def _pool_context():
    """Start method of the local process pool: fork when this process already runs
    single-threaded BLAS (the command line sets it before numpy loads), else a fresh
    interpreter per worker with one BLAS thread set in its environment (a runtime limit
    does not remove the threaded BLAS's overhead on small matrices)."""
    import multiprocessing as mp

    methods = mp.get_all_start_methods()
    if "fork" in methods and _blas_single_threaded():
        return mp.get_context("fork")
    return mp.get_context("forkserver" if "forkserver" in methods else "spawn")


def _local_pool(workers: int | None) -> ProcessPoolExecutor:
    """The study's local process pool (start method: :func:`_pool_context`); its workers
    end when this process dies, even by SIGKILL (:func:`~tribodyn._system.exit_with_parent`),
    instead of waiting on their task pipe for ever."""
    return ProcessPoolExecutor(
        max_workers=workers,
        mp_context=_pool_context(),
        initializer=exit_with_parent,
        initargs=(os.getpid(),),
    )


def _set_task(case, name, inputs) -> SetCycleResult:
    """EHL along the cycle for one surface set (a picklable top-level task)."""
    _limit_threads()
    return ehl_for_set(case, case.surface_set(name), inputs)


def _coupling_task(case, name, dynamics, inputs, first=None):
    """Reference set: its EHL on the explicit dynamics (unless given as ``first``), then
    the implicit coupling iterations. Returns (first, CouplingResult)."""
    _limit_threads()
    s = case.surface_set(name)
    if first is None:
        first = ehl_for_set(case, s, inputs)
    return first, run_coupling(case, s, dynamics, inputs, first)


def _coating_studies_task(case, reference: str, nose, paper_studies: bool = True):
    """The sensitivity study at the case's nose; with ``paper_studies`` also the
    paper's Figs. 5/6 single-contact studies (at the paper's conditions), without them
    every surface set of the case at its own nose."""
    _limit_threads()
    dry = dry_coating_study() if paper_studies else []
    ehl = ehl_coating_study(case.lubricant(), case) if paper_studies else None
    sens = (
        roughness_sensitivity(case, case.surface_set(reference), nose) if nose is not None else None
    )
    own = surface_sets_at_nose(case, nose) if nose is not None and not paper_studies else None
    return dry, ehl, sens, own


@contextmanager
def _single_blas_thread():
    from threadpoolctl import threadpool_limits

    with threadpool_limits(1):
        yield


# ----------------------------------------------------------------------------- driver
def run_cycle_study(
    case: Case,
    *,
    workers: int | None = None,
    progress: Callable[..., None] | None = None,
    executor: Executor | None = None,
    compare_paper: bool | None = None,
) -> CycleStudy:
    """Run the whole study for a validated :class:`~tribodyn.config.Case`.

    The surface sets, the coupling chain (reference set, then the implicit iterations)
    and the single-contact studies are independent tasks, submitted to ``executor`` (any
    :class:`concurrent.futures.Executor`, e.g. a Dask client's ``get_executor()``; every
    task is a picklable top-level function with picklable arguments) or, by default, to
    a local process pool of ``workers`` processes (``workers=1``: in this process).

    ``progress(event, **info)`` receives ``("dynamics", …)``, ``("set", name=, done=,
    total=)`` (done = 0 when a set is submitted, = total when its result is in) and
    ``("done", …)`` events (the CLI drives a progress bar with them); it runs in this
    process only.

    ``compare_paper``: add the paper's comparison (its Figs. 5/6 single-contact studies
    at its conditions, its claims in the report); None: only for the paper's case.
    """
    paper_cmp = compares_paper(case, compare_paper)
    t_start = time.perf_counter()
    n = case.numerics
    report = progress or (lambda *a, **k: None)
    timings = {}
    sets = case.surface_sets()
    ref_name = surface_roles(case)["reference"]
    ref = case.surface_set(ref_name)

    t0 = time.perf_counter()
    report("dynamics")
    dyn = simulate_valvetrain(
        case.cam(),
        case.valvetrain_parameters(),
        tribology=case.analytic_tribology(ref),
        **case.dynamics_options(),
    )
    timings["dynamics_explicit_s"] = time.perf_counter() - t0
    if not dyn.converged:
        raise StudyError(f"valvetrain dynamics failed: {dyn.message}")
    inputs = CycleInputs.from_dynamics(dyn, n.crank_step_deg, case.width)
    if not np.any(inputs.contact_force >= n.min_load):
        raise StudyError(
            f"no EHL sample carries numerics.min_load = {n.min_load:g} N: the peak contact "
            f"force is {inputs.contact_force.max():.1f} N (lower numerics.min_load)"
        )
    nose = nose_condition(inputs)
    total = inputs.crank_angle.size

    if workers is None:
        workers = n.workers or os.cpu_count() or 1
    workers = max(1, min(int(workers), len(sets) + 1))
    t0 = time.perf_counter()
    results: dict = {}
    thermal = {}  # thermal EHL per set (numerics.thermal)
    if executor is None and workers == 1:
        # serial, in this process
        with _single_blas_thread():
            for s in sets:
                report("set", name=s.name, done=0, total=total)
                results[s.name] = ehl_for_set(case, s, inputs)
                report("set", name=s.name, done=total, total=total)
            _, coupling = _coupling_task(case, ref_name, dyn, inputs, first=results[ref_name])
            coating = _coating_studies_task(case, ref_name, nose, paper_cmp)
            if n.thermal:
                from .thermal_study import thermal_for_set

                for s in sets:
                    label = f"{s.name} (thermal)"
                    report("set", name=label, done=0, total=total)
                    thermal[s.name] = thermal_for_set(case, s, inputs)
                    report("set", name=label, done=total, total=total)
    else:
        own = executor is None
        pool: Executor
        if executor is not None:
            pool = executor
        else:
            saved = {k: os.environ.get(k) for k in _THREAD_ENV}
            os.environ.update({k: "1" for k in _THREAD_ENV})
            pool = _local_pool(workers)
        try:
            # the coupling chain is the longest task: submitted first
            fut_c = pool.submit(_coupling_task, case, ref_name, dyn, inputs)
            futs = {
                pool.submit(_set_task, case, s.name, inputs): s.name
                for s in sets
                if s.name != ref_name
            }
            fut_coat = pool.submit(_coating_studies_task, case, ref_name, nose, paper_cmp)
            futs[fut_c] = ref_name
            fut_th = {}
            if n.thermal:
                from .thermal_study import thermal_task

                fut_th = {pool.submit(thermal_task, case, s.name, inputs): s.name for s in sets}
            for s in sets:
                report("set", name=s.name, done=0, total=total)
                if n.thermal:
                    report("set", name=f"{s.name} (thermal)", done=0, total=total)
            for f in as_completed([*futs, fut_coat, *fut_th]):
                if f is fut_coat:
                    coating = f.result()
                    continue
                if f in fut_th:
                    name = fut_th[f]
                    thermal[name] = f.result()
                    report("set", name=f"{name} (thermal)", done=total, total=total)
                    continue
                name = futs[f]
                if f is fut_c:
                    results[name], coupling = f.result()
                else:
                    results[name] = f.result()
                report("set", name=name, done=total, total=total)
        finally:
            if own:
                pool.shutdown(wait=True, cancel_futures=True)
                for k, v in saved.items():
                    if v is None:
                        os.environ.pop(k, None)
                    else:
                        os.environ[k] = v
    timings["ehl_and_coupling_s"] = time.perf_counter() - t0
    for name, r in results.items():  # inside the tasks (their own clocks)
        timings[f"ehl_pass_{name}_s"] = r.runtime_s
    timings["coupling_s"] = coupling.runtime_s
    isothermal = None
    if n.thermal:  # thermal EHL per set; isothermal kept beside it
        isothermal = [results[s.name] for s in sets]
        results = thermal
        for name, r in thermal.items():
            timings[f"thermal_ehl_pass_{name}_s"] = r.runtime_s

    study = CycleStudy(
        case=case,
        dynamics=dyn,
        inputs=inputs,
        sets=[results[s.name] for s in sets],
        labels={s.name: s.coating_label for s in sets},
        coupling=coupling,
        dry=coating[0],
        ehl_coating=coating[1],
        sensitivity=coating[2],
        nose_sets=coating[3],
        timings=timings,
        isothermal_sets=isothermal,
        compare_paper=paper_cmp,
    )
    for res in study.sets:
        if res.failures:
            study.warnings.append(
                f"{res.name}: {len(res.failures)} EHL step(s) did not converge "
                f"(first at {res.failures[0][0]:.0f}°: {res.failures[0][1]}): the film, "
                "pressure and friction of this set at those crank angles (converged = 0 in "
                "results.nc) are the last iterate, not a solution, and are left out of the "
                "film and friction maxima; a finer numerics.crank_step_deg or more "
                "numerics.n usually helps"
            )
    # validity warnings, one line per kind (sets with the same count and start together)
    kinds: dict[tuple, list[str]] = {}
    for res in study.sets:
        for kind, (count, first, text) in res.validity.items():
            kinds.setdefault((kind, count, first), [text]).append(res.name)
    for (_kind, count, first), (text, *names) in kinds.items():
        who = ", ".join(names) if len(names) < len(study.sets) else "every surface set"
        study.warnings.append(
            f"{who}: {count} EHL step(s) outside the model's validity "
            f"(first at {first:.0f}°: {text}): the films, pressures and friction there "
            "are computed but beyond the assumptions of the line-contact model, so treat "
            "them as estimates; " + _validity_advice(text)
        )
    if n.implicit_coupling and not coupling.converged:
        study.warnings.append(
            f"implicit coupling: {coupling.message}: only the implicit curves "
            "(*_implicit in results.nc, the implicit-vs-explicit comparison) are affected; "
            "the explicit dynamics, the EHL along the cycle and the torque are not; raise "
            "numerics.coupling_iterations to converge it, or set "
            "numerics.implicit_coupling = false if the comparison is not needed"
        )
    if dyn.jump:
        study.warnings.append(_jump_warning(dyn))
    study.warnings += plausibility_warnings(study)
    if case.valvetrain_model == "flexible":
        t0 = time.perf_counter()
        report("dynamics")
        study.model_comparison = compare_lumped_flexible(case, case.analytic_tribology(ref), dyn)
        study.warnings += study.model_comparison.messages
        timings["lumped_vs_flexible_s"] = time.perf_counter() - t0
    study.runtime_s = time.perf_counter() - t_start
    study.analyse()
    report("done", runtime_s=study.runtime_s)
    return study


#: What a user can change when EHL steps are outside the model's validity: by a word of
#: the check's message (:mod:`tribodyn.contact.ehl.validity`).
_VALIDITY_ADVICE = {
    "thin-film": "thick films relative to the contact length occur at light load: "
    "they carry little friction; nothing to change unless those samples matter",
    "load-carrying zone": "the contact is wide against the radius of curvature: check the "
    "cam's minimum radius (nose) and the load",
    "Reynolds number": "fluid inertia matters at high speed and thick film: the pressure there "
    "is uncertain by Re*",
    "pressure": "peak pressures beyond 4 GPa: check the load and the radius of "
    "curvature, or the materials",
}


def _validity_advice(text: str) -> str:
    for word, advice in _VALIDITY_ADVICE.items():
        if word in text:
            return advice
    return "see the validity checks in the physics documentation"


def _jump_warning(dyn) -> str:
    """The contact-loss (valve jump) warning, with its share of the cam event."""
    lost = sum(b - a for a, b in dyn.jumps)
    ev = dyn.event_mask()
    step = float(dyn.crank_angle[1] - dyn.crank_angle[0]) if dyn.crank_angle.size > 1 else 0.0
    event = float(ev.sum()) * step
    first = ", ".join(f"{a:.1f}–{b:.1f}°" for a, b in dyn.jumps[:3])
    more = f" and {len(dyn.jumps) - 3} more" if len(dyn.jumps) > 3 else ""
    text = (
        f"the tappet loses contact with the cam (valve jump) for {lost:.1f}° crank of the "
        f"{event:.0f}° cam event ({first}{more})"
    )
    if event > 0 and lost > 0.1 * event:
        text += (
            ": the valvetrain does not follow the cam at this speed (check the masses, "
            "spring rate and preload); films and friction there describe the impacts, "
            "not the design"
        )
    return text

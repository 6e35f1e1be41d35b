"""The cam-cycle study of a case (paper Section 3): the main job of ``tribodyn run``.

1. Valvetrain dynamics, explicit tribology (analytic film + friction, the paper's choice),
   two engine cycles from static equilibrium; the second cycle is presented. It is run
   with the reference surface set's friction and its kinematics and loads drive every set.
2. Transient mixed-EHL along the presented cycle for each surface set (coatings,
   roughness, boundary shear coefficient) at a fixed crank step — in parallel processes.
3. Implicit dynamics for the comparison (paper Figs. 8–10): the numerical EHL film in
   series with the contact stiffness and the EHL friction, coupled by under-relaxed
   waveform iteration (:mod:`tribodyn.cycle.coupling`) for the reference set.
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
from concurrent.futures import Executor, ProcessPoolExecutor
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

import numpy as np

from .._system import exit_with_parent
from .._threads import blas_single_threaded, single_blas_thread, single_blas_thread_env
from ..config.build import BuiltCase, as_built
from ..config.origins import default_warnings
from ..cycle.coupling import CouplingResult, run_coupling
from ..cycle.driver import CycleInputs, SetCycleResult, ehl_for_set
from ..cycle.methods import study_variant
from ..cycle.tasks import InlineExecutor, Task, run_tasks
from ..valvetrain.dynamics import ValvetrainResult, simulate_valvetrain
from .coating_study import (
    CoatingCase,
    EHLCoatingStudy,
    HertzReference,
    dry_coating_study,
    dry_hertz_reference,
    ehl_coating_study,
)
from .engineering import (
    Engineering,
    compares_paper,
    engineering_outputs,
    plausibility_warnings,
)
from .inputs_as_used import InputsAsUsed, inputs_as_used
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
    dry: list[CoatingCase] = field(default_factory=list)  #: Fig. 5 cases
    dry_hertz: HertzReference | None = None  #: Fig. 5's Hertz reference (uncoated steel)
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
    #: subsurface stresses along the cycle per set name (workflow.stress_study.CycleStress;
    #: from the isothermal pass), empty with ``[stress] enabled = false``
    stresses: dict = field(default_factory=dict)
    #: the report carries the paper's comparison (claims, Figs. 5/6 at its conditions)
    compare_paper: bool = False
    engineering: Engineering | None = None  #: torque, pressure, kinematics, surge
    #: the inputs as used (surface sets, cam, thermal oil), for the report
    as_used: InputsAsUsed | None = None

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
def _pool_context():
    """Start method of the local process pool: fork when this process already runs
    single-threaded BLAS (the command line sets it before numpy loads), else a fresh
    interpreter per worker, started with one BLAS thread in its environment
    (:func:`~tribodyn._threads.single_blas_thread_env`)."""
    import multiprocessing as mp

    methods = mp.get_all_start_methods()
    if "fork" in methods and blas_single_threaded():
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


def _pass_task(built: BuiltCase, name: str, inputs):
    """EHL along the cycle for one surface set (a picklable top-level task, which the
    set's stresses and, for the reference set, the coupling wait for)."""
    with single_blas_thread():
        return ehl_for_set(built, built.set(name).surface, inputs)


def _coupling_task(built: BuiltCase, name: str, dynamics, inputs, first):
    """The implicit coupling iterations of the set ``name`` from its pass ``first`` on
    the explicit dynamics (a CouplingResult)."""
    with single_blas_thread():
        return run_coupling(built, built.set(name).surface, dynamics, inputs, first)


def _stress_task(built: BuiltCase, name: str, inputs, first):
    """The subsurface stresses of the set ``name`` along its EHL pass ``first``: a
    CycleStress, None when ``[stress] enabled = false``, or the error text."""
    if not built.case.stress.enabled:
        return None
    from .stress_study import stress_for_set

    own = built.set(name)
    with single_blas_thread():
        try:  # the strengths built with the case
            return stress_for_set(built, own.surface, first, inputs, strengths=own.strengths)
        except Exception as exc:  # the EHL results stay usable; the study warns
            return f"{type(exc).__name__}: {exc}"


def coating_studies_task(built: BuiltCase, reference: str, nose, paper_studies: bool = True):
    """The sensitivity study at the case's nose; with ``paper_studies`` also the
    paper's Figs. 5/6 single-contact studies (at the paper's conditions), without them
    every surface set of the case at its own nose."""
    with single_blas_thread():
        dry = dry_coating_study() if paper_studies else []
        ehl = ehl_coating_study(built.lubricant, built) if paper_studies else None
        sens = (
            roughness_sensitivity(built, built.set(reference).surface, nose)
            if nose is not None
            else None
        )
        own = surface_sets_at_nose(built, nose) if nose is not None and not paper_studies else None
        return dry, ehl, sens, own


def study_tasks(
    built: BuiltCase,
    reference: str,
    dynamics,
    inputs,
    nose,
    paper_studies: bool,
    friction_only: bool = False,
) -> list[Task]:
    """The study's task graph, declared once, in order of priority: the coupling chain of
    the reference set (its EHL pass, then the implicit iterations on it: the longest
    chain, so first), the EHL passes of the other sets, the stresses of every set (each
    waiting for its pass, ``Task.after``: the short tasks last, so that the workers end
    together), the single-contact studies and the passes of the EHL variant
    (:func:`~tribodyn.cycle.methods.study_variant`). Keys: ``"pass:<reference>"``,
    ``"coupling"``, ``"set:<name>"`` (the other sets' passes), ``"stress:<name>"``,
    ``"coating"``, ``"thermal:<name>"``. ``friction_only``: the EHL passes (and the
    variant's) of every set alone, ``"set:<name>"`` for the reference set too."""
    if friction_only:
        tasks = [Task(f"set:{name}", _pass_task, (built, name, inputs)) for name in built.sets]
    else:
        passes = {reference: f"pass:{reference}"}  # the pass's key of each set
        passes.update({name: f"set:{name}" for name in built.sets if name != reference})
        tasks = [Task(key, _pass_task, (built, name, inputs)) for name, key in passes.items()]
        tasks.insert(
            1,
            Task(
                "coupling", _coupling_task, (built, reference, dynamics, inputs), passes[reference]
            ),
        )
        tasks += [
            Task(f"stress:{name}", _stress_task, (built, name, inputs), key)
            for name, key in passes.items()
        ]
        tasks.append(Task("coating", coating_studies_task, (built, reference, nose, paper_studies)))
    return tasks + study_variant(built).tasks(built, inputs)


@contextmanager
def _study_executor(executor: Executor | None, workers: int):
    """The given executor; else :class:`~tribodyn.cycle.tasks.InlineExecutor` for one
    worker, or a local process pool of ``workers`` processes (shut down on exit)."""
    if executor is not None:
        yield executor
    elif workers == 1:
        yield InlineExecutor()
    else:
        # one BLAS thread in the environment while the pool lives: its workers start on
        # demand (at a submission), in fresh interpreters unless forked
        with single_blas_thread_env():
            pool = _local_pool(workers)
            try:
                yield pool
            finally:
                pool.shutdown(wait=True, cancel_futures=True)


# ----------------------------------------------------------------------------- driver
def study_dynamics(case) -> ValvetrainResult:
    """The valvetrain dynamics of a case (Case or BuiltCase) as the study runs them: with
    the explicit (analytic) tribology of its reference surface set; lumped or flexible
    alike (:func:`~tribodyn.valvetrain.dynamics.simulate_valvetrain` takes either)."""
    built = as_built(case)
    return simulate_valvetrain(
        built.cam,
        built.valvetrain,
        tribology=built.analytic_tribology(surface_roles(built)["reference"]),
        **built.dynamics_options,
    )


def run_cycle_study(
    case: Case | BuiltCase,
    *,
    workers: int | None = None,
    progress: Callable[..., None] | None = None,
    executor: Executor | None = None,
    compare_paper: bool | None = None,
    friction_only: bool = False,
) -> CycleStudy:
    """Run the whole study for a validated :class:`~tribodyn.config.Case` (or its
    :class:`~tribodyn.config.build.BuiltCase`).

    The objects of the case are built once (:func:`~tribodyn.config.build.build`). The
    surface sets, the coupling chain (reference set, then the implicit iterations) and
    the single-contact studies are independent tasks (:func:`study_tasks`), submitted to
    ``executor`` (any :class:`concurrent.futures.Executor`, e.g. a Dask client's
    ``get_executor()``; every task is a picklable top-level function with picklable
    arguments) or, by default, to a local process pool of ``workers`` processes
    (``workers=1``: in this process, :class:`~tribodyn.cycle.tasks.InlineExecutor`).

    ``progress(event, **info)`` receives ``("dynamics", …)``, ``("set", name=, done=,
    total=)`` (done = 0 when a set is submitted, = total when its result is in) and
    ``("done", …)`` events (the CLI drives a progress bar with them); it runs in this
    process only.

    ``compare_paper``: add the paper's comparison (its Figs. 5/6 single-contact studies
    at its conditions, its claims in the report); None: only for the paper's case.

    ``friction_only``: what an engine study uses (:mod:`tribodyn.workflow.engine`): the
    dynamics and every set's EHL pass, without the implicit-dynamics comparison, the
    subsurface stresses and the single-contact studies (the results of the passes are
    the same).
    """
    t_start = time.perf_counter()
    built = as_built(case)
    case = built.case
    paper_cmp = compares_paper(case, compare_paper) and not friction_only
    n = case.numerics
    report = progress or (lambda *a, **k: None)
    timings = {}
    sets = built.surface_sets
    variant = study_variant(built)  # isothermal or thermal
    ref_name = surface_roles(built)["reference"]

    t0 = time.perf_counter()
    report("dynamics")
    with single_blas_thread():
        dyn = study_dynamics(built)
    timings["dynamics_explicit_s"] = time.perf_counter() - t0
    if not dyn.converged:
        raise StudyError(f"valvetrain dynamics failed: {dyn.message}")
    inputs = CycleInputs.from_dynamics(dyn, n.crank_step_deg, case.width)
    inputs = inputs.with_rotation(built.tappet_rotation)  # outputs show the EHL's speeds
    # a train thrown off the cam carries no load: the study goes on and reports the jump
    if not np.any(inputs.contact_force >= n.min_load) and not dyn.jump:
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
    stresses: dict = {}
    own: dict = {}  # the variant's own passes by task key (thermal EHL)
    coupling = CouplingResult()
    coating: tuple = ([], None, None, None)

    def label(key: str, end: bool) -> str | None:
        """The progress line of a task at its start or ``end`` (None: none). The
        reference set's line runs from the start of its pass to the end of the
        coupling."""
        kind, _, name = key.partition(":")
        mine = {"set": name, **{k: f"{name} ({k})" for k in variant.kinds}}
        return mine.get(kind) or {"coupling" if end else "pass": ref_name}.get(kind)

    def started(key: str) -> None:
        if (name := label(key, end=False)) is not None:
            report("set", name=name, done=0, total=total)

    def done(key: str, result) -> None:
        nonlocal coupling, coating
        kind, _, name = key.partition(":")
        if kind == "coupling":
            coupling = result
        elif kind in ("pass", "set"):
            results[name] = result
        elif kind == "stress":
            stresses[name] = result
        elif kind in variant.kinds:
            own[key] = result
        else:
            coating = result
        if (text := label(key, end=True)) is not None:
            report("set", name=text, done=total, total=total)

    tasks = study_tasks(built, ref_name, dyn, inputs, nose, paper_cmp, friction_only)
    with _study_executor(executor, workers) as pool:
        # a local pool runs as many tasks as it has workers: the list order decides
        run_tasks(pool, tasks, done, started, limit=None if executor is not None else workers)
    timings["ehl_and_coupling_s"] = time.perf_counter() - t0
    for name, r in results.items():  # inside the tasks (their own clocks)
        timings[f"ehl_pass_{name}_s"] = r.runtime_s
    timings["coupling_s"] = coupling.runtime_s
    for key, r in own.items():
        kind, _, name = key.partition(":")
        timings[f"{kind}_ehl_pass_{name}_s"] = r.runtime_s
    presented, isothermal = variant.collect([s.name for s in sets], results, own)

    study = CycleStudy(
        case=case,
        dynamics=dyn,
        inputs=inputs,
        sets=presented,
        labels={s.name: s.coating_label for s in sets},
        coupling=coupling,
        dry=coating[0],
        dry_hertz=dry_hertz_reference(coating[0]),
        ehl_coating=coating[1],
        sensitivity=coating[2],
        nose_sets=coating[3],
        timings=timings,
        isothermal_sets=isothermal,
        compare_paper=paper_cmp,
        as_used=inputs_as_used(built),
    )
    # the force- and film-deciding values the case left to typical ones, named first
    study.warnings += default_warnings(case)
    fit = getattr(built.cam, "fit_warning", None)  # a lift table's cam
    if fit is not None and (text := fit()) is not None:
        study.warnings.append(text)
    for s in sets:
        st = stresses.get(s.name)
        if isinstance(st, str):
            study.warnings.append(f"{s.name}: subsurface stresses not computed ({st})")
        elif st is not None:
            study.stresses[s.name] = st
            timings[f"stress_{s.name}_s"] = st.runtime_s
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
    if n.implicit_coupling and not friction_only and not coupling.converged:
        study.warnings.append(
            f"implicit coupling: {coupling.message}: only the implicit curves "
            "(*_implicit in results.nc, the implicit-vs-explicit comparison) are affected; "
            "the explicit dynamics, the EHL along the cycle and the torque are not; raise "
            "numerics.coupling_iterations to converge it, or set "
            "numerics.implicit_coupling = false if the comparison is not needed"
        )
    if dyn.jump:
        study.warnings.append(_jump_warning(dyn, built))
    study.warnings += plausibility_warnings(study)
    if built.valvetrain.has_lumped_companion:
        t0 = time.perf_counter()
        report("dynamics")
        study.model_comparison = compare_lumped_flexible(
            built, built.analytic_tribology(ref_name), dyn
        )
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
    "Hertz half-width": "the contact is wide against the radius of curvature: check the "
    "cam's minimum radius (nose) and the load",
    "load-carrying zone": "at light load a thick film carries the load over a long inlet, "
    "where the parabolic gap is short of the circle by the share given: the film and "
    "friction there are off by less than about that share; nothing to change unless "
    "those samples matter",
    "Reynolds number": "fluid inertia matters at high speed and thick film: the pressure there "
    "is uncertain by Re*",
    "at the outlet": "the EHL domain ends before the pressure has fallen: raise "
    "numerics.outlet (in Hertz half-widths) or numerics.outlet_rigid",
    "truncated inlet": "the inlet is cut short: raise numerics.inlet",
    "peak contact pressure": "peak pressures beyond 4 GPa: check the load and the radius of "
    "curvature, or the materials",
}


def _validity_advice(text: str) -> str:
    return next(
        (advice for word, advice in _VALIDITY_ADVICE.items() if word in text),
        "see the validity checks in the physics documentation",
    )


def _jump_warning(dyn, built: BuiltCase) -> str:
    """The contact-loss (valve jump) warning: its intervals, how much of them falls in the
    cam event (cam lift above the jump threshold) and how much outside it, the maximum
    separation, and what to change (the built valvetrain's spring keys)."""
    js = dyn.jump_summary()
    lost = js["contact_lost_deg"]
    ev = dyn.event_mask()
    crank = dyn.crank_angle
    step = float(crank[1] - crank[0]) if crank.size > 1 else 0.0
    event = float(ev.sum()) * step
    edges = np.flatnonzero(np.diff(np.r_[0, ev.astype(np.int8), 0]))
    runs = list(zip(crank[edges[0::2]], crank[edges[1::2] - 1], strict=True))  # the event
    in_event = sum(max(0.0, min(b, e1) - max(a, e0)) for a, b in dyn.jumps for e0, e1 in runs)
    first = ", ".join(f"{a:.1f}–{b:.1f}°" for a, b in dyn.jumps[:3])
    more = f" and {len(dyn.jumps) - 3} more" if len(dyn.jumps) > 3 else ""
    where = f" of the {event:.0f}° cam event"
    if round(lost - in_event) >= 1:  # some of it off the lobe (bouncing on the base circle)
        where = (
            f", {in_event:.0f}° of the {event:.0f}° cam event and {lost - in_event:.0f}° "
            "outside it (base circle and the lowest lift)"
        )
    text = (
        f"the tappet loses contact with the cam (valve jump) for {lost:.1f}° crank{where} "
        f"({first}{more}); maximum separation (tappet lift − cam lift) "
        f"{js['max_separation_m'] * 1e3:.3g} mm at {js['max_separation_crank_deg']:.1f}°"
    )
    if event > 0 and lost > 0.1 * event:
        text += (
            ": the valvetrain does not follow the cam at this speed; films and friction "
            "there describe the impacts, not the design"
        )
    text += (
        f"; to keep the contact raise {built.valvetrain.spring_advice()}, or lower the moving "
        f"masses or the engine speed ({built.case.engine.speed_rpm:g} rpm)"
    )
    return text

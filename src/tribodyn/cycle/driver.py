"""Transient mixed-EHL along a cam cycle for one surface set.

The valvetrain dynamics gives, over the presented engine cycle, the contact force F(t)
(total over the cam width l), entraining and sliding speeds u_e, u_s and the radius of
curvature R. The line contact is solved per unit length, w = F/l, marching the transient
solver (:class:`tribodyn.TransientEHL`) at a fixed crank-angle step. Where F < F_min (the
cam on its base circle carries no load) there is no conjunction to solve: those samples are
marked unloaded and hold NaN film/pressure values by definition (``loaded`` is False).
Each loaded event starts from the steady solution at its first loaded sample.

One driver, :func:`march_cycle`, marches every EHL variant: the events, the time-error
control (:class:`_Marcher`), the sub-steps, the validity warnings and the per-sample
outputs are written once. A variant is a :class:`CycleMethod` — a transient solver that
satisfies :class:`EHLStepper` (:class:`~tribodyn.TransientEHL` or a subclass using its
hooks), the viscous friction of both shear laws on its film, and optional extra
:class:`Recorder` s (the thermal variant's temperatures).

Outputs are totals over the cam width: loads and friction forces [N], friction power
P = (F_v + F_b) u_s [W]; films [m]; pressures [Pa].
"""

from __future__ import annotations

import math
import re
from abc import ABC, abstractmethod
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, ClassVar, NamedTuple, Protocol

import numpy as np

from ..config.build import as_built, options_for
from ..contact.ehl import EHLOptions, EHLResult, TransientEHL
from ..contact.ehl.post_kernels import abs_sum
from ..contact.ehl.postprocess import shear_stress
from ..physics.asperity import Roughness
from ..physics.limits import unchecked
from ..physics.lubricant import Lubricant
from .data import SAMPLE_OUTPUTS, CycleInputs, SampleConditions, SetCycleResult

__all__ = [
    "CycleInputs",
    "SampleConditions",
    "SetCycleResult",
    "EHLStepper",
    "Recorder",
    "CycleMethod",
    "IsothermalCycle",
    "march_cycle",
    "march_for_set",
    "ehl_for_set",
    "PROFILE_POINTS",
]

#: Number of points on which p(x), h(x) of every step are stored: the step's whole solver
#: domain, resampled uniformly (its own x coordinate is stored with it).
PROFILE_POINTS = 512


#: Time-error control: a step whose estimated local error of the central film exceeds this
#: share is repeated in sub-steps (BDF2: error ∝ Δt³) …
TIME_TOL = 2e-3
#: … at most this many (they share the step's end conditions by interpolation).
MAX_SUBSTEPS = 8
#: A sample after a sub-stepped one starts with as many sub-steps and keeps them while
#: each sub-step's estimated error stays below this multiple of the tolerance.
_GUESS_SLACK = 2.0
#: … and the next sample starts with a single step again when the sub-steps' errors say
#: that fewer than this many would have done.
_GUESS_KEEP = 1.5
#: The time-error tolerance of the coupling's re-passes, which feed only the film law (see
#: :func:`ehl_for_set`): their film is needed to the coupling tolerance, not to the
#: reported accuracy.
COUPLING_TIME_TOL = 5e-3


class _FilmLevel(NamedTuple):
    """An accepted level of the march for the time-error estimate."""

    time: float  #: [s]
    central_film: float  #: [m]


class EHLStepper(Protocol):
    """What :func:`march_cycle` needs of a transient EHL solver (the interface of
    :class:`~tribodyn.TransientEHL`): a steady start, an implicit step to given conditions
    (load per unit length [N/m], R [m], u_e, u_s [m/s]) and checkpoints to redo steps."""

    def start_steady(
        self, load, radius, entrainment_speed, sliding_speed, time=0.0
    ) -> EHLResult: ...

    def step(self, dt, load, radius, entrainment_speed, sliding_speed) -> EHLResult: ...

    def checkpoint(self) -> Any: ...

    def rollback(self, checkpoint: Any) -> None: ...


class _Marcher:
    """Marches one loaded event of the transient EHL sample by sample with time-error
    control. The event starts from the steady solution at its first loaded sample (as
    in tribodyn 0.1: the implicit coupling measures the film from that start).

    * Each step's local error is estimated from the central film against its quadratic
      extrapolation from the three previous levels (Milne's device for BDF2 with constant
      steps: e ≈ (2/11)|h − h_pred|/h; after a start, with fewer levels, the linear
      extrapolation, |h − h_pred|/(3h), or |Δh|/(2h)). A step with
      e > TIME_TOL is repeated in m = ⌈(e/TIME_TOL)^(1/3)⌉ ≤ MAX_SUBSTEPS sub-steps with
      the conditions interpolated from the dynamics' output.
    * Time errors come in runs (engagement, impacts, u_e reversals): after a sub-stepped
      sample the next one starts with as many sub-steps instead of trying the whole
      step first. Each sub-step's error is estimated the same way; if one exceeds
      _GUESS_SLACK × TIME_TOL the sample is redone with more sub-steps, and the next
      sample tries a single step again when m·(e_max/TIME_TOL)^(1/3) < _GUESS_KEEP.
    """

    def __init__(
        self, tr: EHLStepper, inp: CycleInputs, min_load: float, time_tol: float = TIME_TOL
    ):
        self.tr, self.inp, self.min_load = tr, inp, float(min_load)
        self.time_tol = float(time_tol)
        self.levels: list[_FilmLevel] = []  # the last accepted levels, newest first
        self.t = 0.0
        self.substeps = 0
        self.guess = 1  # sub-steps to start the next sample with

    def _step(self, t):
        c = self.inp.at(t)
        w = max(c.force, self.min_load) / self.inp.width
        r = self.tr.step(t - self.t, w, c.radius, c.entrainment_speed, c.sliding_speed)
        self.t = t
        return r

    def start(self, i) -> EHLResult:
        inp = self.inp
        F = inp.contact_force
        t_i = float(inp.time[i])
        F_i, ue, us, R = F[i], inp.entrainment_speed[i], inp.sliding_speed[i], inp.radius[i]
        r = self.tr.start_steady(F_i / inp.width, R, ue, us, time=t_i)
        self.levels, self.t, self.substeps, self.guess = (
            [_FilmLevel(t_i, r.central_film)],
            t_i,
            1,
            1,
        )
        return r

    def _error(self, t, h) -> float:
        if not (math.isfinite(h) and h > 0.0):
            return math.inf
        lv = self.levels
        if len(lv) == 1:
            return abs(h - lv[0].central_film) / (2.0 * h)
        if len(lv) == 2:
            (t1, h1), (t0, h0) = lv
            pred = h1 + (t - t1) / (t1 - t0) * (h1 - h0)
            return abs(h - pred) / (3.0 * h)
        (t2, h2), (t1, h1), (t0, h0) = lv
        pred = (
            h0 * (t - t1) * (t - t2) / ((t0 - t1) * (t0 - t2))
            + h1 * (t - t0) * (t - t2) / ((t1 - t0) * (t1 - t2))
            + h2 * (t - t0) * (t - t1) / ((t2 - t0) * (t2 - t1))
        )
        return (2.0 / 11.0) * abs(h - pred) / h

    def _accept(self, t, r):
        self.levels = [_FilmLevel(t, r.central_film), *self.levels][:3]

    def _substeps(self, t_start, t_end, m):
        """March [t_start, t_end] in m equal sub-steps; returns the last result and the
        largest estimated local error of the sub-steps."""
        worst, r = 0.0, None
        for j in range(1, m + 1):
            t = t_start + (t_end - t_start) * j / m
            r = self._step(t)
            if r.converged:
                worst = max(worst, self._error(t, r.central_film))
            self._accept(t, r)
        return r, worst

    def _split(self, err) -> int:
        """Sub-steps that bring a one-step error ``err`` below the tolerance (∝ Δt³)."""
        return int(min(MAX_SUBSTEPS, max(2, math.ceil((err / self.time_tol) ** (1.0 / 3.0)))))

    def advance(self, i) -> EHLResult:
        t_end = float(self.inp.time[i])
        t_start = self.t
        cp = self.tr.checkpoint()
        m = self.guess
        if m > 1:
            # the previous sample needed sub-steps: start with as many, keep them if each
            # meets the tolerance (with a margin for the estimate), else redo with more
            levels = list(self.levels)
            r, worst = self._substeps(t_start, t_end, m)
            if worst > _GUESS_SLACK * self.time_tol and m < MAX_SUBSTEPS:
                self.tr.rollback(cp)
                self.t, self.levels = t_start, levels
                m = max(m + 1, self._split(worst * m**3))
                r, worst = self._substeps(t_start, t_end, m)
            # the sub-steps the next sample starts with (1: a single step is tried first)
            need = (worst * m**3 / self.time_tol) ** (1.0 / 3.0)
            self.guess = 1 if need < _GUESS_KEEP else min(MAX_SUBSTEPS, math.ceil(need))
            self.substeps = m
            return r
        r = self._step(t_end)
        err = self._error(t_end, r.central_film) if r.converged else 0.0
        if err > self.time_tol:
            m = self._split(err)
            self.tr.rollback(cp)
            self.t = t_start
            r, _ = self._substeps(t_start, t_end, m)
            self.guess = m
        else:
            self._accept(t_end, r)
        self.substeps = m
        return r


class Recorder(Protocol):
    """Per-sample outputs of a march: :meth:`record` is called for every loaded sample
    that gave a result (``stepper`` as it stands at the sample), :meth:`fields` gives the
    result's fields at the end."""

    def record(self, i: int, stepper: Any, r: EHLResult) -> None: ...

    def fields(self) -> dict: ...


class CycleMethod(ABC):
    """An EHL variant for :func:`march_cycle`: a fresh transient solver per loaded event,
    the viscous friction of both shear laws on a result's film, and the variant's own
    recorders and result fields (none here)."""

    #: the result class (:class:`SetCycleResult` or a subclass with the extra fields)
    result_type: ClassVar[type[SetCycleResult]] = SetCycleResult
    roughness: Roughness | None

    @abstractmethod
    def new_stepper(self) -> EHLStepper:
        """The transient solver of a new loaded event."""

    def law_friction(self, stepper: Any, r: EHLResult) -> dict[str, float]:
        """{"newtonian": …, "eyring": …}: the viscous friction per unit length ∫|τ_c| dx
        [N/m] of ``r``'s film and pressure under each shear law (the report compares
        them), on the uniform grid of ``r``."""
        shear = self.law_shear(stepper, r)
        dx = r.x[1] - r.x[0]
        return {
            law: abs_sum(np.asarray(shear(law), dtype=float)) * dx
            for law in ("newtonian", "eyring")
        }

    @abstractmethod
    def law_shear(self, stepper: Any, r: EHLResult) -> Callable[[str], np.ndarray]:
        """τ_c(law) [Pa]: the Couette shear stress of ``r``'s film and pressure under the
        shear law ``law`` ("newtonian" or "eyring")."""

    def recorders(self, n: int) -> list[Recorder]:
        """Extra recorders over ``n`` samples."""
        return []

    def result_fields(self) -> dict:
        """Extra constant fields of the result."""
        return {}


@dataclass
class IsothermalCycle(CycleMethod):
    """The isothermal transient EHL (:class:`~tribodyn.TransientEHL`)."""

    bodies: Any
    lubricant: Lubricant
    roughness: Roughness | None
    options: EHLOptions

    def new_stepper(self) -> TransientEHL:
        return TransientEHL(self.bodies, self.lubricant, self.roughness, options=self.options)

    def law_shear(self, stepper, r) -> Callable[[str], np.ndarray]:
        """The result's own law is its post-processed stress (the same call)."""
        opts = self.options
        return lambda law: (
            r.shear_stress
            if law == opts.viscous_model and r.shear_stress is not None
            else shear_stress(
                r.pressure, r.film, r.sliding_speed, self.lubricant, law, opts.limiting_shear
            )
        )

    @classmethod
    def for_set(cls, case, surface_set, options: EHLOptions | None = None) -> IsothermalCycle:
        """The method of one surface set of a case (Case or BuiltCase; its bodies,
        roughness and friction law; the case's lubricant and numerics, or ``options``)."""
        s, built = surface_set, as_built(case)
        return cls(s.bodies, built.lubricant, s.roughness, options or options_for(built, s))


class _SampleRecorder:
    """The outputs every variant records: :data:`SAMPLE_OUTPUTS` (totals over the
    width) and the p(x), h(x) profiles."""

    def __init__(self, n: int, inp: CycleInputs, method: CycleMethod):
        nan = np.full(n, np.nan)
        self.out = {k: nan.copy() for k in SAMPLE_OUTPUTS}
        k = PROFILE_POINTS
        self.x = np.full((n, k), np.nan)
        self.p = np.full((n, k), np.nan, dtype=np.float32)
        self.h = np.full((n, k), np.nan, dtype=np.float32)
        self.inp, self.method = inp, method

    def record(self, i, stepper, r):
        out, l, rough = self.out, self.inp.width, self.method.roughness
        out["central_film"][i] = r.central_film
        out["min_film"][i] = r.min_film
        out["max_pressure"][i] = float(r.pressure.max())
        out["hydrodynamic_load"][i] = r.hydrodynamic_load * l
        out["asperity_load"][i] = r.asperity_load * l
        out["viscous_friction"][i] = r.viscous_friction * l
        for law, f in self.method.law_friction(stepper, r).items():  # same film, both laws
            out[f"viscous_friction_{law}"][i] = f * l
        out["boundary_friction"][i] = r.boundary_friction * l
        out["rolling_friction"][i] = r.rolling_friction * l
        out["friction_power"][i] = (
            (r.viscous_friction + r.boundary_friction) * l * abs(self.inp.sliding_speed[i])
        )
        if rough is not None:
            out["lambda_ratio"][i] = r.min_film / rough.rms
        xs = np.linspace(r.x[0], r.x[-1], PROFILE_POINTS)
        self.x[i] = xs
        self.p[i] = np.interp(xs, r.x, r.pressure)
        self.h[i] = np.interp(xs, r.x, r.film)

    def fields(self) -> dict:
        return {"x": self.x, "pressure": self.p, "film": self.h, **self.out}


def march_cycle(
    inp: CycleInputs,
    name: str,
    label: str,
    method: CycleMethod,
    *,
    min_load: float = 5.0,
    time_tol: float = TIME_TOL,
) -> SetCycleResult:
    """March an EHL variant (``method``) over the cycle for one surface set: each loaded
    event (F ≥ ``min_load``) from the steady solution at its first sample, with the
    time-error control of :class:`_Marcher` (``time_tol``: the local time error of h_c
    above which a step is sub-stepped). A step that raises or does not converge is
    reported in ``failures``; validity warnings are counted by kind."""
    import time as _time

    t_start = _time.perf_counter()
    n = inp.crank_angle.size
    loaded = inp.contact_force >= min_load
    converged = np.ones(n, dtype=bool)
    iterations = np.zeros(n, dtype=int)
    substeps = np.zeros(n, dtype=np.int16)
    recorders: list[Recorder] = [_SampleRecorder(n, inp, method), *method.recorders(n)]
    failures = []
    validity: dict[str, tuple[int, float, str]] = {}
    tr = None
    march = None
    for i in range(n):
        if not loaded[i]:
            tr = None  # the event ended: the next one starts afresh
            continue
        try:
            if tr is None:
                tr = method.new_stepper()
                march = _Marcher(tr, inp, min_load, time_tol)
                r = march.start(i)
            else:
                assert march is not None  # made with tr
                r = march.advance(i)
        except Exception as exc:  # a step that raises is reported, not fatal
            converged[i] = False
            failures.append((float(inp.crank_angle[i]), f"{type(exc).__name__}: {exc}"))
            tr = None
            continue
        substeps[i] = march.substeps
        converged[i] = r.converged
        iterations[i] = r.iterations
        if not r.converged:
            failures.append((float(inp.crank_angle[i]), r.message))
        for text in r.warnings:  # outside the model's validity (contact.ehl.validity)
            kind = re.sub(r"[-+]?\d[\d.eE+-]*", "#", text)
            count, first, example = validity.get(kind, (0, float(inp.crank_angle[i]), text))
            validity[kind] = (count + 1, first, example)
        for rec in recorders:
            rec.record(i, tr, r)
    fields: dict = {}
    for rec in recorders:
        fields.update(rec.fields())
    return method.result_type(
        name=name,
        label=label,
        crank_angle=inp.crank_angle.copy(),
        loaded=loaded,
        converged=converged,
        iterations=iterations,
        failures=failures,
        validity=validity,
        runtime_s=_time.perf_counter() - t_start,
        substeps=substeps,
        **fields,
        **method.result_fields(),
    )


def march_for_set(
    case,
    surface_set,
    inputs: CycleInputs,
    method: CycleMethod,
    *,
    time_tol: float = TIME_TOL,
) -> SetCycleResult:
    """:func:`march_cycle` of ``method`` for one surface set of a case (Case or
    BuiltCase): the set's name and label, the case's tappet rotation and
    ``numerics.min_load``."""
    s, built = surface_set, as_built(case)
    return march_cycle(
        inputs.with_rotation(built.tappet_rotation),
        s.name,
        s.coating_label,
        method,
        min_load=built.case.numerics.min_load,
        time_tol=time_tol,
    )


def ehl_for_set(
    case, surface_set, inputs: CycleInputs, *, film_law_only: bool = False
) -> SetCycleResult:
    """The isothermal march (:class:`IsothermalCycle`, :func:`march_for_set`) of one
    surface set of a case (Case or BuiltCase; its bodies, roughness and friction law; the
    case's lubricant and numerics).

    ``film_law_only``: the pass only feeds the implicit coupling's film law (the
    coupling's re-passes), which needs the film to the coupling tolerance: the grid has
    ``numerics.coupling_n`` nodes (at most ``numerics.n`` when that is set) and the
    time-error tolerance is :data:`COUPLING_TIME_TOL`."""
    s, built = surface_set, as_built(case)
    n = built.case.numerics
    opts = options_for(built, s)
    time_tol = TIME_TOL
    if film_law_only:
        time_tol = COUPLING_TIME_TOL
        nodes = n.coupling_n
        if nodes:  # never finer than the study's own fixed grid (both checked at load)
            opts = unchecked(EHLOptions, **{**opts.__dict__, "n": min(nodes, n.n or nodes)})
    method = IsothermalCycle.for_set(built, s, opts)
    return march_for_set(built, s, inputs, method, time_tol=time_tol)

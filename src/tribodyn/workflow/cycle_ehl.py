"""Transient mixed-EHL along a cam cycle for one surface set.

The valvetrain dynamics gives, over the presented engine cycle, the contact force F(t)
(total over the cam width l), entraining and sliding speeds u_e, u_s and the radius of
curvature R. The line contact is solved per unit length, w = F/l, marching the transient
solver (:class:`tribodyn.TransientEHL`) at a fixed crank-angle step. Where F < F_min (the
cam on its base circle carries no load) there is no conjunction to solve: those samples are
marked unloaded and hold NaN film/pressure values by definition (``loaded`` is False).
Each loaded event starts from the steady solution at its first loaded sample.

Outputs are totals over the cam width: loads and friction forces [N], friction power
P = (F_v + F_b) u_s [W]; films [m]; pressures [Pa].
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..contact.ehl import EHLOptions, TransientEHL
from ..contact.ehl.postprocess import shear_stress
from ..physics.lubricant import Lubricant

__all__ = ["CycleInputs", "SetCycleResult", "ehl_along_cycle", "ehl_for_set",
           "PROFILE_POINTS"]

#: Number of points on which p(x), h(x) of every step are stored: the step's whole solver
#: domain, resampled uniformly (its own x coordinate is stored with it).
PROFILE_POINTS = 512


@dataclass
class CycleInputs:
    """Conjunction conditions over the presented cycle (from the dynamics)."""

    crank_angle: np.ndarray       #: [deg], strictly increasing
    time: np.ndarray              #: [s]
    contact_force: np.ndarray     #: total over the width [N]
    entrainment_speed: np.ndarray  #: [m/s]
    sliding_speed: np.ndarray     #: [m/s]
    radius: np.ndarray            #: radius of curvature [m]
    width: float                  #: cam width [m]

    @classmethod
    def from_dynamics(cls, res, crank_step_deg: float, width: float) -> "CycleInputs":
        """Sample a :class:`~tribodyn.valvetrain.ValvetrainResult` every crank_step_deg."""
        c0, c1 = float(res.crank_angle[0]), float(res.crank_angle[-1])
        n = int(round((c1 - c0) / crank_step_deg)) + 1
        crank = c0 + crank_step_deg * np.arange(n)
        crank = crank[crank <= c1 + 1e-9]

        def at(v):
            return np.interp(crank, res.crank_angle, v)

        return cls(crank, at(res.time), np.maximum(at(res.contact_force), 0.0),
                   at(res.entrainment_speed), at(res.sliding_speed),
                   at(res.radius_of_curvature), float(width))


@dataclass
class SetCycleResult:
    """Transient EHL results of one surface set over the cycle (totals over the width)."""

    name: str
    label: str
    crank_angle: np.ndarray
    loaded: np.ndarray
    converged: np.ndarray
    iterations: np.ndarray
    central_film: np.ndarray
    min_film: np.ndarray
    max_pressure: np.ndarray
    hydrodynamic_load: np.ndarray
    asperity_load: np.ndarray
    viscous_friction: np.ndarray
    viscous_friction_newtonian: np.ndarray  #: the same film and pressure, Newtonian law
    viscous_friction_eyring: np.ndarray     #: the same film and pressure, Eyring law
    boundary_friction: np.ndarray
    rolling_friction: np.ndarray
    friction_power: np.ndarray
    lambda_ratio: np.ndarray       #: h_min/σ
    x: np.ndarray                  #: (crank, k) profile positions [m], NaN where unloaded
    pressure: np.ndarray           #: (crank, k) [Pa], NaN where unloaded
    film: np.ndarray               #: (crank, k) [m]
    failures: list = field(default_factory=list)   #: [(crank_deg, message)]
    runtime_s: float = 0.0

    @property
    def friction(self) -> np.ndarray:
        return self.viscous_friction + self.boundary_friction


def ehl_along_cycle(inp: CycleInputs, name: str, label: str, bodies, lubricant: Lubricant,
                    roughness, options: EHLOptions, *, min_load: float = 5.0,
                    progress=None) -> SetCycleResult:
    """March the transient EHL over the cycle for one surface set.

    ``progress(i, n)`` is called after each sample (for progress bars).
    """
    import time as _time

    t_start = _time.perf_counter()
    n = inp.crank_angle.size
    nan = np.full(n, np.nan)
    out = {k: nan.copy() for k in ("central_film", "min_film", "max_pressure",
                                   "hydrodynamic_load", "asperity_load", "viscous_friction",
                                   "viscous_friction_newtonian", "viscous_friction_eyring",
                                   "boundary_friction", "rolling_friction", "friction_power",
                                   "lambda_ratio")}
    loaded = inp.contact_force >= min_load
    converged = np.ones(n, dtype=bool)
    iterations = np.zeros(n, dtype=int)
    k = PROFILE_POINTS
    x_prof = np.full((n, k), np.nan)
    p_prof = np.full((n, k), np.nan, dtype=np.float32)
    h_prof = np.full((n, k), np.nan, dtype=np.float32)
    failures = []
    l = inp.width
    tr = None
    for i in range(n):
        if not loaded[i]:
            tr = None                       # the event ended: the next one starts afresh
            if progress:
                progress(i + 1, n)
            continue
        w = inp.contact_force[i] / l
        args = (w, inp.radius[i], inp.entrainment_speed[i], inp.sliding_speed[i])
        try:
            if tr is None:
                tr = TransientEHL(bodies, lubricant, roughness, options=options)
                r = tr.start_steady(*args, time=inp.time[i])
            else:
                r = tr.step(inp.time[i] - inp.time[i - 1], *args)
        except Exception as exc:            # a step that raises is reported, not fatal
            converged[i] = False
            failures.append((float(inp.crank_angle[i]), f"{type(exc).__name__}: {exc}"))
            tr = None
            if progress:
                progress(i + 1, n)
            continue
        converged[i] = r.converged
        iterations[i] = r.iterations
        if not r.converged:
            failures.append((float(inp.crank_angle[i]), r.message))
        out["central_film"][i] = r.central_film
        out["min_film"][i] = r.min_film
        out["max_pressure"][i] = float(r.pressure.max())
        out["hydrodynamic_load"][i] = r.hydrodynamic_load * l
        out["asperity_load"][i] = r.asperity_load * l
        out["viscous_friction"][i] = r.viscous_friction * l
        for law in ("newtonian", "eyring"):      # both laws on the same film (report)
            tau = shear_stress(r.pressure, r.film, r.sliding_speed, lubricant, law,
                               options.limiting_shear)
            out[f"viscous_friction_{law}"][i] = float(np.sum(np.abs(tau))) * (
                r.x[1] - r.x[0]) * l
        out["boundary_friction"][i] = r.boundary_friction * l
        out["rolling_friction"][i] = r.rolling_friction * l
        out["friction_power"][i] = (r.viscous_friction + r.boundary_friction) * l * abs(
            inp.sliding_speed[i])
        if roughness is not None:
            out["lambda_ratio"][i] = r.min_film / roughness.rms
        xs = np.linspace(r.x[0], r.x[-1], k)
        x_prof[i] = xs
        p_prof[i] = np.interp(xs, r.x, r.pressure)
        h_prof[i] = np.interp(xs, r.x, r.film)
        if progress:
            progress(i + 1, n)
    return SetCycleResult(
        name=name, label=label, crank_angle=inp.crank_angle.copy(), loaded=loaded,
        converged=converged, iterations=iterations, x=x_prof, pressure=p_prof, film=h_prof,
        failures=failures, runtime_s=_time.perf_counter() - t_start, **out)


def ehl_for_set(case, surface_set, inputs: CycleInputs, progress=None) -> SetCycleResult:
    """:func:`ehl_along_cycle` for one surface set of a case (its bodies, roughness and
    friction law; the case's lubricant and numerics)."""
    s = surface_set
    return ehl_along_cycle(inputs, s.name, s.coating_label, s.bodies, case.lubricant(),
                           s.roughness, case.ehl_options(s),
                           min_load=case.numerics.min_load, progress=progress)

"""Subsurface stresses, safety factors and wear of the cam and the tappet along a cycle.

From a set's cycle EHL pass (:class:`~tribodyn.cycle.data.SetCycleResult`: the
pressure and film profile of every loaded sample) the surface loads of each body are
rebuilt (:func:`tribodyn.contact.stress.profile_surface_loads`: p + p_a, viscous and
boundary shear with their signs) and its stresses evaluated
(:mod:`tribodyn.physics.stress`). Outputs: for each body the traces of the peaks
(von Mises in coating and substrate, largest tensile principal stress on the surface and
in the coating, interface shear and tension) with their positions, each peak's maximum
over the cycle with its crank angle, and the safety factors against the strengths
(:mod:`tribodyn.physics.strength`; min over the cycle = strength / cycle maximum).
Archard wear per cycle and hours to wear through the coating: :func:`wear_for_set`. The
von Mises field at the instant of greatest risk (the report's stress map) is computed with
the peaks: :mod:`~tribodyn.workflow.stress_map`.
"""

from __future__ import annotations

import math
import time as _time
from collections import OrderedDict
from dataclasses import dataclass, field

import numpy as np

from ..config.build import as_built, build, options_for
from ..contact.stress import batch_surface_loads, loaded_ends, loaded_half_width
from ..physics.asperity_stress import micro_contact_estimate
from ..physics.materials import as_bodies, reduced_modulus
from ..physics.strength import (
    TYPICAL_STRENGTH,
    archard_wear_depth_per_cycle,
    hours_to_wear_through,
    safety_factors,
)
from ..physics.stress import PEAKS, StressOperator  # PEAKS: the peaks traced per body
from .conventions import finite
from .stress_map import StressMap, stress_map

__all__ = [
    "PEAKS",
    "BodyStressTrace",
    "CycleStress",
    "stress_along_cycle",
    "stress_for_set",
    "wear_for_set",
    "MODE_PEAK",
    "closest_failure",
    "set_stress_summary",
    "asperity_estimate",
]


@dataclass
class BodyStressTrace:
    """Peak traces of one body along the cycle: value [Pa], x and z [m] of each peak per
    EHL sample (NaN where unloaded or where the peak does not exist, e.g. coating peaks
    of an uncoated body)."""

    body: str
    value: dict
    x: dict
    z: dict

    def maximum(self, name: str, crank_angle: np.ndarray) -> dict:
        """The cycle maximum of peak ``name``: value [Pa], crank angle [deg], x, z [m]."""
        v = self.value[name]
        if not np.any(np.isfinite(v)):
            return {"value": math.nan, "crank_angle": math.nan, "x": math.nan, "z": math.nan}
        i = int(np.nanargmax(v))
        return {
            "value": float(v[i]),
            "crank_angle": float(crank_angle[i]),
            "x": float(self.x[name][i]),
            "z": float(self.z[name][i]),
        }


@dataclass
class CycleStress:
    """Stresses of the cam and the tappet of one surface set along the cycle."""

    name: str
    crank_angle: np.ndarray
    cam: BodyStressTrace
    tappet: BodyStressTrace
    #: {"cam"|"tappet": {peak: {value, crank_angle, x, z}}}
    maxima: dict = field(default_factory=dict)
    #: {"cam"|"tappet": {mode: strength / cycle maximum}} (see physics.strength)
    safety_factors: dict = field(default_factory=dict)
    evaluated: int = 0  #: samples evaluated
    runtime_s: float = 0.0
    #: the von Mises field at the instant of greatest risk (workflow.stress_map)
    map: StressMap | None = None


def stress_along_cycle(
    result,
    inputs,
    bodies,
    lubricant,
    roughness=None,
    options=None,
    *,
    strengths: dict | None = None,
) -> CycleStress:
    """Peak stresses of the cam and the tappet at every loaded sample of a set's cycle
    EHL pass (``result``: SetCycleResult, ``inputs``: its CycleInputs).

    ``options``: the set's :class:`~tribodyn.EHLOptions` (friction laws; default the
    defaults). ``strengths``: {"cam": (substrate, coating|None), "tappet": (…)} of
    :class:`~tribodyn.physics.strength.Strength` (default: typical steel, no coating
    strength). Depths: in the coating h/2 and h, below it geometric levels from half the
    grid spacing to beyond 1.5 b. Evaluated: all loaded, converged samples with a
    profile; the others stay NaN."""
    from ..contact.ehl.options import EHLOptions

    t0 = _time.perf_counter()
    opts = options if options is not None else EHLOptions()
    pair = as_bodies(bodies)
    crank = np.asarray(result.crank_angle, float)
    n = crank.size
    names = ("cam", "tappet")
    traces = {
        b: BodyStressTrace(
            b,
            {k: np.full(n, np.nan) for k in PEAKS},
            {k: np.full(n, np.nan) for k in PEAKS},
            {k: np.full(n, np.nan) for k in PEAKS},
        )
        for b in names
    }
    # samples whose EHL did not converge are left out (NaN): their profile is the last
    # iterate, not a solution
    conv = np.asarray(getattr(result, "converged", np.ones(n, bool)), bool)
    ok = np.asarray(result.loaded, bool) & conv & np.all(np.isfinite(result.pressure), axis=1)
    samples = np.flatnonzero(ok)
    loads = None
    if samples.size:  # all profiles at once (the recorded ones share their length)
        xs = np.asarray(result.x, float)[samples]
        ld = batch_surface_loads(
            xs,
            np.asarray(result.pressure, float)[samples],
            np.asarray(result.film, float)[samples],
            np.asarray(inputs.sliding_speed, float)[samples],
            pair,
            lubricant,
            roughness,
            opts,
        )
        loads = (xs, ld.pressure, ld.traction_cam, ld.traction_tappet)
    _evaluate(samples, loads, pair, traces)
    out = CycleStress(
        name=getattr(result, "name", ""),
        crank_angle=crank,
        cam=traces["cam"],
        tappet=traces["tappet"],
        evaluated=len(samples),
    )
    strengths = strengths or {}
    for name, body in zip(names, pair, strict=True):
        tr = traces[name]
        out.maxima[name] = {k: tr.maximum(k, crank) for k in PEAKS}
        sub, coat = strengths.get(name, (TYPICAL_STRENGTH["steel"], None))
        peaks = {k: out.maxima[name][k]["value"] for k in PEAKS}
        if sub is None:  # no strength of the substrate material: its factors are NaN
            sf = {"substrate_yield": math.nan, "surface_tension": math.nan}
            if coat is not None and body.is_coated:
                sf.update(safety_factors(peaks, TYPICAL_STRENGTH["steel"], coat))
                sf["substrate_yield"] = math.nan
        else:
            sf = safety_factors(peaks, sub, coat if body.is_coated else None)
        if body.is_coated and coat is None:
            sf.update(
                coating_tension=math.nan,
                coating_yield=math.nan,
                interface_shear=math.nan,
                interface_tension=math.nan,
            )
        out.safety_factors[name] = sf
    worst = closest_failure(out.safety_factors, out.maxima)
    if worst is not None:  # the map at the closest failure's sample
        trace = getattr(out, worst["body"]).value[MODE_PEAK[worst["mode"]]]
        out.map = stress_map(worst, trace, result, inputs, pair, lubricant, roughness, opts)
    out.runtime_s = _time.perf_counter() - t0
    return out


#: grid classes: spacings Δ₀ 2^(k/2) (a sample's loads are resampled onto the class
#: spacing at or below its own, so at most √2 finer), one stress operator per class
_CLASS_STEP = 0.5
#: a class with fewer samples is merged into the next finer one
_MIN_CLASS = 8
#: samples per batched transform (memory: batch × depths × 3 × FFT length × 12 bytes of
#: single-precision spectra and fields: ≈ 15 MB at 32 × 20 × 3 × 2000)
_BATCH = 32
#: depths below the coating, in units of the class spacing: geometric from 2Δ to 400Δ
#: (the EHL profiles resolve the loaded half-width b with 50–200 points, so this reaches
#: beyond 1.5 b with a relative step of 42 %); the substrate's von Mises peak is refined
#: by a parabola in ln z through its level and the neighbours: within 0.2 % of a 40-level
#: evaluation along the paper case's cycle
_REL_DEPTHS = np.geomspace(2.0, 400.0, 16)


#: stress operators kept in a process [bytes of transfer functions]: the surface sets of a
#: case share bodies (the uncoated cam) and their class grids, so one set's operators serve
#: the next (least recently used dropped first)
_KEEP_BYTES = 2**27
_OPERATORS: OrderedDict = OrderedDict()


def _operator(n: int, dx: float, body, depths: np.ndarray) -> StressOperator:
    """The :class:`StressOperator` of ``n`` nodes of spacing ``dx`` [m] for ``body`` at
    ``depths`` [m], reused while kept (:data:`_KEEP_BYTES`)."""
    key = (n, dx, body, depths.tobytes())
    op = _OPERATORS.get(key)
    if op is not None:
        _OPERATORS.move_to_end(key)
        return op
    op = StressOperator(n, dx, body, depths)
    _OPERATORS[key] = op
    # the double- and single-precision transfers of each
    while (
        len(_OPERATORS) > 1
        and 1.5 * sum(o.transfer_bytes for o in _OPERATORS.values()) > _KEEP_BYTES
    ):
        _OPERATORS.popitem(last=False)
    return op


def _evaluate(samples: np.ndarray, loads, pair, traces: dict) -> None:
    """Peaks of both bodies at the ``samples`` written into their ``traces``
    ({"cam"|"tappet": BodyStressTrace}) from ``loads`` (x, p, q_cam, q_tappet), arrays
    (len(samples), k). Samples are grouped by grid spacing into classes with one
    operator per body, so the transfer functions are built a few times per cycle, not
    per sample."""
    if loads is None or not len(samples):
        return
    xs, ps, qs = loads[0], loads[1], loads[2:]
    dxs = [float(v) for v in xs[:, 1] - xs[:, 0]]
    dx0 = min(dxs)
    cls = [int(math.floor(math.log2(d / dx0) / _CLASS_STEP + 1e-9)) for d in dxs]
    # a class with few samples joins the next finer populated one (a build costs more
    # than the few larger transforms)
    count: dict = {}
    for k in cls:
        count[k] = count.get(k, 0) + 1
    target: dict = {}
    for k in sorted(count):
        finer = [t for t in target.values() if t < k]
        target[k] = max(finer) if count[k] < _MIN_CLASS and finer else k
    # the window: where p > 1e-3 max p, widened by b/3 each side (the film's shear
    # outside it, μu_s/h over a thick film, is below 1e-4 of p_max)
    (first, final), half = loaded_ends(ps, 1e-3), loaded_half_width(xs, ps)
    plan: dict = {}
    for r in range(len(samples)):
        k = target[cls[r]]
        dxc = dx0 * 2.0 ** (k * _CLASS_STEP)
        x, b = xs[r], float(half[r])
        lo = max(float(x[first[r]]) - b / 3.0, float(x[0]))
        hi = min(float(x[final[r]]) + b / 3.0, float(x[-1]))
        m = int(math.floor((hi - lo) / dxc)) + 1
        plan[r] = (k, dxc, lo, m)
    sizes: dict = {}
    for k, _, _, m in plan.values():
        sizes[k] = max(sizes.get(k, 0), m)
    for k in sorted(sizes):
        members = [r for r in plan if plan[r][0] == k]
        dxc = plan[members[0]][1]
        n = 32 * math.ceil(sizes[k] / 32)
        x0 = np.array([plan[r][2] for r in members])
        xg = x0[:, None] + dxc * np.arange(n)[None, :]
        # the loads resampled onto the class grid (zero beyond the profile's end)
        pr = np.zeros((len(members), n))
        qr = np.zeros((2, len(members), n))
        for j, r in enumerate(members):
            x = xs[r]
            pr[j] = np.interp(xg[j], x, ps[r], right=0.0)
            for body in range(2):
                qr[body, j] = np.interp(xg[j], x, qs[body][r], right=0.0)
        for j, (name, body) in enumerate((("cam", pair[0]), ("tappet", pair[1]))):
            z = dxc * _REL_DEPTHS
            if body.coating is not None:
                hc = body.coating.thickness
                # z = h itself is always evaluated (StressOperator: both sides)
                z = np.concatenate([[0.5 * hc], z[z > hc]])
            op = _operator(n, dxc, body, z)
            tr = traces[name]
            for c0 in range(0, len(members), _BATCH):
                sl = slice(c0, c0 + _BATCH)
                at = samples[members[sl]]
                for key, (v, xp, zp) in op.peaks_batch(pr[sl], qr[j, sl], x0[sl]).items():
                    tr.value[key][at], tr.x[key][at], tr.z[key][at] = v, xp, zp


def stress_for_set(case, surface_set, result, inputs, **kwargs) -> CycleStress:
    """:func:`stress_along_cycle` for a surface set of a case (Case or BuiltCase; its
    bodies, roughness and friction laws, the case's lubricant; ``strengths`` as there)."""
    built = as_built(case)
    return stress_along_cycle(
        result,
        inputs,
        surface_set.bodies,
        built.lubricant,
        surface_set.roughness,
        options_for(built, surface_set),
        **kwargs,
    )


def wear_for_set(
    result,
    inputs,
    wear_coefficient: float,
    swept_length: float,
    thickness: float | None = None,
    cycles_per_hour: float | None = None,
) -> dict:
    """Archard wear of one surface over the presented cycle (one cam revolution):
    mean depth per cycle [m] spread over ``swept_length`` [m] with the user's
    ``wear_coefficient`` k [m³/(N m)] (typical values: physics.strength), and, given the
    coating ``thickness`` [m] and ``cycles_per_hour`` (cam revolutions per hour), the
    hours until it is worn through."""
    w = np.asarray(result.asperity_load, float) / inputs.width  # N/m
    depth = archard_wear_depth_per_cycle(
        inputs.time, w, inputs.sliding_speed, wear_coefficient, swept_length
    )
    out = {"depth_per_cycle_m": depth}
    if thickness is not None and cycles_per_hour is not None:
        out["hours_to_wear_through"] = hours_to_wear_through(thickness, depth, cycles_per_hour)
    return out


#: failure mode (physics.strength.safety_factors) → the peak it is measured against
MODE_PEAK = {
    "substrate_yield": "max_von_mises_substrate",
    "surface_tension": "max_tension_surface",
    "coating_tension": "max_tension_coating",
    "coating_yield": "max_von_mises_coating",
    "interface_shear": "max_interface_shear",
    "interface_tension": "max_interface_tension",
}


def closest_failure(factors: dict, maxima: dict) -> dict | None:
    """The failure mode with the smallest safety factor over both bodies: mode, body,
    safety factor (strength / cycle maximum), the stress [Pa], and where (x along the
    contact, z depth [m]) and when (crank angle [deg]) it peaks. ``factors`` and
    ``maxima`` as :attr:`CycleStress.safety_factors` and :attr:`CycleStress.maxima`. None
    when no factor is finite (no strengths, or nothing loaded)."""
    best = None
    for body in ("cam", "tappet"):
        for mode, sf in factors.get(body, {}).items():
            if not math.isfinite(sf) or (best is not None and sf >= best["safety_factor"]):
                continue
            mx = maxima[body][MODE_PEAK[mode]]
            best = {
                "mode": mode,
                "body": body,
                "safety_factor": float(sf),
                "stress_Pa": mx["value"],
                "crank_deg": mx["crank_angle"],
                "x_m": mx["x"],
                "z_m": mx["z"],
            }
    return best


def asperity_estimate(result, bodies, roughness, strengths: dict | None = None) -> dict | None:
    """ESTIMATE of the asperity-scale stresses (:mod:`tribodyn.physics.asperity_stress`:
    one Hertzian summit at the mean micro-contact pressure p_a/(A_a/A), frictionless,
    homogeneous) at the smallest film of the cycle, where that pressure is largest, for
    the surface material of each body; with the factors yield / von Mises and tensile
    strength / edge tension of that material (``strengths`` as for
    :func:`stress_along_cycle`; None: no factors). None without roughness or a loaded,
    converged sample. Reported beside the EHL-scale margins, never mixed with them."""
    if roughness is None or roughness.law is not None:
        # a measured-surface law has no Greenwood–Tripp summit radius β to build a
        # Hertzian summit from; its micro-contact pressure is the boundary-element one
        return None
    ok = np.asarray(result.loaded, bool) & np.asarray(result.converged, bool)
    hmin = np.where(ok, np.asarray(result.min_film, float), np.nan)
    if not np.any(np.isfinite(hmin)):
        return None
    i = int(np.nanargmin(hmin))
    pair = as_bodies(bodies)
    e_s = reduced_modulus(pair, surface=True)
    out: dict = {"crank_deg": float(result.crank_angle[i]), "gap_m": float(hmin[i])}
    for name, body in zip(("cam", "tappet"), pair, strict=True):
        est = micro_contact_estimate(roughness, float(hmin[i]), e_s, body.surface.nu)
        sub, coat = (strengths or {}).get(name, (None, None))
        mat = coat if body.is_coated else sub
        # None where no summit touches (F_2 = 0 beyond h/σ ≈ 37)
        entry = {
            "gap_ratio": finite(est.gap_ratio),
            "mean_pressure_Pa": finite(est.mean_pressure),
            "peak_pressure_Pa": finite(est.peak_pressure),
            "radius_m": finite(est.radius),
            "radius_over_summit": finite(est.radius_over_summit),
            "max_von_mises_Pa": finite(est.max_von_mises),
            "depth_m": finite(est.depth),
            "edge_tension_Pa": finite(est.edge_tension),
            "safety_factor_yield": finite(mat.yield_stress / est.max_von_mises)
            if mat is not None
            else None,
            "safety_factor_tension": finite(mat.tensile_strength / est.edge_tension)
            if mat is not None
            else None,
        }
        if body.coating is not None:
            entry["radius_over_thickness"] = finite(est.radius / body.coating.thickness)
        out[name] = entry
    return out


def set_stress_summary(study, name: str) -> dict:
    """The stress and wear entries of surface set ``name`` in ``summary.json``: the
    closest failure mode (where and when, its margin), the smallest safety factor, the
    tappet's factors by mode (flat keys ``safety_factor_<mode>``, also sweep outputs),
    both bodies' factors and cycle maxima, and the Archard wear of the tappet surface:
    depth per cycle, hours to wear through the coating, and the depth after
    ``[stress] running_hours``. The wear is spread over the band of the tappet face
    swept by the contact (range of the contact offset e over the cycle; a tappet that
    does not rotate). Empty when the set's stresses were not computed."""
    cs = study.stresses.get(name)
    if cs is None:
        return {}
    case = study.case
    own = build(case).set(name)
    s = own.surface
    worst = closest_failure(
        cs.safety_factors, cs.maxima
    )  # crank_deg: the run's crank angle (conventions.CRANK_ANGLE)
    out: dict = {
        "stress_closest_failure": worst,
        "min_safety_factor": worst["safety_factor"] if worst else None,
    }
    est = asperity_estimate(study.set(name), s.bodies, s.roughness, own.strengths)
    if est is not None:
        out["asperity_scale_estimate"] = est
    for mode in MODE_PEAK:
        out[f"safety_factor_{mode}"] = finite(cs.safety_factors["tappet"].get(mode))
    out["safety_factors"] = {
        b: {m: finite(v) for m, v in sf.items()} for b, sf in cs.safety_factors.items()
    }
    out["stress_maxima"] = {
        b: {k: {kk: finite(vv) for kk, vv in v.items()} for k, v in mx.items()}
        for b, mx in cs.maxima.items()
    }
    k, src = own.wear_coefficient, own.wear_source
    out.update(
        wear_coefficient_m3_per_Nm=k,
        wear_coefficient_source=src or None,
        wear_depth_per_cycle_m=None,
        hours_to_wear_through=None,
    )
    if k is not None:
        swept = float(np.ptp(study.dynamics.contact_offset))
        cph = case.cam_speed / (2.0 * math.pi) * 3600.0  # cam revolutions (cycles) per hour
        thick = s.coating.thickness if s.coating is not None else None
        w = wear_for_set(study.set(name), study.inputs, k, swept, thick, cph)
        out["wear_depth_per_cycle_m"] = w["depth_per_cycle_m"]
        out["wear_swept_length_m"] = swept
        if "hours_to_wear_through" in w:
            out["hours_to_wear_through"] = finite(w["hours_to_wear_through"])
        hours = case.stress.running_hours
        if hours is not None:
            depth = w["depth_per_cycle_m"] * cph * hours
            out["running_hours"] = hours
            out["wear_depth_after_running_hours_m"] = depth
            if thick is not None:
                out["worn_through_in_running_hours"] = bool(depth >= thick)
    return out

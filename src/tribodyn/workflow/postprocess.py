"""Analysis of a finished cycle study: event mask, representative points, Greenwood-chart
regimes, surface-set roles, film-gain statistics and the summary (``summary.json``).

Everything here is computed once from the study's arrays (no solver calls) and attached
to the study as :class:`Analysis`, so the output layer only formats what the study already
knows.

Film-gain rule (:func:`film_gain_mask`): the gain of a coated set over the reference,
100 (h_c,set/h_c,ref − 1) %, is evaluated only at EHL samples that are (a) inside the cam
event (cam lift above the jump threshold, 10 µm), (b) loaded and converged in both sets,
and (c) not within the first :data:`GAIN_SETTLE_STEPS` steps after the contact engages
(each loaded event starts from a steady solution and its first steps carry the transient
of that start). Reported: the gain at the representative points, the median and 95th
percentile of |gain| over the admitted samples, and their maximum
(``max_film_gain_vs_uncoated_pct``, the robust maximum under the rule).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Protocol

import numpy as np
from scipy.optimize import brentq

from .. import paper
from ..config.build import as_built, build
from ..cycle.coupling import implicit_vs_explicit_metrics
from ..physics.materials import reduced_modulus
from ..physics.regimes import greenwood_chart_groups, hamrock_groups, moes_central
from .conventions import CHANGE, CRANK_ANGLE, change_pct, finite
from .regime_map import RegimeMap, regime_code, regime_map
from .thermal_study import thermal_summary
from .variables_sweep import COMPARISON_SCALARS

if TYPE_CHECKING:
    from ..config.case import Case
    from ..cycle.data import CycleInputs, SetCycleResult
    from ..valvetrain.dynamics import ValvetrainResult
    from .engineering import Engineering
    from .model_comparison import ModelComparison

__all__ = [
    "Analysis",
    "analyse",
    "surface_roles",
    "event_mask",
    "representative_points",
    "film_gain_mask",
    "film_gain_statistics",
    "modulus_factor_for_gain",
    "GainFactor",
    "GAIN_SETTLE_STEPS",
    "FILM_GAIN_RULE",
]

#: Samples excluded from the film-gain statistics after each engagement of the contact.
GAIN_SETTLE_STEPS = 5
FILM_GAIN_RULE = (
    "film gain 100·(h_c,set/h_c,reference − 1) % at EHL samples inside the cam event "
    "(lift > 10 µm), loaded and converged in both sets, excluding the first "
    f"{GAIN_SETTLE_STEPS} steps after each engagement; max = robust maximum over those "
    "samples, median and p95 of |gain|, and the gain at the six representative points"
)


class StudyResults(Protocol):
    """What the analysis reads of a finished cycle study (a
    :class:`~tribodyn.workflow.cycle.CycleStudy`)."""

    case: Case
    dynamics: ValvetrainResult
    inputs: CycleInputs
    sets: list[SetCycleResult]
    labels: dict[str, str]
    stresses: dict
    isothermal_sets: list[SetCycleResult] | None
    model_comparison: ModelComparison | None
    compare_paper: bool
    warnings: list[str]
    runtime_s: float

    def set(self, name: str) -> SetCycleResult: ...

    def engineering_outputs(self) -> Engineering: ...


@dataclass
class Analysis:
    """What the report and the figures need beyond the raw arrays of the study."""

    roles: dict  #: role → surface-set name ("reference", "wcc", "dlc")
    in_event: np.ndarray  #: EHL samples inside the cam event
    point_index: np.ndarray  #: indices of the six representative points
    point_crank: np.ndarray  #: their crank angles [deg]
    gV: np.ndarray  #: Greenwood-chart viscosity group (NaN unloaded)
    gE: np.ndarray  #: elasticity group (NaN unloaded)
    regime: np.ndarray  #: regime code (index into REGIMES; −1 unloaded)
    regime_map: RegimeMap  #: the regimes on the Greenwood chart around the samples
    film_gain: dict = field(default_factory=dict)  #: set → film-gain statistics
    modulus_factor: list = field(default_factory=list)  #: GainFactor for +41 % per point
    summary: dict = field(default_factory=dict)  #: summary.json


# ----------------------------------------------------------------------------- roles
def surface_roles(case) -> dict:
    """Surface sets by role: ``reference`` is the first uncoated set (the first set if all
    are coated); for each coating material of the paper (keys ``dlc``, ``wcc`` in
    ``[materials]``) the set with that coating whose thickness is nearest the paper's
    4 µm. Chosen by material key, never by label text. ``case``: a Case or BuiltCase."""
    sets = as_built(case).surface_sets
    roles = {"reference": next((s.name for s in sets if s.coating is None), sets[0].name)}
    for key in paper.MATERIALS:
        cands = [
            (abs(math.log(s.coating.thickness / paper.COATING_THICKNESS)), i, s.name)
            for i, s in enumerate(sets)
            if s.coating is not None and s.coating_material == key
        ]
        if cands:
            roles[key] = min(cands)[2]
    return roles


# ----------------------------------------------------------------------------- masks
def event_mask(dynamics, inputs) -> np.ndarray:
    """EHL samples inside the cam event (cam lift above the jump threshold): the lift
    event proper, without the base-circle ringing of a few newtons."""
    lift = np.interp(inputs.crank_angle, dynamics.crank_angle, dynamics.cam_lift)
    return lift > dynamics.jump_lift_threshold


def representative_points(inputs, dynamics, loaded) -> np.ndarray:
    """Indices of six EHL samples spanning distinct load–speed states of the event
    (paper Fig. 13): the lightly loaded opening ramp, the fastest entrainment on the
    opening flank, the first u_e reversal, the nose (maximum lift), the second reversal,
    and the fastest entrainment on the closing flank."""
    F = inputs.contact_force
    loaded = loaded & (F > 0.05 * F.max())
    idx = np.flatnonzero(loaded)
    if idx.size < 12:
        return np.linspace(0, inputs.crank_angle.size - 1, 6).astype(int)
    lift = np.interp(inputs.crank_angle, dynamics.crank_angle, dynamics.cam_lift)
    i_nose = idx[np.argmax(lift[idx])]
    opening, closing = idx[idx < i_nose], idx[idx > i_nose]
    ue = inputs.entrainment_speed
    pts = []
    if opening.size >= 3:
        i_fast = opening[np.argmax(ue[opening])]
        ramp = opening[opening < i_fast]
        pts.append(ramp[len(ramp) // 2] if ramp.size else opening[0])
        pts.append(i_fast)
        after = opening[opening > i_fast]
        pts.append(after[np.argmin(np.abs(ue[after]))] if after.size else opening[-1])
    pts.append(i_nose)
    if closing.size >= 2:
        i_fast_c = closing[np.argmax(ue[closing])]
        before = closing[closing < i_fast_c]
        pts.append(before[np.argmin(np.abs(ue[before]))] if before.size else closing[0])
        pts.append(i_fast_c)
    pts = sorted(set(int(p) for p in pts))
    for e in idx[np.linspace(0, idx.size - 1, 13).astype(int)]:  # degenerate events
        if len(pts) >= 6:
            break
        if int(e) not in pts:
            pts = sorted(pts + [int(e)])
    return np.array(pts[:6], dtype=int)


def chart(case, inputs, loaded_any):
    """(g_V, g_E, regime code) per EHL sample with the bulk E' of the first surface set
    of ``case`` (a Case or BuiltCase); NaN / −1 where no set is loaded."""
    built = as_built(case)
    lub = built.lubricant
    e_prime = reduced_modulus(built.surface_sets[0].bodies)
    w = np.maximum(inputs.contact_force, 1e-9) / inputs.width
    W, U, G = hamrock_groups(
        w,
        inputs.radius,
        np.maximum(np.abs(inputs.entrainment_speed), 1e-3),
        lub.viscosity,
        lub.pressure_viscosity,
        e_prime,
    )
    gV, gE = greenwood_chart_groups(W, U, G)
    code = regime_code(gV, gE)
    return (
        np.where(loaded_any, gV, np.nan),
        np.where(loaded_any, gE, np.nan),
        np.where(loaded_any, code, -1).astype(np.int8),
    )


# ----------------------------------------------------------------------------- film gain
def _settled(loaded: np.ndarray, steps: int) -> np.ndarray:
    """Loaded samples at least ``steps`` samples after the start of their loaded run."""
    i = np.arange(loaded.size)
    last_off = np.maximum.accumulate(np.where(loaded, -1, i))  # latest unloaded sample
    return i - last_off > steps


def film_gain_mask(
    in_event,
    loaded_ref,
    loaded_set,
    converged_ref,
    converged_set,
    settle_steps: int = GAIN_SETTLE_STEPS,
) -> np.ndarray:
    """Samples admitted to the film-gain statistics (see the module docstring)."""
    both = np.asarray(loaded_ref, bool) & np.asarray(loaded_set, bool)
    return (
        np.asarray(in_event, bool)
        & both
        & np.asarray(converged_ref, bool)
        & np.asarray(converged_set, bool)
        & _settled(both, settle_steps)
    )


def film_gain_statistics(h_ref, h_set, mask, point_index) -> dict:
    """Film gain [%] of ``h_set`` over ``h_ref``: robust maximum, mean, median and 95th
    percentile of |gain| over the ``mask`` samples, and the gain at ``point_index``
    (None where the sample is not admitted)."""
    h_ref, h_set = np.asarray(h_ref, float), np.asarray(h_set, float)
    with np.errstate(invalid="ignore", divide="ignore"):
        gain = (h_set / h_ref - 1.0) * 100.0
    ok = np.asarray(mask, bool) & np.isfinite(gain)
    g = gain[ok]
    at = [float(gain[i]) if ok[i] else None for i in point_index]
    return {
        "max_pct": finite(g.max()) if g.size else None,
        "mean_pct": finite(g.mean()) if g.size else None,
        "median_abs_pct": finite(np.median(np.abs(g))) if g.size else None,
        "p95_abs_pct": finite(np.percentile(np.abs(g), 95)) if g.size else None,
        "at_points_pct": at,
        "samples": int(g.size),
    }


@dataclass(frozen=True)
class GainFactor:
    """Result of :func:`modulus_factor_for_gain`: ``factor`` (NaN when not reached or
    undefined) and, then, ``reason``."""

    factor: float
    reason: str = ""

    @property
    def found(self) -> bool:
        return math.isfinite(self.factor)


#: Largest E' factor :func:`modulus_factor_for_gain` searches.
MAX_MODULUS_FACTOR = 1e6


def modulus_factor_for_gain(
    load,
    radius,
    entrainment_speed,
    viscosity,
    pressure_viscosity,
    e_prime,
    gain=paper.CLAIMS["film_gain_pct"] / 100.0,
) -> GainFactor:
    """Factor f by which E' must fall (E' → E'/f) for the Moes central film to rise by
    ``gain`` at one operating point (w [N/m], R [m], u_e [m/s]; α kept). Not found (NaN,
    with the reason) at an unloaded point, where the film formula is undefined, or if no
    factor up to :data:`MAX_MODULUS_FACTOR` does it."""
    if not (load > 0.0 and radius > 0.0 and math.isfinite(load) and math.isfinite(radius)):
        return GainFactor(math.nan, f"no film formula at w = {load:g} N/m, R = {radius:g} m")
    u = max(abs(entrainment_speed), 1e-3)

    def hc(f):
        W, U, G = hamrock_groups(load, radius, u, viscosity, pressure_viscosity, e_prime / f)
        return float(moes_central(W, U, G, radius))

    h0 = hc(1.0)
    fn = lambda f: hc(f) / h0 - (1.0 + gain)  # noqa: E731
    lo, hi = fn(1.0), fn(MAX_MODULUS_FACTOR)
    if not (math.isfinite(lo) and math.isfinite(hi)):
        return GainFactor(math.nan, "the film formula is undefined at this point")
    if lo * hi > 0.0:  # no sign change in the bracket
        return GainFactor(
            math.nan, f"not reached: E'/{MAX_MODULUS_FACTOR:g} gives {100 * (hi + gain):+.3g} %"
        )
    return GainFactor(float(brentq(fn, 1.0, MAX_MODULUS_FACTOR, xtol=1e-6, rtol=1e-8)))


# ----------------------------------------------------------------------------- analysis
def analyse(study: StudyResults) -> Analysis:
    """The :class:`Analysis` of a :class:`~tribodyn.workflow.cycle.CycleStudy`."""
    built, dyn, inp = build(study.case), study.dynamics, study.inputs
    roles = surface_roles(built)
    ref = study.set(roles["reference"])
    ev = event_mask(dyn, inp)
    loaded_any = np.any([s.loaded for s in study.sets], axis=0)
    pidx = representative_points(inp, dyn, ref.loaded)
    gV, gE, regime = chart(built, inp, loaded_any)
    gains = {}
    for s in study.sets:
        m = film_gain_mask(ev, ref.loaded, s.loaded, ref.converged, s.converged)
        gains[s.name] = film_gain_statistics(ref.central_film, s.central_film, m, pidx)
    lub = built.lubricant
    e_prime = reduced_modulus(built.set(roles["reference"]).surface.bodies)
    factors = [
        modulus_factor_for_gain(
            inp.contact_force[i] / inp.width,
            inp.radius[i],
            inp.entrainment_speed[i],
            lub.viscosity,
            lub.pressure_viscosity,
            e_prime,
        )
        for i in pidx
    ]
    an = Analysis(
        roles=roles,
        in_event=ev,
        point_index=pidx,
        point_crank=inp.crank_angle[pidx],
        gV=gV,
        gE=gE,
        regime=regime,
        regime_map=regime_map(gV, gE),
        film_gain=gains,
        modulus_factor=factors,
    )
    an.summary = summary(study, an)
    return an


def summary(study: StudyResults, an: Analysis) -> dict:
    """The numbers users and scripts read (``summary.json``); totals over the cam width."""
    dyn, inp = study.dynamics, study.inputs
    period = 2.0 * math.pi / study.case.cam_speed  # one engine cycle = one cam rev
    ref = study.set(an.roles["reference"])
    ev = an.in_event
    ref_bf = inp.integral(ref.boundary_friction, ref.loaded & ev)
    ref_c = ref.loaded & ev & ref.converged
    ref_max_bf = np.nanmax(ref.boundary_friction[ref_c]) if ref_c.any() else math.nan
    out: dict[str, Any] = {
        "case": study.case.name,
        "engine_speed_rpm": float(study.case.engine_speed),
        "statistics_over": "cam event (lift > 10 µm), converged EHL samples, for films "
        "and friction maxima; all loaded samples for friction energy "
        "and power",
        "reference_set": ref.name,
        "conventions": {"crank_angle": CRANK_ANGLE, "change_pct": CHANGE},
        "presented_cycle_crank_deg": [float(dyn.crank_angle[0]), float(dyn.crank_angle[-1])],
        "roles": dict(an.roles),
        "film_gain_rule": FILM_GAIN_RULE,
        "representative_points_crank_deg": [float(c) for c in an.point_crank],
        "surface_sets": {},
    }
    for s in study.sets:
        L = s.loaded & ev
        C = L & s.converged  # films and maxima: converged samples only
        any_c = bool(C.any())
        bf = inp.integral(s.boundary_friction, L)
        energy = inp.integral(s.friction_power, s.loaded)
        by_law = {
            law: finite(
                inp.integral(
                    (getattr(s, f"viscous_friction_{law}") + s.boundary_friction)
                    * np.abs(inp.sliding_speed),
                    s.loaded,
                )
            )
            for law in ("newtonian", "eyring")
        }
        g = an.film_gain[s.name]
        out["surface_sets"][s.name] = {
            "label": study.labels[s.name],
            "peak_contact_force_N": finite(dyn.contact_force.max()),
            "min_film_m": finite(np.nanmin(s.min_film[C])) if any_c else None,
            "max_central_film_m": finite(np.nanmax(s.central_film[C])) if any_c else None,
            "max_film_gain_vs_uncoated_pct": g["max_pct"],
            "mean_film_gain_vs_uncoated_pct": g["mean_pct"],
            "median_abs_film_gain_vs_uncoated_pct": g["median_abs_pct"],
            "p95_abs_film_gain_vs_uncoated_pct": g["p95_abs_pct"],
            "film_gain_at_points_pct": g["at_points_pct"],
            "max_boundary_friction_N": finite(np.nanmax(s.boundary_friction[C])) if any_c else None,
            "max_viscous_friction_N": finite(np.nanmax(s.viscous_friction[C])) if any_c else None,
            # changes against the reference set: 100 (x/x_ref − 1), negative = less
            "boundary_friction_cycle_integral_change_pct": change_pct(bf, ref_bf),
            "max_boundary_friction_change_pct": change_pct(
                np.nanmax(s.boundary_friction[C]) if any_c else math.nan, ref_max_bf
            ),
            "friction_energy_per_cycle_J": finite(energy),
            "friction_energy_per_cycle_newtonian_J": by_law["newtonian"],
            "friction_energy_per_cycle_eyring_J": by_law["eyring"],
            "mean_friction_power_W": finite(energy / period),
            "min_lambda": finite(np.nanmin(s.lambda_ratio[C])) if any_c else None,
            "failed_steps": len(s.failures),
        }
        out["surface_sets"][s.name]["friction_energy_change_pct"] = change_pct(
            energy, inp.integral(ref.friction_power, ref.loaded)
        )
        if study.stresses:  # subsurface stresses, margins and wear
            from .stress_study import set_stress_summary

            out["surface_sets"][s.name].update(set_stress_summary(study, s.name))
    from .verdict import coating_verdicts

    verdicts = coating_verdicts(study, ref.name, dict(study.labels))
    built = build(study.case)
    for name, d in out["surface_sets"].items():
        d["asperity_law"] = built.set(name).surface.asperity_law
        d["coating_verdict"] = verdicts.get(name)  # None: the reference set
    _engineering_summary(study, out)
    out["implicit_vs_explicit"] = _implicit_vs_explicit(study)
    if study.isothermal_sets is not None:  # numerics.thermal
        out["thermal"] = thermal_summary(study, an)
    out["dynamics"] = {k: v for k, v in dyn.summary().items() if k != "converged"}
    out["valve_jump"] = _valve_jump(study)
    out["warnings"] = list(study.warnings)
    out["runtime_s"] = float(study.runtime_s)
    if study.model_comparison is not None:
        out["lumped_vs_flexible"] = study.model_comparison.to_dict()
    return out


def _valve_jump(study: StudyResults) -> dict:
    """Contact loss between cam and tappet: intervals, maximum separation, the speed at
    which it begins (with the lumped-vs-flexible comparison's search, else None) and the
    warning naming what to change (None without a jump)."""
    jump = study.dynamics.jump_summary()
    jump["max_separation_crank_deg"] = finite(jump["max_separation_crank_deg"])
    mc = study.model_comparison
    onset = None
    if mc is not None:
        onset = finite(mc.rows.get(study.case.valvetrain.model, {}).get("jump_speed_rpm"))
    jump["onset_speed_rpm"] = onset
    text = [w for w in study.warnings if "valve jump" in w]
    jump["warning"] = text[0] if jump["jump"] and text else None
    return jump


def _engineering_summary(study: StudyResults, out: dict) -> None:
    """The oil as used, torque and pressure scalars per set, the cam kinematics' key
    numbers and the spring's surge modes (:mod:`tribodyn.workflow.engineering`)."""
    from .engineering import oil_as_used

    out["compare_paper"] = bool(study.compare_paper)
    out["lubricant"] = oil_as_used(study.case)
    eng = study.engineering_outputs()
    for name, v in eng.scalars.items():
        out["surface_sets"][name].update({k: finite(x) for k, x in v.items()})
    k = eng.kinematics
    out["cam"] = {
        "max_lift_m": finite(np.max(k["lift"])),
        "max_velocity_m_s": finite(np.max(np.abs(k["velocity"]))),
        "max_acceleration_m_s2": finite(np.max(k["acceleration"])),
        "min_acceleration_m_s2": finite(np.min(k["acceleration"])),
        "min_radius_of_curvature_m": finite(np.min(k["radius"])),
        "table_points": None if eng.table is None else int(eng.table["lift"].size),
        "table_fit_rms_residual_m": None
        if eng.table is None
        else finite(np.sqrt(np.mean(eng.table["residual"] ** 2))),
    }
    sg = eng.surge
    out["spring_surge"] = {
        "cam_frequency_Hz": finite(sg["cam_frequency_Hz"]),
        "surge_frequencies_Hz": [finite(f) for f in sg["surge_frequency_Hz"]],
        "nearest_cam_harmonic": [int(c[1]) for c in sg["closest"]],
    }


def _implicit_vs_explicit(study) -> dict:
    dyn, cp = study.dynamics, study.coupling
    imp = cp.implicit
    if imp is None:
        return {
            **dict.fromkeys(k for k in COMPARISON_SCALARS if not k.startswith("coupling_")),
            "note": "implicit coupling disabled in the case"
            if not study.case.numerics.implicit_coupling
            else cp.message,
        }
    m = implicit_vs_explicit_metrics(dyn, imp)
    last = cp.history[-1] if cp.history else None
    return {
        **{k: finite(v) for k, v in m.items()},
        "coupling_converged": bool(cp.converged),
        "coupling_iterations": len(cp.history),
        "coupling_last_rms_force_change_N": finite(last.rms_force_change_N) if last else None,
        "coupling_last_max_force_change_N": finite(last.max_force_change_N) if last else None,
    }

"""A whole engine's direct-acting valvetrain: camshaft torque per camshaft and in total,
per surface set, over one engine cycle (720° crank), with the auxiliary friction of the
tappet bores, camshaft journals and valve guides beside the cam–tappet contact.

Lobes of one kind (intake or exhaust) are identical: each kind's single-valve study
(:func:`~tribodyn.workflow.cycle.run_cycle_study`: dynamics once, then the transient EHL
of every surface set on the same dynamics) runs once, and its traces are phase-shifted to
every valve of that kind. If the exhaust lobes equal the intake lobes, one study serves
both. The valve of kind k on cylinder c reaches maximum lift at the crank angle

    θ_ck = (θ_fire,c + θ_centre,k) mod 720°

(θ_fire,c: firing TDC of cylinder c, evenly spaced over 720° in firing order), and its
torque trace T_k(θ − θ_ck) is its single-valve trace relative to the crank angle of
maximum lift, interpolated (linear, periodic in 720°) on the engine's crank grid.

Per camshaft j (DOHC: intake, exhaust; one camshaft: all lobes) and surface set:

    T_f,j(θ) = Σ_{valves on j} T_f,valve(θ),     T_drive,j = Σ T_drive,valve      [N m]

the cam–tappet friction and drive torque (:func:`~tribodyn.workflow.engineering.
camshaft_torque`); friction power P_j = T_f,j ω [W] with ω the cam speed. The engine's
friction energy per cycle is E = ∮ (T_f + T_aux) dθ_cam over one cam revolution (one
engine cycle) and the valvetrain friction mean effective pressure FMEP = E / V_d (V_d the
displacement; Heywood, *Internal Combustion Engine Fundamentals*, 1988, §13.1).

Auxiliary friction (:mod:`tribodyn.physics.valvetrain_friction`; all in the oil of the
case at its inlet temperature): tappet–bore friction of each valve from its contact force,
cam friction and offset; valve stem in its guide; camshaft journal bearings (cylinders + 1
per camshaft, the lobes of each cylinder at mid-span between two of them; quasi-static,
rigid shaft, no drive-belt load), with the lobes' normal forces along the tappet axes and
their friction across them.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np

from ..config import Case
from ..config.build import build
from ..physics import valvetrain_friction as vf
from .conventions import CHANGE, ENGINE_CRANK_ANGLE, change_pct
from .cycle import CycleStudy, run_cycle_study
from .engineering import cycle_integral, set_torques

__all__ = ["LobeTraces", "EngineStudy", "run_engine_study", "lobe_traces", "place_trace"]

#: Crank-angle step of the engine grid [°].
ENGINE_GRID_STEP_DEG = 0.5


@dataclass
class LobeTraces:
    """One lobe kind's single-valve traces on its study's EHL samples, relative to the
    crank angle of maximum lift; per-set arrays are (set, sample)."""

    kind: str
    nose: float  #: crank angle of maximum lift of its study [°]
    relative_crank: np.ndarray  #: crank angle − nose [°]
    contact_force: np.ndarray  #: W [N]
    lift_velocity: np.ndarray  #: s' [m/rad]
    friction: np.ndarray  #: signed F_f [N] (set, sample)
    friction_torque: np.ndarray  #: cam–tappet T_f [N m] (set, sample)
    drive_torque: np.ndarray  #: T_drive [N m] (set, sample)
    bore_torque: np.ndarray  #: tappet–bore [N m] (set, sample)
    guide_torque: np.ndarray  #: valve guide [N m] (sample)
    energy: dict  #: set → ∮T_f dθ of one valve [J]
    study: CycleStudy  #: the single-valve study of the lobe kind


def lobe_traces(kind: str, study: CycleStudy, engine_case: Case) -> LobeTraces:
    """The :class:`LobeTraces` of a single-valve study, with the auxiliary friction of the
    engine's ``[engine.auxiliary]``."""
    case, dyn, inp = study.case, study.dynamics, study.inputs
    built = build(case)
    nose = float(dyn.crank_angle[int(np.argmax(dyn.cam_lift))])
    w = case.cam_speed
    eta = float(built.lubricant.viscosity)
    # tappet radius and bore friction: joint parameters, the same in a flexible case's
    # lumped companion
    vt = built.lumped
    bore, guide, _ = engine_case.engine.auxiliary_geometries(
        vt.tappet_radius, vt.bore_friction_coefficient
    )
    _, s1, ff, tf, td = set_torques(study, float(built.cam.base_radius))
    tb = [vf.tappet_bore_friction(inp.contact_force, f, s1, w, eta, bore)[1] for f in ff]
    energy = {r.name: cycle_integral(t_f, inp.crank_angle) for r, t_f in zip(study.sets, tf)}
    _, t_g, _ = vf.valve_guide_friction(s1, w, eta, guide)
    return LobeTraces(
        kind=kind,
        nose=nose,
        relative_crank=np.asarray(inp.crank_angle, float) - nose,
        contact_force=np.asarray(inp.contact_force, float),
        lift_velocity=s1,
        friction=ff,
        friction_torque=tf,
        drive_torque=td,
        bore_torque=np.array(tb),
        guide_torque=t_g,
        energy=energy,
        study=study,
    )


def place_trace(relative_crank, values, nose_deg: float, crank) -> np.ndarray:
    """A valve's trace ``values`` (on ``relative_crank`` = crank − crank of maximum lift,
    covering 720°) at the engine crank angles ``crank`` for a valve whose maximum lift is
    at ``nose_deg``: linear interpolation, periodic in 720°. The last sample is dropped if
    it repeats the first one a period later."""
    x = np.asarray(relative_crank, float)
    v = np.asarray(values, float)
    if x.size > 1 and math.isclose(x[-1] - x[0], 720.0, abs_tol=1e-9):
        x, v = x[:-1], v[..., :-1]
    q = np.asarray(crank, float) - nose_deg
    if v.ndim == 1:
        return np.interp(q, x, v, period=720.0)
    return np.array([np.interp(q, x, row, period=720.0) for row in v])


@dataclass
class EngineStudy:
    """A whole engine's valvetrain (module docstring). Arrays (set, camshaft, crank)."""

    case: Case
    set_names: list[str]
    camshafts: list[str]
    crank_angle: np.ndarray  #: engine crank grid, 0…720° inclusive
    cam_speed: float  #: ω [rad/s]
    friction_torque: np.ndarray  #: cam–tappet [N m]
    drive_torque: np.ndarray  #: [N m]
    bore_torque: np.ndarray  #: tappet–bore [N m]
    guide_torque: np.ndarray  #: valve guides [N m]
    journal_torque: np.ndarray  #: camshaft journals [N m]
    valves: list[dict]  #: cylinder, kind, camshaft, nose_deg per valve
    lobe_friction_torque: np.ndarray  #: (set, valve, crank) cam–tappet T_f per valve
    lobes: dict[str, LobeTraces]
    labels: dict[str, str] = field(default_factory=dict)  #: set name → label
    runtime_s: float = 0.0
    timings: dict = field(default_factory=dict)
    warnings: list[str] = field(default_factory=list)
    summary_block: dict | None = None  #: :meth:`summary`, once computed

    @property
    def auxiliary_torque(self) -> np.ndarray:
        """Bore + guide + journal torque [N m] (set, camshaft, crank)."""
        return self.bore_torque + self.guide_torque + self.journal_torque

    def energy(self, torque) -> np.ndarray:
        """∮ torque dθ_cam over the cycle [J] for each leading index."""
        return cycle_integral(torque, self.crank_angle)

    def summary(self) -> dict:
        """The ``engine`` block of summary.json (:meth:`_summary`), computed once: at the
        end of :func:`run_engine_study`, so that writing the results only reads it."""
        if self.summary_block is None:
            self.summary_block = self._summary()
        return self.summary_block

    def _summary(self) -> dict:
        """``engine`` block of summary.json: per set and camshaft, energies [J], mean
        torques [N m], mean powers [W], FMEP [Pa], each coating's benefit in %, and each
        lobe kind's contact loss (``valve_jump``: intervals, maximum separation)."""
        period = 2.0 * math.pi / self.cam_speed
        vd = float(self.case.engine.displacement or float("nan"))
        parts = {
            "cam_tappet": self.friction_torque,
            "tappet_bore": self.bore_torque,
            "valve_guide": self.guide_torque,
            "camshaft_journal": self.journal_torque,
        }
        e_parts = {k: self.energy(v) for k, v in parts.items()}  # (set, camshaft)
        e_shafts = np.sum(list(e_parts.values()), axis=0)  # all parts, (set, camshaft)
        out: dict = {
            "cylinders": self.case.engine.cylinders,
            "camshafts": self.camshafts,
            "valves": len(self.valves),
            "speed_rpm": self.case.engine.speed_rpm,
            "displacement_m3": vd,
            "surface_sets": {},
        }
        totals = {}
        for i, name in enumerate(self.set_names):
            total = float(sum(e[i].sum() for e in e_parts.values()))
            totals[name] = total
            d = {
                # transient-EHL steps that did not converge, per lobe kind: their
                # friction is unknown and left out of the energies and sums below
                "failed_steps": {k: len(lt.study.sets[i].failures) for k, lt in self.lobes.items()},
                "engine_friction_energy_per_cycle_J": total,
                "valvetrain_friction_mep_Pa": total / vd,
                "mean_friction_power_W": total / period,
                "mean_friction_torque_Nm": total / (2.0 * math.pi),
                "peak_camshaft_drive_torque_Nm": float(
                    np.nanmax(np.abs(self.drive_torque[i].sum(axis=0)))
                ),
                "friction_energy_per_cycle_J": {k: float(e[i].sum()) for k, e in e_parts.items()},
                "camshafts": {
                    c: {
                        "friction_energy_per_cycle_J": float(e_shafts[i, j]),
                        "cam_tappet_friction_energy_per_cycle_J": float(
                            e_parts["cam_tappet"][i, j]
                        ),
                        "mean_friction_torque_Nm": float(e_shafts[i, j] / (2.0 * math.pi)),
                        "max_friction_torque_Nm": float(
                            np.nanmax(self.friction_torque[i, j] + self.auxiliary_torque[i, j])
                        ),
                    }
                    for j, c in enumerate(self.camshafts)
                },
            }
            out["surface_sets"][name] = d
        ref = self.set_names[0]
        for name, d in out["surface_sets"].items():
            # engine friction energy per cycle (= FMEP) against the reference set
            d["friction_energy_change_pct"] = change_pct(totals[name], totals[ref])
        out["reference_set"] = ref
        out["conventions"] = {"crank_angle": ENGINE_CRANK_ANGLE, "change_pct": CHANGE}
        # contact loss of each lobe kind's valve (its single-valve dynamics), at the
        # engine's crank angles of that kind's valve on cylinder 1
        out["valve_jump"] = {k: self._jump_on_cylinder_1(k, lt) for k, lt in self.lobes.items()}
        self._verdicts(out, totals, vd)
        return out

    def _jump_on_cylinder_1(self, kind: str, lt: LobeTraces) -> dict:
        """The single-valve study's ``jump_summary`` of lobe kind ``kind`` with its crank
        angles moved to the engine's (:data:`~tribodyn.workflow.conventions.
        ENGINE_CRANK_ANGLE`) for the valve of that kind on cylinder 1: each start in
        0–720°, an interval keeps its length."""
        j = lt.study.dynamics.jump_summary()
        nose = next(
            (v["nose_deg"] for v in self.valves if v["kind"] == kind and v["cylinder"] == 1), None
        )
        if nose is None:
            return j
        shift = nose - lt.nose

        def at(c):
            return None if c is None else float((c + shift) % 720.0)

        j["contact_loss_crank_deg"] = [
            [at(a), at(a) + (b - a)] for a, b in j["contact_loss_crank_deg"]
        ]
        j["max_separation_crank_deg"] = at(j["max_separation_crank_deg"])
        j["crank_angle"] = f"{ENGINE_CRANK_ANGLE}, the {kind} valve of cylinder 1"
        return j

    def _verdicts(self, out: dict, totals: dict, vd: float) -> None:
        """Each set's ``coating_verdict`` (change of engine friction energy per cycle,
        i.e. of FMEP, with its range; :data:`~tribodyn.workflow.verdict.ENGINE_METHOD`),
        ``asperity_law`` and ``valvetrain_friction_mep_range_Pa`` over the published
        ranges of its ς and the viscous factor."""
        from .verdict import (
            ENGINE_METHOD,
            boundary_ranges,
            set_energy_function,
            verdicts_from_energies,
            viscous_factor_bounds,
        )

        studies = {k: lt.study for k, lt in self.lobes.items()}
        built = build(self.case)
        energies = {}
        for i, name in enumerate(self.set_names):
            parts = []  # (nominal cam–tappet energy of the lobe kind, E(ς', k) of its study)
            for kind, st in studies.items():
                rows = [m for m, v in enumerate(self.valves) if v["kind"] == kind]
                e_ct = float(sum(self.energy(self.lobe_friction_torque[i, m]) for m in rows))
                parts.append((e_ct, set_energy_function(st, name)))
            aux = totals[name] - sum(e for e, _ in parts)
            sig = float(built.set(name).surface.boundary_shear_coefficient)

            def total(s_new, k=1.0, parts=parts, aux=aux, sig=sig):
                return aux + sum(
                    e * f(s_new, k) / f(sig, 1.0) if f(sig, 1.0) > 0 else e for e, f in parts
                )

            energies[name] = total
        sigmas = boundary_ranges(built, self.set_names)
        labels = {n: built.set(n).surface.coating_label for n in self.set_names}
        verdicts = verdicts_from_energies(
            energies, sigmas, self.set_names[0], labels, built, ENGINE_METHOD
        )
        k_lo, k_hi = viscous_factor_bounds(built)
        for name, d in out["surface_sets"].items():
            d["asperity_law"] = built.set(name).surface.asperity_law
            d["coating_verdict"] = verdicts.get(name)
            sig, lo, hi = sigmas[name]
            ends = [energies[name](s_, k) / vd for s_ in (lo, hi) for k in (k_lo, k_hi)]
            d["valvetrain_friction_mep_range_Pa"] = [min(ends), max(ends)]

    def to_dataset(self):
        """xarray Dataset of the traces with units and descriptions (the table of
        :mod:`~tribodyn.workflow.variables_engine`)."""
        import xarray as xr

        from .variables import build
        from .variables_engine import ENGINE

        return build(xr.Dataset(), [ENGINE], self)


def place_known(relative_crank, values, nose_deg: float, crank) -> np.ndarray:
    """:func:`place_trace` of a valve's trace with its unknown (NaN: failed EHL) samples
    counted as 0, as the valve's own cycle energy counts them: for the camshaft sums, in
    which a sample one valve does not know must not erase the other valves'
    contributions (the sets' ``failed_steps`` say what is missing)."""
    return place_trace(relative_crank, np.nan_to_num(values), nose_deg, crank)


def _journal_torque(lobes, valves, set_index, camshafts, case, crank, cam_speed, eta):
    """(camshaft, crank) journal-bearing torque from the lobes' force vectors."""
    aux = case.engine.auxiliary_friction()
    g = vf.JournalGeometry(aux.journal_radius, aux.journal_length, aux.journal_clearance)
    n = case.engine.cylinders
    bearings = np.arange(n + 1, dtype=float)
    out = []
    for shaft in camshafts:
        on = [v for v in valves if v["camshaft"] == shaft]
        forces = np.zeros((n, crank.size, 2))
        for v in on:
            lt = lobes[v["kind"]]
            wn = place_trace(lt.relative_crank, lt.contact_force, v["nose_deg"], crank)
            ft = place_known(lt.relative_crank, lt.friction[set_index], v["nose_deg"], crank)
            forces[v["cylinder"] - 1, :, 0] += wn
            forces[v["cylinder"] - 1, :, 1] += ft
        loads = vf.journal_bearing_loads(forces, bearings[:-1] + 0.5, bearings)
        t, _ = vf.short_bearing_torque(loads, eta, g, cam_speed)
        out.append(t.sum(axis=0))
    return np.array(out)


def run_engine_study(
    case: Case, *, workers: int | None = None, executor=None, progress=None
) -> EngineStudy:
    """Run the engine's valvetrain (module docstring) for a case with ``engine.cylinders``.
    Each distinct lobe kind is one :func:`run_cycle_study` (``workers``/``executor`` as
    there) of its EHL passes alone (``friction_only``: the engine's outputs use neither
    the implicit-dynamics comparison nor the stresses nor the single-contact studies)."""
    from .. import InputError

    e = case.engine
    if e.cylinders is None:
        raise InputError("engine.cylinders: the case describes one valve, not an engine")
    t0 = time.perf_counter()
    kinds = ("intake", "exhaust")
    built = build(case)
    lobe_cases = {k: case.engine_lobe_case(k) for k in kinds}
    studies: dict[str, CycleStudy] = {}
    timings = {}
    for k in kinds:
        same = [j for j in studies if lobe_cases[j] == lobe_cases[k]]
        if same:  # identical lobes: solved once
            studies[k] = studies[same[0]]
            continue
        t1 = time.perf_counter()
        studies[k] = run_cycle_study(
            build(lobe_cases[k]),  # the lobe's own case, built once
            workers=workers,
            executor=executor,
            progress=progress,
            compare_paper=False,
            friction_only=True,  # no comparison, stresses or nose studies: unused here
        )
        timings[f"{k}_study_s"] = time.perf_counter() - t1
    lobes = {k: lobe_traces(k, studies[k], case) for k in kinds}
    set_names = [r.name for r in studies["intake"].sets]
    if [r.name for r in studies["exhaust"].sets] != set_names:
        raise InputError("engine.exhaust.changes: the lobes must keep the case's surface sets")
    camshafts = ["intake", "exhaust"] if e.camshafts == 2 else ["camshaft"]
    fire = e.firing_angles()
    valves = []
    for c in sorted(fire):
        for k in kinds:
            lobe = getattr(e, k)
            for _ in range(lobe.valves):
                valves.append(
                    {
                        "cylinder": c,
                        "kind": k,
                        "camshaft": k if e.camshafts == 2 else "camshaft",
                        "nose_deg": (fire[c] + lobe.centre_angle_deg) % 720.0,
                    }
                )
    crank = np.linspace(0.0, 720.0, int(round(720.0 / ENGINE_GRID_STEP_DEG)) + 1)
    ns, nc = len(set_names), len(camshafts)
    tf = np.zeros((ns, nc, crank.size))
    td, tb, tg = np.zeros_like(tf), np.zeros_like(tf), np.zeros_like(tf)
    per_valve = np.zeros((ns, len(valves), crank.size))
    for m, v in enumerate(valves):
        lt, j = lobes[v["kind"]], camshafts.index(v["camshaft"])
        rel, nose = lt.relative_crank, v["nose_deg"]
        # NaN where this valve's EHL failed (unknown)
        per_valve[:, m] = place_trace(rel, lt.friction_torque, nose, crank)
        tf[:, j] += place_known(rel, lt.friction_torque, nose, crank)
        td[:, j] += place_known(rel, lt.drive_torque, nose, crank)
        tb[:, j] += place_known(rel, lt.bore_torque, nose, crank)
        tg[:, j] += place_trace(rel, lt.guide_torque, nose, crank)
    w = case.cam_speed
    eta = float(built.lubricant.viscosity)
    tj = np.array(
        [_journal_torque(lobes, valves, i, camshafts, case, crank, w, eta) for i in range(ns)]
    )
    warnings = []
    for k in kinds:
        if studies[k] is not studies.get("intake") or k == "intake":
            # the single-valve study's crank angles, with where its maximum lift sits on
            # the engine's clock (cylinder 1's valve of this kind)
            own, on_1 = lobes[k].nose, next(v["nose_deg"] for v in valves if v["kind"] == k)
            clock = (
                f"crank angles of its single-valve study, whose maximum lift at {own:.0f}° "
                f"is {on_1:.0f}° of cylinder 1"
            )
            warnings += [f"{k} lobes ({clock}): {x}" for x in studies[k].warnings]
    study = EngineStudy(
        case=case,
        set_names=set_names,
        camshafts=camshafts,
        crank_angle=crank,
        cam_speed=w,
        friction_torque=tf,
        drive_torque=td,
        bore_torque=tb,
        guide_torque=tg,
        journal_torque=tj,
        valves=valves,
        lobe_friction_torque=per_valve,
        lobes=lobes,
        labels=dict(studies["intake"].labels),
        runtime_s=time.perf_counter() - t0,
        timings=timings,
        warnings=warnings,
    )
    study.summary()  # the coating verdicts and their ranges, computed with the study
    return study

"""Cycle-study results as an xarray Dataset, the summary, and atomic writing.

Dimensions: ``crank_angle`` (dynamics output, deg), ``ehl_crank`` (transient-EHL samples,
deg), ``surface_set``, ``x`` (common EHL profile grid, m), ``point`` (the six
representative points of the paper's Fig. 13), and for the single-contact studies
``dry_ratio``/``dry_x`` (Fig. 5), ``ehl_ratio``/``ehl_pair``/``ehl_x`` (Fig. 6).
Every variable carries ``units`` and ``long_name``. EHL quantities are NaN where the
contact carries no load (``loaded`` false: cam on the base circle) — by definition, not
as a failure; steps that did not converge keep their last iterate and are flagged by
``converged`` false and listed in the ``ehl_failures`` attribute.

Writing is atomic: everything goes to a temporary folder next to the target, which then
replaces the target folder in one rename (the previous results are kept until then).
"""

from __future__ import annotations

import json
import math
import os
import shutil
import tempfile
from pathlib import Path

import numpy as np
import xarray as xr

from .physics.materials import reduced_modulus
from .physics.regimes import REGIMES, greenwood_chart_groups, hamrock_groups, lubrication_regime

__all__ = ["study_to_dataset", "summary", "representative_points", "event_mask",
           "write_atomic", "write_results"]

_UNITS = {
    "contact_force": ("N", "cam–tappet contact force (total over the width)"),
    "tappet_displacement": ("m", "tappet displacement"),
    "tappet_velocity": ("m/s", "tappet velocity"),
    "tappet_acceleration": ("m/s²", "tappet acceleration"),
    "valve_lift": ("m", "valve lift"),
    "seat_force": ("N", "valve seat force"),
    "cam_lift": ("m", "cam lift s"),
    "cam_torque": ("N·m", "camshaft drive torque"),
    "friction_power": ("W", "contact friction power (analytic tribology of the dynamics)"),
    "entrainment_speed": ("m/s", "entraining speed u_e"),
    "sliding_speed": ("m/s", "sliding speed u_s"),
    "radius_of_curvature": ("m", "radius of curvature R of the cam at the contact"),
    "contact_offset": ("m", "contact offset e on the tappet face"),
}
_EHL = {
    "central_film": ("m", "central film thickness h_c (x = 0)"),
    "min_film": ("m", "minimum film thickness h_min"),
    "max_pressure": ("Pa", "maximum hydrodynamic pressure"),
    "hydrodynamic_load": ("N", "load carried by the fluid (total over the width)"),
    "asperity_load": ("N", "load carried by the asperities (total over the width)"),
    "viscous_friction": ("N", "viscous (Couette) friction force"),
    "boundary_friction": ("N", "boundary friction force"),
    "rolling_friction": ("N", "Poiseuille (rolling) part of Eq. 16"),
    "friction_power": ("W", "friction power (viscous + boundary) × u_s"),
    "lambda_ratio": ("1", "λ = h_min/σ"),
}


def _var(data, dims, key, table):
    units, name = table[key]
    return xr.Variable(dims, np.asarray(data), {"units": units, "long_name": name})


def representative_points(study) -> np.ndarray:
    """Six crank angles spanning distinct load–speed states of the event (Fig. 13):
    the lightly loaded opening ramp, the fastest entrainment on the opening flank, the
    first u_e reversal, the nose (maximum lift), the second reversal, and the fastest
    entrainment on the closing flank."""
    inp = study.inputs
    F = inp.contact_force
    loaded = study.sets[0].loaded & (F > 0.05 * F.max())
    idx = np.flatnonzero(loaded)
    if idx.size < 12:
        return inp.crank_angle[np.linspace(0, inp.crank_angle.size - 1, 6).astype(int)]
    lift = np.interp(inp.crank_angle, study.dynamics.crank_angle, study.dynamics.cam_lift)
    i_nose = idx[np.argmax(lift[idx])]
    opening, closing = idx[idx < i_nose], idx[idx > i_nose]
    ue = inp.entrainment_speed
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
    fill = idx[np.linspace(0, idx.size - 1, 13).astype(int)]
    for e in fill:                                 # degenerate events: fill evenly
        if len(pts) >= 6:
            break
        if int(e) not in pts:
            pts = sorted(pts + [int(e)])
    return inp.crank_angle[np.array(pts[:6])]


def study_to_dataset(study) -> xr.Dataset:
    """All results of a :class:`~tribodyn.workflow.cycle.CycleStudy` in one Dataset."""
    from . import __version__
    case = study.case
    dyn = study.dynamics
    inp = study.inputs
    sets = study.sets
    ds = xr.Dataset()
    ds.coords["crank_angle"] = xr.Variable("crank_angle", dyn.crank_angle,
                                           {"units": "deg", "long_name": "crank angle"})
    for k in _UNITS:
        name = "analytic_friction_power" if k == "friction_power" else k
        ds[name] = _var(getattr(dyn, k), "crank_angle", k, _UNITS)
    if study.implicit is not None:
        for k in ("contact_force", "tappet_velocity", "tappet_acceleration", "valve_lift"):
            v = np.interp(dyn.crank_angle, study.implicit.crank_angle, getattr(study.implicit, k))
            units, name = _UNITS[k]
            ds[k + "_implicit"] = xr.Variable("crank_angle", v, {
                "units": units, "long_name": name + " (implicit: numerical EHL in the dynamics)"})

    ds.coords["ehl_crank"] = xr.Variable("ehl_crank", inp.crank_angle, {
        "units": "deg", "long_name": "crank angle of the transient-EHL samples"})
    ds.coords["surface_set"] = xr.Variable("surface_set", [s.name for s in sets])
    ds.attrs["reference_set"] = sets[reference_index(study)].name
    ds["surface_label"] = xr.Variable("surface_set", [study.labels[s.name] for s in sets],
                                      {"long_name": "tappet surface"})
    ds["ehl_contact_force"] = xr.Variable("ehl_crank", inp.contact_force,
                                          {"units": "N", "long_name": "contact force at the EHL samples"})
    ds["ehl_entrainment_speed"] = xr.Variable("ehl_crank", inp.entrainment_speed,
                                              {"units": "m/s", "long_name": "u_e at the EHL samples"})
    ds["ehl_sliding_speed"] = xr.Variable("ehl_crank", inp.sliding_speed,
                                          {"units": "m/s", "long_name": "u_s at the EHL samples"})
    ds["ehl_radius"] = xr.Variable("ehl_crank", inp.radius,
                                   {"units": "m", "long_name": "R at the EHL samples"})
    # Greenwood chart groups (bulk E' of the first set)
    lub = case.lubricant()
    e_prime = reduced_modulus(case.surface_sets()[0].bodies)
    w = np.maximum(inp.contact_force, 1e-9) / inp.width
    W, U, G = hamrock_groups(w, inp.radius, np.maximum(np.abs(inp.entrainment_speed), 1e-3),
                             lub.viscosity, lub.pressure_viscosity, e_prime)
    gV, gE = greenwood_chart_groups(W, U, G)
    loaded_any = np.any([s.loaded for s in sets], axis=0)
    ds["gV"] = xr.Variable("ehl_crank", np.where(loaded_any, gV, np.nan),
                           {"units": "1", "long_name": "Greenwood-chart viscosity group g_V"})
    ds["gE"] = xr.Variable("ehl_crank", np.where(loaded_any, gE, np.nan),
                           {"units": "1", "long_name": "Greenwood-chart elasticity group g_E"})
    code = np.array([REGIMES.index(r) for r in np.atleast_1d(lubrication_regime(gV, gE))])
    ds["regime"] = xr.Variable("ehl_crank", np.where(loaded_any, code, -1).astype(np.int8), {
        "long_name": "lubrication regime", "flag_values": "-1 0 1 2 3",
        "flag_meanings": "unloaded " + " ".join(REGIMES)})

    ds["in_event"] = xr.Variable("ehl_crank", event_mask(study).astype(np.int8), {
        "long_name": "inside the cam lift event (lift > 10 µm)"})
    ds["loaded"] = xr.Variable(("surface_set", "ehl_crank"),
                               np.array([s.loaded for s in sets]).astype(np.int8),
                               {"long_name": "contact loaded (EHL solved)"})
    ds["converged"] = xr.Variable(("surface_set", "ehl_crank"),
                                  np.array([s.converged for s in sets]).astype(np.int8),
                                  {"long_name": "EHL step converged"})
    ds["iterations"] = xr.Variable(("surface_set", "ehl_crank"),
                                   np.array([s.iterations for s in sets]).astype(np.int32),
                                   {"long_name": "Newton iterations"})
    for k in _EHL:
        ds[k] = _var(np.array([getattr(s, k) for s in sets]), ("surface_set", "ehl_crank"),
                     k, _EHL)
    ds.coords["k"] = xr.Variable("k", np.arange(sets[0].x.shape[1]), {
        "long_name": "profile sample index (each step's whole solver domain, uniform)"})
    ds["profile_x"] = xr.Variable(("surface_set", "ehl_crank", "k"),
                                  np.array([s.x for s in sets]),
                                  {"units": "m", "long_name": "position along the contact "
                                   "(positive in the direction of positive u_e)"})
    ds["pressure"] = xr.Variable(("surface_set", "ehl_crank", "k"),
                                 np.array([s.pressure for s in sets]),
                                 {"units": "Pa", "long_name": "hydrodynamic pressure p(x)"})
    ds["film"] = xr.Variable(("surface_set", "ehl_crank", "k"), np.array([s.film for s in sets]),
                             {"units": "m", "long_name": "film thickness h(x)"})
    ds.coords["point"] = xr.Variable("point", np.arange(1, 7))
    ds["point_crank"] = xr.Variable("point", representative_points(study), {
        "units": "deg", "long_name": "crank angle of the representative points (Fig. 13)"})

    _coating_studies(ds, study)
    failures = {s.name: [[c, m] for c, m in s.failures] for s in sets}
    ds.attrs.update({
        "title": f"tribodyn cam-cycle study: {case.name}",
        "tribodyn_version": __version__,
        "case_toml": case.to_toml(),
        "engine_speed_rpm": float(case.engine_speed),
        "cam_width_m": float(case.width),
        "runtime_s": float(study.runtime_s),
        "coupling": json.dumps(study.coupling),
        "warnings": json.dumps(study.warnings),
        "ehl_failures": json.dumps(failures),
        "conventions": "SI; EHL NaN where unloaded (loaded = 0)",
        "roughness_sensitivity": json.dumps(getattr(study, "sensitivity", {}) or {}),
    })
    return ds


def _coating_studies(ds, study):
    if study.dry:
        from .workflow.coating_study import PAPER_FIG5
        ds.attrs["dry_coating_conditions"] = json.dumps(
            {k: v for k, v in PAPER_FIG5.items() if k != "ratios"})
        half = max(1.3 * c.result.half_width for c in study.dry)
        xd = np.linspace(-half, half, 401)
        ds.coords["dry_x"] = xr.Variable("dry_x", xd, {"units": "m"})
        ds.coords["dry_ratio"] = xr.Variable("dry_ratio", [c.ratio for c in study.dry],
                                             {"long_name": "coating/steel modulus ratio"})
        ds["dry_pressure"] = xr.Variable(
            ("dry_ratio", "dry_x"),
            np.array([np.interp(xd, c.result.x, c.result.pressure, left=0, right=0)
                      for c in study.dry]),
            {"units": "Pa", "long_name": "dry contact pressure (Fig. 5)"})
        ds["dry_half_width"] = xr.Variable("dry_ratio", [c.result.half_width for c in study.dry],
                                           {"units": "m"})
        ds["dry_max_pressure"] = xr.Variable("dry_ratio",
                                             [c.result.max_pressure for c in study.dry],
                                             {"units": "Pa"})
    e = study.ehl_coating
    if e:
        all_r = [r for *_, r in e["ratios"]] + [r for _, r in e["pairs"]]
        lo = max(r.x[0] for r in all_r)
        hi = min(r.x[-1] for r in all_r)
        xe = np.linspace(lo, hi, 601)
        ds.coords["ehl_x"] = xr.Variable("ehl_x", xe, {"units": "m"})
        ds.coords["ehl_ratio"] = xr.Variable("ehl_ratio", [ratio for _, ratio, _ in e["ratios"]])
        ds.coords["ehl_pair"] = xr.Variable("ehl_pair", [lab for lab, _ in e["pairs"]])
        for dim, items in (("ehl_ratio", [r for *_, r in e["ratios"]]),
                           ("ehl_pair", [r for _, r in e["pairs"]])):
            ds[f"{dim}_pressure"] = xr.Variable(
                (dim, "ehl_x"), np.array([np.interp(xe, r.x, r.pressure) for r in items]),
                {"units": "Pa", "long_name": "EHL pressure (Fig. 6)"})
            ds[f"{dim}_film"] = xr.Variable(
                (dim, "ehl_x"), np.array([np.interp(xe, r.x, r.film) for r in items]),
                {"units": "m", "long_name": "EHL film (Fig. 6)"})
            ds[f"{dim}_central_film"] = xr.Variable(dim, [r.central_film for r in items],
                                                    {"units": "m"})
            ds[f"{dim}_min_film"] = xr.Variable(dim, [r.min_film for r in items], {"units": "m"})
            ds[f"{dim}_converged"] = xr.Variable(dim, np.array([r.converged for r in items],
                                                               dtype=np.int8))
        ds.attrs["ehl_coating_conditions"] = json.dumps(e["conditions"])


def reference_index(study) -> int:
    """Index of the reference surface set for the "…_vs_uncoated" numbers: the first
    uncoated set of the case, or the first set if every set is coated."""
    for i, s in enumerate(study.case.surface_sets()):
        if s.coating is None:
            return i
    return 0


def event_mask(study) -> np.ndarray:
    """EHL samples inside the cam event (cam lift above the jump threshold): the lift
    event proper, without the base-circle ringing of a few newtons."""
    dyn = study.dynamics
    lift = np.interp(study.inputs.crank_angle, dyn.crank_angle, dyn.cam_lift)
    return lift > dyn.jump_lift_threshold


def _finite(v):
    v = float(v)
    return v if math.isfinite(v) else None


def summary(study) -> dict:
    """The numbers users and scripts read (``summary.json``); totals over the cam width."""
    dyn = study.dynamics
    inp = study.inputs
    t = inp.time
    period = 2.0 * math.pi / study.case.cam_speed       # one engine cycle = one cam rev
    dt = np.gradient(t)
    ref = study.sets[reference_index(study)]
    ev = event_mask(study)
    ref_bf = np.nansum(np.where(ref.loaded & ev, ref.boundary_friction, 0.0) * dt)
    out = {"case": study.case.name, "engine_speed_rpm": float(study.case.engine_speed),
           "statistics_over": "cam event (lift > 10 µm) for films and forces; all loaded "
                              "samples for friction energy and power",
           "reference_set": ref.name,
           "surface_sets": {}}
    for s in study.sets:
        L = s.loaded & ev
        gain = (s.central_film[L] / ref.central_film[L] - 1.0) * 100.0
        bf = np.nansum(np.where(L, s.boundary_friction, 0.0) * dt)
        energy = float(np.nansum(np.where(s.loaded, s.friction_power, 0.0) * dt))
        out["surface_sets"][s.name] = {
            "label": study.labels[s.name],
            "peak_contact_force_N": _finite(dyn.contact_force.max()),
            "min_film_m": _finite(np.nanmin(s.min_film[L])) if L.any() else None,
            "max_central_film_m": _finite(np.nanmax(s.central_film[L])) if L.any() else None,
            "max_film_gain_vs_uncoated_pct": _finite(np.nanmax(gain)) if L.any() else None,
            "mean_film_gain_vs_uncoated_pct": _finite(np.nanmean(gain)) if L.any() else None,
            "max_boundary_friction_N": _finite(np.nanmax(s.boundary_friction[L])) if L.any() else None,
            "max_viscous_friction_N": _finite(np.nanmax(s.viscous_friction[L])) if L.any() else None,
            "boundary_friction_reduction_vs_uncoated_pct":
                _finite((1.0 - bf / ref_bf) * 100.0) if ref_bf > 0 else None,
            "friction_energy_per_cycle_J": _finite(energy),
            "mean_friction_power_W": _finite(energy / period),
            "min_lambda": _finite(np.nanmin(s.lambda_ratio[L])) if L.any() else None,
            "failed_steps": len(s.failures),
        }
    imp = study.implicit
    if imp is not None:
        fi = np.interp(dyn.crank_angle, imp.crank_angle, imp.contact_force)
        vi = np.interp(dyn.crank_angle, imp.crank_angle, imp.tappet_velocity)
        dF = np.abs(fi - dyn.contact_force)
        dv = np.abs(vi - dyn.tappet_velocity)
        out["implicit_vs_explicit"] = {
            "max_contact_force_diff_pct": _finite(dF.max() / dyn.contact_force.max() * 100),
            "max_contact_force_diff_crank_deg": _finite(dyn.crank_angle[dF.argmax()]),
            "max_velocity_diff_pct": _finite(dv.max() / np.abs(dyn.tappet_velocity).max() * 100),
            "max_velocity_diff_crank_deg": _finite(dyn.crank_angle[dv.argmax()]),
            "coupling_converged": bool(study.coupling.get("converged")),
            "coupling_iterations": len(study.coupling.get("history", [])),
            "coupling_last_rms_force_change_N": _finite(
                (study.coupling.get("history") or [{}])[-1].get("rms_force_change_N",
                                                                float("nan"))),
            "coupling_last_max_force_change_N": _finite(
                (study.coupling.get("history") or [{}])[-1].get("max_force_change_N",
                                                                float("nan"))),
        }
    else:
        out["implicit_vs_explicit"] = {"max_contact_force_diff_pct": None,
                                       "max_velocity_diff_pct": None,
                                       "note": "implicit coupling disabled in the case"}
    out["dynamics"] = {k: v for k, v in dyn.summary().items()
                       if k not in ("converged",)}
    out["warnings"] = list(study.warnings)
    out["runtime_s"] = float(study.runtime_s)
    return out


def write_atomic(target: Path, writer) -> Path:
    """Call ``writer(tmpdir)`` to fill a fresh folder, then replace ``target`` with it.

    If ``writer`` raises, ``target`` is left exactly as it was.
    """
    target = Path(target).resolve()
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{target.name}.tmp-", dir=target.parent))
    try:
        writer(tmp)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    old = None
    if target.exists():
        old = target.with_name(f".{target.name}.old-{os.getpid()}")
        if old.exists():
            shutil.rmtree(old)
        target.rename(old)
    try:
        tmp.rename(target)
    except BaseException:
        if old is not None:
            old.rename(target)
        raise
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)
    return target


def write_results(study, out_dir, *, figures=True, report=True) -> dict:
    """Write results.nc, summary.json, figures and report.md atomically into ``out_dir``."""
    ds = study_to_dataset(study)
    summ = summary(study)
    written = {}

    def writer(tmp: Path):
        enc = {v: {"compression": "gzip", "compression_opts": 4}
               for v in ("profile_x", "pressure", "film")}
        ds.to_netcdf(tmp / "results.nc", engine="h5netcdf", encoding=enc)
        (tmp / "summary.json").write_text(json.dumps(summ, indent=2))
        study.case.write_toml(tmp / "case.toml")
        figs = {}
        if figures:
            from .figures import make_figures
            figs = make_figures(ds, tmp)
        if report:
            from .report import write_report
            write_report(ds, summ, figs, tmp / "report.md")
        written.update(figures=figs)

    write_atomic(Path(out_dir), writer)
    return {"summary": summ, **written}

"""``report.md`` of a cam-cycle study: the inputs as used (cam, oil, surfaces), warnings,
results per surface set (films, friction, camshaft torque, contact pressure), the cam and
spring, figures and numerics. For the paper's case (or with ``--compare-paper``) also the
paper's headline claims beside tribodyn's numbers with an explanation of each difference.

Built from the study (its analysis, single-contact studies and the inputs as used it
recorded, :mod:`tribodyn.workflow.inputs_as_used`) and the results Dataset; no solver
calls, no building of the case's objects.
"""

from __future__ import annotations

import json
import math
import re
from pathlib import Path

import numpy as np

from .report_claims import _fmt, claims

__all__ = ["write_report", "report_text", "claims", "figures_section", "with_figures"]

_CAPTIONS = {
    "fig05": "Dry pressure for coating/steel modulus ratios (paper Fig. 5; R = 10 mm assumed).",
    "fig06": "EHL pressure and film for modulus ratios and the real pairs (paper Fig. 6; "
    "u_e = {u} m/s, R = 10 mm assumed).",
    "fig08": "Tappet velocity, implicit vs explicit (paper Fig. 8).",
    "fig09": "Contact force, implicit vs explicit, with the six representative points "
    "(paper Fig. 9).",
    "fig10": "Tappet acceleration, implicit vs explicit (paper Fig. 10).",
    "fig11": "Entraining speed, sliding speed and radius of curvature (paper Fig. 11).",
    "fig12": "Greenwood chart with the cycle's operating points (paper Fig. 12).",
    "fig13": "Pressure and film at the six points, uncoated vs WC-C (paper Fig. 13).",
    "fig14": "Pressure and film of the coatings (paper Fig. 14).",
    "fig15": "Central film over the cycle (paper Fig. 15).",
    "fig16": "Boundary (asperity) load (paper Fig. 16).",
    "fig17": "Boundary friction (paper Fig. 17).",
    "fig18": "Viscous friction (paper Fig. 18).",
    "fig19": "Friction power and friction energy per cycle.",
    "fig20": "Minimum film and λ = h_min/σ over the cycle.",
    "fig21": "Temperatures over the cycle: tappet and cam surfaces, mid-film and maximum "
    "(thermal EHL).",
    "fig22": "Central film and viscous friction, thermal vs isothermal at the inlet temperature.",
    "fig23": "Camshaft drive torque T = W s' + F_f (r_b + s) and friction torque "
    "T_f = F_f (r_b + s) over the cycle, per surface set.",
    "fig24": "Contact pressure over the cycle: Hertz p_h (dashed) and the EHL peak (solid).",
    "fig25": "Cam kinematics as used: lift, velocity, acceleration and radius of curvature "
    "of the fitted profile (with the table's points and the fit residual for a table cam).",
    "fig26": "Lift harmonics of the cam at n·f_cam against the valve spring's surge "
    "frequencies (resonance where a surge line meets a strong harmonic).",
    "fig27": "Subsurface von Mises stress of the body closest to failure, per surface set, at "
    "the crank angle of its smallest safety factor (interface dashed, governing peak marked).",
}
#: Captions of a case other than the paper's where the paper's caption names its own
#: surfaces or conditions (by content name, :func:`~tribodyn.output.figures.content_name`).
_CONTENT_CAPTIONS = {
    "tappet_velocity.png": "Tappet velocity, implicit vs explicit dynamics.",
    "contact_force.png": "Contact force, implicit vs explicit, with the six representative points.",
    "tappet_acceleration.png": "Tappet acceleration, implicit vs explicit dynamics.",
    "pressure_film_points.png": "Pressure and film at the six representative points, per "
    "surface set.",
    "coatings_pressure_film.png": "Pressure and film of the coated surfaces.",
}


def _asperity_models(surfaces: dict) -> str:
    """The asperity model(s) of the surface sets as used (``study.as_used.surfaces``),
    for the method sentence."""
    measured = [name for name, s in surfaces.items() if not s["greenwood_tripp"]]
    if not measured:
        return "Greenwood–Tripp asperities"
    law = "asperity load–separation law of a surface by boundary-element contact"
    if len(measured) == len(surfaces):
        return law
    return f"{law} ({', '.join(measured)}; Greenwood–Tripp for the other sets)"


def _pct_change(change, is_reference):
    """A change against the reference set (negative = less) or "reference"."""
    if is_reference:
        return "reference"
    if change is None:
        return "–"
    return f"{change:+.1f} %".replace("-", "−")


# ----------------------------------------------------------------------------- report
def model_comparison_section(study) -> list[str]:
    """ "Lumped vs flexible" table of a flexible case (empty for a lumped case)."""
    mc = getattr(study, "model_comparison", None)
    if mc is None or not mc.rows:
        return []
    cols = [m for m in ("lumped", "flexible") if m in mc.rows]
    spec = [
        ("peak contact force", "peak_contact_force_N", "N", 1.0),
        ("minimum contact force in the event", "min_contact_force_in_event_N", "N", 1.0),
        ("jump speed (engine)", "jump_speed_rpm", "rpm", 1.0),
        ("valve-seating velocity", "seating_velocity_m_s", "m/s", 1.0),
        ("friction energy per cycle", "friction_energy_per_cycle_J", "mJ", 1e3),
    ]
    lines = [
        "## Lumped vs flexible valvetrain",
        "",
        "The lumped companion has the flexible model's masses, spring rate, preload and "
        "static compliances; the differences are the bodies' flexibility (Craig–Bampton "
        "modes), the spring continuum with coil clash and the camshaft compliance. "
        "Explicit tribology, same cam and numerics.",
        "",
        "| quantity | " + " | ".join(cols) + " |",
        "|---" * (len(cols) + 1) + "|",
    ]
    for label, key, unit, f in spec:
        vals = [mc.rows[m].get(key) for m in cols]
        txt = [_fmt(None if v is None else v * f, unit, 4) for v in vals]
        lines.append(f"| {label} | " + " | ".join(txt) + " |")
    brackets = {m: mc.rows[m].get("jump_speed_bracket_rpm") for m in cols}
    if any(b is not None for b in brackets.values()):
        parts = [
            f"{m} {b[0]:.0f}–{b[1]:.0f} rpm in {mc.rows[m].get('jump_speed_runs', '?')} runs "
            f"(rigid-train quasi-static estimate, corrected by the case-speed run: "
            f"{mc.rows[m].get('quasi_static_jump_speed_rpm', math.nan):.0f} rpm)"
            for m in cols
            if (b := brackets[m]) is not None and all(map(math.isfinite, b))
        ]
        lines += [
            "",
            "Jump speed: the lowest engine speed with cam contact loss during the lift, the "
            "midpoint of a bracket (no jump, jump) of dynamics runs found by secant steps on "
            "the minimum contact force against n²: " + "; ".join(parts) + ".",
        ]
    return lines + [""]


def valve_jump_section(summ) -> list[str]:
    """The contact loss between cam and tappet (``summary["valve_jump"]``), if any: its
    intervals, the maximum separation and what to change."""
    j = summ.get("valve_jump") or {}
    if not j.get("jump"):
        return []
    iv = j.get("contact_loss_crank_deg") or []
    sep = j.get("max_separation_m")
    at = j.get("max_separation_crank_deg")
    lines = [
        "## Valve jump (contact loss)",
        "",
        f"The tappet leaves the cam in {len(iv)} interval(s) of the presented cycle, "
        f"{j.get('contact_lost_deg', 0.0):.1f}° crank in all (contact force zero; "
        "shaded in the contact-force figure). Maximum separation, tappet lift − cam lift: "
        f"{_fmt(sep and sep * 1e3, 'mm')}" + (f" at {at:.1f}° crank." if at is not None else "."),
        "",
        "| contact lost from | to | duration |",
        "|---|---|---|",
    ]
    lines += [f"| {a:.1f}° | {b:.1f}° | {b - a:.1f}° |" for a, b in iv[:10]]
    if len(iv) > 10:
        lines.append(f"| … {len(iv) - 10} more | | |")
    lines.append("")
    if j.get("onset_speed_rpm") is not None:
        lines += [f"Separation begins at about {j['onset_speed_rpm']:.0f} rpm.", ""]
    if j.get("warning"):
        lines += [f"What to change: {j['warning'].split('; to keep the contact ', 1)[-1]}.", ""]
    return lines


def _inputs_section(study, summ) -> list[str]:
    """The inputs as the study used them: cam, oil, surface sets, valvetrain."""
    case, used = study.case, study.as_used
    c = summ.get("cam", {})
    lines = ["## Inputs as used", ""]
    if case.case.description:
        lines += [f"{case.case.description}.", ""]
    kind = case.cam_config.type
    table = ""
    if c.get("table_points"):
        src = case.cam_table_path.name if case.cam_table_path is not None else "table"
        table = (
            f" {src}: {c['table_points']} points incl. the base circle, fit residual "
            f"RMS {_fmt(c['table_fit_rms_residual_m'] * 1e6, 'µm')}"
        )
    lines += [
        f"- Cam ({kind}{table}): base radius {used.cam_base_radius * 1e3:g} mm, width "
        f"{case.width * 1e3:g} mm, max lift {_fmt(c.get('max_lift_m', 0) * 1e3, 'mm', 4)}, "
        f"max tappet velocity {_fmt(c.get('max_velocity_m_s'), 'm/s')}, acceleration "
        f"{_fmt(c.get('min_acceleration_m_s2'), 'm/s²')} to "
        f"{_fmt(c.get('max_acceleration_m_s2'), 'm/s²')}, minimum radius of curvature "
        f"{_fmt((c.get('min_radius_of_curvature_m') or math.nan) * 1e3, 'mm')}; engine "
        f"{case.engine_speed:g} rpm (cam {case.engine_speed / 2:g} rpm)."
    ]
    oil = summ.get("lubricant", {})
    t_in = oil.get("inlet_temperature_C")
    lines.append(
        "- Oil as used"
        + (f" ({oil['oil']})" if oil.get("oil") else "")
        + (
            f" at {t_in:g} °C inlet"
            if t_in is not None
            else " (temperature not given: viscosity given directly)"
        )
        + f": viscosity μ₀ = {_fmt(oil.get('viscosity_Pa_s'), 'Pa s', 4)}, "
        f"pressure–viscosity α = {_fmt(oil.get('pressure_viscosity_1_Pa'), '1/Pa', 4)}, "
        f"density ρ₀ = {_fmt(oil.get('density_kg_m3'), 'kg/m³', 4)}, "
        f"Eyring stress {_fmt(oil.get('eyring_stress_Pa'), 'Pa')}, limiting-shear "
        f"coefficient {_fmt(oil.get('limiting_shear_coefficient'))}, "
        f"{oil.get('viscosity_model', '')} piezo-viscosity"
        + (", Dowson–Higginson density." if oil.get("compressible") else ", incompressible.")
    )
    lines += [
        "",
        "| surface set | coating | σ | asperity model | β | η | ηβσ | ς |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for s in used.surfaces.values():
        coat = (
            f"{s['coating_material']} {s['coating_thickness_m'] * 1e6:g} µm"
            if s["coating_thickness_m"] is not None
            else "none"
        )
        if s["greenwood_tripp"]:
            model = "Greenwood–Tripp"
            gt = (
                f"{s['summit_radius_m'] * 1e6:.3g} µm | {s['asperity_density_per_m2']:.3g} "
                f"/m² | {s['roughness_parameter']:.2g}"
            )
        else:  # β, η, ηβσ are not used by a surface's load–separation law
            model = "surface law (boundary elements)"
            gt = "– | – | –"
        lines.append(
            f"| {s['label']} | {coat} | {s['rms_m'] * 1e6:.3g} µm | {model} | {gt} | "
            f"{s['boundary_shear_coefficient']:g} |"
        )
    lines.append("")
    lines += [
        f"- Asperity law of {s['label']}: {s['asperity_law']}." for s in used.surfaces.values()
    ]
    return lines + [""] + _origins_lines(case)


def _origins_lines(case) -> list[str]:
    """Every engine, cam, valvetrain, lubricant, material and surface value with its
    origin, as the case recorded it (:func:`tribodyn.config.origins.input_origins`)."""
    from ..config.origins import input_origins

    lines = [
        "Every value, and where it comes from: *case* (given in the case file), *typical* "
        "(tribodyn.physics.typical, with how far its source was checked and the source), "
        "*datasheet* (from the oil's datasheet) or *assumed* (tribodyn's default).",
        "",
        "| key | value | origin |",
        "|---|---|---|",
    ]
    for key, value, unit, origin in input_origins(case):
        if value is None:
            shown = "absent"
        elif isinstance(value, bool):
            shown = str(value).lower()
        elif isinstance(value, str):
            shown = value
        else:
            shown = f"{value:g} {unit}".strip()
        lines.append(f"| {key} | {shown} | {origin} |")
    return lines + [""]


def _engineering_section(summ) -> list[str]:
    """Camshaft torque, friction power and contact pressure per set; spring surge."""
    sets = summ["surface_sets"]
    if not any("mean_friction_torque_Nm" in v for v in sets.values()):
        return []
    lines = [
        "## Camshaft torque and contact pressure",
        "",
        "T_f = F_f (r_b + s), T = W s' + T_f (F_f: viscous + boundary friction of the "
        "EHL, signed by the sliding direction; W contact force; s' contact offset); mean "
        "friction torque = ∮T_f dθ / 2π; friction power = mean T_f ω.",
        "",
        "| surface | mean friction torque | max friction torque | peak drive torque | "
        "friction energy per cycle | mean friction power | max Hertz p_h | max EHL "
        "pressure |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for v in sets.values():
        ph, pe = v.get("max_hertz_pressure_Pa"), v.get("max_ehl_pressure_Pa")
        lines.append(
            f"| {v['label']} | {_fmt(v.get('mean_friction_torque_Nm'), 'N m')} | "
            f"{_fmt(v.get('max_friction_torque_Nm'), 'N m')} | "
            f"{_fmt(v.get('peak_drive_torque_Nm'), 'N m')} | "
            f"{_fmt(v.get('friction_energy_per_cycle_from_torque_J'), 'J')} | "
            f"{_fmt(v.get('mean_friction_power_from_torque_W'), 'W')} | "
            f"{_fmt(ph and ph / 1e6, 'MPa')} | {_fmt(pe and pe / 1e6, 'MPa')} |"
        )
    sg = summ.get("spring_surge")
    if sg:
        f_cam = sg["cam_frequency_Hz"]
        parts = [
            f"mode {k} at {f:.0f} Hz ≈ cam harmonic {n} ({n * f_cam:.0f} Hz)"
            for k, (f, n) in enumerate(
                zip(sg["surge_frequencies_Hz"], sg["nearest_cam_harmonic"]), 1
            )
        ]
        lines += [
            "",
            "Valve-spring surge (both ends fixed: (k/2)√(k_s/m_s) of a lumped spring, the "
            f"coil continuum at its installed length of a flexible one): {'; '.join(parts)}. "
            f"The cam frequency is {f_cam:.3g} Hz; the lift's harmonic amplitudes are "
            "in results.nc (harmonic_amplitude) and the spring-surge figure.",
        ]
    return lines + [""]


def _nose_section(study) -> list[str]:
    """The single-contact studies at the case's own nose (steady EHL): every surface set,
    then the reference set's variants."""
    sens = study.sensitivity
    own = getattr(study, "nose_sets", None)
    if sens is None or not sens.cases:
        return []
    n = sens.conditions
    lines = [
        "## Single contact at the cam nose",
        "",
        f"Steady mixed EHL at this case's nose ({n.crank_deg:.0f}° crank: W = "
        f"{n.force:.0f} N, R = {n.radius * 1e3:.3g} mm, u_e = {n.entrainment_speed:.3g} "
        f"m/s, u_s = {n.sliding_speed:.3g} m/s).",
        "",
        "| surface / variant | h_c | h_min | μ | asperity load share | viscous friction "
        "| boundary friction |",
        "|---|---|---|---|---|---|---|",
    ]
    ref = study.labels.get(sens.surface_set, sens.surface_set)
    rows = [(k, c) for k, c in (own.cases.items() if own is not None else [])]
    rows += [(f"{ref}: {k}", c) for k, c in sens.cases.items() if k != "case roughness"]
    lines += [
        f"| {k}{'' if c.converged else ' (not converged)'} | "
        f"{_fmt(c.central_film_m * 1e6, 'µm')} | {_fmt(c.min_film_m * 1e6, 'µm')} | "
        f"{c.friction_coefficient:.3f} | {c.asperity_load_share * 100:.2g} % | "
        f"{_fmt(c.viscous_friction_N, 'N')} | {_fmt(c.boundary_friction_N, 'N')} |"
        for k, c in rows
    ]
    return lines + [""]


def report_text(study, ds, figures: dict) -> str:
    """The report as Markdown: about the case itself; with the paper's comparison (claims
    table, paper figure numbers) only when ``study.compare_paper``."""
    summ = study.analyse().summary
    case = study.case
    coupling = study.coupling
    paper_cmp = bool(getattr(study, "compare_paper", False))
    lines = [f"# tribodyn report — {summ.get('case', '')}", ""]
    lines += [
        f"Engine speed {summ['engine_speed_rpm']:g} rpm (cam {summ['engine_speed_rpm'] / 2:g} "
        f"rpm); cam width {case.width * 1e3:g} mm; tribodyn "
        f"{ds.attrs.get('tribodyn_version', '')}; run time {summ['runtime_s']:.1f} s.",
        "",
    ]
    from .report_first import verdict_section

    # what the engineer asks first: the verdict, torque and pressure, films and λ
    lines += verdict_section(summ)
    lines += _engineering_section(summ)
    first = summ["reference_set"]
    ref_label = summ["surface_sets"][first]["label"]
    lines += [
        "## Films, λ and friction per tappet surface",
        "",
        "Films and forces over the cam event; friction energy over all loaded "
        "samples of the presented cycle (totals over the cam width). Film gain: "
        "robust maximum and median |gain| under the rule at the end of this section. "
        f"Changes against {ref_label}: 100·(x/x_ref − 1), negative = less; of the maximum "
        "F_b, or of its cycle integral ∫F_b dt over the cam event.",
        "",
        "| surface | min film | max h_c | max film gain | median abs. film gain | "
        f"max boundary friction | max F_b vs {ref_label} | max viscous friction | "
        f"∫F_b dt vs {ref_label} | friction energy per cycle | mean friction power | "
        "min λ | failed steps |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    lines += [
        f"| {v['label']} | {_fmt(v['min_film_m'] and v['min_film_m'] * 1e6, 'µm')} | "
        f"{_fmt(v['max_central_film_m'] and v['max_central_film_m'] * 1e6, 'µm')} | "
        f"{_fmt(v['max_film_gain_vs_uncoated_pct'], '%')} | "
        f"{_fmt(v['median_abs_film_gain_vs_uncoated_pct'], '%')} | "
        f"{_fmt(v['max_boundary_friction_N'], 'N')} | "
        f"{_pct_change(v.get('max_boundary_friction_change_pct'), name == first)} | "
        f"{_fmt(v['max_viscous_friction_N'], 'N')} | "
        f"{_pct_change(v['boundary_friction_cycle_integral_change_pct'], name == first)} | "
        f"{_fmt(v['friction_energy_per_cycle_J'], 'J')} | "
        f"{_fmt(v['mean_friction_power_W'], 'W')} | {_fmt(v['min_lambda'])} | "
        f"{v['failed_steps']} |"
        for name, v in summ["surface_sets"].items()
    ]
    lines += ["", f"Film-gain rule: {summ['film_gain_rule']}.", ""]
    d = summ.get("dynamics", {})
    ue = d.get("entrainment_speed_range_m_s") or [None, None]
    rmin = d.get("min_radius_of_curvature_m")
    lines += [
        "Dynamics (explicit): peak contact force "
        f"{_fmt(d.get('peak_contact_force_N'), 'N')} at "
        f"{d.get('peak_contact_force_crank_deg', float('nan')):.1f}° crank; minimum in "
        f"the event {_fmt(d.get('min_contact_force_in_event_N'), 'N')}; u_e from "
        f"{_fmt(ue[0], 'm/s')} to {_fmt(ue[1], 'm/s')}; minimum R "
        f"{_fmt(rmin * 1e3 if rmin is not None else None, 'mm')}; "
        f"jump: {d.get('jump')}; valve bounce: {d.get('valve_bounce')}; seating "
        f"velocity {_fmt(d.get('seating_velocity_m_s'), 'm/s')}.",
        "",
    ]
    lines += valve_jump_section(summ)
    if study.warnings:
        lines += ["## Warnings", ""] + [f"- {w}" for w in study.warnings] + [""]
    lines += _inputs_section(study, summ)

    from .report_stress import stress_section

    lines += stress_section(summ)
    if not paper_cmp:
        lines += _nose_section(study)

    lines += model_comparison_section(study)
    from .report_thermal import thermal_section

    lines += thermal_section(study, summ)
    if paper_cmp:
        lines += [
            "## The paper's claims beside tribodyn",
            "",
            "| claim | paper | tribodyn | why |",
            "|---|---|---|---|",
        ]
        lines += [
            f"| {claim} | {pap} | {ours} | {why} |" for claim, pap, ours, why in claims(study, summ)
        ]
        lines.append("")

    lines += figures_section(ds, figures)

    lines += [
        "## Method",
        "",
        "Valvetrain multi-body dynamics over two engine cycles from static "
        "equilibrium (the second is presented), explicit analytic tribology; transient "
        "mixed-EHL (Reynolds with Roelands and Dowson–Higginson, "
        f"Reynolds cavitation, coated DC-FFT elasticity, {_asperity_models(study.as_used.surfaces)}, "
        f"{case.numerics.viscous_model} shear capped at the limiting shear stress, boundary "
        "friction τ₀ + ς p_a) along the presented cycle for each tappet surface"
        + (
            "; implicit dynamics with the numerical EHL for the comparison"
            + (" of the paper's Figs. 8–10" if paper_cmp else "")
            if case.numerics.implicit_coupling
            else ""
        )
        + ".",
        "",
    ]
    lines += ["## Numerics", ""]
    loaded = np.array([s.loaded for s in study.sets])
    conv = np.array([s.converged for s in study.sets])
    its = np.array([s.iterations for s in study.sets])
    lines.append(
        f"- Transient EHL: {int(loaded.sum())} loaded steps over {len(study.sets)} "
        f"surface sets, {int((loaded & ~conv).sum())} not converged"
        + (
            f"; Newton iterations per step mean {its[loaded].mean():.1f}, max "
            f"{int(its[loaded].max())}."
            if loaded.any()
            else " (no sample carries numerics.min_load: no film to compute)."
        )
    )
    for s in study.sets:
        if s.failures:
            shown = "; ".join(f"{c:.0f}°: {m}" for c, m in s.failures[:10])
            lines.append(
                f"- {s.name}: {len(s.failures)} failed step(s): {shown}"
                + (" …" if len(s.failures) > 10 else "")
            )
    if coupling.history:
        hist = ", ".join(f"{h.rms_force_change_N:.2f} N" for h in coupling.history)
        lines.append(
            f"- Implicit coupling: {coupling.message}; RMS change of the contact "
            f"force per iteration: {hist}."
        )
    lines.append(
        "- EHL NaN values in results.nc mark unloaded samples (the cam on its base "
        "circle carries no load): `loaded` = 0."
    )
    lines += ["", "## Case as run", ""]
    if paper_cmp:
        lines += [
            "The paper does not give the cam profile, tappet mass, spring preload, joint "
            "stiffness and damping, lubricant density or the radius of Figs. 5/6; those "
            "values are assumptions (marked ASSUMED in the bundled case file), and the "
            "paper's errata are corrected (Table 6 moduli are GPa, Table 4's ζ is the "
            "summit density η).",
            "",
        ]
    lines += [
        "The complete case as run (every key, defaults included):",
        "",
        "```toml",
        case.to_toml().strip(),
        "```",
        "",
    ]
    return "\n".join(lines)


#: The heading of the report's figure section (:func:`figures_section`).
FIGURES_HEADING = "## Figures"


def figures_section(ds, figures: dict) -> list[str]:
    """``## Figures`` of report.md: each figure of ``figures`` ({file name: path}) with
    its caption, in the report's order (:func:`~.report_first.figure_rank`); without
    figures, how to draw them (they are drawn on request: ``tribodyn figures``). Reads
    the Dataset's attributes only (``compare_paper``; the Fig. 6 conditions)."""
    lines = [FIGURES_HEADING, ""]
    if not figures:
        return lines + [
            "The static figures (PNG) are drawn on request: `tribodyn figures FOLDER` "
            "draws them into this result folder and lists them here, `tribodyn run "
            "--figures` draws them with the run. report.html shows the interactive traces.",
            "",
        ]
    from .figures import FIGURES, content_name
    from .report_first import METHOD_FIGURES, figure_rank

    paper_cmp = bool(ds.attrs.get("compare_paper", 1))
    coating = ds.attrs.get("ehl_coating_conditions")
    # only the coating study's figures quote it
    u = json.loads(coating).get("entrainment_speed") if coating else "–"
    numbered = {content_name(n): n for n in FIGURES}
    ordered = sorted(figures.items(), key=lambda kv: figure_rank(numbered.get(kv[0], kv[0])))
    method_head = False
    for key, path in ordered:
        name = Path(path).name
        k = numbered.get(name, name)[:5]  # figNN of a numbered or content name
        if k in METHOD_FIGURES and not method_head:
            method_head = True
            lines += [
                "### Method comparisons" + (" (the paper's Figs. 5, 6, 8–11)" if paper_cmp else ""),
                "",
            ]
        cap = _CONTENT_CAPTIONS.get(name) if not paper_cmp else None
        if cap is None:
            cap = _CAPTIONS[k].format(u=u) if k in _CAPTIONS else key
            if not paper_cmp:
                cap = re.sub(r" ?\(paper Fig\. \d+[^)]*\)", "", cap)
        lines += [f"![{cap}]({name})", "", f"*{cap}*", ""]
    return lines


def with_figures(text: str, ds, figures: dict) -> str:
    """report.md ``text`` with its figure section (from :data:`FIGURES_HEADING` to the
    next section of the same level) replaced by :func:`figures_section` of ``figures``.
    Raises :class:`ValueError` if the text has no figure section."""
    lines = text.split("\n")
    try:
        start = lines.index(FIGURES_HEADING)
    except ValueError:
        raise ValueError("report.md has no figure section") from None
    end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("## ")), len(lines))
    return "\n".join(lines[:start] + figures_section(ds, figures) + lines[end:])


def write_report(study, ds, figures: dict, path) -> Path:
    """Write report.md (:func:`~tribodyn._safe_write.atomic_write`); returns its path."""
    from .._safe_write import atomic_write

    return atomic_write(Path(path), report_text(study, ds, figures))

"""``report.md`` of an engine valvetrain study (:mod:`tribodyn.workflow.engine`).

First what an engineer asks: the friction energy per cycle and FMEP of each surface set
with the coating verdict against the reference set, the camshaft torques per shaft (the
numbers that are sums over the camshafts say so), the split between the cam–tappet
contacts and the auxiliary friction, the lobes' film, λ and contact pressure; then the
warnings, figures, the inputs as used, the method and the case as run.

Built from the study's summaries and the results Dataset (reading, no solver calls).
"""

from __future__ import annotations

import numpy as np

from .report_claims import _fmt

__all__ = ["engine_report_text"]

#: The parts of the valvetrain friction (summary key, name in the report): the cam–tappet
#: contacts, then the auxiliary friction.
ENGINE_PARTS = (
    ("cam_tappet", "cam–tappet contacts"),
    ("tappet_bore", "tappet bores"),
    ("valve_guide", "valve guides"),
    ("camshaft_journal", "camshaft journals"),
)
_FIGURES = {
    "engine_camshaft_torque.png": "Camshaft drive torque (top) and friction torque (bottom) "
    "per camshaft over the engine cycle: cam–tappet friction per surface set, the auxiliary "
    "friction (tappet bores + valve guides + journals) of the reference set.",
    "engine_lobe_contributions.png": "Each valve's cam–tappet friction torque, stacked per "
    "camshaft, with the camshaft's sum (reference set).",
}


def _pct(v, ref) -> str:
    if v is None or ref in (None, 0):
        return "–"
    return f"{100.0 * (v / ref - 1.0):+.2f} %".replace("-", "−")


def verdict_lines(eng: dict, labels: dict) -> list[str]:
    """One line per coated set: does it lower the valvetrain friction energy (and so
    the FMEP) against the reference set, and by how much (negative = less). A
    ``coating_verdict`` of the set's summary is used where present."""
    ref = eng["reference_set"]
    sets = eng["surface_sets"]
    e0 = sets[ref]["engine_friction_energy_per_cycle_J"]
    out = []
    for name, d in sets.items():
        if name == ref:
            continue
        lab = labels.get(name, name)
        given = d.get("coating_verdict")
        ct0 = sets[ref]["friction_energy_per_cycle_J"]["cam_tappet"]
        ct = d["friction_energy_per_cycle_J"]["cam_tappet"]
        e = d["engine_friction_energy_per_cycle_J"]
        pct = 100.0 * (e / e0 - 1.0)
        word = "lowers" if pct < 0 else "does not lower"
        rng = given.get("range_pct") if isinstance(given, dict) else None
        extra = ""
        if rng:
            lo, hi = (f"{x:+.1f}".replace("-", "−") for x in rng)
            settled = "" if given.get("sign_settled") else " (the sign is not settled)"
            extra = f" Over the published ranges of ς, τ_E and Λ: {lo} … {hi} %{settled}."
        out.append(
            f"- **{lab}** {word} the valvetrain friction: energy per cycle and FMEP "
            f"{_pct(e, e0)} against {labels.get(ref, ref)} ({_fmt(e, 'J', 4)} vs "
            f"{_fmt(e0, 'J', 4)}); the cam–tappet contacts alone {_pct(ct, ct0)}.{extra}"
        )
    return out


def shaft_peaks(ds) -> np.ndarray | None:
    """Peak |drive torque| (set, camshaft) of the stored traces."""
    if ds is None or "camshaft_drive_torque" not in ds:
        return None
    return np.nanmax(np.abs(np.asarray(ds["camshaft_drive_torque"].values, float)), axis=-1)


def _lobe_rows(study, labels) -> list[str]:
    """Film, λ and contact pressure of each lobe kind's single-valve study."""
    rows = []
    done: dict[int, str] = {}
    for kind, lt in study.lobes.items():
        if lt.study is None:
            continue
        if id(lt.study) in done:
            rows.append(f"| {kind} | (the {done[id(lt.study)]} lobe's numbers) | | | | |")
            continue
        done[id(lt.study)] = kind
        summ = lt.study.analyse().summary["surface_sets"]
        for name, v in summ.items():
            ph, pe = v.get("max_hertz_pressure_Pa"), v.get("max_ehl_pressure_Pa")
            hmin = v.get("min_film_m")
            rows.append(
                f"| {kind} | {labels.get(name, name)} | "
                f"{_fmt(hmin and hmin * 1e6, 'µm')} | {_fmt(v.get('min_lambda'))} | "
                f"{_fmt(ph and ph / 1e6, 'MPa')} | {_fmt(pe and pe / 1e6, 'MPa')} |"
            )
    return rows


def engine_report_text(study, ds, summ: dict, figures, labels: dict | None = None) -> str:
    """The report as Markdown (module docstring). ``summ``: summary.json's content;
    ``figures``: the figure file names written; ``labels``: display names of the sets."""
    eng = summ["engine"]
    labels = labels or {}
    sets = eng["surface_sets"]
    ref = eng["reference_set"]
    shafts = list(eng["camshafts"])
    lab = lambda n: labels.get(n, n)  # noqa: E731
    vd = eng.get("displacement_m3")
    lines = [
        f"# tribodyn engine report — {summ.get('case', '')}",
        "",
        f"{eng['cylinders']} cylinders, {eng['valves']} valves, "
        f"{len(shafts)} camshaft{'s' if len(shafts) > 1 else ''} ({', '.join(shafts)}), "
        f"displacement {_fmt(vd and vd * 1e3, 'l', 4)}, {eng['speed_rpm']:g} rpm "
        f"(camshafts {eng['speed_rpm'] / 2:g} rpm); run time {summ.get('runtime_s', 0):.1f} s.",
        "",
        "## Friction and coating verdict",
        "",
        "Valvetrain friction energy per engine cycle E (cam–tappet contacts + tappet bores "
        "+ valve guides + camshaft journals, all camshafts), FMEP = E / V_d, mean power "
        "P = E / t_cycle, mean torque T = E / 2π (per camshaft revolution, camshafts summed).",
        "",
        *verdict_lines(eng, labels),
        "",
        f"| surface set | E per cycle | FMEP | vs {lab(ref)} | mean friction power | mean "
        "friction torque (camshafts summed) | failed EHL steps |",
        "|---|---|---|---|---|---|---|",
    ]
    e0 = sets[ref]["engine_friction_energy_per_cycle_J"]
    for name, d in sets.items():
        e = d["engine_friction_energy_per_cycle_J"]
        failed = ", ".join(f"{k} {v}" for k, v in d.get("failed_steps", {}).items())
        lines.append(
            f"| {lab(name)} | {_fmt(e, 'J', 4)} | "
            f"{_fmt(d['valvetrain_friction_mep_Pa'] / 1e3, 'kPa', 4)} | "
            f"{'reference' if name == ref else _pct(e, e0)} | "
            f"{_fmt(d['mean_friction_power_W'], 'W', 4)} | "
            f"{_fmt(d['mean_friction_torque_Nm'], 'N·m', 4)} | {failed or '–'} |"
        )
    peaks = shaft_peaks(ds)
    lines += [
        "",
        "## Camshaft torque per camshaft",
        "",
        "Per camshaft: mean friction torque (contacts + auxiliary), the largest friction "
        "torque, the peak |drive torque| of its cam–tappet contacts (T = W s' + T_f summed "
        "over its lobes) and its friction energy per cycle.",
        "",
        "| surface set | camshaft | mean friction torque | max friction torque | peak drive "
        "torque | friction energy | of which cam–tappet |",
        "|---|---|---|---|---|---|---|",
    ]
    for i, (name, d) in enumerate(sets.items()):
        for j, c in enumerate(shafts):
            cs = d["camshafts"][c]
            pk = None if peaks is None else float(peaks[i, j])
            lines.append(
                f"| {lab(name)} | {c} | {_fmt(cs['mean_friction_torque_Nm'], 'N·m', 4)} | "
                f"{_fmt(cs['max_friction_torque_Nm'], 'N·m', 4)} | {_fmt(pk, 'N·m', 4)} | "
                f"{_fmt(cs['friction_energy_per_cycle_J'], 'J', 4)} | "
                f"{_fmt(cs['cam_tappet_friction_energy_per_cycle_J'], 'J', 4)} |"
            )
    lines += [
        "",
        "Sums over all camshafts (summary.json): `mean_friction_torque_Nm` is the mean of "
        "the camshafts' summed friction torque; `peak_camshaft_drive_torque_Nm` is the peak "
        "|drive torque| of the summed camshafts ("
        + ", ".join(
            f"{lab(n)} {_fmt(d['peak_camshaft_drive_torque_Nm'], 'N·m', 4)}"
            for n, d in sets.items()
        )
        + "): the shafts' peaks fall at different crank angles, so it is neither one "
        "shaft's peak nor the sum of their peaks.",
        "",
        "## Where the friction goes",
        "",
        "| surface set | " + " | ".join(p for _, p in ENGINE_PARTS) + " | total |",
        "|---" * (len(ENGINE_PARTS) + 2) + "|",
    ]
    for name, d in sets.items():
        parts = d["friction_energy_per_cycle_J"]
        tot = d["engine_friction_energy_per_cycle_J"]
        cells = [
            f"{_fmt(parts.get(k), 'J', 3)} ({100 * parts.get(k, 0) / tot:.0f} %)" if tot else "–"
            for k, _ in ENGINE_PARTS
        ]
        lines.append(f"| {lab(name)} | " + " | ".join(cells) + f" | {_fmt(tot, 'J', 4)} |")
    lobe = _lobe_rows(study, labels)
    if lobe:
        lines += [
            "",
            "## Film, λ and contact pressure of the lobes",
            "",
            "One valve of each lobe kind (the engine's valves are these, phase-shifted): "
            "minimum film h_min, λ = h_min/σ (below about 3 the asperities touch), largest "
            "Hertz pressure p_h and EHL pressure peak over the cycle.",
            "",
            "| lobe | surface set | min h_min | min λ | max p_h | max EHL pressure |",
            "|---|---|---|---|---|---|",
            *lobe,
        ]
    if summ.get("warnings"):
        lines += ["", "## Warnings", "", *[f"- {w}" for w in summ["warnings"]]]
    lines += [""]
    if figures:
        lines += ["## Figures", ""]
        for name in figures:
            cap = _FIGURES.get(name, name)
            lines += [f"![{cap}]({name})", "", f"*{cap}*", ""]
    lines += _inputs(study)
    lines += [
        "## Method",
        "",
        "Each lobe kind (intake, exhaust) is one cam-cycle study — valvetrain dynamics, "
        "then the transient mixed EHL of every surface set along the cycle — phase-shifted "
        "to every valve of its kind by the firing order. Auxiliary friction beside the "
        "contacts: tappet in its bore (edge reactions × μ_b + Couette shear), valve stem in "
        "its guide (Couette + boundary at the side load), camshaft journals (Ocvirk short "
        "bearing under the lobes' loads). Friction torque T_f = F_f (r_b + s); energy "
        "E = ∮ T dθ over a camshaft revolution.",
        "",
        "## Case as run",
        "",
        "```toml",
        study.case.to_toml().strip(),
        "```",
        "",
    ]
    return "\n".join(lines)


def _inputs(study) -> list[str]:
    """Inputs as used: the first lobe study's cam, oil and surface sets."""
    from .report import _inputs_section

    lt = next((lt for lt in study.lobes.values() if lt.study is not None), None)
    if lt is None or lt.study is None:
        return []
    lines = _inputs_section(lt.study, lt.study.analyse().summary)
    return [ln.replace("## Inputs as used", "## Inputs as used (intake lobe)") for ln in lines]

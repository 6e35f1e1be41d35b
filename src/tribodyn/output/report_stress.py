"""The report's section on coating integrity: per surface set the failure mode closest
to its strength, where (cam or tappet, x along the contact, depth z) and when (crank
angle) it peaks, the margin (safety factor = strength / cycle maximum), and the Archard
wear of the tappet surface. Built from ``summary.json`` (see
:func:`tribodyn.workflow.stress_study.set_stress_summary`)."""

from __future__ import annotations

import math

__all__ = ["stress_section"]

#: The failure modes of the safety factors, in order, with their names in the report.
MODES = {
    "substrate_yield": "substrate yield (von Mises / Tabor H/3)",
    "surface_tension": "surface cracking (tension)",
    "coating_tension": "coating cracking (tension)",
    "coating_yield": "coating yield (von Mises / H/3)",
    "interface_shear": "delamination (interface shear)",
    "interface_tension": "delamination (interface tension)",
}


def table_number(v, fmt, scale=1.0, unit=""):
    """``v`` × ``scale`` in the format ``fmt`` with its ``unit``; "–" if missing or not
    finite."""
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "–"
    return format(v * scale, fmt) + (f" {unit}" if unit else "")


def stress_section(summary: dict) -> list[str]:
    """Markdown lines of the section (empty list when no set has stress results). Crank
    angles are the run's (``crank_deg`` in summary.json: the presented cycle, 720–1440°
    with the default two cycles), as in every other table, figure and warning."""
    sets = {n: e for n, e in summary.get("surface_sets", {}).items() if "min_safety_factor" in e}
    if not sets:
        return []
    a, b = summary.get("presented_cycle_crank_deg") or (720.0, 1440.0)  # as the summary says
    cycle = f"{a:g}–{b:g}°"
    out = [
        "## Coating integrity",
        "",
        "Subsurface stresses of the cam and the tappet at every loaded EHL sample (EHL "
        "pressure with the mean asperity pressure, viscous and boundary shear), against "
        "typical or case-given strengths. Safety factor = strength / cycle maximum "
        "(> 1 survives, elastic analysis). The typical coating tensile and adhesion "
        "strengths and wear coefficients are *assumed* values (tribodyn.physics.strength): "
        "give measured ones in `[strength.<material>]`.",
        "",
        f"| surface | closest failure | body | x [µm] | z [µm] | crank [°, {cycle}] | stress [MPa] "
        "| safety factor |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for name, e in sets.items():
        w = e.get("stress_closest_failure") or {}
        out.append(
            "| {label} | {mode} | {body} | {x} | {z} | {c} | {s} | {sf} |".format(
                label=e.get("label", name),
                mode=MODES.get(str(w.get("mode")), "–"),
                body=w.get("body", "–"),
                x=table_number(w.get("x_m"), ".1f", 1e6),
                z=table_number(w.get("z_m"), ".2f", 1e6),
                c=table_number(w.get("crank_deg"), ".0f"),
                s=table_number(w.get("stress_Pa"), ".0f", 1e-6),
                sf=table_number(w.get("safety_factor"), ".2f"),
            )
        )
    worst = min(sets.items(), key=lambda kv: kv[1]["min_safety_factor"] or math.inf)
    w = worst[1].get("stress_closest_failure")
    if w:
        out += [
            "",
            f"Closest to failure: **{worst[1].get('label', worst[0])}**, "
            f"{MODES[w['mode']]} of the {w['body']} at "
            f"{w['crank_deg']:.0f}° crank (presented cycle {cycle}), "
            f"x = {w['x_m'] * 1e6:.1f} µm, z = {w['z_m'] * 1e6:.2f} µm, "
            f"safety factor {w['safety_factor']:.2f}.",
        ]
    estimates = _wear_lines(sets) + _asperity_lines(sets)
    if estimates:
        out += [
            "",
            "### Estimates outside their validity (not headline numbers)",
            "",
            "These numbers rest on assumed inputs or leave the theory they use; each is "
            "given with its range or its limit, and with the measurement that would pin it.",
            *estimates,
        ]
    hours = {e.get("running_hours") for e in sets.values()} - {None}
    if hours:
        h = hours.pop()
        worn = [
            e.get("label", n) for n, e in sets.items() if e.get("worn_through_in_running_hours")
        ]
        out += [
            "",
            f"After {h:g} running hours: "
            + (("worn through: " + ", ".join(worn)) if worn else "no coating worn through")
            + ".",
        ]
    out.append("")
    return out


def _hours_range(hours, assumed: bool) -> str:
    from ..physics.strength import WEAR_COEFFICIENT_SPREAD as f

    if hours is None or not math.isfinite(hours):
        return "–"
    if not assumed:
        return format(hours, ".3g")
    return f"{hours / f:.3g} … {hours * f:.3g} (at k: {hours:.3g})"


def _wear_lines(sets: dict) -> list[str]:
    """Archard wear per cycle and hours to wear through, over the range of an assumed
    wear coefficient (k/10 … 10 k, physics.strength.WEAR_COEFFICIENT_SPREAD)."""
    from ..physics.strength import WEAR_COEFFICIENT_SPREAD as f

    rows = []
    assumed_any = False
    for name, e in sets.items():
        if e.get("wear_depth_per_cycle_m") is None:
            continue
        src = str(e.get("wear_coefficient_source") or "")
        assumed = "assumed" in src.lower()
        assumed_any |= assumed
        d = e["wear_depth_per_cycle_m"] * 1e9
        depth = f"{d / f:.2e} … {d * f:.2e}" if assumed else f"{d:.2e}"
        rows.append(
            f"| {e.get('label', name)} | {table_number(e.get('wear_coefficient_m3_per_Nm'), '.2g')} "
            f"| {'assumed' if assumed else 'case'} | {depth} | "
            f"{_hours_range(e.get('hours_to_wear_through'), assumed)} |"
        )
    if not rows:
        return []
    srcs = {e.get("wear_coefficient_source") for e in sets.values()} - {None}
    return [
        "",
        "Archard wear of the tappet surface (wear coefficient k "
        + ("assumed: an order of magnitude either way" if assumed_any else "from the case")
        + "; "
        + "; ".join(sorted(srcs))
        + "). A wear depth measured on a tappet after a known running time, or k from a "
        "tribometer test at the contact's pressure, sliding speed and oil, would pin it.",
        "",
        "| surface | k [m³/(N m)] | k from | wear / cycle [nm] | hours to wear through |",
        "|---|---|---|---|---|",
        *rows,
    ]


def _asperity_lines(sets: dict) -> list[str]:
    """The asperity-scale ESTIMATE (physics.asperity_stress) of each set, beside the
    EHL-scale margins above."""
    rows = []
    outside = 0  # rows with a/β above 0.3: outside small-strain Hertz theory
    for name, e in sets.items():
        a = e.get("asperity_scale_estimate")
        if not a:
            continue
        for body in ("cam", "tappet"):
            b = a[body]
            beyond = (b.get("radius_over_summit") or 0.0) > 0.3
            outside += beyond
            if beyond:  # Hertz does not hold: no stress numbers, only the limit
                rows.append(
                    f"| {body} | {e.get('label', name)} | {table_number(b.get('gap_ratio'), '.2f')} "
                    f"| beyond Hertz | {table_number(b.get('radius_m'), '.2f', 1e6)} "
                    f"| {table_number(b.get('radius_over_summit'), '.2f')} | beyond Hertz | – | – | – |"
                )
                continue
            rows.append(
                "| {body} | {label} | {lam} | {pm} | {rad} | {ab} | {vm} | {z} | {sfy} | {sft} |".format(
                    label=e.get("label", name),
                    body=body,
                    lam=table_number(b.get("gap_ratio"), ".2f"),
                    pm=table_number(b.get("mean_pressure_Pa"), ".0f", 1e-6),
                    rad=table_number(b.get("radius_m"), ".2f", 1e6),
                    ab=table_number(b.get("radius_over_summit"), ".2f"),
                    vm=table_number(b.get("max_von_mises_Pa"), ".0f", 1e-6),
                    z=table_number(b.get("depth_m"), ".2f", 1e6),
                    sfy=table_number(b.get("safety_factor_yield"), ".2f"),
                    sft=table_number(b.get("safety_factor_tension"), ".2f"),
                )
            )
    if not rows:
        return []
    return (
        [
            "",
            "Asperity scale, an ESTIMATE (tribodyn.physics.asperity_stress): one Hertzian "
            "summit of radius β at the mean micro-contact pressure p_a/(A_a/A) at the "
            "smallest film of the cycle; elastic, frictionless, homogeneous. Hertz needs "
            "a/β ≪ 1; a factor below 1 means the summits yield (running-in), not that the "
            "coating fails.",
            "",
            "| body | surface | h/σ | p_m [MPa] | a [µm] | a/β | von Mises [MPa] | z [µm] "
            "| yield factor | tension factor |",
            "|---|---|---|---|---|---|---|---|---|---|",
            *rows,
        ]
        + (
            [
                "",
                f"In {outside} of these rows a/β > 0.3: the summits are too sharp for Hertz "
                "theory, so their pressure, von Mises stress and factors are not given: the "
                "estimate is outside the theory it uses (summary.json keeps the numbers for "
                "reference).",
            ]
            if outside
            else []
        )
        + [
            "",
            "The summit radius β and the micro-contact pressure decide these rows. A "
            "topography measured at sub-µm lateral resolution (summit curvatures) and the "
            "real contact area or hardness after running-in would pin them.",
        ]
    )

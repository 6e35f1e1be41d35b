"""What a cycle-study report says first: a coating verdict per coated surface set
(friction energy, friction torque, film and λ against the reference set), and the order
of the figures (the engineer's first: torque, friction power, film and λ, pressure; the
paper's method comparisons last). Reads the study's summary only."""

from __future__ import annotations

__all__ = ["verdict_section", "figure_rank", "METHOD_FIGURES"]

#: Figures comparing methods (explicit vs implicit dynamics, coating moduli): shown last.
METHOD_FIGURES = ("fig08", "fig09", "fig10", "fig11", "fig05", "fig06")
_FIRST = (
    "fig23",
    "fig19",
    "fig20",
    "fig24",
    "fig15",
    "fig17",
    "fig18",
    "fig16",
    "fig21",
    "fig22",
    "fig27",
    "fig12",
    "fig13",
    "fig14",
    "fig25",
    "fig26",
)


def figure_rank(key: str) -> tuple[int, int]:
    """Sort key of a figure by its ``figNN`` key: the engineer's figures first, the
    method comparisons last, anything else between."""
    k = key[:5]
    if k in _FIRST:
        return (0, _FIRST.index(k))
    if k in METHOD_FIGURES:
        return (2, METHOD_FIGURES.index(k))
    return (1, 0)


def _change(v, ref) -> str | None:
    if not isinstance(v, int | float) or not isinstance(ref, int | float) or ref == 0:
        return None
    return f"{100.0 * (v / ref - 1.0):+.1f} %".replace("-", "−")


def verdict_section(summ: dict) -> list[str]:
    """``## Coating verdict``: per coated set, whether it lowers the friction energy per
    cycle against the reference set and by how much (negative = less), with the changes
    of the mean friction torque and of the minimum film and λ. A ``coating_verdict``
    in the set's summary is quoted as it is."""
    sets = summ.get("surface_sets", {})
    ref = summ.get("reference_set")
    if ref not in sets or len(sets) < 2:
        return []
    r = sets[ref]
    lines = [
        "## Coating verdict",
        "",
        f"Against {r.get('label', ref)} (negative = less; friction energy over the cycle, "
        "totals over the cam width):",
        "",
    ]
    for name, v in sets.items():
        if name == ref:
            continue
        lab = v.get("label", name)
        given = v.get("coating_verdict")
        if isinstance(given, str) and given:
            lines.append(f"- **{lab}**: {given}")
            continue
        e, e0 = v.get("friction_energy_per_cycle_J"), r.get("friction_energy_per_cycle_J")
        de = _change(e, e0)
        if de is None:
            lines.append(f"- **{lab}**: no friction energy to compare.")
            continue
        word = "lowers" if e < e0 else "does not lower"
        parts = [f"friction energy per cycle {de} ({e:.4g} J vs {e0:.4g} J)"]
        for key, what in (
            ("mean_friction_torque_Nm", "mean friction torque"),
            ("min_film_m", "minimum film h_min"),
            ("min_lambda", "minimum λ"),
        ):
            d = _change(v.get(key), r.get(key))
            if d is not None:
                parts.append(f"{what} {d}")
        lines.append(f"- **{lab}** {word} the friction: " + ", ".join(parts) + ".")
    return lines + [""]

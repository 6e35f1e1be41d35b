"""What a cycle-study report says first: a coating verdict per coated surface set
(friction energy, friction torque, film and λ against the reference set), and the order
of the figures (the engineer's first: torque, friction power, film and λ, pressure; the
paper's method comparisons last). Reads the study's summary only."""

from __future__ import annotations

from ..workflow.verdict import _pct as _signed  # the verdict sentence's signed percentage

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
    ranged = []  # the sets' coating_verdict records (with their range), for the method
    for name, v in sets.items():
        if name == ref:
            continue
        lab = v.get("label", name)
        given = v.get("coating_verdict")
        e, e0 = v.get("friction_energy_per_cycle_J"), r.get("friction_energy_per_cycle_J")
        de = _change(e, e0)
        parts = [] if de is None else [f"friction energy per cycle {de} ({e:.4g} J vs {e0:.4g} J)"]
        for key, what in (
            ("mean_friction_torque_Nm", "mean friction torque"),
            ("min_film_m", "minimum film h_min"),
            ("min_lambda", "minimum λ"),
        ):
            d = _change(v.get(key), r.get(key))
            if d is not None:
                parts.append(f"{what} {d}")
        if isinstance(given, dict) and given.get("sentence"):
            ranged.append((lab, given))
            if de is not None:  # the sentence gives the change: here only the energies
                parts[0] = f"{e:.4g} J vs {e0:.4g} J"
            lines.append(f"- **{given['sentence']}**" + (f" ({', '.join(parts)})" if parts else ""))
        elif de is None:
            lines.append(f"- **{lab}**: no friction energy to compare.")
        else:
            word = "lowers" if e < e0 else "does not lower"
            lines.append(f"- **{lab}** {word} the friction: " + ", ".join(parts) + ".")
    lines.append("")
    if ranged:
        lines += [f"How the range was computed: {ranged[0][1]['method']}", ""]
        wide = "; ".join(
            f"{lab} {_signed(vd['range_independent_pct'][0])} … "
            f"{_signed(vd['range_independent_pct'][1])} %"
            for lab, vd in ranged
            if vd.get("range_independent_pct")
        )
        if wide:
            lines += [f"With each pair's ς varied on its own: {wide}.", ""]
    return lines

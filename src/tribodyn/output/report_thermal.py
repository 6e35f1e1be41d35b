"""The thermal parts of ``report.md``: a section with temperatures and film/friction
thermal vs isothermal per surface set, and the claims-table row on the coatings' thermal
effect (what the paper's isothermal model cannot see)."""

from __future__ import annotations

from .report_stress import table_number

__all__ = ["thermal_claim_row", "thermal_section"]

_C = 273.15


def thermal_claim_row(study, summ) -> tuple[str, str, str, str]:
    """(claim, paper, tribodyn, why) of the coatings' thermal effect."""
    claim = "Coatings' thermal effect on viscous friction and film (DLC, WC-C at 1 and 4 µm)"
    paper = "not modelled (isothermal model)"
    th = summ.get("thermal")
    if th is None:
        return (
            claim,
            paper,
            "not computed in this run (numerics.thermal = false)",
            "The paper's model, and this run, are isothermal: the oil has its inlet "
            "viscosity everywhere. Run the bundled thermal variant "
            "(`tribodyn run andreou2023_thermal`) for the thermal EHL with the "
            "coatings' conductivities.",
        )
    eff = th.get("coating_thermal_effect", {})
    ref = summ["reference_set"]
    t_ref = th["surface_sets"].get(ref, {}).get("max_surface_temperature_tappet_K")
    parts = [
        f"{study.labels[name]}: viscous friction energy "
        f"{table_number(v['viscous_energy_vs_reference_thermal_pct'], '+.1f', unit='%')} vs "
        f"{study.labels.get(ref, ref)} "
        f"(isothermal {table_number(v['viscous_energy_vs_reference_isothermal_pct'], '+.1f', unit='%')}"
        f"), mean film {table_number(v['mean_film_vs_reference_thermal_pct'], '+.1f', unit='%')} "
        f"(isothermal {table_number(v['mean_film_vs_reference_isothermal_pct'], '+.2f', unit='%')}); "
        f"tappet surface up to "
        f"{table_number(v['max_tappet_surface_temperature_K'] - _C, '.0f', unit='°C')}"
        for name, v in eff.items()
    ]
    ours = "; ".join(parts) if parts else "no coated surface set converged in all runs"
    if t_ref is not None:
        ours += f" (uncoated tappet surface up to {t_ref - _C:.0f} °C)"
    why = (
        "The coatings conduct heat poorly (DLC ≈ 1, WC-C ≈ 2 W/(m K) against 46 for "
        "steel; effusivity √(kρc) 8× and 6× lower): the frictional heat stays at the "
        "tappet surface, which runs hotter, and the oil sheared against it thins, so "
        "the viscous friction falls — more for the thicker layer, where the tappet "
        "surface moves slowly through the contact and the heat has time to build up. "
        "The film, formed in the inlet before most heat is generated, changes much "
        "less. The isothermal model sees only the modulus and roughness of the "
        "coatings. Differences are thermal minus isothermal changes against the "
        "uncoated tappet over the cam event (samples converged in all runs)."
    )
    return claim, paper, ours, why


def thermal_section(study, summ) -> list[str]:
    th = summ.get("thermal")
    if th is None:
        return []
    t_in = th.get("inlet_temperature_K")
    oil = study.as_used.thermal_oil
    lines = [
        "## Thermal EHL",
        "",
        f"Oil {oil['name'] or 'from the case'} supplied at {table_number(t_in - _C, '.0f', unit='°C')}"
        f" (μ = {oil['viscosity_Pa_s'] * 1e3:.3g} mPa·s, α = "
        f"{oil['pressure_viscosity_1_Pa'] * 1e9:.3g} 1/GPa, β = "
        f"{oil['temperature_viscosity_1_K']:.3g} 1/K there); the cam and the "
        "tappet far from the contact at the same temperature. Generalized Reynolds "
        "equation with the viscosity varying across the film, energy equation in the "
        "film (conduction across, convection along and across, shear and compression "
        "heating), conduction in the moving cam and in the coated tappet, Eyring shear "
        "at the local temperature capped by the limiting shear stress, boundary-"
        "friction heat at the surfaces. The isothermal results are the same EHL at the "
        "inlet temperature. The implicit dynamics comparison, if run, uses the "
        "isothermal EHL.",
        "",
        "| surface | max tappet surface | max cam surface | max mid-film | max "
        "temperature | mean h_c thermal vs isothermal | viscous friction energy thermal "
        "/ isothermal | friction energy thermal / isothermal |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for name, v in th["surface_sets"].items():
        if not v.get("samples"):
            lines.append(f"| {study.labels[name]} | – | – | – | – | – | – | – |")
            continue
        lines.append(
            f"| {study.labels[name]} | "
            f"{table_number(v['max_surface_temperature_tappet_K'] - _C, '.0f', unit='°C')} | "
            f"{table_number(v['max_surface_temperature_cam_K'] - _C, '.0f', unit='°C')} | "
            f"{table_number(v['max_mid_film_temperature_K'] - _C, '.0f', unit='°C')} | "
            f"{table_number(v['max_temperature_K'] - _C, '.0f', unit='°C')} | "
            f"{table_number(v['mean_central_film_change_pct'], '+.1f', unit='%')} | "
            f"{table_number(v['viscous_friction_energy_thermal_J'], '.3g')} / "
            f"{table_number(v['viscous_friction_energy_isothermal_J'], '.3g', unit='J')} | "
            f"{table_number(v['friction_energy_thermal_J'], '.3g')} / "
            f"{table_number(v['friction_energy_isothermal_J'], '.3g', unit='J')} |"
        )
    lines += [
        "",
        "Temperatures: maxima over the cam event; energies over the samples that "
        "converged in both models. The per-surface table above and the figures show "
        "the thermal model.",
        "",
    ]
    return lines

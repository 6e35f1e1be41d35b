"""The table of ``tribodyn contact``: one contact's results in engineering units (µm,
MPa), with the regime and the subsurface stresses.
"""

from __future__ import annotations

from pathlib import Path

from rich.markup import escape
from rich.table import Table

_REGIME_NAMES = {
    "IR": "isoviscous–rigid",
    "PR": "piezoviscous–rigid",
    "IE": "isoviscous–elastic",
    "PE": "piezoviscous–elastic",
}


def _g(v, scale=1.0, digits=4) -> str:
    if v is None:
        return "–"
    return f"{v * scale:.{digits}g}"


def _table(r: dict) -> Table:
    dry = r["mode"] == "dry"
    title = (
        "tribodyn contact — dry line contact (frictionless)"
        if dry
        else "tribodyn contact — steady mixed-EHL line contact"
    )
    t = Table(
        title=title,
        title_justify="left",
        show_header=True,
        caption=None
        if dry
        else "* hydrodynamic rolling force (Poiseuille part of Eq. 16): acts on the cam "
        "and on the tappet alike, > 0 against the entrainment; not in the friction total",
        caption_justify="left",
    )
    t.add_column("quantity")
    t.add_column("value", justify="right")
    t.add_column("unit")

    def sec(name):
        t.add_row(f"[bold]{name}[/bold]", "", "")

    sec("inputs")
    if r["case"]:
        t.add_row("case", escape(Path(r["case"]).name), "")
    if r["surface_set"]:
        t.add_row("surface set", escape(r["surface_set"]), "")
    t.add_row("surfaces (tappet)", escape(r["surfaces"]), "")
    t.add_row("load W (over width)", _g(r["load_N"]), "N")
    t.add_row("width", _g(r["width_m"], 1e3), "mm")
    t.add_row("load per length w", _g(r["load_per_length_N_per_m"], 1e-3), "kN/m")
    t.add_row("radius R", _g(r["radius_m"], 1e3), "mm")
    if not dry:
        t.add_row("entrainment speed u_e", _g(r["entrainment_speed_m_per_s"]), "m/s")
        t.add_row("sliding speed u_s", _g(r["sliding_speed_m_per_s"]), "m/s")
        if r["roughness_rms_m"] is not None:
            t.add_row(
                "roughness η, σ, β",
                f"{r['asperity_density_per_m2']:.3g}, "
                f"{r['roughness_rms_m'] * 1e6:.4g}, {r['summit_radius_m'] * 1e6:.4g}",
                "1/m², µm, µm",
            )
        else:
            t.add_row("roughness", "smooth", "")
        if r.get("inlet_temperature_K") is not None and not r.get("thermal"):
            t.add_row(
                "oil, inlet temperature (isothermal)",
                f"{escape(str(r['oil'] or 'case'))}, {r['inlet_temperature_K'] - 273.15:.1f}",
                "°C",
            )
        t.add_row(
            "lubricant μ₀, α",
            f"{r['viscosity_Pa_s']:.4g}, {r['pressure_viscosity_per_Pa'] * 1e9:.4g}",
            "Pa·s, 1/GPa",
        )
        t.add_row(
            "boundary ς, τ₀",
            f"{r['boundary_shear_coefficient']:.4g}, {r['boundary_shear_strength_Pa'] * 1e-6:.4g}",
            "–, MPa",
        )
    t.add_row("reduced modulus E' (bulk)", _g(r["reduced_modulus_Pa"], 1e-9), "GPa")
    if r["coating_thickness_m"] is not None:
        t.add_row("E' of the surfaces", _g(r["surface_reduced_modulus_Pa"], 1e-9), "GPa")
    sec("Hertz (bulk E')")
    t.add_row("half-width b", _g(r["hertz_half_width_m"], 1e6), "µm")
    t.add_row("max pressure p_h", _g(r["hertz_max_pressure_Pa"], 1e-6), "MPa")
    if dry:
        sec("dry solution")
        t.add_row("half-width", _g(r["half_width_m"], 1e6), "µm")
        t.add_row("max pressure", _g(r["max_pressure_Pa"], 1e-6), "MPa")
        t.add_row("b / b_Hertz", _g(r["half_width_m"] / r["hertz_half_width_m"], 1, 5), "")
    else:
        sec("film")
        t.add_row("central film h_c", _g(r["central_film_m"], 1e6), "µm")
        t.add_row("minimum film h_min", _g(r["min_film_m"], 1e6), "µm")
        t.add_row("  at x", _g(r["min_film_position_m"], 1e6), "µm")
        t.add_row("λ = h_min/σ", _g(r["film_parameter_lambda"], 1, 3), "")
        t.add_row("max pressure", _g(r["max_pressure_Pa"], 1e-6), "MPa")
        t.add_row(
            "Pan–Hamrock h_c, h_min",
            f"{r['pan_hamrock_central_film_m'] * 1e6:.4g}, {r['pan_hamrock_min_film_m'] * 1e6:.4g}",
            "µm",
        )
        t.add_row("Moes h_c", _g(r["moes_central_film_m"], 1e6), "µm")
        sec("loads, friction (over width)")
        t.add_row("hydrodynamic load", _g(r["hydrodynamic_load_N"]), "N")
        t.add_row(
            "asperity load",
            "–"
            if r["asperity_load_N"] is None
            else f"{r['asperity_load_N']:.4g} ({100 * r['asperity_load_share']:.3g} %)",
            "N",
        )
        t.add_row("viscous friction", _g(r["viscous_friction_N"]), "N")
        t.add_row("boundary friction", _g(r["boundary_friction_N"]), "N")
        t.add_row("friction", _g(r["friction_N"]), "N")
        t.add_row("friction coefficient", _g(r["friction_coefficient"], 1, 4), "")
        t.add_row("rolling force, each surface*", _g(r["rolling_friction_N"]), "N")
        t.add_row(
            "force on cam, tappet (along u_e)",
            "–"
            if r["surface_friction_cam_N"] is None
            else f"{r['surface_friction_cam_N']:.4g}, {r['surface_friction_tappet_N']:.4g}",
            "N",
        )
        if r.get("thermal"):
            c = 273.15
            sec("thermal (vs isothermal at the inlet temperature)")
            t.add_row(
                "oil, inlet temperature",
                f"{escape(str(r['oil'] or 'case'))}, {r['inlet_temperature_K'] - c:.1f}",
                "°C",
            )
            t.add_row("max temperature", _g(r["max_temperature_K"] - c, 1, 4), "°C")
            t.add_row(
                "surfaces cam, tappet (max)",
                f"{r['max_surface_temperature_cam_K'] - c:.4g}, "
                f"{r['max_surface_temperature_tappet_K'] - c:.4g}",
                "°C",
            )
            t.add_row("mid-film at x = 0", _g(r["central_mid_film_temperature_K"] - c, 1, 4), "°C")
            t.add_row(
                "h_c thermal, isothermal",
                f"{r['central_film_m'] * 1e6:.4g}, {r['isothermal_central_film_m'] * 1e6:.4g}",
                "µm",
            )
            t.add_row(
                "viscous friction th., iso.",
                f"{r['viscous_friction_N']:.4g}, {r['isothermal_viscous_friction_N']:.4g}",
                "N",
            )
        if "stress" in r:
            _stress_rows(t, sec, r["stress"])
        sec("regime (Greenwood chart)")
        t.add_row("g_V, g_E", f"{r['greenwood_gV']:.4g}, {r['greenwood_gE']:.4g}", "")
        t.add_row("regime", r["regime"], _REGIME_NAMES.get(r["regime"], ""))
    sec("solver")
    ok = "[green]yes[/green]" if r["converged"] else "[red]NO[/red]"
    t.add_row("converged", ok, "")
    t.add_row("grid nodes, iterations", f"{r['grid_points']}, {r['iterations']}", "")
    return t


def _stress_rows(t: Table, sec, st: dict | None) -> None:
    """Rows of ``--stress``: the peaks of each body and the safety factors (a mode's
    name: its key, spaced)."""
    from ..output.report_stress import MODES

    sec("subsurface stress (peak; x, z)")
    if st is None:
        t.add_row("stresses", "–", "no EHL solution")
        return
    for body in ("cam", "tappet"):
        for k, label in (
            ("max_von_mises_substrate", "von Mises, substrate"),
            ("max_von_mises_coating", "von Mises, coating"),
            ("max_tension_surface", "tension, surface"),
            ("max_interface_shear", "|shear|, interface"),
            ("max_interface_tension", "tension, interface"),
        ):
            v = st.get(f"{body}_{k}_Pa")
            if v is None:
                continue
            x, z = st[f"{body}_{k}_x_m"] * 1e6, st[f"{body}_{k}_z_m"] * 1e6
            t.add_row(f"{body}: {label}", f"{v * 1e-6:.4g}", f"MPa at {x:.3g}, {z:.3g} µm")
    sec("safety factors (strength / peak)")
    for body in ("cam", "tappet"):
        for mode in MODES:
            v = st.get(f"safety_factor_{body}_{mode}")
            if v is not None:
                t.add_row(
                    f"{body}: {mode.replace('_', ' ')}",
                    "∞" if v == float("inf") else f"{v:.3g}",
                    "",
                )
    w = st.get("closest_failure")
    if w:
        t.add_row(
            "closest to failure",
            f"{w['safety_factor']:.3g}",
            f"{w['body']}, {w['mode'].replace('_', ' ')}",
        )

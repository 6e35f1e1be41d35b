"""File names and titles of the report figures: their one list, read by the figures and
by the rules of a result folder (which files are tribodyn's), without loading matplotlib."""

from __future__ import annotations

import re

__all__ = ["FIGURES", "content_name"]

#: File names and titles of the figures :func:`make_figures` writes, in order.
FIGURES = {
    "fig05_dry_pressure.png": "Dry contact pressure for coating/steel modulus ratios (paper Fig. 5)",
    "fig06_ehl_pressure_film.png": "EHL pressure and film for coating moduli and real pairs (paper Fig. 6)",
    "fig08_tappet_velocity.png": "Tappet velocity, explicit vs implicit EHL (paper Fig. 8)",
    "fig09_contact_force.png": "Cam–tappet contact force, explicit vs implicit EHL (paper Fig. 9)",
    "fig10_tappet_acceleration.png": "Tappet acceleration, explicit vs implicit EHL (paper Fig. 10)",
    "fig11_entrainment_speed.png": "Entraining speed, sliding speed and radius of curvature (paper Fig. 11)",
    "fig12_greenwood_chart.png": "Greenwood chart of the operating points (paper Fig. 12)",
    "fig13_pressure_film_points.png": "Pressure and film at the six representative points (paper Fig. 13)",
    "fig14_coatings_pressure_film.png": "Pressure and film of the coated surfaces (paper Fig. 14)",
    "fig15_central_film.png": "Central film thickness over the cycle (paper Fig. 15)",
    "fig16_boundary_load.png": "Asperity (boundary) load over the cycle (paper Fig. 16)",
    "fig17_boundary_friction.png": "Boundary friction over the cycle (paper Fig. 17)",
    "fig18_viscous_friction.png": "Viscous friction over the cycle (paper Fig. 18)",
    "fig19_friction_power.png": "Friction power and friction energy per cycle",
    "fig20_min_film_lambda.png": "Minimum film thickness and λ = h_min/σ over the cycle",
    "fig21_temperatures.png": "Temperatures over the cycle (thermal EHL)",
    "fig22_thermal_vs_isothermal.png": "Film and viscous friction, thermal vs isothermal",
    "fig23_camshaft_torque.png": "Camshaft drive and friction torque over the cycle",
    "fig24_contact_pressure.png": "Contact pressure over the cycle: Hertz and EHL peak",
    "fig25_cam_kinematics.png": "Cam kinematics as used (fitted profile)",
    "fig26_spring_surge.png": "Valve-spring surge modes against the cam's excitation harmonics",
    "fig27_stress_map.png": "Subsurface von Mises stress at the instant of greatest risk",
}


def content_name(name: str) -> str:
    """The file name of a figure named by its content: ``fig23_camshaft_torque.png`` →
    ``camshaft_torque.png`` (a case other than the paper's gets these names)."""
    return re.sub(r"^fig\d\d_", "", name)


class _Titles(dict):
    """Figure titles by file name; a content name (:func:`content_name`) gets its
    numbered figure's title without the paper's figure number."""

    def __missing__(self, key):
        for name, title in self.items():
            if content_name(name) == key:
                return re.sub(r" \(paper Fig\. \d+\)", "", title)
        raise KeyError(key)


FIGURES = _Titles(FIGURES)

"""The asperity-scale stress ESTIMATE (tribodyn.physics.asperity_stress) for the bundled
cases' roughness at a few film ratios h/σ, steel on steel, with the typical steel
strengths. Not a timed test.

    python benchmarks/asperity_estimate_table.py
"""

import tribodyn  # noqa: F401  (one BLAS thread, before numpy loads)
from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.physics.asperity_stress import micro_contact_estimate
from tribodyn.physics.materials import STEEL, Body, reduced_modulus
from tribodyn.physics.strength import TYPICAL_STRENGTH


def main():
    steel = TYPICAL_STRENGTH["steel"]
    e_red = reduced_modulus((Body(STEEL), Body(STEEL)), surface=True)
    print(
        "| case (first surface set) | σ/β | h/σ | p_m [GPa] | a [µm] | a/β | von Mises [GPa] "
        "| z [µm] | yield factor | tension factor |"
    )
    print("|---|---|---|---|---|---|---|---|---|---|")
    for name in ("andreou2023", "engine_dohc16", "flat_tappet_rig"):
        case = load_case(name)
        r = build(case).surface_sets[0].roughness
        for lam in (1.0, 2.0, 3.0):
            m = micro_contact_estimate(r, lam * r.rms, e_red, STEEL.nu)
            print(
                f"| {name} | {r.rms / r.summit_radius:.3g} | {lam:.0f} | "
                f"{m.mean_pressure / 1e9:.2f} | {m.radius * 1e6:.2f} | "
                f"{m.radius_over_summit:.3f} | {m.max_von_mises / 1e9:.2f} | "
                f"{m.depth * 1e6:.2f} | {steel.yield_stress / m.max_von_mises:.2f} | "
                f"{steel.tensile_strength / m.edge_tension:.2f} |"
            )


if __name__ == "__main__":
    main()

"""Greenwood–Tripp with a surface's own McCool parameters against the boundary-element
load–separation law of the same surface (synthetic self-affine, σ 0.2 µm, H 0.8,
wavelengths 3.2 or 6.4 µm to 25.6 µm; steel pair, hardness 7 GPa). Greenwood–Tripp two
ways: as tribodyn uses it (summit heights with the surface's σ about its mean plane) and
with McCool's summit-height mean y_s and spread σ_s (p ∝ (ηβσ_s)² √(σ_s/β) F₅/₂((h −
y_s)/σ_s)). Separations where the 128² boundary-element map has contact only (λ ≤ 2).
Prints JSON."""

from __future__ import annotations

import json

from tribodyn.physics.asperity import Roughness, greenwood_tripp
from tribodyn.topography.load_separation import synthetic_load_separation
from tribodyn.topography.spectral_moments import mccool_parameters
from tribodyn.topography.synthetic import synthetic_moments

E_PRIME = 2.3e11  # steel pair [Pa]
SIGMA, HURST, LONG = 0.2e-6, 0.8, 25.6e-6


def main() -> None:
    out = []
    for short in (3.2e-6, 6.4e-6):
        mc = mccool_parameters(synthetic_moments(SIGMA, HURST, short, LONG))
        gt = Roughness(mc.asperity_density, SIGMA, mc.summit_radius)
        law = synthetic_load_separation(SIGMA, HURST, short, LONG, E_PRIME, 7e9)
        rows = []
        eta, beta = mc.asperity_density, mc.summit_radius
        ys, ss = mc.summit_height_mean, mc.summit_height_std
        scale = gt.pressure_scale(E_PRIME) * (ss / SIGMA) ** 2.5
        for lam in (2.0, 1.5, 1.0, 0.6, 0.3):
            p_gt = float(gt.asperity_pressure(lam * SIGMA, E_PRIME))
            p_gts = scale * float(greenwood_tripp(2.5, (lam * SIGMA - ys) / ss))
            p_bem = float(law.pressure_ratio(lam)[0]) * E_PRIME
            rows.append(
                {
                    "lambda": lam,
                    "gt_Pa": p_gt,
                    "gt_summit_datum_Pa": p_gts,
                    "bem_Pa": p_bem,
                    "ratio_bem_gt": p_bem / p_gt,
                    "ratio_bem_gt_summit_datum": p_bem / p_gts,
                }
            )
        out.append(
            {
                "short_cutoff_m": short,
                "eta_beta_sigma": eta * beta * SIGMA,
                "sigma_over_beta": SIGMA / beta,
                "summit_mean_over_sigma": ys / SIGMA,
                "summit_std_over_sigma": ss / SIGMA,
                "bem_points_lambda": [float(x) for x in law.lam],
                "points": rows,
            }
        )
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()

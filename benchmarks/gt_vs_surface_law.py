"""Greenwood–Tripp with a surface's own McCool parameters against the boundary-element
load–separation law of the same surface (synthetic self-affine, σ 0.2 µm, H 0.8,
wavelengths 3.2 or 6.4 µm to 25.6 µm; steel pair, hardness 7 GPa). Prints JSON."""

from __future__ import annotations

import json

from tribodyn.physics.asperity import Roughness
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
        for lam in (3.0, 2.0, 1.5, 1.0, 0.6, 0.3):
            p_gt = float(gt.asperity_pressure(lam * SIGMA, E_PRIME))
            p_bem = float(law.pressure_ratio(lam)[0]) * E_PRIME
            rows.append({"lambda": lam, "gt_Pa": p_gt, "bem_Pa": p_bem, "ratio": p_bem / p_gt})
        out.append(
            {
                "short_cutoff_m": short,
                "eta_beta_sigma": mc.asperity_density * mc.summit_radius * SIGMA,
                "sigma_over_beta": SIGMA / mc.summit_radius,
                "points": rows,
            }
        )
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()

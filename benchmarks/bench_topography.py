"""Timings of the topography analysis (prints JSON). Not a test.

Synthetic isotropic Gaussian surfaces (0.1 µm pixels, wavelengths 0.2–51.2 µm) are
analysed with a Gaussian band-pass of 1.6–25.6 µm (16–256 pixels): periodic maps as
generated, non-periodic ones cropped (mirror-stitched filtering), and one read from an
``.x3p`` file. Each case reports the best of ``REPEAT`` runs.
"""

from __future__ import annotations

import json
import platform
import tempfile
import warnings
from pathlib import Path

import numpy as np

from timing import best_of
from tribodyn.topography import analyse_surface, synthetic_surface, write_topography

PIXEL = 0.1e-6
BAND = (16 * PIXEL, 256 * PIXEL)
REPEAT = 2


def summary(r) -> dict:
    return {
        "summit_count": r.summit_stats.count,
        "eta_summits_per_m2": r.summits.asperity_density,
        "eta_spectral_per_m2": r.spectral.asperity_density,
        "beta_summits_m": r.summits.summit_radius,
        "beta_spectral_m": r.spectral.summit_radius,
        "eta_deviation": r.summits.asperity_density / r.spectral.asperity_density - 1,
        "beta_deviation": r.summits.summit_radius / r.spectral.summit_radius - 1,
    }


def main():
    from SurfaceTopography import Topography

    warnings.filterwarnings("ignore", category=DeprecationWarning)
    results = []
    for n in (512, 2048):
        t_gen, topo = best_of(
            lambda: synthetic_surface(
                (n, n),
                PIXEL,
                rms=0.3e-6,
                hurst=0.8,
                short_cutoff=2 * PIXEL,
                long_cutoff=n // 4 * PIXEL,
                seed=1,
            ),
            REPEAT,
        )
        t_per, r_per = best_of(lambda: analyse_surface(topo, band=BAND), REPEAT)
        m = n - n // 16
        crop = Topography(topo.heights()[:m, :m], (m * PIXEL, m * PIXEL), periodic=False, unit="m")
        t_non, r_non = best_of(lambda: analyse_surface(crop, band=BAND), REPEAT)
        with tempfile.TemporaryDirectory() as tmp:
            path = write_topography(crop, Path(tmp) / "map.x3p")
            t_file, _ = best_of(lambda: analyse_surface(path, band=BAND), REPEAT)
        results.append(
            {
                "grid": [n, n],
                "generate_s": round(t_gen, 3),
                "analyse_periodic_s": round(t_per, 3),
                "analyse_nonperiodic_s": round(t_non, 3),
                "nonperiodic_grid": [m, m],
                "read_x3p_and_analyse_s": round(t_file, 3),
                "periodic": summary(r_per),
                "nonperiodic": summary(r_non),
            }
        )
    print(
        json.dumps(
            {
                "benchmark": "topography",
                "band_m": list(BAND),
                "pixel_m": PIXEL,
                "python": platform.python_version(),
                "numpy": np.__version__,
                "cases": results,
            },
            indent=2,
        )
    )


if __name__ == "__main__":
    main()

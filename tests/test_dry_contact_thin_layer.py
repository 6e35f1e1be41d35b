"""Coated dry contact in the thin-soft-layer limit: the layer acts as an elastic foundation.

A layer of thickness h ≪ a bonded to a much stiffer substrate is compressed in uniaxial
strain (it cannot expand sideways, to leading order in h/a), so the local pressure is
p = k·(compression), k = E_c(1 − ν_c)/((1 + ν_c)(1 − 2ν_c) h) (the P-wave, or constrained,
modulus over h). With a rigid cylinder of radius R (Winkler foundation):

    p(x) = p₀(1 − x²/a²),   a = (3wR/(2k))^(1/3),   p₀ = k a²/(2R).

The profile is parabolic, not Hertz's ellipse; its size depends on ν_c through the
lateral constraint. Corrections: the edge layer of width ~h (O(h/a)) and the compliance
of substrate and counterface, ~(k h/E'_s)(a/h) ≈ 0.5 % here.
"""

import numpy as np
import pytest

from tribodyn import Body, Coating, Material, solve_dry_contact

STIFF = Material(2e12, 0.1)  # substrate and counterface: 10⁴ × the layer
R = 0.01
A = 100e-6  # target half-width; h/a = 0.05


@pytest.mark.parametrize("nu_c", [0.2, 0.3])
def test_thin_soft_layer_on_stiff_substrate_is_an_elastic_foundation(nu_c):
    ec, h = 2e8, 5e-6
    k = ec * (1 - nu_c) / ((1 + nu_c) * (1 - 2 * nu_c) * h)
    w = 2 * k * A**3 / (3 * R)
    a = (3 * w * R / (2 * k)) ** (1 / 3)
    p0 = k * a**2 / (2 * R)
    r = solve_dry_contact(w, R, (Body(STIFF), Body(STIFF, Coating(ec, nu_c, h))))
    assert r.converged, r.message
    # measured: a −0.8 / −0.7 %, p₀ −0.2 %, RMS 0.2 % p₀ (ν_c = 0.2 / 0.3, 1024 nodes)
    assert r.half_width == pytest.approx(a, rel=1.5e-2)
    assert r.max_pressure == pytest.approx(p0, rel=1e-2)
    p_ref = p0 * np.clip(1 - (r.x / a) ** 2, 0, None)
    assert np.sqrt(np.mean((r.pressure - p_ref)[np.abs(r.x) < 1.2 * a] ** 2)) < 1e-2 * p0
    # the bulk Hertz contact would be 16 times narrower: the layer governs
    assert r.hertz.half_width < 0.1 * a

"""The asperity-scale stress ESTIMATE (physics.asperity_stress): a Hertzian summit at the
mean micro-contact pressure of the Greenwood–Tripp model.

References: Boussinesq's point-load field integrated numerically over the Hertz pressure
(independent of the closed form under test); Hertz's sphere (Johnson, Contact Mechanics,
§4.2); the published maximum shear 0.31 p0 at 0.47–0.48a for ν = 0.3 and the edge
tension (1 − 2ν)p0/3 (Johnson §3.4; both as quoted in secondary sources, e.g.
"Rules of Thumb for Mechanical Engineers", p. 230, for the edge tension)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import numpy as np
import pytest
from scipy import integrate

from tribodyn import InputError
from tribodyn.physics.asperity import Roughness
from tribodyn.physics.asperity_stress import (
    hertz_sphere_axis_stress,
    hertz_sphere_peak_von_mises,
    mean_micro_contact_pressure,
    micro_contact_estimate,
)
from tribodyn.physics.materials import Body, Coating, Material, reduced_modulus
from tribodyn.physics.strength import TYPICAL_STRENGTH
from tribodyn.workflow.stress_study import asperity_estimate


def _boussinesq_axis(zeta: float, nu: float) -> tuple[float, float]:
    """σ_z/p0, σ_r/p0 on the axis of the Hertz pressure p0√(1 − r²) (a = 1), summed from
    Boussinesq's point loads on rings: a ring of load dP at radius r gives on the axis
    σ_z = −3 dP z³/(2πρ⁵) and σ_r = ½(σ_r + σ_θ) of the point load,
    dP/(4π)[(1 − 2ν) z/ρ³ − 3 z r²/ρ⁵], ρ² = r² + z² (Boussinesq; Johnson §3.2)."""
    z = zeta

    def dp(r):
        return math.sqrt(max(1.0 - r * r, 0.0)) * 2.0 * math.pi * r

    def sz(r):
        rho = math.hypot(r, z)
        return -3.0 * dp(r) * z**3 / (2.0 * math.pi * rho**5)

    def sr(r):
        rho = math.hypot(r, z)
        return dp(r) / (4.0 * math.pi) * ((1.0 - 2.0 * nu) * z / rho**3 - 3.0 * z * r * r / rho**5)

    opts = {"epsabs": 1e-13, "epsrel": 1e-11, "limit": 400}
    return integrate.quad(sz, 0.0, 1.0, **opts)[0], integrate.quad(sr, 0.0, 1.0, **opts)[0]


@pytest.mark.parametrize("nu", [0.3, 0.22])
def test_axis_field_against_boussinesq_quadrature(nu):
    for zeta in (0.05, 0.2, 0.48, 1.0, 2.5):
        sz_ref, sr_ref = _boussinesq_axis(zeta, nu)
        sz, sr = hertz_sphere_axis_stress(zeta, nu)
        assert float(sz) == pytest.approx(sz_ref, abs=1e-8)
        assert float(sr) == pytest.approx(sr_ref, abs=1e-8)
    # at the surface: σ_z = −p0, σ_r = −(1 + 2ν)p0/2 (Johnson §3.4, at r = 0)
    sz0, sr0 = hertz_sphere_axis_stress(0.0, nu)
    assert float(sz0) == pytest.approx(-1.0, abs=1e-12)
    assert float(sr0) == pytest.approx(-(1.0 + 2.0 * nu) / 2.0, abs=1e-12)


def test_peak_von_mises_against_published_shear_maximum():
    vm, zeta = hertz_sphere_peak_von_mises(0.3)
    # on the axis σ_vM = 2 τ_max: published 0.31 p0 at 0.47–0.48 a (ν = 0.3)
    assert vm / 2.0 == pytest.approx(0.31, abs=0.005)
    assert 0.465 <= zeta <= 0.49
    # and the brute-force maximum of the independent quadrature field
    zs = np.linspace(0.40, 0.56, 33)
    ref = max(abs(sr - sz) for sz, sr in (_boussinesq_axis(z, 0.3) for z in zs))
    assert vm == pytest.approx(ref, rel=2e-4)


def test_micro_contact_is_a_hertz_summit_at_the_mean_asperity_pressure():
    rough = Roughness(asperity_density=2e9, rms=0.2e-6, summit_radius=20e-6)
    e_red = 231e9  # E' (1/E' = ½Σ(1−ν²)/E); E* = E'/2
    for lam in (0.5, 1.5, 3.0):
        h = lam * rough.rms
        pm = float(mean_micro_contact_pressure(rough, h, e_red))
        # the model's own mean asperity pressure over its real-area fraction
        ref = float(rough.asperity_pressure(h, e_red)) / float(rough.contact_area_fraction(h))
        assert pm == pytest.approx(ref, rel=1e-12)
        est = micro_contact_estimate(rough, h, e_red, 0.3)
        # Hertz sphere of radius β on a flat, E* = E'/2: a = √(βw), P = (4/3)E*√β w^{3/2}
        w = est.radius**2 / rough.summit_radius
        load = 4.0 / 3.0 * (e_red / 2.0) * math.sqrt(rough.summit_radius) * w**1.5
        assert load / (math.pi * est.radius**2) == pytest.approx(pm, rel=1e-12)
        assert est.peak_pressure == pytest.approx(3.0 * load / (2.0 * math.pi * est.radius**2))
        assert est.edge_tension == pytest.approx(0.4 / 3.0 * est.peak_pressure)
        assert est.max_von_mises == pytest.approx(0.620 * est.peak_pressure, rel=2e-3)
        assert est.depth == pytest.approx(0.481 * est.radius, rel=2e-3)
    # the mean micro-contact pressure is largest at the smallest gap
    p = mean_micro_contact_pressure(rough, np.linspace(-1.0, 4.0, 51) * rough.rms, e_red)
    assert np.all(np.diff(p) < 0.0)


def test_cycle_estimate_at_the_smallest_film_with_the_surface_strengths():
    steel = Material(E=210e9, nu=0.3)
    cam = Body(steel)
    tappet = Body(steel, Coating(E=150e9, nu=0.2, thickness=2e-6))
    rough = Roughness(asperity_density=2e9, rms=0.2e-6, summit_radius=20e-6)
    film = np.array([np.nan, 0.5e-6, 0.25e-6, 0.1e-6, 0.3e-6])
    result = SimpleNamespace(
        crank_angle=np.array([300.0, 320.0, 340.0, 360.0, 380.0]),
        loaded=np.array([False, True, True, True, True]),
        converged=np.array([False, True, True, False, True]),  # 360° did not converge
        min_film=film,
    )
    strengths = {
        "cam": (TYPICAL_STRENGTH["steel"], None),
        "tappet": (TYPICAL_STRENGTH["steel"], TYPICAL_STRENGTH["dlc"]),
    }
    est = asperity_estimate(result, (cam, tappet), rough, strengths)
    assert est["crank_deg"] == 340.0 and est["gap_m"] == 0.25e-6
    e_s = reduced_modulus((cam, tappet), surface=True)
    for name, mat, nu in (("cam", "steel", 0.3), ("tappet", "dlc", 0.2)):
        ref = micro_contact_estimate(rough, 0.25e-6, e_s, nu)
        got = est[name]
        assert got["max_von_mises_Pa"] == pytest.approx(ref.max_von_mises)
        s = TYPICAL_STRENGTH[mat]
        assert got["safety_factor_yield"] == pytest.approx(s.yield_stress / ref.max_von_mises)
        assert got["safety_factor_tension"] == pytest.approx(s.tensile_strength / ref.edge_tension)
    assert est["tappet"]["radius_over_thickness"] == pytest.approx(est["tappet"]["radius_m"] / 2e-6)
    assert "radius_over_thickness" not in est["cam"]
    assert asperity_estimate(result, (cam, tappet), None, strengths) is None
    # no summit touches: no numbers (None in summary.json, not NaN)
    far = SimpleNamespace(**{**vars(result), "min_film": np.full(5, 40.0 * rough.rms)})
    est = asperity_estimate(far, (cam, tappet), rough, strengths)
    assert est["cam"]["max_von_mises_Pa"] is None
    assert est["tappet"]["safety_factor_yield"] is None
    assert est["tappet"]["radius_over_thickness"] is None


def test_bad_inputs_are_input_errors():
    rough = Roughness(asperity_density=2e9, rms=0.2e-6, summit_radius=20e-6)
    with pytest.raises(InputError, match="nu"):
        micro_contact_estimate(rough, 0.2e-6, 231e9, 0.7)
    with pytest.raises(InputError, match="reduced_modulus"):
        micro_contact_estimate(rough, 0.2e-6, -1.0, 0.3)
    with pytest.raises(InputError, match="zeta"):
        hertz_sphere_axis_stress(-0.1, 0.3)


def test_no_summit_estimate_for_a_measured_surface_law():
    """A measured-surface law has no Greenwood–Tripp summit radius: no Hertzian summit
    is built from it (the estimate would mix the law's pressure with an unrelated β)."""
    from tribodyn.physics.asperity_law import LoadSeparationLaw

    steel = Material(E=210e9, nu=0.3)
    pair = (Body(steel), Body(steel))
    lam = np.array([0.0, 1.0, 2.0, 3.0])
    law = LoadSeparationLaw(lam, [1e9, 1e8, 1e7, 1e6], [0.5, 0.1, 0.01, 0.001], 2.3e11)
    rough = Roughness(asperity_density=2e9, rms=0.2e-6, summit_radius=20e-6, law=law)
    result = SimpleNamespace(
        crank_angle=np.array([340.0]),
        loaded=np.array([True]),
        converged=np.array([True]),
        min_film=np.array([0.1e-6]),
    )
    assert asperity_estimate(result, pair, rough) is None
    assert asperity_estimate(result, pair, Roughness(2e9, 0.2e-6, 20e-6)) is not None

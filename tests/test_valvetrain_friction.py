"""Auxiliary friction of a direct-acting valvetrain against closed forms and independent
quadratures (tappet bore, camshaft journal bearings, valve guide)."""

import math

import numpy as np
import pytest
from scipy import integrate

from tribodyn import InputError
from tribodyn.physics import valvetrain_friction as vf


def test_tappet_side_loads_satisfy_rigid_body_equilibrium():
    """The edge reactions balance the cam's forces: solved here as a generic 2-D linear
    equilibrium (forces across the axis and moments about the face centre)."""
    g = vf.BoreGeometry(diameter=0.033, guided_length=0.02, clearance=2e-5, edge_offset=0.004)
    rng = np.random.default_rng(1)
    for _ in range(20):
        w, ff, e = rng.uniform(10, 3000), rng.uniform(-100, 100), rng.uniform(-0.01, 0.01)
        # unknowns N_a (at z = a), N_b (at z = a + L); cam friction on the tappet −F_f at
        # z = 0, normal force W at x = e; M_y = z F_x − x F_z about the face centre
        a, L = g.edge_offset, g.guided_length
        A = np.array([[1.0, 1.0], [a, a + L]])
        b = np.array([ff, e * w])  # ΣF_x: N_a + N_b − F_f = 0; ΣM: a N_a + (a+L) N_b − e W = 0
        ref = np.linalg.solve(A, b)
        na, nb = vf.tappet_side_loads(w, ff, e, g)
        assert na == pytest.approx(ref[0], rel=1e-12, abs=1e-9)
        assert nb == pytest.approx(ref[1], rel=1e-12, abs=1e-9)


def test_thin_annulus_couette_matches_exact_coaxial_flow():
    """η π D L v / c against the exact 2 π η L v / ln(R_o/R_i) of axial Couette flow
    between coaxial cylinders: equal to O(c/D)."""
    eta, d, length, v = 0.01, 0.007, 0.04, 3.0
    for c in (5e-6, 2e-5):
        exact = 2 * math.pi * eta * length * v / math.log((d / 2 + c) / (d / 2))
        thin = vf.annulus_couette_force(eta, d, length, c, v)
        assert thin == pytest.approx(exact, rel=2.0 * c / d)
        assert abs(thin / exact - 1) > 0.1 * c / d  # the thin-film limit, not the exact law


def test_bore_friction_torque_is_power_over_speed():
    g = vf.BoreGeometry(diameter=0.033, guided_length=0.02, clearance=2e-5)
    s1 = np.linspace(-0.008, 0.008, 9)
    f, t, p = vf.tappet_bore_friction(800.0, 20.0, s1, 150.0, 0.01, g)
    assert np.allclose(t * 150.0, p)
    assert np.all(f >= 0)
    # at the base circle (s' = 0) only the cam friction presses the tappet on the bore
    assert f[4] == pytest.approx(0.1 * 20.0, rel=1e-12)


def _short_bearing_quadrature(eps, eta, g, omega):
    """Independent: half-Sommerfeld short-bearing pressure integrated numerically."""
    u, c, R, L = omega * g.radius, g.clearance, g.radius, g.length

    def p_bar(th):  # ∫ p dz over the length
        h = c * (1 + eps * math.cos(th))
        return 3 * eta * u * c * eps * math.sin(th) / (R * h**3) * L**3 / 6

    wt = integrate.quad(lambda th: p_bar(th) * math.sin(th) * R, 0, math.pi)[0]
    wr = integrate.quad(lambda th: -p_bar(th) * math.cos(th) * R, 0, math.pi)[0]
    couette = integrate.quad(
        lambda th: eta * u / (c * (1 + eps * math.cos(th))) * R * L * R, 0, 2 * math.pi
    )[0]

    def dp(th):  # ∂(∫p dz)/∂θ by central difference
        d = 1e-6
        return (p_bar(th + d) - p_bar(th - d)) / (2 * d)

    poiseuille = integrate.quad(
        lambda th: 0.5 * c * (1 + eps * math.cos(th)) * dp(th) / R * R * R, 0, math.pi, limit=200
    )[0]
    return math.hypot(wt, wr), math.atan2(wt, wr), couette + poiseuille


@pytest.mark.parametrize("eps", [0.1, 0.5, 0.8])
def test_short_bearing_against_quadrature(eps):
    g = vf.JournalGeometry(radius=0.0125, length=0.018, clearance=3e-5)
    eta, omega = 0.01, 300.0
    w_ref, phi_ref, t_ref = _short_bearing_quadrature(eps, eta, g, omega)
    w, phi = vf.short_bearing_load(eps, eta, g, omega)
    assert float(w) == pytest.approx(w_ref, rel=1e-6)
    assert float(phi) == pytest.approx(phi_ref, rel=1e-6)
    t, e = vf.short_bearing_torque(w_ref, eta, g, omega)
    assert float(e) == pytest.approx(eps, rel=1e-8)
    assert float(t) == pytest.approx(t_ref, rel=1e-5)


def test_lightly_loaded_journal_gives_petroff():
    g = vf.JournalGeometry(radius=0.0125, length=0.018, clearance=3e-5)
    eta, omega = 0.01, 300.0
    petroff = 2 * math.pi * eta * omega * g.radius**3 * g.length / g.clearance
    t, eps = vf.short_bearing_torque(1e-3, eta, g, omega)
    assert float(eps) < 1e-4
    assert float(t) == pytest.approx(petroff, rel=1e-6)


def test_bearing_loads_lever_rule_and_balance():
    f = np.zeros((2, 1, 2))
    f[0, 0] = [100.0, 0.0]  # at 0.25 of the first span
    f[1, 0] = [0.0, 40.0]  # on the middle bearing
    loads = vf.journal_bearing_loads(f, [0.025, 0.1], [0.0, 0.1, 0.2])
    assert loads[:, 0] == pytest.approx([75.0, math.hypot(25.0, 40.0), 0.0])
    with pytest.raises(InputError, match="outside"):
        vf.journal_bearing_loads(f, [0.3, 0.1], [0.0, 0.1, 0.2])


def test_valve_guide_petroff_and_side_load():
    g = vf.GuideGeometry(stem_diameter=0.006, length=0.04, clearance=2e-5, side_load=10.0)
    f, t, p = vf.valve_guide_friction([0.0, 0.005], 150.0, 0.01, g)
    assert f[0] == 0.0
    v = 150.0 * 0.005
    assert f[1] == pytest.approx(0.01 * math.pi * 0.006 * 0.04 * v / 2e-5 + 0.1 * 10.0)
    assert p[1] == pytest.approx(f[1] * v)


def test_geometry_validated():
    with pytest.raises(InputError, match="clearance"):
        vf.JournalGeometry(radius=0.01, length=0.01, clearance=0.001)
    with pytest.raises(InputError, match="diameter"):
        vf.BoreGeometry(diameter=-1, guided_length=0.02, clearance=2e-5)
    bore = dict(diameter=0.033, guided_length=0.02, clearance=2e-5)
    guide = dict(stem_diameter=0.006, length=0.04, clearance=2e-5)
    for cls, kw, field, bad in [
        (vf.BoreGeometry, bore, "edge_offset", -1e-3),
        (vf.BoreGeometry, bore, "friction_coefficient", 1.5),
        (vf.BoreGeometry, bore, "guided_length", "long"),
        (vf.GuideGeometry, guide, "side_load", "10 N"),
        (vf.GuideGeometry, guide, "friction_coefficient", float("nan")),
        (vf.JournalGeometry, dict(radius=0.01, length=0.01, clearance=2e-5), "length", None),
    ]:
        with pytest.raises(InputError, match=field):
            cls(**{**kw, field: bad})

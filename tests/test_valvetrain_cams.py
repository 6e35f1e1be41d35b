"""Cam profiles: design constraints, exact geometry, tabulated copies, errors."""

import math

import numpy as np
import pytest

from tribodyn import InputError
from tribodyn.valvetrain import AccelerationCam, CircularArcCam, TabulatedCam

DEG = math.pi / 180.0


def _central_diff(f, th, h=1e-5):
    return (f(th + h) - f(th - h)) / (2 * h)


# -- AccelerationCam ---------------------------------------------------------------------
def test_acceleration_cam_meets_its_design_constraints():
    cam = AccelerationCam(0.015, 9.3e-3)
    nose = math.pi
    s, s1, s2 = cam.derivatives(np.array([nose]))
    assert s[0] == pytest.approx(9.3e-3, abs=1e-15)  # max lift at the nose
    assert s1[0] == pytest.approx(0.0, abs=1e-15)
    assert 0.015 + s[0] + s2[0] == pytest.approx(3e-3, abs=1e-15)  # nose radius
    # Event: 171° including ramps, symmetric about the nose, zero lift outside.
    th = np.linspace(0, 2 * np.pi, 36001)
    lift = cam.lift(th)
    assert np.all(lift[np.abs(th - nose) > 85.5 * DEG + 1e-9] == 0.0)
    assert np.all(lift[np.abs(th - nose) < 85.5 * DEG - 0.3 * DEG] > 0.0)
    x = np.linspace(0, 90 * DEG, 500)
    np.testing.assert_allclose(cam.lift(nose + x), cam.lift(nose - x), atol=1e-15)
    # Ramp: 0.2 mm over the first 20°.
    assert cam.lift(np.array([nose - 65.5 * DEG]))[0] == pytest.approx(0.2e-3, rel=1e-12)
    assert cam.min_radius_of_curvature > 0.0


def test_acceleration_cam_derivatives_are_consistent():
    cam = AccelerationCam()
    th = np.linspace(0.0, 2 * np.pi, 2000, endpoint=False) + 1e-3
    s, s1, s2 = cam.derivatives(th)
    np.testing.assert_allclose(_central_diff(cam.lift, th), s1, atol=1e-9)
    np.testing.assert_allclose(_central_diff(lambda t: cam.derivatives(t)[1], th), s2, atol=1e-6)
    # s, s' and s'' continuous across every segment boundary (one-sided limits).
    for b in cam._breakpoints():
        lo = [v[0] for v in cam.derivatives(np.array([b - 1e-9]))]
        hi = [v[0] for v in cam.derivatives(np.array([b + 1e-9]))]
        np.testing.assert_allclose(lo, hi, atol=1e-9)
    # Scalar fast path agrees with the vectorised one.
    for t in np.linspace(-1.0, 8.0, 301):
        np.testing.assert_allclose(
            cam.scalar_derivatives(t),
            [v[0] for v in cam.derivatives(np.array([t]))],
            rtol=0,
            atol=1e-15,
        )


def test_acceleration_cam_extremes_from_the_lift_alone():
    """Minimum radius of curvature and maximum contact offset against finite differences
    of the lift values alone (R = r_b + s + s'', e = s'), on a 0.01° grid."""
    cam = AccelerationCam()
    h = 0.01 * DEG
    th = np.arange(0.0, 2 * np.pi, h)
    s = cam.lift(th)
    sp, sm = cam.lift(th + h), cam.lift(th - h)
    s1 = (sp - sm) / (2 * h)
    s2 = (sp - 2 * s + sm) / h**2
    assert cam.min_radius_of_curvature == pytest.approx(np.min(0.015 + s + s2), abs=2e-6)
    assert cam.max_contact_offset == pytest.approx(np.max(np.abs(s1)), abs=1e-7)
    assert cam.max_lift == pytest.approx(s.max(), rel=1e-9)
    # the designed nose radius (3 mm) is not the minimum: R dips below it on the flanks of
    # the nose, where the negative acceleration peaks
    assert cam.min_radius_of_curvature < 3e-3


@pytest.mark.parametrize(
    "kw, match",
    [
        (dict(event_angle=120 * DEG), "radius of curvature"),
        (dict(pulse_share=0.6), "radius of curvature"),
        (dict(tappet_radius=0.012), "tappet radius"),
        (dict(base_radius=-0.015), "base_radius"),
        (dict(pulse_share=1.2), "pulse_share"),
        (dict(nose_radius=0.03), "nose_radius"),
        (dict(ramp_height=0.2e-3, ramp_angle=0.0), "ramp"),
        (dict(event_angle=30 * DEG), "event_angle"),
    ],
)
def test_acceleration_cam_rejects_bad_designs(kw, match):
    with pytest.raises(InputError, match=match):
        AccelerationCam(**kw)


# -- CircularArcCam ----------------------------------------------------------------------
def test_circular_arc_cam_radius_is_the_arc_radius():
    rb, rf, rn, L = 0.015, 0.030, 0.003, 9.3e-3
    cam = CircularArcCam(rb, L, flank_radius=rf, nose_radius=rn)
    th = np.linspace(0, 2 * np.pi, 7201, endpoint=False)
    R = cam.radius_of_curvature(th)
    assert set(np.round(np.unique(R), 12)) <= {rb, rf, rn}
    # Independent geometry: the nose arc holds the follower at d cos φ + ρ_n − r_b.
    d = rb + L - rn
    phi = np.linspace(-10 * DEG, 10 * DEG, 21)
    np.testing.assert_allclose(cam.lift(math.pi + phi), d * np.cos(phi) + rn - rb, atol=1e-15)
    # Numerical R = r_b + s + s'' from the lift alone, away from the junctions.
    s = cam.lift(th)
    h = th[1] - th[0]
    s2 = (np.roll(s, -1) - 2 * s + np.roll(s, 1)) / h**2
    bp = cam._breakpoints()
    far = (
        np.min(np.abs((th[:, None] - bp[None, :] + np.pi) % (2 * np.pi) - np.pi), axis=1)
        > 0.5 * DEG
    )
    np.testing.assert_allclose((rb + s + s2)[far], R[far], rtol=1e-4)
    assert cam.max_lift == pytest.approx(L, rel=1e-12)
    assert cam.min_radius_of_curvature == pytest.approx(rn, rel=1e-12)


@pytest.mark.parametrize(
    "kw, match",
    [
        (dict(flank_radius=0.014), "flank_radius"),
        (dict(flank_radius=0.0151), "tangentially"),
        (dict(nose_radius=0.02), "nose_radius"),
        (dict(tappet_radius=0.01), "tappet radius"),
    ],
)
def test_circular_arc_cam_rejects_bad_geometry(kw, match):
    with pytest.raises(InputError, match=match):
        CircularArcCam(**kw)


# -- TabulatedCam ------------------------------------------------------------------------
def _far_from(cam, th, spacings, n):
    bp = cam._breakpoints()
    d = np.min(np.abs((th[:, None] - bp[None, :] + np.pi) % (2 * np.pi) - np.pi), axis=1)
    return d > spacings * 2 * np.pi / n


@pytest.mark.parametrize("analytic, spacings", [(AccelerationCam(), 5), (CircularArcCam(), 10)])
def test_tabulated_copy_matches_analytic_profile(analytic, spacings):
    n = 720  # 0.5° table
    th_tab, s_tab = analytic.table(n)
    cam = TabulatedCam(th_tab, s_tab, base_radius=analytic.base_radius)
    th = np.linspace(0, 2 * np.pi, 14400, endpoint=False)
    far = _far_from(analytic, th, spacings, n)
    R_a = analytic.radius_of_curvature(th)
    R_t = cam.radius_of_curvature(th)
    assert np.max(np.abs(R_t / R_a - 1)[far]) < 0.005
    np.testing.assert_allclose(cam.lift(th), analytic.lift(th), atol=1e-7)  # 0.1 µm
    np.testing.assert_allclose(cam.lift(th)[far], analytic.lift(th)[far], atol=1e-10)
    # an exact table is fitted to a fraction of a nanometre (the floor is 1e-9 of the lift)
    assert np.sqrt(np.mean((cam.lift(th_tab) - s_tab) ** 2)) <= 2e-8 * s_tab.max()
    np.testing.assert_allclose(cam.lift(th_tab), s_tab, atol=2e-9)


def test_tabulated_scalar_path_and_periodicity():
    th_tab, s_tab = AccelerationCam().table(360)
    cam = TabulatedCam(th_tab, s_tab, 0.015)
    for t in np.linspace(-7.0, 14.0, 97):
        np.testing.assert_allclose(
            cam.scalar_derivatives(t),
            [v[0] for v in cam.derivatives(np.array([t]))],
            rtol=1e-10,
            atol=1e-14,
        )
    x = np.linspace(0, 2 * np.pi, 50)
    np.testing.assert_allclose(cam.lift(x + 2 * np.pi), cam.lift(x), atol=1e-15)
    # A closed table (last point = first + 360°) is accepted and gives the same spline.
    cam2 = TabulatedCam(np.append(th_tab, th_tab[0] + 2 * np.pi), np.append(s_tab, s_tab[0]), 0.015)
    np.testing.assert_allclose(cam2.lift(x), cam.lift(x), atol=1e-15)


def test_tabulated_smoothing_of_a_noisy_table():
    ref = AccelerationCam()
    th_tab, s_tab = ref.table(720)
    rng = np.random.default_rng(1)
    noisy = s_tab + rng.normal(0.0, 0.3e-6, s_tab.size) * (s_tab > 0)
    cam = TabulatedCam(th_tab, noisy, 0.015)  # precision estimated from the table
    assert cam.precision == pytest.approx(0.3e-6, rel=0.25)
    rms = np.sqrt(np.mean((cam.lift(th_tab) - noisy) ** 2))
    assert rms <= cam.precision * 1.001
    assert cam.min_radius_of_curvature > 0.0
    given = TabulatedCam(th_tab, noisy, 0.015, smoothing=0.3e-6)
    assert given.precision == 0.3e-6 and given.min_radius_of_curvature > 0.0


def test_tabulated_from_csv(tmp_path):
    ref = AccelerationCam()
    th, s = ref.table(720)
    f = tmp_path / "lift.csv"
    lines = ["cam angle [deg], lift [mm]", "# supplier table"]
    lines += [f"{a:.10f}, {b:.12f}" for a, b in zip(np.degrees(th), s * 1e3)]
    f.write_text("\n".join(lines) + "\n")
    cam = TabulatedCam.from_csv(f, base_radius=0.015)
    direct = TabulatedCam(th, s, 0.015)
    x = np.linspace(0, 2 * np.pi, 999)
    np.testing.assert_allclose(cam.lift(x), direct.lift(x), atol=1e-14)
    bad = tmp_path / "bad.csv"
    bad.write_text("angle,lift\n0,0\n1,abc\n")
    with pytest.raises(InputError, match="line 3"):
        TabulatedCam.from_csv(bad, base_radius=0.015)
    with pytest.raises(InputError, match="cannot read"):
        TabulatedCam.from_csv(tmp_path / "missing.csv", base_radius=0.015)


def test_tabulated_rejects_bad_tables():
    th, s = AccelerationCam().table(360)
    with pytest.raises(InputError, match="strictly increasing"):
        TabulatedCam(th[::-1], s, 0.015)
    with pytest.raises(InputError, match="not periodic"):
        TabulatedCam(np.append(th, th[0] + 2 * np.pi), np.append(s, 1e-3), 0.015)
    with pytest.raises(InputError, match="one revolution"):
        TabulatedCam(np.append(th, th[0] + 2.5 * np.pi), np.append(s, 0.0), 0.015)
    with pytest.raises(InputError, match="full revolution"):
        TabulatedCam(th[:200], s[:200], 0.015)
    with pytest.raises(InputError, match="same length"):
        TabulatedCam(th, s[:-1], 0.015)
    with pytest.raises(InputError, match=">= 0"):
        TabulatedCam(th, s - 1e-4, 0.015)
    with pytest.raises(InputError, match="base_radius"):
        TabulatedCam(th, s, 0.0)
    spike = s.copy()
    spike[100] += 1e-3
    with pytest.raises(InputError, match="radius of curvature"):
        TabulatedCam(th, spike, 0.015)
    with pytest.raises(InputError, match="tappet radius"):
        TabulatedCam(th, s, 0.015, tappet_radius=0.010)

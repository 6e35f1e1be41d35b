"""Flat-follower kinematics: base circle, first-principles rolling/sliding, tabulated copy."""

import math

import numpy as np
import pytest

from tribodyn import InputError
from tribodyn.valvetrain import (
    AccelerationCam,
    CircularArcCam,
    TabulatedCam,
    flat_follower_kinematics,
    quasi_static_jump_speed,
    rpm_to_cam_speed,
)

W = 157.07963267948966  # 1500 rpm cam


@pytest.mark.parametrize(
    "cam", [AccelerationCam(), CircularArcCam(), TabulatedCam(*AccelerationCam().table(720), 0.015)]
)
def test_base_circle_speeds_are_exact(cam):
    th = np.linspace(-0.5, 0.5, 101)  # base circle (nose at π)
    k = flat_follower_kinematics(cam, W, th)
    if isinstance(cam, TabulatedCam):  # spline: zero to round-off
        assert np.max(np.abs(k.lift)) < 1e-12
        np.testing.assert_allclose(k.entrainment_speed, W * 0.015 / 2, rtol=1e-9)
        np.testing.assert_allclose(k.sliding_speed, W * 0.015, rtol=1e-9)
        return
    assert np.all(k.entrainment_speed == W * 0.015 / 2)
    assert np.all(k.sliding_speed == W * 0.015)
    assert np.all(k.tappet_velocity == 0.0) and np.all(k.tappet_acceleration == 0.0)
    assert np.all(k.radius_of_curvature == 0.015)


def test_rolling_and_sliding_from_rigid_body_motion():
    """u_e and u_s of the circular-arc cam from the rotating arc centres (no cam code)."""
    rb, rf, rn, L = 0.015, 0.030, 0.003, 9.3e-3
    cam = CircularArcCam(rb, L, flank_radius=rf, nose_radius=rn, nose_angle=0.0)
    d = rb + L - rn
    # Flank centre from the two tangency conditions, solved here independently.
    a, b = rf - rb, rf - rn
    yf = (a * a - b * b + d * d) / (2 * d)
    cf = np.array([-math.sqrt(a * a - yf * yf), yf])
    cn = np.array([0.0, d])

    def contact(alpha, centre, rho):
        """Contact point on a follower face normal to +y, cam turned by alpha (CCW)."""
        c, s_ = math.cos(alpha), math.sin(alpha)
        C = np.array([c * centre[0] - s_ * centre[1], s_ * centre[0] + c * centre[1]])
        return C + np.array([0.0, rho])

    dt = 1e-7
    for alpha, centre, rho in [(0.05, cn, rn), (0.3, cn, rn), (0.9, cf, rf), (1.2, cf, rf)]:
        P = contact(alpha, centre, rho)
        P2 = contact(alpha + W * dt, centre, rho)
        v_contact = (P2[0] - P[0]) / dt  # contact point along the face
        u_cam = -W * P[1] - v_contact  # cam surface rel. to contact
        u_tap = 0.0 - v_contact  # tappet surface rel. to contact
        k = flat_follower_kinematics(cam, W, np.array([alpha]))
        # The package uses the opposite sign convention for the rotation sense.
        assert -0.5 * (u_cam + u_tap) == pytest.approx(k.entrainment_speed[0], rel=1e-5)
        assert abs(u_cam - u_tap) == pytest.approx(k.sliding_speed[0], rel=1e-9)
        assert P[0] == pytest.approx(k.contact_offset[0], rel=1e-9)  # e = s'
        assert P[1] - rb == pytest.approx(k.lift[0], rel=1e-12)


def test_entrainment_speed_from_the_lift_alone_and_its_reversals():
    """u_e = ω(r_b + s + 2s'')/2 against finite differences of the lift values; for this
    symmetric cam u_e changes sign twice, at angles symmetric about the nose, where
    s'' = −(r_b + s)/2."""
    cam = AccelerationCam()
    h = 0.01 * math.pi / 180
    th = np.arange(0.0, 2 * np.pi, h)
    k = flat_follower_kinematics(cam, W, th)
    s, sp, sm = cam.lift(th), cam.lift(th + h), cam.lift(th - h)
    ue = W * (0.015 + s + 2 * (sp - 2 * s + sm) / h**2) / 2
    # the acceleration jumps at the segment boundaries of the design: compare elsewhere
    smooth = np.all(np.abs(th[:, None] - np.asarray(cam._breakpoints())[None, :]) > 2 * h, axis=1)
    np.testing.assert_allclose(k.entrainment_speed[smooth], ue[smooth], atol=2e-4 * W * 0.015)
    assert k.entrainment_speed.min() == pytest.approx(ue.min(), abs=1e-3)
    assert k.entrainment_speed.max() == pytest.approx(ue.max(), abs=1e-3)
    flips = th[np.flatnonzero(np.diff(np.sign(k.entrainment_speed)) != 0)]
    assert flips.size == 2
    assert flips[0] + flips[1] == pytest.approx(2 * math.pi, abs=2 * h)  # symmetric about π


def test_tabulated_copy_kinematics_match():
    ref = AccelerationCam()
    tab = TabulatedCam(*ref.table(1440), 0.015)
    th = np.linspace(0, 2 * np.pi, 3600, endpoint=False)
    a = flat_follower_kinematics(ref, W, th)
    b = flat_follower_kinematics(tab, W, th)
    np.testing.assert_allclose(b.sliding_speed, a.sliding_speed, rtol=1e-7)
    np.testing.assert_allclose(b.tappet_velocity, a.tappet_velocity, atol=1e-4)
    np.testing.assert_allclose(b.contact_offset, a.contact_offset, atol=1e-6)


def test_quasi_static_jump_speed_and_helpers():
    """ω_jump is the lowest cam speed at which F₀ + k s + m ω² s'' reaches zero anywhere on
    the closing side: checked against a brute-force scan of that force with finite-
    difference s'' over cam speeds and angles."""
    cam = AccelerationCam()
    w, th = quasi_static_jump_speed(cam, 250.0, 33750.0, 0.122)
    s, s1, s2 = cam.derivatives(np.array([th]))
    assert s1[0] < 0 and s2[0] < 0  # closing side
    assert 250.0 + 33750.0 * s[0] + 0.122 * w**2 * s2[0] == pytest.approx(0.0, abs=1e-9)
    h = 0.01 * math.pi / 180
    grid = np.arange(math.pi, 2 * math.pi, h)
    sg, sp, sm = cam.lift(grid), cam.lift(grid + h), cam.lift(grid - h)
    acc = (sp - 2 * sg + sm) / h**2

    def separates(omega):
        return np.any(250.0 + 33750.0 * sg + 0.122 * omega**2 * acc < 0.0)

    assert not separates(0.999 * w) and separates(1.001 * w)
    assert rpm_to_cam_speed(3000.0) == pytest.approx(W)
    with pytest.raises(InputError, match="cam_speed"):
        flat_follower_kinematics(cam, -1.0, 0.0)
    with pytest.raises(InputError, match="angle"):
        flat_follower_kinematics(cam, W, [0.0, np.nan])

"""Tappet rotation: sliding and entrainment of a rotating bucket against closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest

from tribodyn import InputError
from tribodyn.config import Case, load_case
from tribodyn.config.build import build
from tribodyn.cycle import driver
from tribodyn.cycle.driver import CycleInputs
from tribodyn.valvetrain.tappet_rotation import TappetRotation


def test_sliding_vector_is_the_rigid_body_velocity_difference():
    """Independent form: the tappet surface velocity is Ω × r in 3-D, with Ω along the
    tappet axis (−ẑ for ω_t > 0, so that the surface at (0, e_o) moves along +x, with the
    cam); sliding = cam surface velocity (u_s, 0, 0) − tappet surface velocity."""
    rng = np.random.default_rng(3)
    for _ in range(50):
        w = rng.uniform(50.0, 500.0)
        ratio = rng.uniform(-0.3, 0.3)
        e_o = rng.uniform(0.0, 0.01)
        e = rng.uniform(-0.01, 0.01)
        ue, us = rng.uniform(-2.0, 10.0), rng.uniform(0.5, 10.0)
        v = TappetRotation(ratio, e_o).speeds(w, e, ue, us)
        v_t = np.cross([0.0, 0.0, -ratio * w], [e, e_o, 0.0])
        slide = np.array([us, 0.0, 0.0]) - v_t
        assert float(v.sliding_x) == pytest.approx(slide[0], rel=1e-12, abs=1e-12)
        assert float(v.sliding_y) == pytest.approx(slide[1], rel=1e-12, abs=1e-12)
        assert float(v.sliding_speed) == pytest.approx(np.linalg.norm(slide), rel=1e-12)
        assert float(v.entrainment_speed) == pytest.approx(ue + 0.5 * v_t[0], rel=1e-12)
        assert float(v.torque_share) == pytest.approx(slide[0] / np.linalg.norm(slide))


def test_pure_rolling_when_the_tappet_surface_keeps_up_with_the_cam():
    # e = 0 (contact on the cam's centre line) and ω_t e_o = u_s: no sliding, and both
    # surfaces then move at the cam surface speed, u_e' = u_cam = u_e + u_s/2
    w, e_o, us, ue = 200.0, 0.004, 0.5, 1.1
    rot = TappetRotation(us / (w * e_o), e_o)
    v = rot.speeds(w, 0.0, ue, us)
    assert float(v.sliding_speed) == pytest.approx(0.0, abs=1e-12)
    assert float(v.entrainment_speed) == pytest.approx(ue + 0.5 * us)
    assert float(v.torque_share) == 1.0


def test_no_rotation_changes_nothing():
    inp = _inputs()
    assert inp.with_rotation(TappetRotation()) is inp
    assert inp.with_rotation(None) is inp


def _inputs():
    t = np.linspace(0.0, 0.01, 5)
    e = np.array([0.0, 0.003, 0.0, -0.003, 0.0])
    ue = np.array([1.0, 2.0, -0.5, 2.0, 1.0])
    us = np.array([3.0, 3.5, 4.0, 3.5, 3.0])
    R = np.full(5, 0.01)
    F = np.array([0.0, 200.0, 500.0, 200.0, 0.0])
    fine = (t, F, ue, us, R)
    return CycleInputs(
        np.linspace(0.0, 4.0, 5),
        t,
        F,
        ue,
        us,
        R,
        0.012,
        fine,
        contact_offset=e,
        fine_contact_offset=e,
        cam_speed=157.0,
    )


def test_cycle_inputs_with_rotation():
    inp = _inputs()
    ratio, e_o, w = 0.05, 0.004, 157.0
    rot = inp.with_rotation(TappetRotation(ratio, e_o))
    wt = ratio * w
    sx = inp.sliding_speed - wt * e_o
    sy = wt * inp.contact_offset
    np.testing.assert_allclose(rot.sliding_speed, np.hypot(sx, sy), rtol=1e-13)
    np.testing.assert_allclose(rot.entrainment_speed, inp.entrainment_speed + 0.5 * wt * e_o)
    np.testing.assert_allclose(rot.torque_share, sx / np.hypot(sx, sy), rtol=1e-13)
    # the sub-step conditions (fine output) are rotated too
    c = rot.at(float(inp.time[1]))
    assert c.sliding_speed == pytest.approx(rot.sliding_speed[1])
    assert c.entrainment_speed == pytest.approx(rot.entrainment_speed[1])
    # rotation lowers the sliding along the cam motion: partial rolling
    assert np.all(rot.sliding_speed < inp.sliding_speed)
    # applied once: the same rotation again changes nothing, another one is refused
    assert rot.with_rotation(TappetRotation(ratio, e_o)) is rot
    with pytest.raises(InputError, match="already include"):
        rot.with_rotation(TappetRotation(0.1, e_o))


def test_rotation_without_offsets_is_an_input_error():
    inp = _inputs()
    bare = CycleInputs(
        *[getattr(inp, k) for k in ("crank_angle", "time", "contact_force")],
        inp.entrainment_speed,
        inp.sliding_speed,
        inp.radius,
        inp.width,
    )
    with pytest.raises(InputError, match="contact offset"):
        bare.with_rotation(TappetRotation(0.1, 0.004))


def test_bad_rotation_inputs_name_the_field():
    with pytest.raises(InputError, match="speed_ratio"):
        TappetRotation(2.0, 0.004)
    with pytest.raises(InputError, match="cam_offset"):
        TappetRotation(0.1, -1e-3)
    with pytest.raises(InputError, match=r"tappet_rotation\.speed_ratio"):
        Case.from_toml_string("[tappet_rotation]\nspeed_ratio = 3.0\n")
    with pytest.raises(InputError, match=r"tappet_rotation\.cam_offset"):
        Case.from_toml_string("[tappet_rotation]\ncam_offset = 0.2\n")


def test_case_rotation_reaches_the_cycle_driver(monkeypatch):
    case = load_case().updated(
        {"tappet_rotation.speed_ratio": 0.05, "tappet_rotation.cam_offset": 0.003}
    )
    assert build(case).tappet_rotation == TappetRotation(0.05, 0.003)
    assert build(load_case()).tappet_rotation.active is False  # the paper's tappet: none
    seen = {}

    def fake(inputs, *a, **k):
        seen["inputs"] = inputs

    monkeypatch.setattr(driver, "march_cycle", fake)
    inp = _inputs()
    driver.ehl_for_set(case, build(case).surface_sets[0], inp)
    expected = inp.with_rotation(TappetRotation(0.05, 0.003))
    np.testing.assert_array_equal(seen["inputs"].sliding_speed, expected.sliding_speed)


def test_cam_offset_must_keep_the_contact_on_the_tappet_face():
    """e_o = 49 mm on a 16.5 mm tappet used to be accepted (the torque-based friction
    energy came out negative). The contact line at x = e ≤ max|s'|, y = e_o ± l/2 must stay
    within the face: e_o ≤ √(R_t² − e_max²) − l/2, by hand from the cam's s'."""
    case = load_case()
    th = np.linspace(0.0, 2.0 * np.pi, 7201)
    e_max = np.max(np.abs(build(case).cam.derivatives(th)[1]))
    rt, half = case.valvetrain.tappet_radius, 0.5 * case.width
    reach = math.sqrt(rt**2 - e_max**2) - half
    assert 0.0 < reach < 0.005  # the paper's cam runs close to the face edge
    with pytest.raises(InputError, match=rf"tappet_rotation\.cam_offset: .*<= {reach:.4g} m"):
        case.updated({"tappet_rotation.speed_ratio": 0.05, "tappet_rotation.cam_offset": 0.049})
    with pytest.raises(InputError, match=r"tappet_rotation\.cam_offset"):
        case.updated({"tappet_rotation.cam_offset": reach * 1.01})
    case.updated({"tappet_rotation.cam_offset": reach * 0.99})
    # the API object: the same rule, with the field and its range named
    with pytest.raises(InputError, match=r"^cam_offset must be >= 0 and <= "):
        TappetRotation(0.05, 0.049).check_fit(rt, case.width, e_max, build(case).cam.base_radius)


def test_tappet_cannot_overtake_the_cam_surface():
    """ω_t e_o ≥ ω r_b would make the tappet (turned by the cam's friction) move faster
    than the cam surface on the base circle, the friction then driving the camshaft."""
    rot = TappetRotation(1.0, 0.004)
    with pytest.raises(InputError, match=r"^speed_ratio must lie in \(-0\.5, 0\.5\)"):
        rot.check_fit(0.05, 0.01, 0.01, 0.002)  # r_b = 2 mm: |ω_t/ω| < r_b/e_o = 0.5
    TappetRotation(0.4, 0.004).check_fit(0.05, 0.01, 0.01, 0.002)

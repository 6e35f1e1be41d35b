"""Surface loads and stresses at an EHL solution (contact.stress), strengths, safety
factors and Archard wear (physics.strength), and peak traces along a cycle
(workflow.stress_study)."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from tribodyn import (
    Body,
    Coating,
    InputError,
    Lubricant,
    Material,
    Roughness,
    solve_ehl,
    subsurface_stress,
)
from tribodyn.contact.stress import ehl_stresses, profile_surface_loads, surface_loads
from tribodyn.physics.strength import (
    TYPICAL_STRENGTH,
    Strength,
    archard_wear_depth_per_cycle,
    hours_to_wear_through,
    safety_factors,
)
from tribodyn.workflow.stress_study import PEAKS, stress_along_cycle, wear_for_set

STEEL = Material(210e9, 0.3)
CAM, TAPPET = Body(STEEL), Body(STEEL, Coating(180e9, 0.2, 2e-6))
OIL = Lubricant(0.04, 1.5e-8)


@pytest.fixture(scope="module")
def mixed():
    """A steady mixed-EHL solution with asperity contact and sliding (cam faster)."""
    rough = Roughness(asperity_density=1e10, rms=0.2e-6, summit_radius=2e-4)
    r = solve_ehl(1.5e5, 0.02, 0.5, 0.4, (CAM, TAPPET), OIL, rough)
    assert r.converged, r.message
    return r, rough


def test_surface_loads_signs_and_totals(mixed):
    """u_s = u_cam − u_tappet > 0: the film and the asperities hold the faster cam back
    (−x) and drag the tappet along (+x); the integrals of the Couette and boundary shear
    are the solver's viscous and boundary friction; both bodies carry p + p_a."""
    r, rough = mixed
    ld = surface_loads(r, (CAM, TAPPET), OIL, rough)
    dx = r.x[1] - r.x[0]
    assert np.all(ld.viscous_shear >= 0) and ld.viscous_shear.max() > 0
    assert np.sum(ld.viscous_shear) * dx == pytest.approx(r.viscous_friction, rel=1e-9)
    assert np.sum(ld.boundary_shear) * dx == pytest.approx(r.boundary_friction, rel=1e-6)
    assert r.boundary_friction > 0
    assert np.allclose(ld.asperity_pressure, r.asperity_pressure, rtol=1e-6, atol=1.0)
    assert np.allclose(ld.pressure, r.pressure + r.asperity_pressure, rtol=1e-6, atol=1.0)
    shear = ld.viscous_shear + ld.boundary_shear
    assert np.allclose(ld.traction_tappet - ld.traction_cam, 2 * shear)
    assert np.allclose(ld.traction_tappet + ld.traction_cam, 2 * ld.poiseuille_shear)
    # the Poiseuille traction −(h/2)dp/dx pushes towards lower pressure
    i = int(np.argmax(np.gradient(r.pressure, dx)))
    assert ld.poiseuille_shear[i] < 0
    # reversing the sliding reverses the shear on each surface
    rev = profile_surface_loads(r.x, r.pressure, r.film, -0.4, (CAM, TAPPET), OIL, rough)
    assert np.allclose(rev.traction_cam - rev.poiseuille_shear, shear)


def test_ehl_stresses_of_both_bodies(mixed):
    r, rough = mixed
    cam, tap, ld = ehl_stresses(r, (CAM, TAPPET), OIL, rough)
    pmax = ld.pressure.max()
    for s in (cam, tap):
        assert 0.4 < s.max_von_mises_substrate.value / pmax < 0.75
    assert math.isnan(cam.max_von_mises_coating.value)
    assert tap.max_von_mises_coating.z <= 2e-6
    assert tap.max_interface_shear.z == 2e-6
    # the same loads straight through the public function give the same field
    z = tap.depths
    direct = subsurface_stress(r.x, ld.pressure, ld.traction_tappet, TAPPET, z)
    assert np.allclose(direct.von_mises, tap.von_mises)


def test_strength_tabor_and_safety_factors():
    s = Strength(tensile_strength=1e9, hardness=9e9)
    assert s.yield_stress == pytest.approx(3e9)
    assert Strength(1e9, 9e9, yield_strength=2e9).yield_stress == 2e9
    peaks = {
        "max_von_mises_coating": 1e9,
        "max_von_mises_substrate": 0.5e9,
        "max_tension_surface": -1e6,  # compressive: no tension
        "max_tension_coating": 0.2e9,
        "max_interface_shear": 0.1e9,
        "max_interface_tension": math.nan,
    }
    sf = safety_factors(peaks, TYPICAL_STRENGTH["steel"], TYPICAL_STRENGTH["dlc"])
    assert sf["coating_yield"] == pytest.approx(20e9 / 3 / 1e9)
    assert sf["substrate_yield"] == pytest.approx(7e9 / 3 / 0.5e9)
    assert sf["surface_tension"] == math.inf
    assert sf["coating_tension"] == pytest.approx(1.8e9 / 0.2e9)
    assert sf["interface_shear"] == pytest.approx(5.0)
    assert math.isnan(sf["interface_tension"])
    with pytest.raises(InputError, match="hardness"):
        Strength(tensile_strength=1e9, hardness=-1.0)


def test_archard_wear():
    """Constant load and speed: Δh = k w u T / L exactly; hours = thickness/(Δh n)."""
    t = np.linspace(0.0, 0.04, 81)
    w = np.full(t.size, 2e4)  # N/m
    w[:10] = np.nan  # unloaded samples count as zero
    us = np.full(t.size, -3.0)
    d = archard_wear_depth_per_cycle(t, w, us, 1e-17, 5e-3)
    assert d == pytest.approx(1e-17 * 2e4 * 3.0 * (0.04 - t[9] - 0.5 * (t[10] - t[9])) / 5e-3)
    assert hours_to_wear_through(2e-6, d, 90000.0) == pytest.approx(2e-6 / (d * 90000.0))
    assert hours_to_wear_through(2e-6, 0.0, 1.0) == math.inf
    with pytest.raises(InputError, match="wear_coefficient"):
        archard_wear_depth_per_cycle(t, w, us, -1.0, 5e-3)
    res = SimpleNamespace(asperity_load=w * 0.012)
    inp = SimpleNamespace(time=t, sliding_speed=us, width=0.012)
    out = wear_for_set(res, inp, 1e-17, 5e-3, thickness=2e-6, cycles_per_hour=90000.0)
    assert out["depth_per_cycle_m"] == pytest.approx(d)


def _synthetic_cycle():
    """Three samples of smooth contact pressures p0(1 − x²/b²)^{3/2} on EHL-like grids
    (512 nodes over 7b, as the cycle pass records them), different widths; a thick film
    (no asperity contact). Smooth, so that the Poiseuille traction −(h/2)dp/dx stays
    bounded: a √-edge (Hertz) makes it a spike whose surface stress depends on the grid."""
    crank = np.array([0.0, 1.0, 2.0, 3.0])
    widths = [np.nan, 100e-6, 300e-6, 60e-6]
    p0s = [np.nan, 0.6e9, 0.9e9, 0.4e9]
    n = 512
    x = np.full((4, n), np.nan)
    p = np.full((4, n), np.nan)
    h = np.full((4, n), np.nan)
    for i in (1, 2, 3):
        b = widths[i]
        x[i] = np.linspace(-5.5 * b, 1.5 * b, n)
        p[i] = p0s[i] * np.clip(1 - (x[i] / b) ** 2, 0, None) ** 1.5
        h[i] = 1e-6 + 1e-6 * (x[i] / b) ** 2
    res = SimpleNamespace(
        name="s",
        crank_angle=crank,
        loaded=np.array([False, True, True, True]),
        converged=np.array([True, True, True, True]),
        x=x,
        pressure=p,
        film=h,
        asperity_load=np.zeros(4),
    )
    inp = SimpleNamespace(sliding_speed=np.array([0.0, 2.0, -1.0, 4.0]), width=0.012)
    return res, inp, widths


#: a weakly piezoviscous oil: the film's shear stays smooth across the contact (a sharp
#: drop of the traction, as at a real EHL outlet, makes the surface σ_xx there depend
#: on the grid: log-singular for a jump)
SMOOTH_OIL = Lubricant(0.04, 1e-9)


def test_cycle_traces_match_direct_evaluation():
    """The cycle's class grids and depth levels reproduce the peaks of the stresses
    evaluated directly on each recorded profile with fine depths (within 1.5 %), and
    report the crank angle of each maximum."""
    res, inp, widths = _synthetic_cycle()
    st = stress_along_cycle(res, inp, (CAM, TAPPET), SMOOTH_OIL)
    assert st.evaluated == 3
    for name in PEAKS:
        assert math.isnan(st.tappet.value[name][0])  # unloaded
    h = TAPPET.coating.thickness
    for i in (1, 2, 3):
        ld = profile_surface_loads(
            res.x[i],
            res.pressure[i],
            res.film[i],
            inp.sliding_speed[i],
            (CAM, TAPPET),
            SMOOTH_OIL,
        )
        z = np.concatenate([np.linspace(0, h, 9)[1:], np.linspace(h, 1.5 * widths[i], 300)[1:]])
        tol = 1e-3 * np.nanmax(res.pressure[i])
        for body, q, tr in (
            (CAM, ld.traction_cam, st.cam),
            (TAPPET, ld.traction_tappet, st.tappet),
        ):
            d = subsurface_stress(res.x[i], ld.pressure, q, body, z)
            for k in ("max_von_mises_substrate", "max_tension_surface"):
                ref = getattr(d, k).value
                assert tr.value[k][i] == pytest.approx(ref, rel=0.015, abs=tol), (i, k)
        # between depth levels the substrate's peak is refined (parabola in ln z): 0.2 %
        assert st.tappet.value["max_von_mises_substrate"][i] == pytest.approx(
            d.max_von_mises_substrate.value, rel=2e-3
        )
        assert st.tappet.value["max_von_mises_coating"][i] == pytest.approx(
            d.max_von_mises_coating.value, rel=0.015
        )
        assert st.tappet.value["max_interface_shear"][i] == pytest.approx(
            d.max_interface_shear.value, rel=0.015
        )
    m = st.maxima["tappet"]["max_von_mises_substrate"]
    assert m["crank_angle"] == 2.0
    assert m["value"] == pytest.approx(np.nanmax(st.tappet.value["max_von_mises_substrate"]))
    # safety factors: strength / cycle maximum; no coating strength given → NaN
    sf = st.safety_factors["tappet"]
    assert sf["substrate_yield"] == pytest.approx(
        TYPICAL_STRENGTH["steel"].yield_stress / m["value"]
    )
    assert math.isnan(sf["coating_yield"])
    assert "coating_yield" not in st.safety_factors["cam"]
    # a sample whose EHL did not converge is not evaluated
    res.converged[3] = False
    st2 = stress_along_cycle(res, inp, (CAM, TAPPET), SMOOTH_OIL)
    assert st2.evaluated == 2
    assert math.isnan(st2.tappet.value["max_von_mises_substrate"][3])


def test_batched_surface_loads_equal_the_single_profile_ones(mixed):
    """The cycle's batched surface loads are those of each profile alone (mixed EHL with
    asperity contact, sliding of either sign, two different grids)."""
    from tribodyn.contact.stress import batch_surface_loads

    r, rough = mixed
    x2 = 1.5 * r.x
    xs = np.stack([r.x, x2])
    ps, hs, us = np.stack([r.pressure, r.pressure]), np.stack([r.film, r.film]), [0.4, -0.7]
    b = batch_surface_loads(xs, ps, hs, np.array(us), (CAM, TAPPET), OIL, rough)
    for j in range(2):
        one = profile_surface_loads(xs[j], ps[j], hs[j], us[j], (CAM, TAPPET), OIL, rough)
        for f in ("pressure", "traction_cam", "traction_tappet", "boundary_shear"):
            a, c = getattr(b, f)[j], getattr(one, f)
            assert np.allclose(a, c, rtol=1e-12, atol=1e-12 * np.abs(c).max()), f

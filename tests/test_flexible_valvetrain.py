"""Flexible valvetrain: bar elements, Craig–Bampton, spring continuum with coil clash,
camshaft compliance, and the assembled model in simulate_valvetrain."""

import math

import numpy as np
import pytest
import scipy.linalg as sla

from tribodyn import InputError
from tribodyn.config import Case, load_case
from tribodyn.config.build import build
from tribodyn.valvetrain import AccelerationCam, CircularArcCam, simulate_valvetrain
from tribodyn.valvetrain.camshaft import Camshaft, lobe_polar_inertia
from tribodyn.valvetrain.fe import AxialFEModel, craig_bampton
from tribodyn.valvetrain.flexible import FlexibleValvetrain, ValveGeometry
from tribodyn.valvetrain.flexible_model import FlexibleValvetrainModel
from tribodyn.valvetrain.spring import HelicalSpring
from tribodyn.valvetrain.tribology import Frictionless

E, RHO, L, A = 210e9, 7850.0, 0.1, 2.4e-5
C = math.sqrt(E / RHO)


def _reduced_frequencies(r):
    """Natural frequencies f = √ω²/2π [Hz] of a reduced body's K φ = ω² M φ, free–free."""
    w2 = sla.eigh(r.K, r.M, eigvals_only=True)
    return np.sqrt(np.clip(w2, 0.0, None)) / (2.0 * np.pi)


@pytest.fixture(scope="module")
def flex():
    return build(load_case("andreou2023_flexible")).valvetrain


# -- bar elements --------------------------------------------------------------------------
@pytest.mark.parametrize("elements", [12, ValveGeometry.__dataclass_fields__["elements"].default])
def test_bar_frequencies_match_the_analytic_ones(elements):
    """Free–free f_n = n c/(2L), fixed–free f_n = (2n − 1) c/(4L) (Timoshenko): the first
    three within 0.5 % with the default mesh (mixed mass matrix)."""
    m = AxialFEModel()
    a = m.node()
    m.bar(a, L, E, A, RHO, elements)
    n = np.arange(1, 4)
    free = m.frequencies()[1:4]  # [0] is the rigid-body mode
    fixed = m.frequencies(fixed=[0])[:3]
    np.testing.assert_allclose(free, n * C / (2 * L), rtol=5e-3)
    np.testing.assert_allclose(fixed, (2 * n - 1) * C / (4 * L), rtol=5e-3)
    assert float(m.M.sum()) == pytest.approx(RHO * A * L, rel=1e-12)


def test_bar_check_can_fail():
    """Two elements are far off: the tolerance above means something."""
    m = AxialFEModel()
    m.bar(m.node(), L, E, A, RHO, 2)
    assert abs(m.frequencies(fixed=[0])[1] / (3 * C / (4 * L)) - 1) > 0.05


# -- Craig–Bampton ------------------------------------------------------------------------
def test_craig_bampton_reduced_vs_full():
    """Free–free valve: the lowest elastic frequencies of the reduced model converge to the
    full FE model's from above as fixed-interface modes are added (Craig & Bampton 1968);
    with k = 4 the first three are within 0.5 %."""
    v = ValveGeometry(
        stem_diameter=5.5e-3,
        stem_length=0.105,
        retainer_position=0.006,
        retainer_mass=0.02,
        head_mass=0.03,
        head_stiffness=5e8,
        seat_stiffness=5e8,
        elements=24,
    )
    fe = v.fe_model()
    full = fe.frequencies()[1:4]
    errs = []
    for k in (0, 1, 2, 4, 8):
        r = craig_bampton(fe.M, fe.K, [fe.labels["seat"], fe.labels["retainer"]], modes=k)
        assert r.n == 2 + k
        f = _reduced_frequencies(r)[1:4]
        assert np.all(f >= full[: f.size] * (1 - 1e-9))  # Rayleigh–Ritz: from above
        errs.append(float(np.max(f / full[: f.size] - 1)))
        if k >= 4:
            np.testing.assert_allclose(f, full, rtol=5e-3)
    assert errs[-1] < errs[2] < errs[1]
    # the reduced mass and static stiffness are exact: total mass and interface compliance
    r = craig_bampton(fe.M, fe.K, [fe.labels["seat"], fe.labels["retainer"]], modes=0)
    assert r.M.sum() == pytest.approx(fe.M.sum(), rel=1e-12)
    k_series = 1 / (1 / v.stem_stiffness_below_retainer + 1 / v.head_stiffness)
    assert r.K[0, 0] == pytest.approx(k_series, rel=1e-9)


# -- spring -------------------------------------------------------------------------------
def test_spring_rate_mass_and_surge():
    """k = G d⁴/(8 D³ n), m = ρ π² d² D n/4 (Wahl 1963); fixed–fixed surge (n/2)√(k/m)."""
    d, D, n, G, rho = 3.8e-3, 21.6e-3, 6, 79.3e9, 7850.0
    s = HelicalSpring(
        d, D, n, free_length=0.05, installed_length=0.043, dead_coils=0, elements_per_coil=2
    )
    k = G * d**4 / (8 * D**3 * n)
    m = rho * math.pi**2 * d**2 * D * n / 4
    assert s.rate == pytest.approx(k, rel=1e-12)
    assert s.active_mass == pytest.approx(m, rel=1e-12)
    surge = 0.5 * np.arange(1, 4) * math.sqrt(k / m)
    np.testing.assert_allclose(s.surge_frequencies(0.007), surge, rtol=5e-3)
    fe = s.fe_model()
    np.testing.assert_allclose(fe.frequencies(fixed=[0, fe.n - 1])[:3], surge, rtol=5e-3)


def test_progressive_spring_against_hand_calculation():
    """Two tight coils (gaps 0.7 mm) close first: δ(F) = Σ min(F/k_c, g_i) (rigid clash),
    rate k_c/6 → k_c/4, and the first surge frequency rises by 6/4 (four open coils)."""
    d, D = 3.8e-3, 21.6e-3
    p = (4.5e-3, 4.5e-3, 7e-3, 7e-3, 7e-3, 7e-3)
    s = HelicalSpring(d, D, 6, free_length=sum(p) + 2 * d, installed_length=0.040, pitches=p)
    kc = 79.3e9 * d**4 / (8 * D**3)
    gaps = np.array(p) - d

    def hand(delta):  # bisection on the hand formula
        lo, hi = 0.0, 1e5
        for _ in range(200):
            F = 0.5 * (lo + hi)
            lo, hi = (F, hi) if np.minimum(F / kc, gaps).sum() < delta else (lo, F)
        return F

    deltas = [0.5e-3, 1.2e-3, 1.6e-3, 3e-3, 6e-3, 8e-3]
    F = np.array([s.statics(x).force for x in deltas])
    Fh = np.array([hand(x) for x in deltas])
    np.testing.assert_allclose(F, Fh, rtol=5e-4)  # clash contact compliance ~0.4 µm
    rate_open = (s.statics(1.2e-3).force - s.statics(0.5e-3).force) / 0.7e-3
    rate_closed = (s.statics(8e-3).force - s.statics(6e-3).force) / 2e-3
    assert rate_open == pytest.approx(kc / 6, rel=1e-6)
    assert rate_closed == pytest.approx(kc / 4, rel=1e-3)
    f_open = s.surge_frequencies(1e-3)[0]
    f_closed = s.surge_frequencies(6e-3)[0]
    assert f_closed / f_open == pytest.approx(6 / 4, rel=5e-3)
    assert s.statics(6e-3).closed.sum() == 4  # two coils × two elements


def test_spring_input_errors():
    with pytest.raises(InputError, match="mean_diameter"):
        HelicalSpring(3e-3, 2e-3, 6, 0.05, 0.04)
    with pytest.raises(InputError, match="installed_length"):
        HelicalSpring(3.8e-3, 21.6e-3, 6, 0.05, 0.02)
    with pytest.raises(InputError, match="pitches"):
        HelicalSpring(3.8e-3, 21.6e-3, 6, 0.05, 0.04, pitches=(5e-3,) * 5)


# -- camshaft -----------------------------------------------------------------------------
def test_camshaft_stiffness_and_lobe_inertia():
    cs = Camshaft(
        diameter=0.025,
        bearing_span=0.09,
        lobe_position=0.045,
        drive_stiffness=1e30,
        drive_length=0.25,
    )
    Ip = math.pi * 0.025**4 / 32
    assert cs.torsional_stiffness == pytest.approx(cs.shear_modulus * Ip / 0.25, rel=1e-9)
    I = math.pi * 0.025**4 / 64  # mid-span: F L³/(48 E I)
    assert 1 / cs.bending_compliance == pytest.approx(48 * cs.E * I / 0.09**3, rel=1e-9)
    # a cam with a tiny lift is a disc: J = ρ w π r⁴/2
    cam = CircularArcCam(0.015, 1e-5, flank_radius=0.02, nose_radius=0.01)
    assert lobe_polar_inertia(cam, 0.012, 7850.0) == pytest.approx(
        7850 * 0.012 * math.pi * 0.015**4 / 2, rel=2e-3
    )
    with pytest.raises(InputError, match="lobe_position"):
        Camshaft(0.025, 0.09, 0.06, 1e4, 0.2)


# -- the assembled model --------------------------------------------------------------------
def test_flexible_case_and_its_lumped_companion(flex):
    assert isinstance(flex, FlexibleValvetrain)
    lp = flex.lumped_equivalent()
    assert lp.valve_mass == pytest.approx(0.07, rel=1e-3)  # Table 7 by design
    assert lp.spring_mass == pytest.approx(0.036, rel=1e-3)
    assert lp.spring_rate == pytest.approx(33750.0, rel=1e-3)
    assert lp.spring_preload == pytest.approx(250.0, rel=1e-3)
    b = flex.reduced_bodies(9.3e-3)
    assert b["valve"].modal_frequencies.size == 0  # first mode 24 kHz
    assert b["spring"].modal_frequencies[0] == pytest.approx(
        flex.spring.surge_frequency(), rel=5e-3
    )


def test_flexible_model_checks_its_arguments_as_the_lumped_one(flex):
    """Both models start from static equilibrium on the base circle and name a bad
    argument (one shared check)."""
    with pytest.raises(InputError, match="start_angle must be on the base circle"):
        FlexibleValvetrainModel(AccelerationCam(), flex, 157.08, Frictionless(), math.pi)
    with pytest.raises(InputError, match="params must be a FlexibleValvetrain"):
        FlexibleValvetrainModel(AccelerationCam(), flex.lumped_equivalent(), 157.08, Frictionless())


def test_analytic_jacobian_matches_finite_differences(flex):
    cam = AccelerationCam()
    m = FlexibleValvetrainModel(cam, flex, 157.08, Frictionless())
    n = m.n
    rng = np.random.default_rng(0)
    t = 0.02
    s, s1, _ = cam.scalar_derivatives(m.theta0 + m.w * t)
    y = np.zeros(2 * n + 2)
    y[:n] = rng.normal(0, 1e-7, n)
    y[m.i_face], y[m.i_seat], y[m.i_groove] = s - 2e-6, s, s - 1e-7
    y[n : 2 * n] = rng.normal(0, 1e-3, n)
    y[n + m.i_face] = m.w * s1
    J = m.jacobian(t, y)[: 2 * n, : 2 * n]
    Jfd = np.zeros_like(J)
    for j in range(2 * n):
        h = 1e-10 if j < n else 1e-7
        yp, ym = y.copy(), y.copy()
        yp[j] += h
        ym[j] -= h
        Jfd[:, j] = (m.rhs(t, yp) - m.rhs(t, ym))[: 2 * n] / (2 * h)
    assert np.max(np.abs(J - Jfd)) < 1e-5 * np.max(np.abs(Jfd))


def test_low_speed_matches_the_lumped_companion_and_energy_balances(flex):
    """At 1500 rpm both models carry nearly the quasi-static F₀ + k s + m_eff ω² s'': the
    contact force agrees within 1 % of the peak in RMS over the event (the largest local
    difference, ~5 %, sits where the contact picks up on the opening ramp); frictionless,
    the energy balance W = ΔT + ΔU + D closes to 1e-5 of the cam work."""
    cam = AccelerationCam()
    kw = dict(engine_speed=1500.0, tribology=None, cycles=1, output_step=1.0)
    a = simulate_valvetrain(cam, flex, **kw)
    b = simulate_valvetrain(cam, flex.lumped_equivalent(), **kw)
    assert a.converged and b.converged, (a.message, b.message)
    peak = b.contact_force.max()
    ev = b.event_mask()
    d = a.contact_force - b.contact_force
    assert np.sqrt(np.mean(d[ev] ** 2)) < 0.01 * peak
    assert np.max(np.abs(d)) < 0.08 * peak
    assert abs(a.energy["relative_residual"]) < 1e-5


def test_time_response_converges_with_spring_modes(flex):
    """Spring modes 1, 3 and all 11 (valve and tappet by their 5 kHz cut-off): the contact
    force over the presented cycle approaches the all-mode response."""
    import dataclasses

    cam = AccelerationCam()
    res = {}
    for k in (1, 3, None):
        f = flex.replace(
            spring=dataclasses.replace(flex.spring, modes=k, cutoff=None if k is None else 5000.0)
        )
        r = simulate_valvetrain(cam, f, tribology=None, cycles=1, output_step=1.0)
        assert r.converged, r.message
        res[k] = r.contact_force
    ref = res[None]
    e1 = np.max(np.abs(res[1] - ref))
    e3 = np.max(np.abs(res[3] - ref))
    assert e3 < e1
    assert e3 < 0.02 * ref.max()


def test_flexible_case_keys_are_checked():
    with pytest.raises(InputError, match=r"valvetrain.spring_rate: only with model"):
        Case.from_toml_string('[valvetrain]\nmodel = "flexible"\nspring_rate = 3e4\n')
    with pytest.raises(InputError, match=r"valvetrain.valve: only with model"):
        Case.from_toml_string("[valvetrain.valve]\nstem_diameter = 0.006\n")
    with pytest.raises(InputError, match=r"valvetrain.tappet.mass: required"):
        Case.from_toml_string(
            '[valvetrain]\nmodel = "flexible"\n[valvetrain.tappet]\nmodel = "lumped"\n'
        )
    with pytest.raises(InputError, match=r"valvetrain.spring.wire_diameter: must be > 0"):
        Case.from_toml_string(
            '[valvetrain]\nmodel = "flexible"\n[valvetrain.spring]\nwire_diameter = -1.0\n'
        )
    case = load_case("andreou2023_flexible")
    assert Case.from_toml_string(case.to_toml()) == case
    assert build(case).lumped.spring_rate == pytest.approx(33750.0, rel=1e-3)

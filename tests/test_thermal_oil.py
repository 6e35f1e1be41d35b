"""The oil from its datasheet: ASTM D341, Roelands with temperature, So–Klaus α, Cragoe's
k and c_p, Larsson–Andersson pressure law, bundled oils, case keys."""

import math

import numpy as np
import pytest

from tribodyn import InputError
from tribodyn.config import Case, load_case
from tribodyn.config.build import build
from tribodyn.physics.oils import OILS
from tribodyn.physics.thermal_oil import (
    T40,
    T100,
    ThermalLubricant,
    kelvin,
    so_klaus_alpha,
    walther_constants,
    walther_viscosity,
)

SHEET = {"kinematic_viscosity_40": 64.0e-6, "kinematic_viscosity_100": 11.0e-6, "density": 852.0}


def test_astm_d341_line_through_the_datasheet_points():
    A, B = walther_constants(64e-6, 11e-6)
    assert walther_viscosity(T40, A, B) == pytest.approx(64e-6, rel=1e-4)
    assert walther_viscosity(T100, A, B) == pytest.approx(11e-6, rel=1e-4)
    # Walther's law by hand (the D341 correction terms are < 1e-6 cSt above 5 cSt):
    # loglog(ν + 0.7) linear in log T → ν(70 °C)
    y = [math.log10(math.log10(v + 0.7)) for v in (64.0, 11.0)]
    x = [math.log10(313.15), math.log10(373.15)]
    y70 = y[0] + (y[1] - y[0]) * (math.log10(343.15) - x[0]) / (x[1] - x[0])
    nu70 = 10**10**y70 - 0.7
    assert walther_viscosity(343.15, A, B) * 1e6 == pytest.approx(nu70, rel=1e-5)
    assert 3.0 < B < 4.5  # ASTM slope of engine oils


def test_dynamic_viscosity_density_and_expansion():
    oil = ThermalLubricant(kelvin(90.0), **SHEET)
    rho90 = 852.0 * (1 - 6.5e-4 * 75.0)
    assert float(oil.density_at(0.0, kelvin(90.0))) == pytest.approx(rho90, rel=1e-12)
    nu90 = float(walther_viscosity(kelvin(90.0), *walther_constants(64e-6, 11e-6)))
    assert oil.inlet_viscosity == pytest.approx(nu90 * rho90, rel=1e-12)
    assert oil.isothermal().viscosity == pytest.approx(oil.inlet_viscosity)
    # Dowson–Higginson times the thermal factor
    assert float(oil.density_at(1e9, kelvin(90.0))) == pytest.approx(
        rho90 * (1 + 0.6 / 2.7), rel=1e-12
    )


def test_roelands_with_temperature_reduces_to_the_paper_law_at_the_inlet():
    # inlet form with the paper's oil: μ(1 GPa) = 7.868253 Pa·s by hand (test_materials)
    oil = ThermalLubricant(
        kelvin(40.0),
        viscosity=0.055,
        viscosity_temperature_coefficient=0.03,
        density=850.0,
        density_temperature=kelvin(40.0),
        pressure_viscosity=1.05e-8,
    )
    assert float(oil.viscosity_at(1e9, kelvin(40.0))) == pytest.approx(7.868253, rel=1e-6)
    assert oil.temperature_viscosity_coefficient() == pytest.approx(0.03, rel=1e-6)
    # Roelands' temperature term by hand at 80 °C: S0 = β(T−138)/(ln μ + 9.67)
    s0 = 0.03 * (313.15 - 138.0) / (math.log(0.055) + 9.67)
    lnmu = (math.log(0.055) + 9.67) * ((353.15 - 138) / (313.15 - 138)) ** (-s0) - 9.67
    assert float(oil.ambient_viscosity(kelvin(80.0))) == pytest.approx(math.exp(lnmu), rel=1e-12)
    # α falls with temperature: α(T) = 5.1e-9 Z (ln μ₀(T) + 9.67)
    hot = oil.at(kelvin(80.0))
    assert hot.pressure_viscosity < 1.05e-8
    assert hot.pressure_viscosity == pytest.approx(
        5.1e-9 * oil.roelands_z * (lnmu + 9.67), rel=1e-12
    )


@pytest.mark.parametrize("model, compressible", [("roelands", True), ("barus", False)])
def test_pressure_laws_are_the_isothermal_ones_with_the_ambient_viscosity_at_t(model, compressible):
    # Roelands (Eq. 3) and Dowson–Higginson (Eq. 2) by hand, on a grid of p and T
    oil = ThermalLubricant(kelvin(90.0), **SHEET, viscosity_model=model, compressible=compressible)
    p = np.concatenate([[-1e8, 0.0], np.geomspace(1e3, 3e9, 40)])[:, None]
    T = np.linspace(280.0, 450.0, 18)[None, :]
    l0 = np.log(oil.ambient_viscosity(T))
    pp, z, alpha = np.maximum(p, 0.0), oil.roelands_z, oil.inlet_pressure_viscosity
    if model == "barus":
        lnmu, dlnmu = l0 + alpha * pp, np.where(p >= 0.0, alpha, 0.0) + 0.0 * T
    else:
        lnmu = -9.67 + (l0 + 9.67) * (1.0 + 5.1e-9 * pp) ** z
        dlnmu = np.where(p >= 0.0, (l0 + 9.67) * z * 5.1e-9 * (1.0 + 5.1e-9 * pp) ** (z - 1), 0.0)
    pg, thermal = pp * 1e-9, 1.0 - 6.5e-4 * (T - 288.15)
    rho = 852.0 * thermal * ((1.0 + 0.6 * pg / (1.0 + 1.7 * pg)) if compressible else 1.0 + 0 * p)
    drho = (
        852.0 * thermal * np.where((p >= 0.0) & compressible, 0.6e-9 / (1.0 + 1.7 * pg) ** 2, 0.0)
    )
    np.testing.assert_allclose(oil.log_viscosity(p, T), lnmu, rtol=0.0, atol=1e-13)
    np.testing.assert_allclose(oil.viscosity_at(p, T), np.exp(lnmu), rtol=1e-13)
    np.testing.assert_allclose(oil.dlog_viscosity_dp(p, T), dlnmu, rtol=1e-13, atol=0.0)
    np.testing.assert_allclose(oil.density_at(p, T), rho, rtol=1e-13)
    np.testing.assert_allclose(oil.ddensity_dp(p, T), drho, rtol=1e-13, atol=0.0)
    # at the inlet temperature, the isothermal oil's laws
    iso, Ti = oil.isothermal(), kelvin(90.0)
    np.testing.assert_allclose(oil.viscosity_at(p, Ti), iso.viscosity_at(p), rtol=1e-13)
    np.testing.assert_allclose(oil.density_at(p, Ti), iso.density_at(p), rtol=1e-13)


def test_so_klaus_correlation():
    # So & Klaus (1980): α·1e8 = 1.216 + 4.143 L^3.0627 + 2.848e-4 b^5.1903 L^1.5976
    #                            − 3.999 L^3.0975 ρ^0.1162, L = log10 ν[cSt], ρ [g/cm³]
    L = math.log10(50.0)
    by_hand = (
        1.216
        + 4.143 * L**3.0627
        + 2.848e-4 * 3.5**5.1903 * L**1.5976
        - 3.999 * L**3.0975 * 0.85**0.1162
    ) * 1e-8
    assert so_klaus_alpha(50e-6, 850.0, 3.5) == pytest.approx(by_hand, rel=1e-12)
    assert 1.5e-8 < by_hand < 3e-8  # a 50 cSt mineral oil
    with pytest.raises(InputError, match="So–Klaus"):
        so_klaus_alpha(0.9e-6, 850.0, 3.5)


@pytest.mark.parametrize("grade", list(OILS))
def test_cold_datasheet_oil_has_a_rising_positive_alpha(grade):
    """At 223 K the So–Klaus polynomial is past its maximum (negative α for 5W-20 and
    5W-30: 'pressure_viscosity must be >= 0' before). Colder than the maximum, α follows
    Roelands' constant Z: α ∝ ln μ₀ + 9.67, continuous at T*, rising as the oil cools."""
    sheet = {k: v for k, v in OILS[grade].items() if k != "description"}
    Ts = [223.15 + 5.0 * k for k in range(30)]
    oils = []
    for T in Ts:
        try:
            oils.append(ThermalLubricant(inlet_temperature=T, **sheet))
        except InputError as exc:  # too viscous: the message names the temperature
            assert str(exc).startswith("inlet_temperature must be >= ")
            assert oils == []  # only at the cold end
    alphas = np.array([o.inlet_pressure_viscosity for o in oils])
    assert np.all(alphas > 1e-8) and np.all(alphas < 6e-8)
    assert np.all(np.diff(alphas) < 0)  # α falls as the oil warms
    t_star = [o._c.get("so_klaus_temperature") for o in oils]
    ts = next(t for t in t_star if t is not None)
    assert 500.0 < float(oils[-1].kinematic_viscosity(ts)) * 1e6 < 5000.0  # ~2000 cSt
    from scipy.optimize import minimize_scalar

    def so_klaus_at(T):  # the correlation along the oil's line, computed here
        o = oils[-1]
        nu = float(o.kinematic_viscosity(T))
        return so_klaus_alpha(nu, float(o.density_at(0.0, T)), o._c.get("B"))

    peak = minimize_scalar(lambda T: -so_klaus_at(T), bounds=(225.0, 300.0), method="bounded")
    assert ts == pytest.approx(peak.x, abs=0.05)
    below = ThermalLubricant(inlet_temperature=ts - 1e-3, **sheet)
    above = ThermalLubricant(inlet_temperature=ts + 1e-3, **sheet)
    assert below.inlet_pressure_viscosity == pytest.approx(above.inlet_pressure_viscosity, rel=1e-4)
    cold = oils[0]
    ratio = (math.log(cold.inlet_viscosity) + 9.67) / (
        math.log(float(above.ambient_viscosity(ts))) + 9.67
    )
    assert cold.inlet_pressure_viscosity == pytest.approx(
        above.inlet_pressure_viscosity * ratio, rel=1e-3
    )


def test_oil_outside_its_temperature_range_names_the_inlet_temperature():
    sheet = {k: v for k, v in OILS["10W-40"].items() if k != "description"}
    with pytest.raises(InputError, match=r"^inlet_temperature must be >= 229\.\d+ K") as e:
        ThermalLubricant(inlet_temperature=223.0, **sheet)
    assert "Pa·s" in str(e.value) and "pressure_viscosity" not in str(e.value)
    sheet = {k: v for k, v in OILS["5W-20"].items() if k != "description"}
    with pytest.raises(InputError, match=r"^inlet_temperature must be < 58\d\.\d+ K"):
        ThermalLubricant(inlet_temperature=600.0, **sheet)
    with pytest.raises(InputError, match=r"^viscosity must be > 6\.31499e-05 and <= 100 \[Pa·s\]"):
        ThermalLubricant(
            inlet_temperature=300.0,
            viscosity=200.0,
            viscosity_temperature_coefficient=0.03,
            pressure_viscosity=2e-8,
        )


def test_thermal_properties_cragoe_and_larsson_andersson():
    oil = ThermalLubricant(kelvin(90.0), **SHEET)
    s = 0.852
    assert float(oil.conductivity(0.0, kelvin(90.0))) == pytest.approx(
        0.1172 * (1 - 5.4e-4 * 90) / s, rel=1e-12
    )
    assert float(oil.specific_heat_at(kelvin(90.0))) == pytest.approx(
        (1685 + 3.39 * 90) / math.sqrt(s), rel=1e-12
    )
    k0 = float(oil.conductivity(0.0, kelvin(90.0)))
    assert float(oil.conductivity(1e9, kelvin(90.0))) / k0 == pytest.approx(1 + 1.72 / 1.54)
    assert float(oil.eyring_stress_at(2 * kelvin(90.0))) == pytest.approx(2 * oil.eyring_stress)
    assert float(oil.expansivity(oil.density_temperature)) == pytest.approx(6.5e-4)


def test_bundled_oils_lie_in_their_sae_grades():
    windows = {"20": (6.9, 9.3), "30": (9.3, 12.5), "40": (12.5, 16.3)}  # SAE J300, 100 °C
    for name, d in OILS.items():
        lo, hi = windows[name.split("-")[1]]
        assert lo <= d["kinematic_viscosity_100"] * 1e6 < hi, name
        oil = ThermalLubricant(kelvin(40.0), **{k: v for k, v in d.items() if k != "description"})
        assert 1.2e-8 < oil.inlet_pressure_viscosity < 3e-8, name
        assert 0.12 < float(oil.conductivity(0.0, kelvin(100.0))) < 0.15


def test_bad_oil_input_names_the_field():
    with pytest.raises(InputError, match="kinematic_viscosity_100 must be below"):
        ThermalLubricant(kelvin(40.0), kinematic_viscosity_40=10e-6, kinematic_viscosity_100=20e-6)
    with pytest.raises(InputError, match="either kinematic_viscosity_40"):
        ThermalLubricant(kelvin(40.0), kinematic_viscosity_40=10e-6)
    with pytest.raises(InputError, match="inlet_temperature"):
        ThermalLubricant(1000.0, **SHEET)


def test_case_keys_datasheet_and_thermal():
    c = Case.from_toml_string('[lubricant]\noil = "5W-30"\ninlet_temperature_c = 90.0\n')
    oil = build(c).thermal_oil()
    assert oil.inlet_temperature == pytest.approx(363.15)
    assert build(c).lubricant.viscosity == pytest.approx(oil.inlet_viscosity)
    again = Case.from_toml_string(c.to_toml())
    assert again == c and build(again).thermal_oil().inlet_pressure_viscosity == pytest.approx(
        oil.inlet_pressure_viscosity
    )
    own = Case.from_toml_string(
        "[lubricant]\nkinematic_viscosity_40_cst = 100.0\n"
        "kinematic_viscosity_100_cst = 14.8\ninlet_temperature_c = 100\n"
        "pressure_viscosity = 2e-8\n"
    )
    assert build(own).lubricant.pressure_viscosity < 2e-8  # α given at 100 °C → Z
    assert build(own).thermal_oil().inlet_pressure_viscosity == 2e-8
    msgs = []
    for text in (
        '[lubricant]\noil = "5W-30"\nviscosity = 0.05\ninlet_temperature_c = 90.0\n',
        '[lubricant]\noil = "15W-50"\n',
        "[numerics]\nthermal = true\n",
        "[lubricant]\nkinematic_viscosity_40_cst = 50.0\ninlet_temperature_c = 90\n",
    ):
        with pytest.raises(InputError) as ei:
            Case.from_toml_string(text)
        msgs.append(str(ei.value))
    assert "lubricant.viscosity: not with a datasheet oil" in msgs[0]
    assert "lubricant.oil" in msgs[1]
    assert "inlet_temperature_c" in msgs[2]
    assert "lubricant.kinematic_viscosity_100_cst: required" in msgs[3]
    bad = (
        '[lubricant]\noil = "5W-30"\ninlet_temperature_c = 90.0\n[numerics]\nthermal = true\n'
        "[materials.x]\nE = 2e11\nnu = 0.3\nboundary_shear_coefficient = 0.1\n"
        '[[surface_sets]]\nname = "a"\nsubstrate = "x"\n'
        "roughness = { asperity_density = 1e9, rms = 1e-7, summit_radius = 1e-6 }\n"
        '[cam]\nmaterial = "x"\n'
    )
    with pytest.raises(InputError, match=r"materials.x.thermal_conductivity: required"):
        Case.from_toml_string(bad)


def test_bundled_thermal_case():
    case = load_case("andreou2023_thermal")
    assert case.numerics.thermal and case.lubricant_config.oil == "5W-20"
    assert build(case).thermal_oil().inlet_temperature == pytest.approx(363.15)
    cam, tappet = build(case).set("dlc_4um").thermal_bodies
    assert tappet.coating.conductivity == 1.0 and tappet.thickness == 4e-6
    assert cam.coating is None and cam.substrate.conductivity == 46.0
    paper = load_case()
    assert not paper.numerics.thermal  # the paper's case stays isothermal
    assert np.isclose(build(paper).lubricant.viscosity, 0.055)

"""Typical (sourced) defaults of the physics objects; the paper's values stay in its case."""

from __future__ import annotations

import pytest

from tribodyn import InputError, paper
from tribodyn.config.build import build
from tribodyn.config.schema import LubricantConfig, SurfaceSetConfig
from tribodyn.contact.ehl.options import EHLOptions
from tribodyn.physics import typical
from tribodyn.physics.friction import BOUNDARY_SHEAR_STRENGTH
from tribodyn.physics.lubricant import Lubricant
from tribodyn.physics.thermal_oil import ThermalLubricant
from tribodyn.workflow.coating_study import SAE_5W20


def _all_values():
    yield typical.EYRING_STRESS
    yield typical.LIMITING_SHEAR_COEFFICIENT
    yield typical.LIMITING_SHEAR_STRESS
    yield typical.BOUNDARY_SHEAR_STRENGTH
    yield typical.ROUGHNESS_PARAMETER
    yield typical.RMS_TO_SUMMIT_RADIUS
    yield from typical.BOUNDARY_FRICTION.values()
    yield from typical.COMPOSITE_RMS.values()
    yield typical.SURFACE_HURST
    yield typical.SURFACE_SHORT_CUTOFF
    yield typical.SURFACE_LONG_CUTOFF
    yield typical.FILTER_SHORT_WAVELENGTH
    yield typical.FILTER_LONG_WAVELENGTH


def test_every_typical_value_has_a_source_and_lies_in_its_range():
    for v in _all_values():
        assert v.source.strip()
        assert v.low <= v.value <= v.high


def test_every_value_says_how_far_its_source_was_checked():
    for v in _all_values():
        assert v.status in typical.STATUSES
        if v.status != "verified":  # a number not seen in its source is labelled
            assert "ASSUMED" in v.note, v
    # checked against the source's text: Zhang et al. (2021), 0.09-0.14, secondary 0.115
    zddp = typical.boundary_friction("steel", "zddp")
    assert zddp.status == "verified" and zddp.value == 0.115
    with pytest.raises(ValueError, match="status"):
        typical.TypicalValue(1.0, 0.0, 2.0, "-", "x", status="checked")


def test_published_ranges():
    # Eyring stress of mineral oils 2-10 MPa (Johnson & Tevaarwerk 1977); ZDDP boundary
    # friction 0.09-0.14 (Zhang et al. 2021); ηβσ 0.03-0.05 (Arnell et al. 1991)
    assert (typical.EYRING_STRESS.low, typical.EYRING_STRESS.high) == (2e6, 10e6)
    zddp = typical.boundary_friction("steel", "ZDDP")
    assert (zddp.low, zddp.high) == (0.09, 0.14)
    assert 0.03 <= typical.ROUGHNESS_PARAMETER.value <= 0.05
    # the boundary data give coatings no large gain over steel in ZDDP oils
    for coat in ("a-C:H", "ta-C", "WC-C"):
        assert typical.boundary_friction(coat).value <= zddp.value


def test_unknown_pair_is_an_input_error():
    with pytest.raises(InputError, match="known: steel/zddp"):
        typical.boundary_friction("brass")


def test_physics_defaults_are_typical():
    oil = Lubricant(0.01, 1.5e-8)
    assert oil.eyring_stress == typical.EYRING_STRESS.value
    assert oil.limiting_shear_coefficient == typical.LIMITING_SHEAR_COEFFICIENT.value
    assert BOUNDARY_SHEAR_STRENGTH == typical.BOUNDARY_SHEAR_STRENGTH.value
    opts = EHLOptions()
    assert opts.boundary_shear_coefficient == typical.boundary_friction("steel").value
    assert opts.boundary_shear_strength == typical.BOUNDARY_SHEAR_STRENGTH.value
    assert ThermalLubricant.__dataclass_fields__["eyring_stress"].default == 5e6


def test_paper_values_stay_with_the_paper():
    assert SAE_5W20.eyring_stress == paper.LUBRICANT["eyring_stress"]
    assert SAE_5W20.limiting_shear_coefficient == paper.LUBRICANT["limiting_shear_coefficient"]
    # case-file defaults are the typical values; the paper's case states its own
    assert LubricantConfig().eyring_stress == typical.EYRING_STRESS.value
    assert (
        SurfaceSetConfig.model_fields["boundary_shear_strength"].default
        == typical.BOUNDARY_SHEAR_STRENGTH.value
    )
    from tribodyn.config import load_case

    case = load_case("andreou2023")
    assert build(case).lubricant.eyring_stress == paper.LUBRICANT["eyring_stress"]
    assert {s.boundary_shear_strength for s in build(case).surface_sets} == {
        paper.BOUNDARY_SHEAR_STRENGTH
    }


def test_rig_case_uses_the_typical_friction_values():
    from tribodyn.config import load_case

    case = load_case("flat_tappet_rig")
    oil = build(case).lubricant
    assert oil.eyring_stress == typical.EYRING_STRESS.value
    assert oil.limiting_shear_coefficient == typical.LIMITING_SHEAR_COEFFICIENT.value
    sets = {s.name: s for s in build(case).surface_sets}
    assert sets["steel"].boundary_shear_coefficient == typical.boundary_friction("steel").value
    assert sets["dlc_2um"].boundary_shear_coefficient == typical.boundary_friction("a-C:H").value
    for s in sets.values():
        assert s.boundary_shear_strength == typical.BOUNDARY_SHEAR_STRENGTH.value
        r = s.roughness
        assert r.roughness_parameter == pytest.approx(typical.ROUGHNESS_PARAMETER.value)
        assert r.rms / r.summit_radius == pytest.approx(typical.RMS_TO_SUMMIT_RADIUS.value)


def test_greenwood_tripp_bound_with_typical_roughness():
    """With typical ηβσ and σ/β the asperities carry at most a few per cent of a Hertz
    pressure at λ = 0: p_a(0) = (8√2/15)π F_5/2(0) (ηβσ)² √(σ/β) E', with the closed form
    F_5/2(0) = 2^(3/4) Γ(7/4)/√(2π) = 0.6166 (the constant of the paper's Eq. 7 fit)."""
    import math

    from tribodyn.physics.asperity import Roughness

    ebs, ratio, sigma = (
        typical.ROUGHNESS_PARAMETER.value,
        typical.RMS_TO_SUMMIT_RADIUS.value,
        0.2e-6,
    )
    beta = sigma / ratio
    rough = Roughness(ebs / (beta * sigma), sigma, beta)
    e_prime = 210e9 / (1 - 0.3**2)
    f52 = 2**0.75 * math.gamma(1.75) / math.sqrt(2 * math.pi)
    assert f52 == pytest.approx(0.6166, abs=1e-4)
    expected = 8 * math.sqrt(2) / 15 * math.pi * f52 * ebs**2 * math.sqrt(ratio) * e_prime
    assert rough.asperity_pressure(0.0, e_prime) == pytest.approx(expected, rel=1e-10)
    assert 15e6 < expected < 20e6  # vs Hertz pressures of 0.3-1 GPa at a cam nose


def test_typical_spectrum_of_the_default_surface_law():
    """Persson (2014): D_f = 2.15 ± 0.15, so H = 3 − D_f = 0.85 (0.7–1.0); the cutoffs
    fit the default 128² map (λ_s ≥ 4 pixels of side 2λ_L at every end of the ranges
    the sensitivity study uses)."""
    h = typical.SURFACE_HURST
    assert (h.value, h.low, h.high) == pytest.approx((0.85, 0.7, 1.0))
    assert h.status == "verified"
    ls, ll = typical.SURFACE_SHORT_CUTOFF, typical.SURFACE_LONG_CUTOFF
    assert ls.status == ll.status == "assumed"
    for short, long in ((ls.low, ll.value), (ls.value, ll.high), (ls.high, ll.low)):
        assert short >= 4 * 2 * long / 128 and 2 * short <= long


def test_boundary_friction_range_keeps_the_relative_spread():
    """The range of a pair's ς is the published one, scaled to the ς in use."""
    z = typical.boundary_friction("steel")
    assert typical.boundary_friction_range("steel", z.value) == pytest.approx((z.low, z.high))
    lo, hi = typical.boundary_friction_range("dlc", 0.18)
    d = typical.boundary_friction("a-C:H")
    assert (lo, hi) == pytest.approx((0.18 * d.low / d.value, 0.18 * d.high / d.value))
    assert typical.boundary_friction_range("brass", 0.2) == pytest.approx(
        (0.2 * z.low / z.value, 0.2 * z.high / z.value)
    )

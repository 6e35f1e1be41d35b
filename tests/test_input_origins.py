"""A case of your own never runs silently on the paper's engine: the values it leaves out
are typical ones that a warning names, and "Inputs as used" lists every value with its
origin (case, typical with its source, datasheet, assumed)."""

from __future__ import annotations

import pytest

from tribodyn import paper
from tribodyn.config import Case, load_case
from tribodyn.config.build import build
from tribodyn.config.origins import default_warnings, input_origins
from tribodyn.output.report import _origins_lines

#: A case of one's own: oil, roughness and a DLC coating, no [valvetrain].
OWN = """
[lubricant]
viscosity = 0.012
pressure_viscosity = 1.8e-8

[[surface_sets]]
name = "dlc"
coating = "dlc"
coating_thickness = 2e-6
roughness = { asperity_density = 1e10, rms = 0.2e-6, summit_radius = 20e-6 }
"""

FORCE_KEYS = ("valve_mass", "tappet_mass", "spring_mass", "spring_rate", "spring_preload")


def _origins(case):
    return {k: (v, o) for k, v, _, o in input_origins(case)}


def test_a_case_without_valvetrain_is_warned_value_by_value():
    case = Case.from_toml_string(OWN)
    (warning,) = default_warnings(case)  # the oil is given: only the valvetrain's
    assert warning.startswith("valvetrain: the case does not give ")
    for k in FORCE_KEYS:
        assert k in warning
    # the values it runs on are named with their units, and are not the paper's
    for text in ("spring_rate = 35000 N/m", "spring_preload = 250 N", "valve_mass = 0.06 kg"):
        assert text in warning
    vt = case.valvetrain
    assert (vt.valve_mass, vt.spring_mass, vt.spring_rate) != (
        paper.VALVE_MASS,
        paper.SPRING_MASS,
        paper.SPRING_RATE,
    )


def test_the_warning_names_only_what_is_missing():
    case = Case.from_toml_string(
        OWN + "[valvetrain]\nspring_rate = 28000.0\nspring_preload = 180.0\n"
    )
    (warning,) = default_warnings(case)
    assert "spring_rate" not in warning and "spring_preload" not in warning
    assert "valve_mass" in warning and "tappet_mass" in warning and "spring_mass" in warning
    given = "".join(f"{k} = 0.05\n" for k in ("valve_mass", "tappet_mass", "spring_mass"))
    full = Case.from_toml_string(
        OWN + "[valvetrain]\nspring_rate = 28000.0\n" + given + "spring_preload = 180.0\n"
    )
    assert default_warnings(full) == []


def test_an_empty_case_also_warns_about_the_oil():
    warnings = default_warnings(Case())
    assert len(warnings) == 2
    assert warnings[0].startswith("lubricant: the case does not give viscosity, pressure_viscosity")


def test_bundled_paper_case_gives_every_force_value():
    case = load_case("andreou2023")
    assert default_warnings(case) == []
    o = _origins(case)
    for k in FORCE_KEYS:
        assert o[f"valvetrain.{k}"][1] == "case", k
    assert o["valvetrain.spring_rate"][0] == paper.SPRING_RATE
    assert all(origin == "case" or origin.startswith("assumed") for _, origin in o.values())


def test_origins_of_an_own_case():
    o = _origins(Case.from_toml_string(OWN))
    assert o["lubricant.viscosity"] == (0.012, "case")
    assert o["surface_sets[dlc].roughness.rms"] == (0.2e-6, "case")
    assert o["valvetrain.spring_rate"][1].startswith("typical (")
    assert o["valvetrain.contact_damping"][1].startswith("assumed")
    assert o["lubricant.eyring_stress"][1].startswith("typical (assumed; K. L. Johnson")
    assert o["materials.dlc.E"][1].startswith("typical (assumed; J. Robertson")
    assert o["surface_sets[dlc].boundary_shear_strength"][1].startswith("typical (")
    assert o["engine.speed_rpm"][1].startswith("typical (")
    assert o["cam.width"][1].startswith("typical (")


def test_a_datasheet_oil_is_its_origin():
    case = load_case("flat_tappet_rig")
    o = _origins(case)
    assert o["lubricant.viscosity"][1].startswith("datasheet (kinematic viscosities at ")
    assert o["lubricant.viscosity"][0] == pytest.approx(build(case).lubricant.viscosity)


def test_a_changed_key_becomes_given_and_the_others_keep_their_origin():
    case = Case.from_toml_string(OWN)
    new = case.updated({"valvetrain.spring_rate": 30000.0})
    o = _origins(new)
    assert o["valvetrain.spring_rate"] == (30000.0, "case")
    assert o["valvetrain.valve_mass"][1].startswith("typical (")
    assert o["lubricant.viscosity"] == (0.012, "case")
    assert "spring_rate" not in default_warnings(new)[0]


def test_the_report_lists_every_value_with_its_origin():
    case = Case.from_toml_string(OWN)
    lines = _origins_lines(case)
    table = [ln for ln in lines if ln.startswith("| ") and not ln.startswith("| key")]
    assert len(table) == len(input_origins(case))
    assert any(ln.startswith("| valvetrain.spring_rate | 35000 N/m | typical (") for ln in table)
    assert "| lubricant.viscosity | 0.012 Pa·s | case |" in table
    assert "| valvetrain.contact_stiffness | absent | assumed" in "\n".join(table)


#: A set that gives only σ, all the default surface law needs.
RMS_ONLY = """
[[surface_sets]]
name = "ground"
roughness = { rms = 0.25e-6 }
"""


def test_summits_not_given_follow_from_rms_with_the_typical_ratios():
    # σ/β = 1e-3 and ηβσ = 0.04 (physics.typical, ASSUMED): β = 250 µm, η = 6.4e8 1/m²
    case = Case.from_toml_string(RMS_ONLY)
    rough = build(case).set("ground").surface.roughness
    assert rough.summit_radius == pytest.approx(0.25e-6 / 1e-3, rel=1e-12)
    assert rough.asperity_density == pytest.approx(0.04 / (250e-6 * 0.25e-6), rel=1e-12)
    assert rough.law is not None  # the surface law, which uses σ alone
    o = _origins(case)
    assert o["surface_sets[ground].roughness.rms"] == (0.25e-6, "case")
    beta, origin = o["surface_sets[ground].roughness.summit_radius"]
    assert beta == pytest.approx(250e-6, rel=1e-12)
    assert origin.startswith("typical (") and origin.endswith("β = σ/(σ/β)")
    eta, origin = o["surface_sets[ground].roughness.asperity_density"]
    assert eta == pytest.approx(6.4e8, rel=1e-12)
    assert origin.endswith("η = ηβσ/(βσ)")
    # the case file keeps what was given: re-read, the same case
    again = Case.from_toml_string(case.to_toml())
    assert again == case
    assert again.surface_set_configs[0].roughness.summit_radius is None

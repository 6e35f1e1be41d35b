"""The report's lumped-vs-flexible section: the five compared quantities, both models,
and how the jump speed was found."""

from types import SimpleNamespace

from tribodyn.output.report import model_comparison_section
from tribodyn.workflow.model_comparison import ModelComparison


def _row(peak, jump):
    return {
        "peak_contact_force_N": peak,
        "min_contact_force_in_event_N": 200.0,
        "seating_velocity_m_s": 0.055,
        "friction_energy_per_cycle_J": 0.219,
        "jump_speed_rpm": jump,
        "jump_speed_bracket_rpm": [jump - 50.0, jump + 50.0],
        "quasi_static_jump_speed_rpm": 7419.0,
        "jump_speed_runs": 6,
    }


def test_section_has_the_five_quantities_side_by_side():
    mc = ModelComparison(rows={"lumped": _row(513.8, 7700.0), "flexible": _row(522.8, 6400.0)})
    text = "\n".join(model_comparison_section(SimpleNamespace(model_comparison=mc)))
    assert "| quantity | lumped | flexible |" in text
    for label in (
        "peak contact force",
        "minimum contact force in the event",
        "jump speed (engine)",
        "valve-seating velocity",
        "friction energy per cycle",
    ):
        assert f"| {label} |" in text
    assert "513.8 N" in text and "522.8 N" in text
    assert "6400 rpm" in text and "7700 rpm" in text
    assert "flexible 6350–6450 rpm in 6 runs" in text
    assert "219 mJ" in text


def test_no_section_for_a_lumped_case():
    assert model_comparison_section(SimpleNamespace(model_comparison=None)) == []

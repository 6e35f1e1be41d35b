"""A study of the flexible valvetrain case (Craig–Bampton bodies): its engineering outputs
and an engine's auxiliary friction take the flexible valvetrain's own spring and joints."""

import math

import numpy as np
import pytest

from conftest import ENGINE, REDUCED
from tribodyn.config import load_case
from tribodyn.workflow.cycle import run_cycle_study
from tribodyn.workflow.engine import lobe_traces


def _case(**more):
    base = load_case("andreou2023_flexible")
    sets = base.to_dict()["surface_sets"][:1]  # uncoated
    return base.updated(
        {**REDUCED, "numerics.implicit_coupling": False, "surface_sets": sets, **ENGINE, **more}
    )


@pytest.fixture(scope="module")
def study():
    return run_cycle_study(_case(), workers=1, compare_paper=False)


def test_flexible_study_has_engineering_outputs(study):
    eng = study.engineering_outputs()
    assert np.all(np.isfinite(eng.friction_torque)) and np.any(eng.friction_torque != 0.0)
    assert eng.surge["harmonic_amplitude_m"].size >= 40


def test_surge_frequencies_of_the_flexible_spring(study):
    # Closed form of a uniform helical spring fixed at both ends (Wahl, Mechanical Springs,
    # 1963, ch. 25) from the case file's spring: k = G d⁴/(8 D³ n_a), active mass
    # m_s = ρ (π d²/4)(π D) n_a, f_n = (n/2)√(k/m_s).
    G, d, D, n_a, rho = 79.3e9, 0.0037874, 0.021596, 6.0, 7850.0
    k = G * d**4 / (8.0 * D**3 * n_a)
    m_s = rho * math.pi * d * d / 4.0 * math.pi * D * n_a
    f1 = 0.5 * math.sqrt(k / m_s)
    # Table 7 of the paper (k = 33 750 N/m, m_s = 0.036 kg), which the geometry matches
    assert f1 == pytest.approx(0.5 * math.sqrt(33750.0 / 0.036), rel=1e-4)
    f = study.engineering_outputs().surge["surge_frequency_Hz"]
    # the spring's 12-element continuum (mixed mass): discretisation error ≪ 0.1 %
    assert f[0] == pytest.approx(f1, rel=1e-3)
    assert f[1:] == pytest.approx(f1 * np.array([2.0, 3.0]), rel=2e-3)


def test_engine_bore_friction_of_a_flexible_valvetrain(study):
    # no [engine.auxiliary] coefficient: the tappet–bore friction takes the flexible
    # valvetrain's bore_friction_coefficient (0.1 in the case file)
    own = lobe_traces("intake", study, _case())
    given = lobe_traces(
        "intake", study, _case(**{"engine.auxiliary.bore_friction_coefficient": 0.1})
    )
    other = lobe_traces(
        "intake", study, _case(**{"engine.auxiliary.bore_friction_coefficient": 0.05})
    )
    assert np.all(np.isfinite(own.bore_torque)) and np.max(np.abs(own.bore_torque)) > 0.0
    np.testing.assert_allclose(own.bore_torque, given.bore_torque, rtol=1e-12, atol=0.0)
    assert not np.allclose(own.bore_torque, other.bore_torque)

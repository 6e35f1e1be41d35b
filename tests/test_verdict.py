"""The coating verdict (tribodyn.workflow.verdict): the friction energy recomputed from
stored traces for other ς and viscous factors, against hand sums; the range and the
sentence."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from tribodyn.config import load_case
from tribodyn.physics import typical
from tribodyn.workflow.verdict import (
    coating_verdicts,
    set_energy_function,
    verdict_sentence,
    viscous_factor_bounds,
)


@pytest.fixture(scope="module")
def case():
    # Greenwood–Tripp keeps the fixture cheap; the verdict does not depend on the law
    return load_case("flat_tappet_rig").updated(
        {"surface_sets[*].asperity_model": "greenwood_tripp"}
    )


def _set(name, f_v, w_a, sigma, tau0_area=0.0):
    n = 4
    loaded = np.array([True, True, True, False])
    return SimpleNamespace(
        name=name,
        loaded=loaded,
        viscous_friction=np.full(n, f_v),
        asperity_load=np.full(n, w_a),
        boundary_friction=np.full(n, sigma * w_a + tau0_area),
    )


def _study(case, sets):
    inp = SimpleNamespace(time=np.arange(4) * 0.5, sliding_speed=np.array([2.0, -2.0, 2.0, 2.0]))
    by = {s.name: s for s in sets}
    return SimpleNamespace(case=case, inputs=inp, sets=sets, set=lambda n: by[n])


def test_energy_for_another_boundary_coefficient_by_hand(case):
    """E = Σ (F_v + F_b)|u_s| Δt over loaded samples (Δt = 0.5 s, |u_s| = 2 m/s, three
    loaded samples): F_v = 1 N, W_a = 100 N, ς = 0.115 → 3·(1 + 11.5)·1 = 37.5 J; with
    ς' = 0.09 the boundary part becomes 3·9 = 27 J; k = 2 doubles the viscous 3 J."""
    s = _set("steel", 1.0, 100.0, 0.115)
    e = set_energy_function(_study(case, [s]), "steel")
    assert e(0.115) == pytest.approx(37.5)
    assert e(0.09) == pytest.approx(3.0 + 27.0)
    assert e(0.115, 2.0) == pytest.approx(6.0 + 34.5)
    # τ₀ A_a is kept: F_b = τ₀A_a + ς W_a (Eq. 17), only the ς part changes
    s0 = _set("steel", 1.0, 100.0, 0.115, tau0_area=5.0)
    e0 = set_energy_function(_study(case, [s0]), "steel")
    assert e0(0.09) == pytest.approx(3.0 + 3 * (9.0 + 5.0))


def test_verdict_of_a_coating_with_its_range(case):
    """DLC with ς 0.09 against steel with ς 0.115 on equal asperity loads, no viscous
    friction: change = 0.09/0.115 − 1 = −21.7 %; with both ς at the same end of their
    published ranges: 0.06/0.09 − 1 and 0.12/0.14 − 1 (physics.typical)."""
    steel = _set("steel", 0.0, 100.0, 0.115)
    dlc = _set("dlc_2um", 0.0, 100.0, 0.09)
    v = coating_verdicts(_study(case, [steel, dlc]), "steel", {"steel": "steel", "dlc_2um": "DLC"})
    assert set(v) == {"dlc_2um"}
    d = v["dlc_2um"]
    assert d["friction_energy_change_pct"] == pytest.approx(100 * (0.09 / 0.115 - 1))
    zs, zd = typical.boundary_friction("steel"), typical.boundary_friction("a-C:H")
    ends = sorted([100 * (zd.low / zs.low - 1), 100 * (zd.high / zs.high - 1)])
    assert d["range_pct"] == pytest.approx(ends)
    wide = [100 * (zd.low / zs.high - 1), 100 * (zd.high / zs.low - 1)]
    assert d["range_independent_pct"] == pytest.approx(wide)
    assert d["lowers_friction"] is True and d["sign_settled"] is True
    assert d["sentence"].startswith("DLC lowers friction energy per cycle by 22 %")
    assert "stored traces" in d["method"]


def test_viscous_bounds_follow_the_published_ranges(case):
    """τ_E = 5 MPa (2–10 MPa) and Λ = 0.08 (0.05–0.12): k from min(1, 0.4, 0.625) = 0.4
    to max(1, 2, 1.5) = 2 (Eyring with the limiting shear stress)."""
    assert viscous_factor_bounds(case) == pytest.approx((0.4, 2.0))
    newt = case.updated({"numerics.viscous_model": "newtonian"})
    assert viscous_factor_bounds(newt) == pytest.approx((0.625, 1.5))


def test_sentence_says_when_the_sign_is_not_settled():
    s = verdict_sentence("WC-C 2 µm", "steel", -3.0, -12.0, 4.0)
    assert "sign is not settled" in s and "−12 … +4.0 %" in s
    assert "raises" in verdict_sentence("X", "steel", 12.0, 5.0, 20.0)

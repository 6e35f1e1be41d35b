"""The plausibility warnings of a study (workflow.engineering.plausibility_warnings) on
made-up results of the paper case's sets: the comparison with the default surface law
is made when the set's own asperity share could be below a tenth of it, and the law is
not computed when it cannot (a share of 0.1 or more: the law's share is at most 1)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from tribodyn import _cache
from tribodyn.config import load_case, measured_surface
from tribodyn.workflow.engineering import plausibility_warnings


@pytest.fixture(autouse=True)
def _own_cache(tmp_path, monkeypatch):
    monkeypatch.setenv(_cache.CACHE_ENV, str(tmp_path))


def _study(share: float, lam: float = 0.23):
    case = load_case()
    force = np.array([0.0, 800.0, 900.0])
    inputs = SimpleNamespace(
        contact_force=force,
        width=case.width,
        radius=np.full(3, 0.02),
        crank_angle=np.array([900.0, 1000.0, 1100.0]),
    )
    sets = [
        SimpleNamespace(
            name=name,
            loaded=np.array([False, True, True]),
            converged=np.array([True, True, True]),
            lambda_ratio=np.array([np.nan, 2.0, lam]),
            asperity_load=share * force,
        )
        for name in case.surface_set_names
    ]
    return SimpleNamespace(case=case, inputs=inputs, sets=sets)


def test_a_low_share_is_compared_with_the_surface_law():
    out = plausibility_warnings(_study(share=1e-4))
    assert sum("the surface law of a typical ground surface" in w for w in out) == 5


@pytest.mark.parametrize("share", [0.1, 0.3, 0.9])
def test_a_share_of_a_tenth_or_more_needs_no_law(monkeypatch, share):
    with_law = plausibility_warnings(_study(share, lam=0.05))

    def no_law(*a, **k):
        raise AssertionError("the law was computed")

    monkeypatch.setattr(measured_surface, "typical_surface_law", no_law)
    assert plausibility_warnings(_study(share, lam=0.05)) == with_law
    assert any("thinner than a tenth" in w for w in with_law) == (share < 0.5)

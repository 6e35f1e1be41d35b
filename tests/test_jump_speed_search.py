"""Jump-speed search of the lumped-vs-flexible comparison: few runs, the same answer as a
bisection, and an honest failure."""

import math

import numpy as np
import pytest

from tribodyn.valvetrain import AccelerationCam, ValvetrainParameters
from tribodyn.valvetrain.sweep import (
    corrected_jump_speed_estimate,
    jump_speed,
    locate_jump_speed,
)

CAM = AccelerationCam()
KW = dict(tribology=None, output_step=1.0, cycles=1)  # one cycle from rest: fast


def test_estimate_without_correction_is_the_quasi_static_speed():
    """Without a dynamics run the estimate is the rigid-train quasi-static speed
    ω² = (F₀ + k s)/(m_e|s''|) minimised over the event (brute force over a 0.01° grid)."""
    p = ValvetrainParameters(spring_masses=0)
    th = np.radians(np.arange(0.0, 360.0, 0.01))
    s, _, s2 = CAM.derivatives(th)
    m = p.tappet_mass + p.valve_mass + p.spring_mass / 3
    ok = (s > 10e-6) & (s2 < 0)
    w = np.sqrt(np.min((p.spring_preload + p.spring_rate * s[ok]) / (m * -s2[ok])))
    assert corrected_jump_speed_estimate(CAM, p) == pytest.approx(w * 60 / math.pi, rel=1e-4)


def test_search_agrees_with_bisection_in_fewer_runs():
    """Eight-mass spring (surge lowers the jump speed well below the quasi-static one): the
    search's 100 rpm bracket overlaps the bisection's 50 rpm bracket, in at
    most 7 runs beside the start (the bisection needs 2 + log₂(range/50) ≈ 9)."""
    p = ValvetrainParameters(spring_masses=8)
    found = locate_jump_speed(CAM, p, start=3000.0, high=12000.0, tolerance=100.0, **KW)
    assert found.converged, found.message
    lo, hi = jump_speed(CAM, p, low=3000.0, high=12000.0, tolerance=50.0, **KW)
    a, b = found.bracket
    assert b - a <= 100.0 and a < hi and lo < b  # the brackets overlap
    assert len(found.runs) - 1 <= 7
    assert [j for n, _, j in found.runs if n == a] == [False]
    assert [j for n, _, j in found.runs if n == b] == [True]


def test_search_says_when_there_is_no_jump():
    p = ValvetrainParameters(spring_masses=0)
    found = locate_jump_speed(CAM, p, start=1000.0, high=2000.0, **KW)
    assert not found.converged and math.isnan(found.speed)
    assert "no jump up to high = 2000 rpm" in found.message

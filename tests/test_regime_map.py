"""The Greenwood chart's regime map that the study stores for Fig. 12: its axes cover the
operating points and its regions meet where the Johnson (1970) asymptotes are equal."""

import numpy as np
import pytest

from tribodyn.physics.regimes import REGIMES
from tribodyn.workflow.regime_map import regime_map


def test_the_axes_cover_the_chart_and_the_operating_points():
    gV = np.array([np.nan, 0.5, 2e5, 30.0, -1.0])  # NaN unloaded; ≤ 0 not a point
    gE = np.array([np.nan, 0.1, 20.0, 500.0, 3.0])
    m = regime_map(gV, gE)
    assert m.gE.size == m.gV.size == 600 and m.regime.shape == (600, 600)
    assert m.gE[0] == pytest.approx(1e-2) and m.gE[-1] == pytest.approx(3 * 500.0)
    assert m.gV[0] == pytest.approx(1e-2) and m.gV[-1] == pytest.approx(3 * 2e5)
    for axis in (m.gE, m.gV):  # log-uniform
        np.testing.assert_allclose(np.diff(np.log(axis)), np.log(axis[1] / axis[0]), rtol=1e-9)
    none = regime_map([np.nan], [np.nan])  # no operating point: the least chart
    assert none.gE[-1] == pytest.approx(1e2) and none.gV[-1] == pytest.approx(1e4)


def test_the_regions_meet_where_the_asymptotes_are_equal():
    m = regime_map([], [])
    name = np.array(REGIMES)[m.regime]
    ir_ie = (4.9 / 3.01) ** 1.25  # 4.9 = 3.01 g_E^0.8
    ir_pr = (4.9 / 1.66) ** 1.5  # 4.9 = 1.66 g_V^(2/3)
    bottom, left = name[0], name[:, 0]  # g_V = 0.01, g_E = 0.01
    assert set(bottom[m.gE < ir_ie]) == {"IR"} and set(bottom[m.gE > ir_ie]) == {"IE"}
    assert set(left[m.gV < ir_pr]) == {"IR"} and set(left[m.gV > ir_pr]) == {"PR"}
    assert name[-1, -1] == "PE"  # g_V = 10⁴, g_E = 10²: classical EHL
    assert m.regime.dtype == np.int8 and set(np.unique(m.regime)) == set(range(len(REGIMES)))

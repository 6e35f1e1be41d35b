"""The film-gain rule of the summary (workflow.postprocess): robust statistics that ignore
engagement transients and non-converged steps."""

import numpy as np
import pytest

from tribodyn.workflow.postprocess import (
    GAIN_SETTLE_STEPS,
    film_gain_mask,
    film_gain_statistics,
)


def synthetic_study(spike=-10.7, failed_spike=+25.0):
    """Two loaded events of a reference and a coated set whose films differ by +0.3 %,
    with (a) an engagement spike of ``spike`` % in the coated set's first loaded step of
    the main event and (b) a non-converged step of ``failed_spike`` % mid-event."""
    n = 200
    loaded = np.zeros(n, bool)
    loaded[20:30] = True  # a light ramp event
    loaded[60:160] = True  # the main event
    in_event = np.zeros(n, bool)
    in_event[55:165] = True
    h_ref = np.where(loaded, 1e-6 * (1 + 0.2 * np.sin(np.arange(n) / 9)), np.nan)
    h_set = h_ref * 1.003
    h_set[60] = h_ref[60] * (1 + spike / 100)  # engagement transient
    h_set[110] = h_ref[110] * (1 + failed_spike / 100)  # a failed step
    conv_ref = np.ones(n, bool)
    conv_set = np.ones(n, bool)
    conv_set[110] = False
    return dict(
        in_event=in_event,
        loaded=loaded,
        h_ref=h_ref,
        h_set=h_set,
        conv_ref=conv_ref,
        conv_set=conv_set,
    )


def test_engagement_spike_and_failed_step_are_excluded():
    s = synthetic_study()
    mask = film_gain_mask(s["in_event"], s["loaded"], s["loaded"], s["conv_ref"], s["conv_set"])
    assert not mask[60 : 60 + GAIN_SETTLE_STEPS].any()  # first steps after engagement
    assert mask[60 + GAIN_SETTLE_STEPS]
    assert not mask[110]  # not converged
    assert not mask[20:30].any()  # outside the cam event
    g = film_gain_statistics(s["h_ref"], s["h_set"], mask, [80, 110, 140])
    assert g["max_pct"] == pytest.approx(0.3, rel=1e-9)
    assert g["median_abs_pct"] == pytest.approx(0.3, rel=1e-9)
    assert g["p95_abs_pct"] == pytest.approx(0.3, rel=1e-9)
    assert g["at_points_pct"][0] == pytest.approx(0.3, rel=1e-9)
    assert g["at_points_pct"][1] is None  # the failed step is not admitted
    assert g["samples"] == 100 - GAIN_SETTLE_STEPS - 1


def test_without_the_rule_the_spikes_would_dominate():
    """The naive point-by-point maximum picks up the injected spikes (what the rule is for)."""
    s = synthetic_study(spike=+10.7)
    naive = np.nanmax((s["h_set"] / s["h_ref"] - 1) * 100)
    assert naive == pytest.approx(25.0)
    mask = film_gain_mask(s["in_event"], s["loaded"], s["loaded"], s["conv_ref"], s["conv_set"])
    assert film_gain_statistics(s["h_ref"], s["h_set"], mask, [])["max_pct"] < 0.31


def test_no_admitted_sample_gives_none():
    n = 10
    g = film_gain_statistics(np.ones(n), np.ones(n), np.zeros(n, bool), [0])
    assert g["max_pct"] is None and g["median_abs_pct"] is None and g["at_points_pct"] == [None]

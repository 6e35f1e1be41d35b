"""The implicit coupling where the unloaded tappet used to chatter on the film off the
cam lobe: the paper's case at 4000 rpm (coarse EHL) converges, with the film as a state
of the dynamics (modelled off the lobe, tests/test_squeeze_film_state.py), and the force
between the EHL samples no longer depends on their spacing."""

import dataclasses

import numpy as np
import pytest

from conftest import explicit_run
from film_table_law import ehl_tribology
from tribodyn import InputError
from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.cycle.coupling import (
    COUPLING_MAX_TOL,
    COUPLING_RMS_TOL,
    film_state_tribology,
    run_coupling,
    valve_timing,
)
from tribodyn.cycle.driver import ehl_for_set
from tribodyn.physics.materials import reduced_modulus
from tribodyn.valvetrain.dynamics import simulate_valvetrain

COARSE = {
    "engine.speed_rpm": 4000.0,
    "numerics.crank_step_deg": 4.0,
    "numerics.n": 128,
    "numerics.coupling_n": 128,
    "numerics.output_step_deg": 1.0,
}


@pytest.fixture(scope="module")
def paper_4000():
    case = load_case().updated(COARSE)
    s, dyn, inputs = explicit_run(case)
    first = ehl_for_set(case, s, inputs)
    return case, s, dyn, inputs, first


def test_the_coupling_converges_where_the_tappet_chattered(paper_4000):
    # before the film law was restricted to the lobe this ran 6 iterations without
    # converging (chatter: 90 % of the last change off the lobe, 44 N at most)
    case, s, dyn, inputs, first = paper_4000
    c = run_coupling(case, s, dyn, inputs, first)
    assert c.converged, c.message
    assert len(c.history) <= 3
    peak = dyn.contact_force.max()
    last = c.history[-1]
    assert last.rms_force_change_N < COUPLING_RMS_TOL * peak
    assert last.max_force_change_N < COUPLING_MAX_TOL * peak
    # the implicit run rides on the film: the load squeezes the base-circle film on the
    # lobe, and after seating the tappet lands on a recovered film again
    im = c.implicit
    h = im.tribology_report["film_thickness"]
    ev = dyn.event_mask()
    assert np.median(h[~ev]) > 3.0 * np.median(h[ev])
    assert h.min() < 0.1 * h[-1] and h[-1] > 0.5e-6
    # the film separates the surfaces from metal contact (the explicit run's datum): the
    # valve timing moves by a fraction of a degree (the paper: insignificant, Figs. 8-10)
    # and does not depend on the assumed oil supply, which only bounds the film; the
    # earlier datum at the supply film acted as a lash of h_s (+2.5 deg at 10 um)
    (o_e, c_e), (o_i, c_i) = valve_timing(dyn), valve_timing(im)
    assert abs(o_i - o_e) < 1.0 and abs(c_i - c_e) < 1.0
    twice = case.updated(
        {"numerics.coupling_supply_film": 2.0 * case.numerics.coupling_supply_film}
    )
    c2 = run_coupling(twice, s, dyn, inputs, first)
    assert c2.converged, c2.message
    o_2, c_2 = valve_timing(c2.implicit)
    assert abs(o_2 - o_i) < 0.1 and abs(c_2 - c_i) < 0.1


def _every(obj, k):
    """The dataclass ``obj`` with its per-sample arrays taken at every k-th sample."""
    n = obj.crank_angle.size
    arrays = {
        f.name: v[::k]
        for f in dataclasses.fields(obj)
        if isinstance(v := getattr(obj, f.name), np.ndarray) and v.shape[:1] == (n,)
    }
    return dataclasses.replace(obj, **arrays)


def test_force_between_samples_does_not_depend_on_their_spacing(paper_4000):
    """The same transient EHL, tabulated at every sample (4°) and at every other one
    (8°): the implicit dynamics' contact force differs by less than 1 % of the peak in
    RMS over the event and 5 % at most. Between the samples the film's physics shapes
    the force, not an interpolated law; the linearised film law of earlier versions
    (``ehl_tribology``; measured 11 N RMS, 47 N max, peak 650 N) fails the same bound."""
    case, s, dyn, inputs, first = paper_4000
    period = 2.0 * np.pi / case.cam_speed
    e_prime = reduced_modulus(s.bodies)
    built = build(case)
    lub = built.lubricant
    ev = dyn.event_mask()
    peak = dyn.contact_force.max()

    def spread(tribology):
        F = []
        for k in (1, 2):
            inp, ehl = _every(inputs, k), _every(first, k)
            r = simulate_valvetrain(
                built.cam,
                built.valvetrain,
                tribology=tribology(inp, ehl),
                **built.dynamics_options,
            )
            assert r.converged, r.message
            F.append(r.contact_force)
        d = F[1] - F[0]
        return float(np.sqrt(np.mean(d[ev] ** 2))), float(np.abs(d).max())

    rms, mx = spread(lambda i, e: film_state_tribology(i, e, lub, e_prime, period, case.width))
    assert rms < 0.01 * peak and mx < 0.05 * peak, (rms, mx)

    def old(i, e):
        lobe = np.interp(i.crank_angle, dyn.crank_angle, dyn.cam_lift) > dyn.jump_lift_threshold
        return ehl_tribology(i, e, lub, e_prime, period, lobe)

    rms_old, mx_old = spread(old)
    assert rms_old > 0.01 * peak or mx_old > 0.05 * peak  # the bound can fail


@pytest.mark.parametrize("value", [0.0, -1e-6, 2.0])
def test_supply_film_out_of_range_is_an_input_error(value):
    with pytest.raises(InputError, match="coupling_supply_film"):
        load_case().updated({"numerics.coupling_supply_film": value})

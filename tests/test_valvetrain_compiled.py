"""The compiled lumped valvetrain (numba right-hand side, one LSODA call) against the
Python model it compiles: the same equations at arbitrary states, and the same motion."""

import math

import numpy as np
import pytest

from tribodyn.valvetrain import AccelerationCam, ValvetrainParameters, simulate_valvetrain
from tribodyn.valvetrain import dynamics as dynamics_module
from tribodyn.valvetrain.compiled import compiled_model
from tribodyn.valvetrain.kinematics import rpm_to_cam_speed
from tribodyn.valvetrain.model import ValvetrainModel
from tribodyn.valvetrain.tribology import AnalyticTribology, FilmTableTribology


def _film_table(w):
    """A film law of the implicit coupling's form: h_k(t) falls by 1 µm over the event."""
    period = 2.0 * math.pi / w
    t = np.linspace(0.0, period, 721)
    h = -1e-6 * np.sin(np.pi * t / period) ** 2
    return FilmTableTribology(
        AnalyticTribology(), t, h, -2e-10 * np.ones_like(t), 300.0 * np.ones_like(t), period=period
    )


@pytest.mark.parametrize("film", [False, True])
def test_compiled_equations_equal_the_python_model(film):
    w = rpm_to_cam_speed(3000.0)
    trib = _film_table(w) if film else AnalyticTribology()
    model = ValvetrainModel(AccelerationCam(), ValvetrainParameters(), w, trib)
    cm = compiled_model(model)
    assert cm is not None
    rng = np.random.default_rng(1)
    n = model.n
    period = 2.0 * math.pi / w
    for t in rng.uniform(0.0, period, 40):
        s = AccelerationCam().scalar_derivatives(w * t)[0]
        y = np.zeros(2 * n + 2)
        y[0] = s - rng.uniform(-5e-6, 30e-6)  # into the contact or apart
        y[1] = y[0] - rng.uniform(-2e-6, 4e-6) + model.d_seat * rng.uniform(0, 2)
        y[2:n] = y[1] * np.linspace(1, 0, n - 2) + rng.normal(0, 1e-6, n - 2)
        y[n : 2 * n] = rng.normal(0, 0.5, n)
        a, b = cm.rhs(t, y), model.rhs(t, y)
        scale = np.maximum(np.abs(b), 1e-3 * np.abs(b).max())
        assert np.all(np.abs(a - b) <= 1e-6 * scale + 1e-9), (t, np.abs(a - b) / scale)
        ja, jb = cm.jac(t, y), model.jacobian(t, y)
        assert np.allclose(ja, jb, rtol=1e-6, atol=1e-6 * np.abs(jb).max())


def test_compiled_lift_is_the_cam_lift_of_the_outputs():
    # the event search's lift alone: the outputs' s at any state, and the cam's own lift
    w = rpm_to_cam_speed(3000.0)
    model = ValvetrainModel(AccelerationCam(), ValvetrainParameters(), w, AnalyticTribology())
    cm = compiled_model(model)
    assert cm is not None
    T = np.linspace(0.0, 4.0 * math.pi / w, 3001)
    Y = np.random.default_rng(2).normal(0.0, 1e-5, (2 * model.n + 2, T.size))
    s = cm.lift(T)
    assert np.array_equal(s, cm.outputs(T, Y)["s"])
    np.testing.assert_allclose(s, AccelerationCam().lift(model.theta0 + w * T), rtol=0, atol=1e-10)


def test_compiled_motion_equals_the_solve_ivp_path(monkeypatch):
    """Same LSODA algorithm and tolerances, two implementations: compare what the
    integration error defines, not the chaotic details of the small impacts where the
    tappet takes up the ramp (lift < jump_lift_threshold; there the force history of one
    impact depends on round-off, e.g. the BLAS kernel, by several N).

    * inside the lift event (cam lift > 10 µm, the follower driven by the cam) the force
      histories agree to 0.1 % of the peak (measured 0.045 %);
    * the peak force to 0.02 % and its crank angle to the output step;
    * the impulse ∫F_c dt over the cycle (momentum, well defined through impacts) to
      0.01 % (measured 1e-5 relative);
    * the seating velocity to 0.5 % (measured 0.02 %) and the energy balance to 1e-4."""
    kw = dict(engine_speed=3000.0, tribology="explicit", output_step=0.5)
    fast = simulate_valvetrain(AccelerationCam(), ValvetrainParameters(), **kw)
    monkeypatch.setattr(dynamics_module, "compiled_model", lambda m: None)
    slow = simulate_valvetrain(AccelerationCam(), ValvetrainParameters(), **kw)
    assert fast.converged and slow.converged
    assert "event_intervals" in fast.stats and "event_intervals" not in slow.stats
    peak = slow.contact_force.max()
    driven = fast.event_mask() & slow.event_mask()
    assert driven.sum() > 0.4 * driven.size
    d = fast.contact_force - slow.contact_force
    assert np.abs(d[driven]).max() < 1e-3 * peak
    assert fast.contact_force.max() == pytest.approx(peak, rel=2e-4)
    assert fast.crank_angle[fast.contact_force.argmax()] == pytest.approx(
        slow.crank_angle[slow.contact_force.argmax()], abs=0.5
    )
    impulse = [np.trapezoid(r.contact_force, r.time) for r in (fast, slow)]
    assert impulse[0] == pytest.approx(impulse[1], rel=1e-4)
    assert fast.seating_velocity == pytest.approx(slow.seating_velocity, rel=5e-3)
    assert len(fast.seatings) == len(slow.seatings)
    assert abs(fast.energy["relative_residual"]) < 1e-4
    assert abs(slow.energy["relative_residual"]) < 1e-4


def _film_state_run(monkeypatch, python):
    """The tabulated example cam at 6000 rpm (5W-30, its second surface set) with the
    film as a state and a correction r(t) that varies over the cycle, compiled or on the
    Python path (``python``)."""
    from tribodyn.config import load_case
    from tribodyn.config.build import build
    from tribodyn.physics.materials import reduced_modulus
    from tribodyn.valvetrain.tribology import FilmStateTribology

    case = load_case("example_table_cam").updated({"engine.speed_rpm": 6000.0})
    built = build(case)
    s = built.surface_sets[-1]
    period = 2.0 * math.pi / rpm_to_cam_speed(6000.0)
    t = np.linspace(0.0, period, 181)
    trib = FilmStateTribology(
        built.analytic_tribology(s.name),
        width=case.width,
        lubricant=built.lubricant,
        e_prime=reduced_modulus(s.bodies),
        time=t,
        correction=1.0 + 0.5 * np.sin(2.0 * np.pi * t / period) ** 2,
        period=period,
    )
    opts = dict(built.dynamics_options)
    if python:
        monkeypatch.setattr(dynamics_module, "compiled_model", lambda m: None)
    r = simulate_valvetrain(built.cam, built.valvetrain, tribology=trib, **opts)
    monkeypatch.undo()
    assert r.converged, r.message
    # the follower is driven through the lift event: its peak is the cam's lift, less
    # the chain's elastic compression under a few hundred newtons (≪ 1 %)
    lift = built.cam.max_lift
    assert abs(r.tappet_displacement.max() - lift) < 0.02 * lift
    return r, opts


def test_film_state_runs_take_the_compiled_path(monkeypatch):
    fast, _ = _film_state_run(monkeypatch, python=False)
    slow, _ = _film_state_run(monkeypatch, python=True)
    assert "event_intervals" in fast.stats  # the compiled driver's statistics
    assert "event_intervals" not in slow.stats


def test_compiled_film_state_motion_equals_the_python_path(monkeypatch):
    """Both paths integrate the same equations (bit-identical on the same cam values,
    ``test_film_state_jacobian_matches_finite_differences``) with LSODA at the same
    tolerances, so they differ by what the tolerances allow: each state's local error
    is held below rtol·|y| + atol, and the global errors of the two runs over two cycles
    (impacts on the ramps included) stay within a few tens of that (measured 0.14, 3.5
    and 20 times for the tappet displacement, the film and the tappet velocity):

    * tappet displacement, film and tappet velocity within 50 (rtol · peak + atol);
    * the contact force, which differentiates the displacement through the stiff
      contact, within 1000 rtol of its peak at every sample (measured 410 rtol);
    * the energy balance of both within 1e-5."""
    fast, opts = _film_state_run(monkeypatch, python=False)
    slow, _ = _film_state_run(monkeypatch, python=True)
    rtol = opts.get("rtol", 1e-6)
    # atol on displacements and the film, on velocities (``simulate_valvetrain``)
    film = "film_thickness"
    for a, b, atol in (
        (fast.tappet_displacement, slow.tappet_displacement, 1e-10),
        (fast.tribology_report[film], slow.tribology_report[film], 1e-10),
        (fast.tappet_velocity, slow.tappet_velocity, 1e-6),
    ):
        assert np.abs(a - b).max() <= 50.0 * (rtol * np.abs(b).max() + atol)
    peak = slow.contact_force.max()
    assert np.abs(fast.contact_force - slow.contact_force).max() <= 1e3 * rtol * peak
    assert abs(fast.energy["relative_residual"]) < 1e-5
    assert abs(slow.energy["relative_residual"]) < 1e-5

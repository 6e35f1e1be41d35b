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

"""The one cycle driver and the one BDF2 stepper: the thermal EHL is marched along the
cycle like the isothermal one (time-error control, sub-steps, validity warnings), and the
thermal transient step is the isothermal one through its hooks (Newton predictor, history
reset at a steady start)."""

import numpy as np
import pytest

from conftest import cycle_inputs, isothermal_cycle, ramp_inputs
from tribodyn import Body, Material, TransientEHL
from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.contact.ehl.steady import state_from_dimensional
from tribodyn.contact.ehl.thermal_transient import ThermalTransientEHL
from tribodyn.cycle.driver import IsothermalCycle, march_cycle
from tribodyn.cycle.methods import IsothermalStudy, ThermalStudy, study_variant
from tribodyn.cycle.thermal import ThermalCycle
from tribodyn.physics.heat_conduction import ThermalBody, ThermalProperties
from tribodyn.physics.thermal_oil import ThermalLubricant, kelvin

# the thermal paper case on a coarse thermal grid (the march is under test)
CASE = load_case("andreou2023_thermal").updated(
    {
        "numerics.thermal_x_nodes": 48,
        "numerics.thermal_solid_nodes": 8,
        "numerics.thermal_film_nodes": 5,
    }
)
UNCOATED = build(CASE).set("uncoated").surface
WIDTH = CASE.width


def _thermal(inp):
    """The thermal march of the uncoated set (the driver with :class:`ThermalCycle`)."""
    s, built = UNCOATED, build(CASE)
    method = ThermalCycle(
        s.bodies,
        built.thermal_oil(),
        built.set(s.name).thermal_bodies,
        s.roughness,
        built.set(s.name).options,
        built.thermal_solver_options(),
    )
    return march_cycle(inp, "u", "u", method)


def _ramp_inputs(step_deg):
    return ramp_inputs(step_deg, 10.0, WIDTH)


def test_thermal_cycle_has_the_time_error_control():
    """Through the engagement (the squeeze of the thick start film) the thermal march at
    1° sub-steps the steps after the steady start, as the isothermal one does, records
    its sub-steps, and reproduces the films of a 0.25° march within 1 %."""
    a, b = _thermal(_ramp_inputs(1.0)), _thermal(_ramp_inputs(0.25))
    iso = isothermal_cycle(CASE, UNCOATED, _ramp_inputs(1.0))
    assert a.converged[a.loaded].all() and b.converged[b.loaded].all()
    assert a.substeps is not None and np.array_equal(a.substeps > 0, a.loaded)
    first = np.flatnonzero(a.loaded)[1:3]  # the steps after the steady start
    assert np.all(a.substeps[first] > 1) and np.all(iso.substeps[first] > 1)
    k = np.searchsorted(_ramp_inputs(0.25).crank_angle, a.crank_angle)
    both = a.loaded & b.loaded[k]
    assert both.sum() >= 7
    assert np.allclose(a.central_film[both], b.central_film[k][both], rtol=0.01)
    assert np.isfinite(a.max_temperature[a.loaded]).all()


def test_thermal_march_reports_validity_warnings():
    """10 N on a 1 mm radius at 10 m/s: the load-carrying zone reaches a quarter of R
    (flagged above 0.1 R: the parabolic gap and half-space elasticity no longer hold).
    The thermal march counts the warning per kind and first crank angle like the
    isothermal one, so a thermal study reports it."""
    crank = np.arange(0.0, 3.0 + 1e-9, 1.0)
    n = crank.size
    inp = cycle_inputs(crank, 10.0, 10.0, 2.0, 1e-3, WIDTH)
    th = _thermal(inp)
    iso = march_cycle(inp, "u", "u", IsothermalCycle.for_set(CASE, UNCOATED))
    assert th.converged.all() and iso.converged.all()
    assert set(th.validity) == set(iso.validity)
    (count, first, text), *_ = th.validity.values()
    assert count == n and first == 0.0
    assert text.startswith("the load-carrying zone reaches 0.2")


def test_study_variant():
    """``numerics.thermal`` chooses the study's variant: the thermal one adds a thermal
    pass per set with the case's thermal oil; the isothermal one adds none."""
    thermal = study_variant(build(CASE))
    assert isinstance(thermal, ThermalStudy) and thermal.kinds == ("thermal",)
    assert thermal.oil(build(CASE)) is not None
    assert [t.key for t in thermal.tasks(build(CASE), _ramp_inputs(1.0))] == [
        f"thermal:{n}" for n in build(CASE).sets
    ]
    iso = build(CASE.updated({"numerics.thermal": False}))
    assert type(study_variant(iso)) is IsothermalStudy
    assert study_variant(iso).oil(iso) is None and study_variant(iso).tasks(iso, None) == []


# ----------------------------------------------------------------------------- the stepper
STEEL = Material(210e9, 0.3)
PAIR = (Body(STEEL), Body(STEEL))
STEEL_T = ThermalProperties(46.0, 7850.0, 470.0)
OIL = ThermalLubricant(
    kelvin(40.0), kinematic_viscosity_40=64e-6, kinematic_viscosity_100=11e-6, density=852.0
)
W, R = 2e5, 0.02


def _stepper(kind):
    if kind == "thermal":
        return ThermalTransientEHL(PAIR, OIL, (ThermalBody(STEEL_T), ThermalBody(STEEL_T)), n=128)
    return TransientEHL(PAIR, OIL.isothermal(), n=128)


@pytest.mark.parametrize("kind", ["isothermal", "thermal"])
def test_steps_use_the_newton_predictor(monkeypatch, kind):
    """Every step starts Newton from the predictor; from the second step after a start
    (two levels known) it extrapolates the pressure, i.e. changes the start."""
    seen = []
    orig = TransientEHL._predict

    def spy(self, sysm, dt):
        q = state_from_dimensional(sysm, self._grid.x, self._q, self._h0).Q  # the last level
        out = orig(self, sysm, dt)
        seen.append(not np.array_equal(out.Q, q))
        return out

    monkeypatch.setattr(TransientEHL, "_predict", spy)
    tr = _stepper(kind)
    tr.start_steady(W, R, 2.0, 1.0)
    for k in range(1, 4):
        assert tr.step(2e-5, W * (1 + 0.1 * k), R, 2.0, 1.0).converged
    assert seen == [False, True, True]


@pytest.mark.parametrize("kind", ["isothermal", "thermal"])
def test_start_steady_resets_the_history(kind):
    """A stepper restarted by start_steady holds the one level of its start, the same as
    a fresh stepper started there, and marches on identically."""
    a, b = _stepper(kind), _stepper(kind)
    a.start_steady(W, R, 2.0, 1.0)
    for k in range(1, 3):
        a.step(2e-5, W, R, 2.0, 1.0 + 0.2 * k)
    a.start_steady(1.5 * W, R, 2.5, 1.0, time=1.0)
    b.start_steady(1.5 * W, R, 2.5, 1.0, time=1.0)
    assert len(a._levels) == len(b._levels) == 1
    la, lb = a._levels[0], b._levels[0]
    assert la.dt is None and np.array_equal(la.q, lb.q) and np.array_equal(la.rho_h, lb.rho_h)
    for k in range(1, 3):
        ra, rb = (s.step(2e-5, 1.5 * W * (1 + 0.1 * k), R, 2.5, 1.0) for s in (a, b))
        assert ra.central_film == rb.central_film and ra.friction == rb.friction

"""Numerics of the cycle study: accuracy of the automatic grid at cam-cycle conditions,
the time-error control of the transient march, the Anderson-
accelerated coupling, and distribution through any concurrent.futures Executor."""

import pickle
from concurrent.futures import Executor, Future

import numpy as np
import pytest

from conftest import cycle_inputs, isothermal_cycle, ramp_inputs
from tribodyn import solve_ehl
from tribodyn.config import load_case
from tribodyn.config.build import build
from tribodyn.cycle.coupling import AndersonMixer
from tribodyn.cycle.driver import IsothermalCycle, ehl_for_set, march_cycle
from tribodyn.workflow.cycle import run_cycle_study

CASE = load_case()
UNCOATED = build(CASE).set("uncoated").surface
WCC = build(CASE).set("wcc_4um").surface
WIDTH = CASE.width


# Conditions of the paper's cam cycle (explicit dynamics, 3000 rpm): the cam nose
# (R = 3 mm, reversed entrainment), the fast closing flank (R = 77 mm, thick film) and a
# light bounce after valve closing (10 N, nearly rigid).
@pytest.mark.parametrize(
    "F, R, ue, us, surface",
    [
        (513.3, 2.99e-3, -1.44, 2.55, WCC),
        (466.5, 77.0e-3, 10.89, 22.0, UNCOATED),
        (10.1, 15.0e-3, 1.18, 2.36, UNCOATED),
    ],
)
def test_default_grid_is_accurate_at_cycle_conditions(F, R, ue, us, surface):
    """The automatic grid's discretisation error, measured against four times the nodes
    on the same domain (second-order convergence: the 4× solution is ~16× closer), is
    within 0.5 % for the films and 0.3 % for the friction."""
    opts = build(CASE).set(surface.name).options
    args = (F / WIDTH, R, ue, us, surface.bodies, build(CASE).lubricant, surface.roughness)
    a = solve_ehl(*args, options=opts)
    b = solve_ehl(*args, options=opts, n=4 * a.x.size)
    assert a.converged and b.converged
    assert b.x[0] == pytest.approx(a.x[0], rel=1e-12)
    assert a.central_film == pytest.approx(b.central_film, rel=5e-3)
    assert a.min_film == pytest.approx(b.min_film, rel=5e-3)
    assert a.friction == pytest.approx(b.friction, rel=3e-3)


def _ramp_inputs(step_deg):
    return ramp_inputs(step_deg, 60.0, WIDTH)


def test_time_error_control_resolves_the_engagement():
    """Both samplings start at the same sample (3° crank, 7 N); with the time-error
    control, 1° samples reproduce the films of 0.25° samples through the engagement
    transient (squeeze of the thick start film) within 1 %, and the control subdivides
    the steps there."""
    lub = build(CASE).lubricant
    opts = build(CASE).set(UNCOATED.name).options
    res = {}
    for step in (1.0, 0.25):
        inp = _ramp_inputs(step)
        res[step] = (
            inp,
            march_cycle(
                inp, "u", "u", IsothermalCycle(UNCOATED.bodies, lub, UNCOATED.roughness, opts)
            ),
        )
    (ia, a), (ib, b) = res[1.0], res[0.25]
    assert a.converged[a.loaded].all() and b.converged[b.loaded].all()
    k = np.searchsorted(ib.crank_angle, ia.crank_angle)
    both = a.loaded & b.loaded[k]
    assert both.sum() > 40
    assert np.allclose(a.central_film[both], b.central_film[k][both], rtol=0.01)
    first = np.flatnonzero(a.loaded)[1:3]  # the steps after the steady start
    assert np.all(a.substeps[first] > 1)


def test_anderson_mixer_accelerates_a_linear_fixed_point():
    """x = A x + c with a slowly contracting A: plain relaxation (memory 0) needs many
    iterations; Anderson with memory 2 solves the 2-D problem in a few."""
    A = np.array([[0.9, 0.05], [0.0, 0.8]])
    c = np.array([1.0, 2.0])
    exact = np.linalg.solve(np.eye(2) - A, c)

    def iterations(memory):
        mix, x = AndersonMixer(beta=0.5, memory=memory), np.zeros(2)
        for k in range(1, 200):
            x = mix(x, A @ x + c)
            if np.max(np.abs(x - exact)) < 1e-10:
                return k
        return 200

    assert iterations(2) <= 5
    assert iterations(0) > 50


class PicklingExecutor(Executor):
    """Runs every task in this process after a pickle round trip of the callable, its
    arguments and its result, as a process or cluster executor would."""

    def __init__(self):
        self.calls = []

    def submit(self, fn, /, *args, **kwargs):
        fn, args, kwargs = pickle.loads(pickle.dumps((fn, args, kwargs)))
        self.calls.append(fn.__name__)
        f = Future()
        f.set_result(pickle.loads(pickle.dumps(fn(*args, **kwargs))))
        return f


def _light_case(values):
    """The paper's case with its first two surface sets (uncoated, the reference, and
    DLC 1 µm), one engine cycle, coarse steps and grid, and ``values``: the plumbing is
    under test, not the physics."""
    sets = CASE.to_dict()["surface_sets"][:2]
    light = {
        "numerics.crank_step_deg": 4.0,
        "numerics.n": 128,
        "numerics.cycles": 1,
        "numerics.output_step_deg": 1.0,
    }
    return CASE.updated({**light, **values, "surface_sets": sets})


def test_study_runs_through_any_executor():
    case = _light_case({"numerics.implicit_coupling": False})
    events = []
    ex = PicklingExecutor()
    study = run_cycle_study(
        case, executor=ex, progress=lambda e, **i: events.append((e, i.get("name"), i.get("done")))
    )
    n_sets = len(case.surface_set_names)
    assert sorted(ex.calls) == sorted(
        ["_pass_task", "_stress_task"] * n_sets + ["_coupling_task", "coating_studies_task"]
    )
    assert [s.name for s in study.sets] == case.surface_set_names
    done = {name for e, name, d in events if e == "set" and d}
    assert done == set(case.surface_set_names)
    for a in study.sets[:2]:  # the same as a pass in this process
        b = ehl_for_set(case, build(case).set(a.name).surface, study.inputs)
        assert np.array_equal(a.central_film, b.central_film, equal_nan=True)


def test_friction_only_runs_the_passes_alone():
    # what an engine study runs: every set's EHL pass (the reference set's too), no
    # implicit comparison, stresses or single-contact studies; the passes unchanged
    case = _light_case({})
    ex = PicklingExecutor()
    study = run_cycle_study(case, executor=ex, friction_only=True)
    assert ex.calls == ["_pass_task"] * len(case.surface_set_names)
    assert [s.name for s in study.sets] == case.surface_set_names
    assert study.implicit is None and not study.stresses
    assert study.sensitivity is None and study.ehl_coating is None and not study.dry
    assert not any("implicit coupling" in w for w in study.warnings)
    a = study.reference
    b = ehl_for_set(case, build(case).set(a.name).surface, study.inputs)
    assert np.array_equal(a.central_film, b.central_film, equal_nan=True)
    assert np.array_equal(a.boundary_friction, b.boundary_friction, equal_nan=True)


def test_validity_warnings_of_the_steps_reach_the_study():
    """Steps outside the model's validity (here: a 0.5 mm radius under 5 kN, contact
    pressure beyond the elastic limit) are collected per kind with their first crank angle
    and count, so the study's warnings (report, summary.json) name them."""
    inp = cycle_inputs(np.arange(0.0, 6.0 + 1e-9, 1.0), 5000.0, 3.0, 6.0, 5e-4, WIDTH)
    r = isothermal_cycle(CASE, UNCOATED, inp)
    assert r.loaded.all()
    kinds = {text.split(" ")[0]: (count, first) for count, first, text in r.validity.values()}
    assert "peak" in kinds  # "peak contact pressure … GPa exceeds …"
    count, first = kinds["peak"]
    assert count == int(r.converged.sum()) and first == 0.0


def test_coupling_re_passes_use_their_own_grid_and_time_tolerance(monkeypatch):
    """film_law_only passes run on numerics.coupling_n nodes (never finer than a fixed
    numerics.n) at COUPLING_TIME_TOL; the reported passes keep numerics.n and TIME_TOL."""
    import tribodyn.cycle.driver as ce

    seen = []
    monkeypatch.setattr(
        ce, "march_cycle", lambda *a, **k: seen.append((a[3].options.n, k["time_tol"]))
    )
    inp = _ramp_inputs(1.0)
    for changes, expect in (
        ({}, [(None, ce.TIME_TOL), (192, ce.COUPLING_TIME_TOL)]),
        ({"numerics.n": 128}, [(128, ce.TIME_TOL), (128, ce.COUPLING_TIME_TOL)]),
        ({"numerics.n": 512}, [(512, ce.TIME_TOL), (192, ce.COUPLING_TIME_TOL)]),
        ({"numerics.coupling_n": 0}, [(None, ce.TIME_TOL), (None, ce.COUPLING_TIME_TOL)]),
    ):
        case = CASE.updated(changes)
        seen.clear()
        ehl_for_set(case, build(case).set("uncoated").surface, inp)
        ehl_for_set(case, build(case).set("uncoated").surface, inp, film_law_only=True)
        assert seen == expect, changes
    assert ce.COUPLING_TIME_TOL > ce.TIME_TOL

"""pytest plugin of the do-nothing check: replace one solver's iteration by one that returns
its starting state and reports convergence, and record which tests still pass.

A good solver test fails under this replacement, because it checks the answer, not the
start. Enabled only with ``-p do_nothing`` and the environment variable
``TRIBODYN_DO_NOTHING`` set to ``dry``, ``ehl``, ``dynamics``, ``thermal`` or ``coupling``;
the outcome of every test that called the replaced iteration is appended (JSON lines) to
the file named by ``TRIBODYN_DO_NOTHING_REPORT``. Run them all with
``python tests/check_do_nothing.py``.
"""

import importlib
import json
import os
from collections.abc import Callable

import numpy as np
import pytest

_calls = {"n": 0}


def _dry_nothing(op, geom, w, dx, p, tol, max_iter):
    """The CGM of contact/dry.py, doing nothing: the starting pressure, 'converged'."""
    _calls["n"] += 1
    return p, True, 0, "converged (do-nothing)"


def _newton_nothing(sysm, st, tol, max_iter, lu=None, coarse=None, release_blocks=True):
    """The EHL Newton iteration doing nothing: the starting state, 'converged'."""
    from tribodyn.contact.ehl.newton import NewtonOutcome, State

    _calls["n"] += 1
    ev = sysm.evaluate(st.Q, st.H0)
    return NewtonOutcome(
        State(st.Q, st.H0, np.maximum(ev.P, 0.0), ev.H), True, 0, "converged (do-nothing)", None
    )


class _Constant:
    """A solve_ivp result that stays at the initial state, with no events."""

    def __init__(self, t_eval, y0, n_events):
        self.t = np.asarray(t_eval)
        self.y = np.repeat(np.asarray(y0, float)[:, None], self.t.size, axis=1)
        self.t_events = [np.array([]) for _ in range(n_events)]
        self.y_events = [np.empty((0, len(y0))) for _ in range(n_events)]
        self.status, self.message, self.success = 0, "do-nothing", True
        self.nfev = self.njev = self.nlu = 0


def _ivp_nothing(fun, t_span, y0, method="RK45", t_eval=None, events=None, **kw):
    _calls["n"] += 1
    n_events = 0 if events is None else (len(events) if isinstance(events, (list, tuple)) else 1)
    return _Constant(t_eval if t_eval is not None else [t_span[0], t_span[1]], y0, n_events)


def _odeint_nothing(func, y0, t, *args, full_output=False, **kw):
    """scipy.integrate.odeint that stays at the initial state (the compiled lumped path)."""
    _calls["n"] += 1
    Y = np.repeat(np.asarray(y0, float)[None, :], len(t), axis=0)
    if not full_output:
        return Y
    n = np.zeros(max(len(t) - 1, 1), dtype=int)
    return Y, {"nfe": n, "nje": n, "message": "Integration successful."}


def _energy_nothing(self, x, p, h, pa, cond, rough, opts, *, refresh=True, **kw):
    """The thermal EHL's energy-equation solve (ThermalField.update) doing nothing: the
    temperature stays where it started (the inlet), and the change reported is 0 K."""
    _calls["n"] += 1
    if refresh:
        self.refresh(x, p, h, pa, cond, rough, opts)
    return 0.0


def _coupling_nothing(case, surface_set, dynamics, inputs, first, progress=None):
    """The implicit coupling doing nothing: the explicit dynamics returned as the implicit
    run, 'converged' after one iteration with zero change."""
    from tribodyn.cycle.coupling import CouplingIteration, CouplingResult

    _calls["n"] += 1
    out = CouplingResult()
    if not case.numerics.implicit_coupling:
        return out
    out.history.append(CouplingIteration(1, 0.0, 0.0))
    out.implicit, out.converged, out.message = dynamics, True, "converged (do-nothing)"
    return out


#: solver → [(module, attribute, replacement)]: every place the iteration is looked up
#: (``attribute`` may be ``Class.method``).
PATCHES: dict[str, list[tuple[str, str, Callable]]] = {
    "dry": [("tribodyn.contact.dry", "_cgm", _dry_nothing)],
    "ehl": [
        ("tribodyn.contact.ehl.steady", "newton", _newton_nothing),
        ("tribodyn.contact.ehl.transient", "newton", _newton_nothing),
    ],
    "dynamics": [
        ("tribodyn.valvetrain.dynamics", "solve_ivp", _ivp_nothing),
        ("tribodyn.valvetrain.compiled", "odeint", _odeint_nothing),
        ("tribodyn.valvetrain.compiled", "solve_ivp", _ivp_nothing),
    ],
    "thermal": [("tribodyn.contact.ehl.thermal_field", "ThermalField.update", _energy_nothing)],
    "coupling": [
        ("tribodyn.cycle.coupling", "run_coupling", _coupling_nothing),
        ("tribodyn.workflow.cycle", "run_coupling", _coupling_nothing),
    ],
}


def pytest_configure(config):
    which = os.environ.get("TRIBODYN_DO_NOTHING")
    if not which:
        return
    for mod, attr, fn in PATCHES[which]:
        owner = importlib.import_module(mod)
        *path, name = attr.split(".")
        for part in path:
            owner = getattr(owner, part)
        if not hasattr(owner, name):
            raise RuntimeError(f"do-nothing check: {mod}.{attr} not found (update PATCHES)")
        setattr(owner, name, fn)


_fixture_uses_solver: set[str] = set()


@pytest.hookimpl(hookwrapper=True)
def pytest_fixture_setup(fixturedef, request):
    before = _calls["n"]
    yield
    if _calls["n"] > before:
        _fixture_uses_solver.add(fixturedef.argname)


@pytest.hookimpl(tryfirst=True)
def pytest_runtest_setup(item):
    _calls["n"] = 0


def pytest_runtest_makereport(item, call):
    path = os.environ.get("TRIBODYN_DO_NOTHING_REPORT")
    if not path or call.when != "call":
        return
    used = _calls["n"] > 0 or bool(_fixture_uses_solver & set(item.fixturenames))
    with open(path, "a", encoding="utf-8") as f:
        f.write(
            json.dumps({"test": item.nodeid, "passed": call.excinfo is None, "solver_called": used})
            + "\n"
        )

"""Bad input and non-convergence of the EHL solver are reported, never hidden."""

import dataclasses

import numpy as np
import pytest

from ehl_cases import OIL_055 as OIL
from ehl_cases import PAIR, STEEL
from tribodyn import (
    Body,
    InputError,
    Roughness,
    TransientEHL,
    solve_dry_contact,
    solve_ehl,
)
from tribodyn.physics import limits as L


@pytest.mark.parametrize(
    "args, name",
    [
        ((-1e4, 0.01, 1.0, 0.0), "load"),
        ((0.0, 0.01, 1.0, 0.0), "load"),
        ((1e4, 0.0, 1.0, 0.0), "radius"),
        ((1e4, -0.01, 1.0, 0.0), "radius"),
        ((1e4, 0.01, float("nan"), 0.0), "entrainment_speed"),
        ((1e4, 0.01, 1.0, float("inf")), "sliding_speed"),
    ],
)
def test_bad_arguments_name_the_field(args, name):
    with pytest.raises(InputError, match=rf"^{name} must"):
        solve_ehl(*args, PAIR, OIL)


# extreme operating points used to end in ZeroDivisionError (w = 5e-324 in the grid),
# OverflowError (w = 1e300) or "dx must be a finite real number" (u_e = 1e300): now the
# shared limits reject them, naming the argument and the range
@pytest.mark.parametrize(
    "args, name, limit",
    [
        ((5e-324, 0.01, 1.0, 0.5), "load", L.LINE_LOAD),
        ((1e-300, 0.01, 1.0, 0.5), "load", L.LINE_LOAD),
        ((1e300, 0.01, 1.0, 0.5), "load", L.LINE_LOAD),
        ((1e4, 5e-324, 1.0, 0.5), "radius", L.CONTACT_RADIUS),
        ((1e4, 1e300, 1.0, 0.5), "radius", L.CONTACT_RADIUS),
        ((1e4, 0.01, 1e300, 0.5), "entrainment_speed", L.SURFACE_SPEED),
        ((1e4, 0.01, -1e300, 0.5), "entrainment_speed", L.SURFACE_SPEED),
        ((1e4, 0.01, 1.0, 1e300), "sliding_speed", L.SURFACE_SPEED),
        ((10**400, 0.01, 1.0, 0.5), "load", L.LINE_LOAD),
    ],
)
def test_extreme_operating_points_name_the_argument_and_range(args, name, limit):
    with pytest.raises(InputError, match=rf"^{name} must be") as err:
        solve_ehl(*args, PAIR, OIL, n=64)
    assert limit.describe(unit=False) in str(err.value)
    with pytest.raises(InputError, match=rf"^{name} must be"):
        TransientEHL(PAIR, OIL, n=64).start_steady(*args)
    if name in ("load", "radius"):
        with pytest.raises(InputError, match=rf"^{name} must be"):
            solve_dry_contact(args[0], args[1], PAIR, n=64)


@pytest.mark.parametrize(
    "w, R, u",
    [(L.LINE_LOAD.ge, L.CONTACT_RADIUS.le, 5e-324), (L.LINE_LOAD.le, L.CONTACT_RADIUS.ge, 1e3)],
)
def test_corners_of_the_allowed_range_end_honestly(w, R, u):
    """At the corners of the ranges the solver answers: converged with a physical film
    (and a warning where the model does not apply) or not converged with a message."""
    rough = Roughness(2.7e9, 0.347e-6, 0.217e-6)
    r = solve_ehl(w, R, u, u, PAIR, OIL, rough, n=64, max_iter=10)
    if r.converged:
        assert np.all(np.isfinite(r.film)) and np.all(r.film > 0)
        assert r.central_film < 0.02 * R or r.warnings
    else:
        assert r.message


def test_zero_entrainment_needs_the_transient_solver():
    with pytest.raises(InputError, match="entrainment_speed must be non-zero"):
        solve_ehl(1e4, 0.01, 0.0, 1.0, PAIR, OIL)


def test_wrong_model_objects():
    with pytest.raises(InputError, match="lubricant"):
        solve_ehl(1e4, 0.01, 1.0, 0.0, PAIR, "oil")
    with pytest.raises(InputError, match="roughness"):
        solve_ehl(1e4, 0.01, 1.0, 0.0, PAIR, OIL, roughness=0.4e-6)
    with pytest.raises(InputError, match="bodies"):
        solve_ehl(1e4, 0.01, 1.0, 0.0, (Body(STEEL),), OIL)


def test_nonconvergence_is_reported_without_nans():
    r = solve_ehl(4e5, 0.01, 0.5, 0.0, PAIR, OIL, max_iter=1)
    assert r.converged is False
    assert r.message and "converged in" not in r.message
    for arr in (r.pressure, r.film, r.asperity_pressure):
        assert np.all(np.isfinite(arr))
    assert np.isfinite(r.central_film) and np.isfinite(r.viscous_friction)


def test_a_domain_that_cannot_be_sized_is_said_in_the_users_terms(monkeypatch):
    """Safety net behind the limits: non-finite scales of the grid (the old
    'dx must be a finite real number (got nan)') name load, radius and speed."""
    import tribodyn.contact.ehl.grid as G

    monkeypatch.setattr(G, "_length_scale", lambda *a, **k: (float("nan"), 1e-4, 1e-6))
    with pytest.raises(InputError, match=r"^load 10000 N/m, radius 0\.01 m and entrainment"):
        solve_ehl(1e4, 0.01, 1.0, 0.5, PAIR, OIL, n=64)


def test_capping_the_newton_iterations_checks_no_option_again(monkeypatch):
    """The options with fewer Newton iterations (a last short attempt) are a copy of
    checked ones: no range is checked again, and they equal a checked copy."""
    tr = TransientEHL(PAIR, OIL, n=64)
    calls = []
    check = L.Limit.check
    monkeypatch.setattr(L.Limit, "check", lambda self, *a: calls.append(a) or check(self, *a))
    with tr._max_iter(5):
        capped = tr.opts
    assert calls == []
    assert capped == dataclasses.replace(tr.opts, max_iter=5) != tr.opts

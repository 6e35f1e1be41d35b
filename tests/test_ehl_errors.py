"""Bad input and non-convergence of the EHL solver are reported, never hidden."""

import numpy as np
import pytest

from tribodyn import Body, EHLOptions, InputError, Lubricant, Material, solve_ehl

STEEL = Material(210e9, 0.3)
PAIR = (Body(STEEL), Body(STEEL))
OIL = Lubricant(0.055, 1.05e-8)


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


def test_zero_entrainment_needs_the_transient_solver():
    with pytest.raises(InputError, match="entrainment_speed must be non-zero"):
        solve_ehl(1e4, 0.01, 0.0, 1.0, PAIR, OIL)


@pytest.mark.parametrize(
    "kw, name",
    [
        (dict(n=8), "n"),
        (dict(inlet=0.5), "inlet"),
        (dict(outlet=-1.0), "outlet"),
        (dict(viscous_model="bingham"), "viscous_model"),
        (dict(time_order=3), "time_order"),
        (dict(max_iter=0), "max_iter"),
        (dict(tol=0.0), "tol"),
    ],
)
def test_bad_options(kw, name):
    with pytest.raises(InputError, match=name):
        EHLOptions(**kw)


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

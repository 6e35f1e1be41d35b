"""Property-based check of solve_ehl over wide physical ranges: whatever the inputs, a
result that says ``converged=True`` has a positive, finite film, finite pressures and
friction, and every result explains itself in ``message``. Inputs span loads from a
hair's weight to far beyond yield, radii from 0.1 mm to 1 m, speeds from 1 mm/s to
1 km/s in either direction, thin and thick oils, soft and stiff solids, smooth and rough
surfaces (coated or not).

The grid is fixed (128 nodes) and the examples are derandomised, so the test is fast and
reproducible; hypothesis searches the corners of this space more widely than a
hand-written grid would.
"""

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from tribodyn import (
    Body,
    Coating,
    InputError,
    Lubricant,
    Material,
    Roughness,
    solve_ehl,
)


def log_uniform(lo, hi):
    return st.floats(math.log10(lo), math.log10(hi)).map(lambda e: 10.0**e)


signed_speed = st.tuples(log_uniform(1e-3, 1e3), st.sampled_from([-1.0, 1.0])).map(
    lambda t: t[0] * t[1]
)

roughness = st.one_of(
    st.none(),
    st.builds(
        Roughness,
        asperity_density=log_uniform(1e8, 1e14),
        rms=log_uniform(1e-8, 1e-5),
        summit_radius=log_uniform(1e-7, 1e-3),
    ),
)

coating = st.one_of(
    st.none(),
    st.builds(
        Coating,
        E=log_uniform(1e9, 1e12),
        nu=st.floats(0.0, 0.45),
        thickness=log_uniform(1e-7, 1e-4),
    ),
)


@settings(
    max_examples=25,
    deadline=None,
    derandomize=True,
    print_blob=True,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.filter_too_much],
)
@given(
    load=log_uniform(1e-2, 1e9),  # the allowed range (physics.limits.LINE_LOAD)
    radius=log_uniform(1e-4, 1.0),
    ue=signed_speed,
    us=st.floats(-100.0, 100.0),
    mu0=log_uniform(1e-4, 1.0),
    alpha=st.floats(0.0, 4e-8),
    E=log_uniform(1e9, 1e12),
    nu=st.floats(0.0, 0.45),
    rough=roughness,
    coat=coating,
    barus=st.booleans(),
)
@pytest.mark.filterwarnings("ignore::RuntimeWarning")
@pytest.mark.filterwarnings("ignore::scipy.integrate.IntegrationWarning")
def test_converged_means_a_physical_film(
    load, radius, ue, us, mu0, alpha, E, nu, rough, coat, barus
):
    mat = Material(E, nu)
    bodies = (Body(mat), Body(mat, coat))
    oil = Lubricant(mu0, alpha, viscosity_model="barus" if barus else "roelands")
    r = solve_ehl(load, radius, ue, us, bodies, oil, rough, n=128, max_iter=30)
    assert isinstance(r.message, str) and r.message
    if r.converged:
        assert np.all(np.isfinite(r.film)) and np.all(r.film > 0.0)
        assert r.central_film > 0.0 and r.min_film > 0.0
        assert np.all(np.isfinite(r.pressure)) and np.all(np.isfinite(r.asperity_pressure))
        for f in (r.viscous_friction, r.boundary_friction, r.hydrodynamic_load, r.asperity_load):
            assert math.isfinite(f) and f >= 0.0
    else:  # the message does not claim convergence
        assert not r.message.startswith("converged")


@settings(max_examples=40, deadline=None, derandomize=True)
@given(
    load=st.one_of(
        st.floats(allow_nan=True, allow_infinity=True),
        st.integers(),
        st.text(max_size=3),
        st.none(),
    )
)
def test_bad_loads_are_input_errors(load):
    mat = Material(210e9, 0.3)
    oil = Lubricant(0.055, 1e-8)
    ok = (
        isinstance(load, (int, float))
        and not isinstance(load, bool)
        and math.isfinite(load)
        and load > 0
    )
    if ok:
        return
    with pytest.raises(InputError, match="load"):
        solve_ehl(load, 0.01, 1.0, 0.0, (Body(mat), Body(mat)), oil, n=128)

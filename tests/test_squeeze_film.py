"""The squeeze-film closed form of the reduced film model against the transient EHL."""

import math

import numpy as np

from tribodyn import Body, Lubricant, Material, TransientEHL
from tribodyn.valvetrain.tribology import squeeze_film_load

STEEL = Material(210e9, 0.3)
PAIR = (Body(STEEL), Body(STEEL))


def test_squeeze_closed_form_carries_the_load_of_the_transient_ehl():
    """A rigid isoviscous cylinder pressed onto a plane at constant load with no
    entrainment: the load the closed form gives for the numerical film and its rate of
    approach (central differences) must be the imposed load (the solver is independent:
    finite-volume Reynolds with ∂(ρh)/∂t, BDF2)."""
    R, w, eta, h_i = 0.015, 2e4, 0.01, 1e-6
    oil = Lubricant(viscosity=eta, pressure_viscosity=0.0, compressible=False)
    tr = TransientEHL(PAIR, oil, elastic=False, inlet_rigid=8, n=256)
    tr.start_film(h_i, w, R)
    k = w / (3 * math.sqrt(2) * math.pi * eta * R**1.5)
    dt = 4.0 / (k * math.sqrt(h_i)) / 80  # the film falls to 1/9 of h_i
    t, h = [0.0], [h_i]
    for _ in range(80):
        r = tr.step(dt, w, R, 0.0, 0.0)
        assert r.converged, r.message
        t.append(r.time)
        h.append(r.central_film)
    t, h = np.array(t), np.array(h)
    V = -np.gradient(h, t)
    w_sq = squeeze_film_load(h, V, R, eta)
    assert np.all(np.abs(w_sq[5:-5] / w - 1.0) < 0.03)

"""Implicit coupling of the valvetrain dynamics and the numerical (transient) EHL.

The paper's "implicit" model solves the EHL inside the multi-body dynamics, so that the
film acts in series with the contact stiffness and the EHL friction acts on the bodies.
Here the two are coupled by waveform relaxation, which converges to the same coupled
solution:

1. dynamics with a film law (initially none: the explicit run) → F(t), u_e, u_s, R;
2. transient EHL along the presented cycle → central film h_c(t), friction F_f(t);
3. dynamics again with h(t, F) = h_k(t) + c_k(t)(F − F_k(t)) in series with the contact
   stiffness (valvetrain ``FilmTableTribology``) and the EHL friction coefficient
   μ_k(t) = F_f/F; repeat until the contact force stops changing.

At the fixed point F = F_k, so the linearisation c_k = dh/dF only speeds convergence; it is
taken from the local logarithmic slope of the Moes film formula, c = h_c (∂ln h/∂ln w)/F.
Only changes of the film act on the motion: h_k is measured from the film at the start of
each loaded event (the base circle carries no load and has no film). The EHL of the
presented cycle drives both simulated cycles (the tables are periodic in the cam angle).
"""

from __future__ import annotations

import numpy as np

from ..physics.regimes import hamrock_groups, moes_central
from ..valvetrain.tribology import FilmTableTribology, TribologyModel

__all__ = ["FrictionCoefficientTable", "film_law_from_ehl", "ehl_tribology"]


class FrictionCoefficientTable(TribologyModel):
    """Friction F_f = μ(t) F from a tabulated coefficient (periodic in time)."""

    name = "ehl-friction-table"
    periodic_in_cam_angle = True

    def __init__(self, time, coefficient, period: float):
        self.time = np.asarray(time, dtype=float)
        self.mu = np.asarray(coefficient, dtype=float)
        self.period = float(period)
        self._t0 = float(self.time[0])

    def friction(self, t, force, entrainment_speed, sliding_speed, radius):
        tt = self._t0 + np.mod(np.asarray(t, dtype=float) - self._t0, self.period)
        mu = np.interp(tt, self.time, self.mu)
        return mu * np.maximum(np.asarray(force, dtype=float), 0.0)


def _bridge(values, loaded):
    """Fill non-finite values of loaded samples (failed steps) by linear interpolation
    from their loaded neighbours, so a failed step does not reset the tables."""
    v = np.array(values, dtype=float)
    good = loaded & np.isfinite(v)
    bad = loaded & ~good
    if bad.any() and good.sum() >= 2:
        idx = np.arange(v.size)
        v[bad] = np.interp(idx[bad], idx[good], v[good])
    return v


def film_law_from_ehl(inputs, ehl, lubricant, e_prime: float):
    """(h_k, c_k, F_k) over the samples of ``inputs`` from a transient-EHL cycle result."""
    F = inputs.contact_force
    loaded = ehl.loaded
    hc = _bridge(ehl.central_film, loaded)
    h = np.zeros_like(F)
    c = np.zeros_like(F)
    start = None
    for i in range(F.size):
        if not loaded[i] or not np.isfinite(hc[i]):
            start = None
            continue
        if start is None:
            start = hc[i]
        h[i] = hc[i] - start
        w = F[i] / inputs.width
        u = max(abs(inputs.entrainment_speed[i]), 1e-3)
        R = inputs.radius[i]
        W1, U, G = hamrock_groups(w, R, u, lubricant.viscosity, lubricant.pressure_viscosity,
                                  e_prime)
        W2, _, _ = hamrock_groups(1.01 * w, R, u, lubricant.viscosity,
                                  lubricant.pressure_viscosity, e_prime)
        slope = np.log(moes_central(W2, U, G, R) / moes_central(W1, U, G, R)) / np.log(1.01)
        c[i] = min(0.0, hc[i] * slope / F[i])
    return h, c, F


def ehl_tribology(inputs, ehl, lubricant, e_prime: float, period: float) -> FilmTableTribology:
    """Tribology model of the implicit coupling from one transient-EHL cycle."""
    ff = _bridge(ehl.friction, ehl.loaded)
    mu = np.where(ehl.loaded & np.isfinite(ff),
                  ff / np.maximum(inputs.contact_force, 1e-12), 0.0)
    friction = FrictionCoefficientTable(inputs.time, mu, period)
    h, c, F = film_law_from_ehl(inputs, ehl, lubricant, e_prime)
    return FilmTableTribology(friction, inputs.time, h, c, F, period=period)

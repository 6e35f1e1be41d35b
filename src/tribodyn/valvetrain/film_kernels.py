"""Compiled (numba) forms of the film state's laws
(:mod:`tribodyn.physics.film_state_laws`), shared by the dynamics' kernels
(:mod:`.compiled`) and :class:`~tribodyn.valvetrain.tribology.FilmStateTribology`: the
same operations as the Python laws, without per-sample Python overhead."""

from __future__ import annotations

import math

import numpy as np
from numba import njit

from ..physics import film_state_laws as laws

__all__ = ["entraining_film_load", "steady_films", "STEADY_BISECTIONS", "STEADY_FILM_FLOOR"]

_OPTS = dict(cache=True, nogil=True)

#: :func:`~tribodyn.physics.film_state_laws.entraining_film_load`, compiled
entraining_film_load = njit(**_OPTS)(laws.entraining_film_load)

#: The steady film's bisection in ln h: this many halvings of [ln STEADY_FILM_FLOOR,
#: ln h_s] (80 halvings of that ≈ 17.5-wide bracket end far below a float's resolution
#: of ln h) …
STEADY_BISECTIONS = 80
#: … from this film [m] up.
STEADY_FILM_FLOOR = 1e-12


@njit(**_OPTS)
def steady_films(force, ue, R, r, eta, alpha, e_prime, supply, width):
    """Film h [m] per sample whose entraining load L w'_ent(h; u_e, R, r) equals the force
    F [N] (no squeeze; L = ``width`` [m], w'_ent of :func:`entraining_film_load` with η₀
    ``eta``, α ``alpha``, E' ``e_prime``, h_s ``supply``), by STEADY_BISECTIONS
    bisections in ln h on [ln STEADY_FILM_FLOOR, ln h_s]; h_s where F ≤ 0 or u_e = 0 (no
    steady load then). ``force``, ``ue``, ``R``, ``r``: 1-D arrays of one length."""
    out = np.full(force.size, supply)
    for i in range(force.size):
        if not (force[i] > 0.0 and ue[i] != 0.0):
            continue
        lo, hi = math.log(STEADY_FILM_FLOOR), math.log(supply)
        for _ in range(STEADY_BISECTIONS):
            mid = 0.5 * (lo + hi)
            w, _ = entraining_film_load(
                math.exp(mid), ue[i], R[i], eta, alpha, e_prime, supply, r[i]
            )
            if width * w > force[i]:
                lo = mid
            else:
                hi = mid
        out[i] = math.exp(0.5 * (lo + hi))
    return out

"""Compiled per-iteration work of the semismooth Newton solver (:func:`.newton.newton`):
what the solver needs at an accepted iterate (row scaling, merit, active set) in one call,
the start's given active set, and the finiteness test of a Newton direction. Each
kernel calls or repeats the operations of :mod:`.kernels` in the same order, so that the
iterates are those of separate calls bit for bit.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from .kernels import cavitated_nodes, merit, row_scale

__all__ = ["iterate_terms", "given_active_set", "trial_point"]

_OPTS = dict(cache=True, nogil=True, fastmath=False)


@njit(**_OPTS)
def iterate_terms(AP, AH, D, kcoef, elastic, P, R, load):
    """(c, merit, cavitated) at an iterate: the row scaling c of :func:`.kernels.row_scale`,
    the merit |Φ|² + load² with it (:func:`.kernels.merit`) and the active set
    P_i < −c_i R_i (:func:`.kernels.cavitated_nodes`)."""
    c = row_scale(AP, AH, D, kcoef, elastic)
    return c, merit(P, R, load, c), cavitated_nodes(P, R, c)


@njit(**_OPTS)
def given_active_set(pa, Q, share, given, standard):
    """(set, differs): the cavitated set ``given`` where the asperity pressure exceeds
    ``share`` times the largest total pressure max Q (NaN if a Q is: then nowhere), the
    ``standard`` set elsewhere, the end nodes free; and whether it differs from
    ``standard``."""
    big = -np.inf
    for v in Q:
        if v > big or v != v:  # NaN stays
            big = v
            if v != v:
                break
    thr = share * big
    n = Q.size
    out = np.empty(n, dtype=np.bool_)
    differs = False
    for i in range(n):
        out[i] = given[i] if pa[i] > thr else standard[i]
    out[0] = out[n - 1] = False
    for i in range(n):
        differs |= out[i] != standard[i]
    return out, differs


@njit(**_OPTS)
def trial_point(Q, dQ, step):
    """Q + step·δQ (a line search's trial iterate), as NumPy forms it: the product, then
    the sum."""
    out = np.empty(Q.size)
    for i in range(Q.size):
        out[i] = Q[i] + step * dQ[i]
    return out

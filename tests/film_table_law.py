"""The linearised film-table law h = h_k + c_k (F − F_k) of earlier versions of the
implicit coupling (valvetrain ``FilmTableTribology``), built from a transient-EHL cycle:
the comparison the coupling tests and the cycle benchmark measure the film-state law
(:func:`tribodyn.cycle.film_laws.film_state_tribology`) against."""

from __future__ import annotations

import numpy as np

from tribodyn.cycle.film_laws import FrictionCoefficientTable, _bridge
from tribodyn.physics.regimes import hamrock_groups, moes_central
from tribodyn.valvetrain.tribology import FilmTableTribology, squeeze_film_load

#: The compliance of the film law is the secant of the Moes film over this share of the
#: cycle's peak force above the sample's force (the tangent at light loads would let a
#: later impact sink through microns of film within one sample).
SECANT_SHARE = 0.2


def _runs(mask):
    """(start, stop) index pairs of the runs of True in ``mask``."""
    m = np.concatenate([[False], np.asarray(mask, dtype=bool), [False]])
    d = np.flatnonzero(np.diff(m.astype(np.int8)))
    return list(zip(d[::2].tolist(), d[1::2].tolist()))


def film_law_from_ehl(inputs, ehl, lubricant, e_prime: float, lobe=None):
    """(h_k, c_k, F_k) over the samples of ``inputs`` from a transient-EHL cycle result.

    Reduced film model of the dynamics, tabulated in time:

    - *datum*: the film at the first loaded sample on the cam lobe (``lobe``: samples
      with cam lift above the jump threshold; a kinematic mask, the same in every
      iteration; default all). h_k = h_c − datum on the lobe's loaded samples,
      interpolated over samples where the tappet is off the cam; off the lobe h_k
      returns linearly to the datum over the base circle (no step at the lobe's end);
    - *compliance* on the loaded lobe: the Moes film's secant slope over
      [F_k, F_k + SECANT_SHARE·F̂], limited by the squeeze film's damping over one sample
      interval τ: 1/|c_k| = 1/|c_Moes| + D/τ, with D = 3√2 π η R^(3/2) L / h_c^(3/2)
      (rigid-cylinder squeeze, :func:`~tribodyn.valvetrain.tribology.squeeze_film_load`,
      over the width L): a film cannot thin faster than its squeeze flow allows;
    - *off the lobe* c_k = 0: the film is held at the datum (not modelled there).

    The earlier law of the coupling (now
    :func:`~tribodyn.cycle.film_laws.film_state_tribology`): at the samples a
    fixed point has F = F_k, between them c_k and the sample interval shape the force
    (docs/convergence.md). D uses the central film, the closed form the minimum film
    (h_min ≈ 0.75 h_c: D is about 1.5× low), and is isoviscous."""
    F = inputs.contact_force
    n = F.size
    lobe = np.ones(n, dtype=bool) if lobe is None else np.asarray(lobe, dtype=bool)
    hc = _bridge(ehl.central_film, ehl.loaded)
    valid = lobe & ehl.loaded & np.isfinite(hc) & (hc > 0)
    h = np.zeros(n)
    c = np.zeros(n)
    kx: list[float] = []
    kv: list[float] = []
    for a, b in _runs(lobe):
        idx = np.arange(a, b)
        ok = idx[valid[a:b]]
        kx.append(a - 1.0)  # the datum just before the lobe
        kv.append(0.0)
        if ok.size:
            kx.extend(ok.tolist())
            kv.extend((hc[ok] - hc[ok[0]]).tolist())
    if kx:
        order = np.argsort(kx)
        period = n - 1 if n > 1 else None  # the last sample repeats the first's phase
        h = np.interp(np.arange(n), np.asarray(kx)[order], np.asarray(kv)[order], period=period)
    f_peak = float(F.max()) if n else 0.0
    tau = float(np.median(np.diff(inputs.time))) if n > 1 else 0.0
    eta = lubricant.viscosity
    for i in np.flatnonzero(valid):
        R = inputs.radius[i]
        u = max(abs(inputs.entrainment_speed[i]), 1e-3)
        w1 = F[i] / inputs.width
        w2 = (F[i] + SECANT_SHARE * f_peak) / inputs.width
        hm = []
        for w in (w1, w2):
            W, U, G = hamrock_groups(w, R, u, eta, lubricant.pressure_viscosity, e_prime)
            hm.append(moes_central(W, U, G, R))
        k_moes = SECANT_SHARE * f_peak / max(float(hm[0] - hm[1]), 1e-300)
        damping = float(squeeze_film_load(hc[i], 1.0, R, eta)) * inputs.width
        c[i] = -1.0 / (k_moes + (damping / tau if tau > 0 else 0.0))
    return h, c, F


def ehl_tribology(
    inputs, ehl, lubricant, e_prime: float, period: float, lobe=None
) -> FilmTableTribology:
    """Tribology model of the implicit coupling from one transient-EHL cycle (``lobe``:
    see :func:`film_law_from_ehl`)."""
    ff = _bridge(ehl.friction, ehl.loaded)
    mu = np.where(ehl.loaded & np.isfinite(ff), ff / np.maximum(inputs.contact_force, 1e-12), 0.0)
    friction = FrictionCoefficientTable(inputs.time, mu, period)
    h, c, F = film_law_from_ehl(inputs, ehl, lubricant, e_prime, lobe)
    return FilmTableTribology(friction, inputs.time, h, c, F, period=period)

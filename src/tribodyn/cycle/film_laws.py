"""The film and friction laws that the implicit coupling hands to the dynamics, built
from a transient-EHL cycle (used by :mod:`tribodyn.cycle.coupling`):

- :func:`film_state_tribology`: the film as a state of the dynamics (valvetrain
  ``FilmStateTribology``) with the correction of its flooded film towards the EHL
  (:func:`film_correction_from_ehl`) and the EHL friction coefficient
  (:class:`FrictionCoefficientTable`); what the coupling iterates.
"""

from __future__ import annotations

import math

import numpy as np

from ..valvetrain import tribology as _tribology
from ..valvetrain.tribology import (
    FilmStateTribology,
    TribologyModel,
    squeeze_film_load,
)

__all__ = [
    "FrictionCoefficientTable",
    "film_correction_from_ehl",
    "film_state_tribology",
    "state_vector",
    "state_from_vector",
]


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


#: The film correction is taken from EHL samples carrying at least this share of the
#: cycle's peak force (lighter contacts, e.g. off the lobe, follow the reduced model) …
CORRECTION_MIN_LOAD_SHARE = 0.02
#: … where the entraining film carries at least this share of the force (where the
#: squeeze carries most of it, near u_e = 0, r is ill-conditioned) …
CORRECTION_MIN_ENTRAINING_SHARE = 0.5
#: … and whose film is below this share of the supply film (above it the reduced model's
#: starvation, not the flooded EHL, sets the film).
CORRECTION_MAX_SUPPLY_SHARE = 0.5
#: Outside the span of such samples ln r returns to 0 (the reduced model alone) over this
#: crank angle [deg] (a physical span, not a number of samples) …
CORRECTION_TAPER_DEG = 10.0
#: Samples whose r falls outside [1/CORRECTION_LIMIT, CORRECTION_LIMIT] are not used:
#: there the reduced model's physics does not describe the EHL (near u_e = 0 the
#: piezoviscous squeeze holds a film that the isoviscous squeeze lets collapse).
CORRECTION_LIMIT = 2.0


def film_correction_from_ehl(inputs, ehl, model: FilmStateTribology) -> np.ndarray:
    """ln r_k over the samples of ``inputs``: the correction of the reduced film model
    (:class:`~tribodyn.valvetrain.tribology.FilmStateTribology`) towards the transient EHL.

    At an EHL sample with central film h_E, its rate ḣ_E (central differences) and force
    F_k, the film's balance F_k = F_ent(h) + D(h)(−ḣ) gives the load the entraining film
    carries there, F_ent = F_k + D(h_E) ḣ_E; r_k is the factor on the reduced model's
    flooded film for which its entraining film of load F_ent is h_E (with the model's
    starvation law: h_f(h_E) = r h_f,model(F_ent), h_f(h) = h h_s/(h_s − h)). So where
    the dynamics carries F_k with the EHL's film history, the film state is h_E.

    Used at samples that are loaded, carry at least CORRECTION_MIN_LOAD_SHARE of the
    peak force, have h_E < CORRECTION_MAX_SUPPLY_SHARE·h_s and
    F_ent ≥ CORRECTION_MIN_ENTRAINING_SHARE·F_k (near u_e = 0 the squeeze carries the
    load and r is ill-conditioned); ln r is
    interpolated linearly in crank angle between them and returns to 0 over
    CORRECTION_TAPER_DEG outside their span (periodic); samples with |ln r| above
    ln CORRECTION_LIMIT are left out (the reduced model does not describe the EHL there).
    D uses the central film (the closed form's minimum film is ~0.75 h_c) and η₀."""
    F = np.asarray(inputs.contact_force, dtype=float)
    n = F.size
    crank = np.asarray(inputs.crank_angle, dtype=float)
    hc = _bridge(ehl.central_film, ehl.loaded)
    hs = model.supply_film
    ok = ehl.loaded & np.isfinite(hc) & (hc > 0.0)
    rate = np.zeros(n)
    if ok.sum() >= 2:
        idx = np.flatnonzero(ok)
        rate[idx] = np.gradient(hc[idx], inputs.time[idx])
    damping = np.zeros(n)
    damping[ok] = (
        squeeze_film_load(hc[ok], 1.0, inputs.radius[ok], model.lubricant.viscosity) * model.width
    )
    f_ent = F + damping * rate
    f_peak = float(F.max()) if n else 0.0
    valid = (
        ok
        & (F >= CORRECTION_MIN_LOAD_SHARE * f_peak)
        & (hc < CORRECTION_MAX_SUPPLY_SHARE * hs)
        & (f_ent >= CORRECTION_MIN_ENTRAINING_SHARE * F)
        & (np.abs(inputs.entrainment_speed) > 0.0)
    )
    lnr = np.zeros(n)
    if not valid.any():
        return lnr
    i = np.flatnonzero(valid)
    h_model = model.steady_film(
        inputs.time[i], f_ent[i], inputs.entrainment_speed[i], inputs.radius[i], correction=1.0
    )

    def flooded(h):
        return h * hs / (hs - h)

    vals = np.log(flooded(hc[i]) / flooded(h_model))
    keep = np.abs(vals) <= math.log(CORRECTION_LIMIT)
    if not keep.any():
        return lnr
    i, vals = i[keep], vals[keep]
    # anchors: the valid samples, and ln r = 0 a taper's span outside each cluster of them
    period = crank[-1] - crank[0] if n > 1 else 720.0  # the last sample repeats the first
    x, v = crank[i].tolist(), vals.tolist()
    gaps = np.flatnonzero(np.diff(crank[i]) > 2.0 * CORRECTION_TAPER_DEG)
    starts = np.concatenate([[0], gaps + 1])
    ends = np.concatenate([gaps, [i.size - 1]])
    for a, b in zip(starts, ends):
        x += [crank[i[a]] - CORRECTION_TAPER_DEG, crank[i[b]] + CORRECTION_TAPER_DEG]
        v += [0.0, 0.0]
    xa, va = np.asarray(x), np.asarray(v)
    order = np.argsort(xa)
    lnr = np.interp(crank, xa[order], va[order], period=period)
    return lnr


def film_state_tribology(
    inputs,
    ehl,
    lubricant,
    e_prime: float,
    period: float,
    width: float,
    supply_film: float | None = None,
    checked: tuple[str, ...] = (),
) -> FilmStateTribology:
    """Tribology of the implicit coupling from one transient-EHL cycle: the EHL friction
    coefficient μ_k = F_f/F (:class:`FrictionCoefficientTable`) and the film as a state
    (:class:`~tribodyn.valvetrain.tribology.FilmStateTribology`, supply film h_s default
    ``tribology.SUPPLY_FILM``; ``checked`` ("supply_film") if checked where it entered) with
    the correction of :func:`film_correction_from_ehl`."""
    hs = _tribology.SUPPLY_FILM if supply_film is None else supply_film
    ff = _bridge(ehl.friction, ehl.loaded)
    mu = np.where(ehl.loaded & np.isfinite(ff), ff / np.maximum(inputs.contact_force, 1e-12), 0.0)
    friction = FrictionCoefficientTable(inputs.time, mu, period)
    base = FilmStateTribology(
        friction, width=width, lubricant=lubricant, e_prime=e_prime, supply_film=hs, checked=checked
    )
    lnr = film_correction_from_ehl(inputs, ehl, base)
    return FilmStateTribology(
        friction,
        width=width,
        lubricant=lubricant,
        e_prime=e_prime,
        supply_film=base.supply_film,
        time=inputs.time,
        correction=np.exp(lnr),
        period=period,
        checked=("supply_film",),
    )


def state_vector(table: FilmStateTribology) -> np.ndarray:
    """[ln r_k, μ_k] of a coupling table (the vector the coupling iterates)."""
    fm = table.friction_model
    if not isinstance(fm, FrictionCoefficientTable):
        raise TypeError(f"not a coupling table: its friction is a {type(fm).__name__}")
    return np.concatenate([np.log(table.correction), fm.mu])


def state_from_vector(v, like: FilmStateTribology, period) -> FilmStateTribology:
    """The coupling table of the vector ``v`` = [ln r_k, μ_k] on the samples of ``like``
    (μ ≥ 0, |ln r| ≤ ln CORRECTION_LIMIT)."""
    n = like.time.size
    lim = math.log(CORRECTION_LIMIT)
    return FilmStateTribology(
        FrictionCoefficientTable(like.time, np.maximum(v[n:], 0.0), period),
        width=like.width,
        lubricant=like.lubricant,
        e_prime=like.e_prime,
        supply_film=like.supply_film,
        checked=("supply_film",),
        time=like.time,
        correction=np.exp(np.clip(v[:n], -lim, lim)),
        period=period,
        growth_limited=like.growth_limited,
    )

"""Engine-speed sweeps of the valvetrain: peak and minimum contact force, jump onset.

:func:`speed_sweep` runs :func:`simulate_valvetrain` at each engine speed and collects
peak contact force, minimum contact force inside the lift event (cam lift above the jump
threshold), whether the cam contact was lost (jump), valve bounce and seating velocity.
:func:`jump_speed` brackets the lowest engine speed with contact loss by bisection.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._typing import ArrayLike
from .._validation import InputError, check_array, check_positive
from .cams import CamProfile
from .dynamics import ValvetrainResult, simulate_valvetrain
from .parameters import ValvetrainParameters
from .tribology import TribologyModel

__all__ = [
    "SpeedSweepResult",
    "speed_sweep",
    "jump_speed",
    "JumpSpeedSearch",
    "locate_jump_speed",
    "corrected_jump_speed_estimate",
]


@dataclass
class SpeedSweepResult:
    """Sweep outputs, one entry per engine speed [rpm] (NaN where a run failed)."""

    engine_speed: np.ndarray
    peak_contact_force: np.ndarray  #: [N]
    min_contact_force: np.ndarray  #: [N] inside the lift event
    jump: np.ndarray  #: contact lost while the cam lifts
    jump_onset_crank_angle: np.ndarray  #: [deg in the presented cycle] (NaN: no jump)
    valve_bounce: np.ndarray
    seating_velocity: np.ndarray  #: [m/s]
    converged: np.ndarray
    messages: list = field(default_factory=list)

    @property
    def jump_onset_speed(self) -> float:
        """Lowest swept speed with contact loss [rpm] (NaN if none; resolution = grid)."""
        ok = self.jump & self.converged
        return float(self.engine_speed[ok].min()) if ok.any() else float("nan")

    def to_dict(self) -> dict:
        return {
            k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in self.__dict__.items()
        } | {"jump_onset_speed": self.jump_onset_speed}


def _row(r: ValvetrainResult):
    if not r.converged:
        return (math.nan,) * 2 + (False, math.nan, False, math.nan, False)
    ev = r.event_mask()
    fmin = float(r.contact_force[ev].min()) if ev.any() else math.nan
    onset = r.jumps[0][0] if r.jumps else math.nan
    return (
        float(r.contact_force.max()),
        fmin,
        r.jump,
        onset,
        r.valve_bounce,
        r.seating_velocity,
        True,
    )


def speed_sweep(
    cam: CamProfile,
    engine_speeds: ArrayLike,
    params: ValvetrainParameters | None = None,
    *,
    tribology: TribologyModel | str | None = "explicit",
    **kwargs,
) -> SpeedSweepResult:
    """Simulate at each engine speed [rpm] (sorted ascending); kwargs go to
    :func:`simulate_valvetrain`."""
    n = check_array("engine_speeds", engine_speeds, min_size=1)
    if np.any(n <= 0.0):
        raise InputError("engine_speeds must all be > 0 [rpm]")
    n = np.sort(n)
    rows, msgs = [], []
    for rpm in n:
        r = simulate_valvetrain(cam, params, engine_speed=float(rpm), tribology=tribology, **kwargs)
        rows.append(_row(r))
        msgs.append(r.message)
    cols = list(zip(*rows))
    return SpeedSweepResult(
        engine_speed=n,
        peak_contact_force=np.array(cols[0]),
        min_contact_force=np.array(cols[1]),
        jump=np.array(cols[2], dtype=bool),
        jump_onset_crank_angle=np.array(cols[3]),
        valve_bounce=np.array(cols[4], dtype=bool),
        seating_velocity=np.array(cols[5]),
        converged=np.array(cols[6], dtype=bool),
        messages=msgs,
    )


def jump_speed(
    cam: CamProfile,
    params: ValvetrainParameters | None = None,
    *,
    low: float = 2000.0,
    high: float = 12000.0,
    tolerance: float = 10.0,
    tribology: TribologyModel | str | None = "explicit",
    **kwargs,
) -> tuple[float, float]:
    """Bracket [n_lo, n_hi] [rpm] of the lowest engine speed with cam contact loss.

    Requires no jump at ``low`` and a jump at ``high``; bisects until the bracket is
    narrower than ``tolerance`` [rpm]. Raises RuntimeError if a run fails to converge.
    (Assumes a single onset: above the returned speed the follower keeps jumping.)
    """
    lo = check_positive("low", low, "rpm")
    hi = check_positive("high", high, "rpm")
    tol = check_positive("tolerance", tolerance, "rpm")
    if hi <= lo:
        raise InputError(f"high must exceed low (got {lo:g}, {hi:g} rpm)")

    def jumps(rpm):
        r = simulate_valvetrain(cam, params, engine_speed=rpm, tribology=tribology, **kwargs)
        if not r.converged:
            raise RuntimeError(f"valvetrain run at {rpm:g} rpm failed: {r.message}")
        return r.jump

    if jumps(lo):
        raise InputError(f"the follower already jumps at low = {lo:g} rpm")
    if not jumps(hi):
        raise InputError(f"no jump up to high = {hi:g} rpm")
    while hi - lo > tol:
        mid = 0.5 * (lo + hi)
        if jumps(mid):
            hi = mid
        else:
            lo = mid
    return lo, hi


@dataclass
class JumpSpeedSearch:
    """Result of :func:`locate_jump_speed`: ``speed`` [rpm] (midpoint of ``bracket``; NaN if
    not found), the bracket (no jump, jump) [rpm], the quasi-static estimate [rpm], the
    dynamics runs as (rpm, minimum contact force in the event [N], jump) in run order."""

    speed: float
    bracket: tuple
    quasi_static: float
    runs: list
    converged: bool
    message: str

    def to_dict(self) -> dict:
        return dict(self.__dict__)


def corrected_jump_speed_estimate(
    cam: CamProfile, params: ValvetrainParameters, dynamic=None
) -> float:
    """Engine speed [rpm] at which the follower's inertia first exceeds the spring force:
    min over the decelerating part of the event of ω² = (F₀ + k s)/(m_e |s''|), m_e =
    m_tappet + m_valve + m_spring/3 (rigid train, the classical estimate as
    :func:`~tribodyn.valvetrain.kinematics.quasi_static_jump_speed`, both flanks), ω the
    cam speed.

    ``dynamic`` = (n_a [rpm], F_min,a [N]): a dynamics run without jump; its shortfall
    D_a = F_qs(n_a) − F_min,a below the quasi-static margin F_qs(n) = min(F₀ + k s −
    m_e ω² s''⁻) is scaled as n² (inertia-driven vibration) and the speed where
    F_qs(n) − D_a (n/n_a)² = 0 is returned instead."""
    th = np.linspace(0.0, 2.0 * math.pi, 7201)
    s, _, s2 = cam.derivatives(th)
    ev = s > 10e-6
    if not ev.any():
        raise InputError("the cam has no lift event")
    m_e = params.effective_mass
    spring = params.spring_preload + params.spring_rate * s[ev]
    dec = np.clip(-s2[ev], 0.0, None)  # |s''| where the cam decelerates the follower

    def margin(rpm):
        w = rpm * math.pi / 60.0
        return float(np.min(spring - m_e * w * w * dec))

    shortfall = 0.0
    if dynamic is not None:
        n_a, f_a = dynamic
        shortfall = (margin(n_a) - f_a) / n_a**2
    lo, hi = 0.0, 1000.0
    while margin(hi) - shortfall * hi * hi > 0.0:
        lo, hi = hi, 2.0 * hi
        if hi > 1e6:
            return math.inf
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        if margin(mid) - shortfall * mid * mid > 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def locate_jump_speed(
    cam: CamProfile,
    params,
    *,
    start: float,
    high: float,
    tolerance: float = 50.0,
    max_runs: int = 10,
    tribology="explicit",
    start_result: ValvetrainResult | None = None,
    **kwargs,
) -> JumpSpeedSearch:
    """Lowest engine speed [rpm] with cam contact loss, within ``tolerance`` [rpm], in few
    dynamics runs.

    1. The run at ``start`` (or ``start_result``) must keep contact; its minimum contact
       force corrects the quasi-static estimate (:func:`corrected_jump_speed_estimate` of the
       lumped equivalent) → first guess.
    2. Each run gives its minimum contact force in the event F_min (no jump) or a jump.
       The next guess is the secant of F_min against n² through the two fastest runs
       without jump (the inertia forces grow with n²), kept inside the bracket [fastest
       run without jump, slowest with jump]; a guess that would not shrink the bracket
       by at least ``tolerance`` probes one tolerance beyond its fastest non-jumping end,
       and a bracket without a secant is bisected.
    3. Stops when the bracket is narrower than ``tolerance``: speed = its midpoint
       (± tolerance/2). ``converged=False`` with a message after ``max_runs`` runs, if a
       run fails, or without a jump up to ``high`` (speed NaN). Assumes one onset, as
       :func:`jump_speed`.
    """
    lo = check_positive("start", start, "rpm")
    hi_cap = check_positive("high", high, "rpm")
    tol = check_positive("tolerance", tolerance, "rpm")
    if hi_cap <= lo:
        raise InputError(f"high must exceed start (got {lo:g}, {hi_cap:g} rpm)")
    lumped = params.lumped_equivalent()
    runs: list = []

    def run(rpm):
        r = simulate_valvetrain(cam, params, engine_speed=rpm, tribology=tribology, **kwargs)
        if not r.converged:
            raise RuntimeError(f"valvetrain run at {rpm:g} rpm failed: {r.message}")
        fmin = float(r.contact_force[r.event_mask()].min()) if not r.jump else 0.0
        runs.append((float(rpm), fmin, bool(r.jump)))
        return r

    def result(ok, msg, n_lo, n_hi, qs):
        speed = 0.5 * (n_lo + n_hi) if ok else math.nan
        return JumpSpeedSearch(speed, (n_lo, n_hi), qs, runs, ok, msg)

    try:
        r0 = start_result if start_result is not None else run(lo)
        if start_result is not None:
            runs.append((float(lo), float(r0.contact_force[r0.event_mask()].min()), r0.jump))
        if r0.jump:
            raise InputError(f"the follower already jumps at start = {lo:g} rpm")
        qs = corrected_jump_speed_estimate(cam, lumped, (lo, runs[-1][1]))
        n_hi = math.inf
        guess = min(max(qs, lo + tol), hi_cap)
        while n_hi - lo > tol:
            if len(runs) >= max_runs + (start_result is not None):
                return result(False, f"no {tol:g} rpm bracket in {max_runs} runs", lo, n_hi, qs)
            r = run(guess)
            if r.jump:
                n_hi = guess
            else:
                lo = guess
            if n_hi - lo <= tol:
                break
            ok = sorted((n, f) for n, f, j in runs if not j)
            (n1, f1), (n2, f2) = ok[-2] if len(ok) > 1 else ok[-1], ok[-1]
            cand = math.nan
            if f1 > f2 > 0.0:  # F_min falls with speed: secant to F_min = 0 in n²
                cand = math.sqrt(n2 * n2 + f2 * (n2 * n2 - n1 * n1) / (f1 - f2))
            if math.isfinite(n_hi):
                if not (lo < cand < n_hi):
                    cand = 0.5 * (lo + n_hi)
                cand = min(max(cand, lo + tol), n_hi - tol) if n_hi - lo > 2 * tol else lo + tol
                if n_hi - lo <= 2 * tol:
                    cand = 0.5 * (lo + n_hi)
            else:
                if not cand > lo:
                    cand = 2.0 * lo
                cand = max(cand, lo + tol)
                if lo >= hi_cap:
                    return result(False, f"no jump up to high = {hi_cap:g} rpm", lo, n_hi, qs)
                cand = min(cand, hi_cap)
            guess = cand
    except (RuntimeError, InputError) as exc:
        return JumpSpeedSearch(math.nan, (math.nan, math.nan), math.nan, runs, False, str(exc))
    return result(True, f"bracketed within {n_hi - lo:.0f} rpm in {len(runs)} runs", lo, n_hi, qs)

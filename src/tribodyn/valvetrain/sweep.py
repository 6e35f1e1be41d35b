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

__all__ = ["SpeedSweepResult", "speed_sweep", "jump_speed"]


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

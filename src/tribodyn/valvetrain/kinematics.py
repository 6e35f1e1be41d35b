"""Flat-follower kinematics over cam angle (docs/conventions.md).

For a cam turning at constant speed ω [rad/s] with lift law s(θ) and a flat-faced
follower::

    tappet velocity       v = ω s'                       [m/s]
    tappet acceleration   a = ω² s''                     [m/s²]
    radius of curvature   R = r_b + s + s''              [m]
    contact offset        e = s'                         [m]
    cam surface speed     u_cam = ω R,  follower surface speed u_f = ω s''
    entrainment speed     u_e = (u_cam + u_f)/2 = ω (r_b + s + 2 s'')/2     (changes sign
                          near the nose where s'' < −(r_b + s)/2)
    sliding speed         u_s = u_cam − u_f = ω (r_b + s)

On the base circle u_e = ω r_b/2 and u_s = ω r_b exactly.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._typing import ArrayLike
from .._validation import InputError, check_array, check_int
from ..physics import limits as L
from .cams import CamProfile

__all__ = [
    "FlatFollowerKinematics",
    "flat_follower_kinematics",
    "quasi_static_jump_speed",
    "rpm_to_cam_speed",
]


def rpm_to_cam_speed(engine_speed: float) -> float:
    """Cam speed ω [rad/s] of a four-stroke engine at ``engine_speed`` [rpm] (cam = crank/2);
    engine_speed in (0, 50 000] rpm (the case file's range, L.ENGINE_SPEED)."""
    n = L.ENGINE_SPEED.check("engine_speed", engine_speed)
    return n / 2.0 * 2.0 * math.pi / 60.0


@dataclass
class FlatFollowerKinematics:
    """Kinematic state of a flat follower (arrays over the requested cam angles)."""

    angle: np.ndarray  #: cam angle θ [rad]
    cam_speed: float  #: ω [rad/s]
    lift: np.ndarray  #: s [m]
    lift_velocity: np.ndarray  #: s' [m/rad]
    lift_acceleration: np.ndarray  #: s'' [m/rad²]
    radius_of_curvature: np.ndarray  #: R = r_b + s + s'' [m]
    contact_offset: np.ndarray  #: e = s' [m]
    entrainment_speed: np.ndarray  #: u_e = ω(r_b + s + 2s'')/2 [m/s]
    sliding_speed: np.ndarray  #: u_s = ω(r_b + s) [m/s]
    tappet_velocity: np.ndarray  #: ω s' [m/s]
    tappet_acceleration: np.ndarray  #: ω² s'' [m/s²]

    @property
    def crank_angle(self) -> np.ndarray:
        """Crank angle [deg] = 2θ in degrees (four-stroke)."""
        return np.degrees(2.0 * self.angle)


def flat_follower_kinematics(
    cam: CamProfile, cam_speed: float, angle: ArrayLike
) -> FlatFollowerKinematics:
    """Kinematics of a flat follower on ``cam`` at constant ``cam_speed`` ω [rad/s] (> 0)
    at cam angles ``angle`` [rad] (scalar or array); ω in L.CAM_SPEED (≤ 2618 rad/s, the
    cam speed of 50 000 rpm)."""
    if not isinstance(cam, CamProfile):
        raise InputError(f"cam must be a CamProfile (got {type(cam).__name__})")
    w = L.CAM_SPEED.check("cam_speed", cam_speed)
    th = check_array("angle", np.atleast_1d(np.asarray(angle, dtype=float)), ndim=1)
    s, s1, s2 = cam.derivatives(th)
    rb = cam.base_radius
    R = rb + s + s2
    return FlatFollowerKinematics(
        angle=th,
        cam_speed=w,
        lift=s,
        lift_velocity=s1,
        lift_acceleration=s2,
        radius_of_curvature=R,
        contact_offset=s1.copy(),
        entrainment_speed=0.5 * w * (rb + s + 2.0 * s2),
        sliding_speed=w * (rb + s),
        tappet_velocity=w * s1,
        tappet_acceleration=w * w * s2,
    )


def quasi_static_jump_speed(
    cam: CamProfile, preload: float, spring_rate: float, effective_mass: float, *, n: int = 36000
) -> tuple[float, float]:
    """Quasi-static jump (follower separation) speed of a cam with a rigid follower train.

    Contact is lost where F₀ + k s + m_eff ω² s'' = 0 first occurs, i.e.::

        ω_jump = min over {s'' < 0, closing side} √((F₀ + k s)/(m_eff |s''|))

    Returns (ω_jump [rad/s], cam angle of the minimum [rad]). For a symmetric cam the
    opening side gives the same value; the closing side (s' < 0) is used, where
    the spring decelerates the train towards the seat. Multiply ω by 60/π to get engine rpm.
    """
    if not isinstance(cam, CamProfile):
        raise InputError(f"cam must be a CamProfile (got {type(cam).__name__})")
    F0 = L.SPRING_PRELOAD.check("preload", preload)
    k = L.SPRING_RATE.check("spring_rate", spring_rate)
    m = L.MASS.check("effective_mass", effective_mass)
    n = check_int("n", n)
    if n < 360:
        raise InputError(f"n must be an integer >= 360 (got {n})")
    th = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    s, s1, s2 = cam.derivatives(th)
    mask = (s2 < 0.0) & (s1 < 0.0)
    if not mask.any():
        mask = s2 < 0.0
    if not mask.any():
        return math.inf, math.nan
    w2 = (F0 + k * s[mask]) / (m * np.abs(s2[mask]))
    j = int(np.argmin(w2))
    return float(math.sqrt(w2[j])), float(th[mask][j])

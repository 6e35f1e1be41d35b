"""Sliding and entrainment of a rotating bucket tappet (docs/conventions.md, "Tappet
rotation").

The cam of a direct-acting bucket is offset from the bucket axis by e_o along the cam
axis, so its contact line acts off-centre and the tappet turns about its own axis at
ω_t. Face-plane frame of the tappet: x along the motion of the cam surface at the contact
(the direction of u_s), y along the cam axis. The contact (mid-width of the line) sits at
r = (e, e_o) from the tappet axis, with e = s' the contact offset of the flat follower.
The tappet surface there moves at

    v_t = ω_t × r = ω_t (e_o, −e)                                     [m/s]

taking ω_t > 0 in the sense in which the cam's friction drives it (its surface at the
cam moves with the cam surface). The cam surface slides over a non-rotating tappet at
u_s along x (:mod:`tribodyn.valvetrain.kinematics`), so::

    sliding vector        s = (u_s − ω_t e_o, ω_t e)
    sliding speed         |s| = √((u_s − ω_t e_o)² + (ω_t e)²)
    entrainment speed     u_e' = u_e + ω_t e_o / 2   (x only: y is along the contact line,
                                                      where the line-contact model has
                                                      no flow)
    friction direction    the friction force opposes s; only its x share s_x/|s| acts
                          against the cam's rotation (camshaft torque); the y share is an
                          axial thrust on the camshaft.

The values are those at the mid-width of the line; along the width y runs over
e_o ± l/2 and the x sliding varies by ± ω_t l/2 about the mid value.

Willermet & Pieprzak (J. Tribol. 112 (1990) 655) measured instantaneous tappet rotation
and friction torque in a cam/tappet rig: faster rotation gave lower friction, mostly
near maximum lift, through the partial rolling of the surfaces (the −ω_t e_o above). No
typical ratio ω_t/ω was found in the sources checked; the input default is 0 (a tappet
that does not turn).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._typing import ArrayLike
from .._validation import InputError

__all__ = ["TappetRotation", "RotatingContactSpeeds"]


@dataclass(frozen=True)
class RotatingContactSpeeds:
    """Contact speeds with tappet rotation (module text); arrays like the inputs."""

    entrainment_speed: np.ndarray  #: u_e' = u_e + ω_t e_o/2 [m/s]
    sliding_x: np.ndarray  #: s_x = u_s − ω_t e_o [m/s]
    sliding_y: np.ndarray  #: s_y = ω_t e [m/s]

    @property
    def sliding_speed(self) -> np.ndarray:
        """|s| = √(s_x² + s_y²) [m/s]."""
        return np.hypot(self.sliding_x, self.sliding_y)

    @property
    def signed_sliding_speed(self) -> np.ndarray:
        """|s| with the sign of s_x: the scalar sliding speed of the line-contact solver
        (its friction then acts along x with the right sign)."""
        return np.where(self.sliding_x < 0.0, -1.0, 1.0) * self.sliding_speed

    @property
    def torque_share(self) -> np.ndarray:
        """s_x/|s|: share of the friction force acting against the cam's rotation (1
        where there is no sliding)."""
        mag = self.sliding_speed
        safe = np.where(mag > 0.0, mag, 1.0)
        return np.where(mag > 0.0, self.sliding_x / safe, 1.0)


@dataclass(frozen=True)
class TappetRotation:
    """Rotation of a bucket tappet: ω_t = ``speed_ratio`` · ω_cam, cam offset e_o =
    ``cam_offset`` [m] from the tappet axis along the cam axis. ``speed_ratio = 0`` is a
    tappet that does not turn (the speeds are returned unchanged)."""

    speed_ratio: float = 0.0
    cam_offset: float = 0.0

    def __post_init__(self):
        for name in ("speed_ratio", "cam_offset"):
            v = getattr(self, name)
            if not isinstance(v, (int, float)) or not math.isfinite(v):
                raise InputError(f"{name} must be a finite number (got {v!r})")
        if not -1.0 <= self.speed_ratio <= 1.0:
            raise InputError(
                f"speed_ratio (ω_t/ω_cam) must lie in [-1, 1] (got {self.speed_ratio})"
            )
        if not 0.0 <= self.cam_offset < 0.05:
            raise InputError(f"cam_offset must lie in [0, 0.05) m (got {self.cam_offset})")

    @property
    def active(self) -> bool:
        return self.speed_ratio != 0.0

    def check_fit(
        self, tappet_radius: float, cam_width: float, max_contact_offset: float, base_radius: float
    ) -> None:
        """Raise :class:`InputError` naming ``cam_offset`` or ``speed_ratio`` (with the
        allowed range) unless the rotating contact is physical for this cam and tappet:

        * the contact line, at x = e (|e| ≤ ``max_contact_offset`` = max |s'|) and
          y = e_o ± l/2 (l = ``cam_width``), stays on the tappet face of radius R_t:
          e_o ≤ √(R_t² − e_max²) − l/2;
        * the tappet, turned by the cam's friction, does not overtake the cam surface:
          ω_t e_o < u_s, with u_s ≥ ω r_b, so |ω_t/ω| e_o < r_b (``base_radius``).

        All lengths in m."""
        rt, half = float(tappet_radius), 0.5 * float(cam_width)
        e = abs(float(max_contact_offset))
        reach = math.sqrt(max(rt * rt - e * e, 0.0)) - half
        if self.cam_offset > reach:
            raise InputError(
                f"cam_offset must be >= 0 and <= {max(reach, 0.0):.4g} m (got "
                f"{self.cam_offset:g}): the contact line (half width {half * 1e3:.3g} mm, "
                f"offset up to {e * 1e3:.3g} mm along the motion) must stay on the "
                f"tappet face of radius {rt * 1e3:.3g} mm"
            )
        if abs(self.speed_ratio) * self.cam_offset >= base_radius:
            top = base_radius / self.cam_offset
            raise InputError(
                f"speed_ratio must lie in (-{top:.4g}, {top:.4g}) with cam_offset "
                f"{self.cam_offset:g} m (got {self.speed_ratio:g}): the tappet, turned by "
                "the cam's friction, cannot move faster than the cam surface at the "
                f"contact (|ω_t/ω| e_o < r_b = {base_radius * 1e3:.3g} mm)"
            )

    def speeds(
        self,
        cam_speed: float,
        contact_offset: ArrayLike,
        entrainment_speed: ArrayLike,
        sliding_speed: ArrayLike,
    ) -> RotatingContactSpeeds:
        """Contact speeds with rotation from those of a non-rotating tappet.

        cam_speed ω [rad/s]; contact_offset e = s' [m]; entrainment_speed u_e and
        sliding_speed u_s [m/s] of :func:`~tribodyn.valvetrain.flat_follower_kinematics`
        (or the dynamics)."""
        wt = self.speed_ratio * float(cam_speed)
        e = np.asarray(contact_offset, float)
        ue = np.asarray(entrainment_speed, float)
        us = np.asarray(sliding_speed, float)
        vx = wt * self.cam_offset
        return RotatingContactSpeeds(ue + 0.5 * vx, us - vx, wt * e)

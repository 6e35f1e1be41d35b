"""Cam profiles for a flat-faced follower.

A profile is the lift s(θ) [m] of a flat follower above the base circle as a function of
the cam angle θ [rad], periodic over one revolution, with s' = ds/dθ [m/rad] and
s'' = d²s/dθ² [m/rad²]. For a flat follower (docs/conventions.md)::

    radius of curvature   R = r_b + s + s''      (must stay > 0: convex cam)
    contact offset        e = s'                 (must stay below the tappet radius)

Three profiles:

* :class:`AccelerationCam` — the default, designed in the acceleration domain
  (ramps, positive half-sine pulse, negative region down to the nose radius);
* :class:`CircularArcCam` — the classic base/flank/nose circular-arc cam, exact from
  the support function of its arcs;
* :class:`~tribodyn.valvetrain.cam_tabulated.TabulatedCam` — a lift table (measured or
  from a supplier) fitted by a periodic quintic spline that keeps the curvature jumps and smooths the noise
  (:mod:`tribodyn.valvetrain.cam_tabulated`).

Each profile reports its minimum radius of curvature and maximum contact offset and
refuses profiles with R ≤ 0 (or, when a tappet radius is given, |e| above it).
"""

from __future__ import annotations

import bisect
import math
from abc import ABC, abstractmethod

import numpy as np

from .._validation import InputError, check_nonnegative, check_positive, check_range
from ..physics import typical_engine

__all__ = ["CamProfile", "AccelerationCam", "CircularArcCam"]

TWO_PI = 2.0 * math.pi
#: 0.01° grid for the curvature / offset checks and the event
_CHECK_GRID = np.linspace(0.0, TWO_PI, 36000, endpoint=False)
_CHECK_GRID.flags.writeable = False


class CamProfile(ABC):
    """Periodic lift law of a flat-follower cam (abstract base).

    Subclasses implement :meth:`derivatives` (vectorised) and may override
    :meth:`scalar_derivatives` with a fast path used inside the dynamics.
    """

    base_radius: float

    @abstractmethod
    def derivatives(self, angle) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(s, s', s'') [m, m/rad, m/rad²] at cam angle(s) θ [rad] (any real θ)."""

    def scalar_derivatives(self, angle: float) -> tuple[float, float, float]:
        """(s, s', s'') at one angle, as Python floats (fast path for ODE right-hand sides)."""
        s, s1, s2 = self.derivatives(np.array([angle], dtype=float))
        return float(s[0]), float(s1[0]), float(s2[0])

    # -- derived quantities -------------------------------------------------------------
    def lift(self, angle) -> np.ndarray:
        """Follower lift s(θ) [m]."""
        return self.derivatives(angle)[0]

    def radius_of_curvature(self, angle) -> np.ndarray:
        """R = r_b + s + s'' [m]."""
        s, _, s2 = self.derivatives(angle)
        return self.base_radius + s + s2

    def _check_angles(self) -> np.ndarray:
        """The 0.01° grid plus the profile's breakpoints."""
        return np.concatenate([_CHECK_GRID, self._breakpoints()])

    @property
    def min_radius_of_curvature(self) -> float:
        """min R over the revolution [m] (0.01° grid plus the profile's breakpoints)."""
        th = self._check_angles()
        return float(np.min(self.radius_of_curvature(th)))

    @property
    def max_contact_offset(self) -> float:
        """max |e| = max |s'| over the revolution [m]."""
        th = self._check_angles()
        return float(np.max(np.abs(self.derivatives(th)[1])))

    @property
    def max_lift(self) -> float:
        """Largest lift over the revolution [m]."""
        th = self._check_angles()
        return float(np.max(self.lift(th)))

    def _breakpoints(self) -> np.ndarray:
        """Angles where the profile changes law (checked exactly); none by default."""
        return np.empty(0)

    def check(self, tappet_radius: float | None = None) -> None:
        """Raise :class:`InputError` if R ≤ 0 anywhere or max |e| ≥ tappet radius."""
        th = self._check_angles()
        s, s1, s2 = self.derivatives(th)
        R = self.base_radius + s + s2
        k = int(np.argmin(R))
        if not R[k] > 0.0:
            g = _CHECK_GRID
            Rg = self.radius_of_curvature(g)
            bad = Rg <= 0.0
            i = int(np.argmin(Rg))
            a, b = i, i  # the concave arc around the minimum
            while bad[(a - 1) % g.size] and (i - a) < g.size:
                a -= 1
            while bad[(b + 1) % g.size] and (b - i) < g.size:
                b += 1
            arc = (
                f"concave from {math.degrees(g[a % g.size]):.2f}° to "
                f"{math.degrees(g[b % g.size]):.2f}° cam"
                if bad.any()
                else f"concave at {math.degrees(th[k] % TWO_PI):.2f}° cam"
            )
            raise InputError(
                f"{type(self).__name__}: radius of curvature R = r_b + s + s'' must be > 0 "
                f"everywhere (got R = {R[k] * 1e3:.4g} mm at cam angle "
                f"{math.degrees(th[k] % TWO_PI):.2f}°): the cam would be {arc}"
            )
        if tappet_radius is not None:
            rt = check_positive("tappet_radius", tappet_radius, "m")
            j = int(np.argmax(np.abs(s1)))
            if abs(s1[j]) >= rt:
                raise InputError(
                    f"{type(self).__name__}: contact offset |e| = |s'| must stay below the "
                    f"tappet radius {rt * 1e3:.4g} mm (got {abs(s1[j]) * 1e3:.4g} mm at cam "
                    f"angle {math.degrees(th[j] % TWO_PI):.2f}°): the contact would run off "
                    "the tappet face"
                )

    def event(self, threshold: float = 1e-9) -> tuple[float, float]:
        """(opening, closing) cam angles [rad] where s first/last exceeds ``threshold`` [m].

        The angles are in [0, 2π) on a 0.01° grid; the closing angle may be numerically
        smaller than the opening one if the event wraps through θ = 0.
        """
        th = _CHECK_GRID
        on = self.lift(th) > threshold
        if not on.any():
            return (float("nan"), float("nan"))
        if on.all():
            return (0.0, TWO_PI)
        # Start from a base-circle point so the event does not wrap in the scan.
        k0 = int(np.argmin(on))
        idx = (np.arange(th.size) + k0) % th.size
        onr = on[idx]
        first = idx[int(np.argmax(onr))]
        last = idx[th.size - 1 - int(np.argmax(onr[::-1]))]
        return float(th[first]), float(th[last])

    @property
    def event_angle(self) -> float:
        """Cam-angle duration [rad] of the lift event (lift > 1 nm)."""
        a, b = self.event()
        return float((b - a) % TWO_PI + TWO_PI / _CHECK_GRID.size)

    def table(self, n: int = 720) -> tuple[np.ndarray, np.ndarray]:
        """(θ, s) on n equally spaced angles over one revolution (θ in rad, s in m)."""
        th = np.linspace(0.0, TWO_PI, int(n), endpoint=False)
        return th, self.lift(th)


# --------------------------------------------------------------------------------------
# Acceleration-designed cam
# --------------------------------------------------------------------------------------
# Each segment's acceleration is a known function of x ∈ [0, β] with closed-form first and
# second integrals from 0 (zero initial velocity and lift), so lift, velocity and
# acceleration are exact. Kinds:
#   "sine"   a = A sin(π x/β)                           (half-sine pulse)
#   "zero"   a = 0                                      (constant velocity)
#   "neg"    a = −[N sin(π x/(2β)) + B ψ(1−ψ)²], ψ = x/β (negative region to the nose)


def _seg_eval(kind, beta, p, x, sin, cos):
    """(a, ∫a, ∬a) of one segment at local angle x (floats with math, arrays with numpy)."""
    if kind == "zero":
        z = 0.0 * x
        return z, z, z
    if kind == "sine":
        A = p[0]
        w = math.pi / beta
        return (A * sin(w * x), A * (1.0 - cos(w * x)) / w, A * (x - sin(w * x) / w) / w)
    # "neg"
    N, B = p
    w = 0.5 * math.pi / beta
    psi = x / beta
    a = -(N * sin(w * x) + B * psi * (1.0 - psi) ** 2)
    i1 = -(
        N * (1.0 - cos(w * x)) / w + B * beta * (psi**2 / 2.0 - 2.0 * psi**3 / 3.0 + psi**4 / 4.0)
    )
    i2 = -(
        N * (x - sin(w * x) / w) / w + B * beta**2 * (psi**3 / 6.0 - psi**4 / 6.0 + psi**5 / 20.0)
    )
    return a, i1, i2


class AccelerationCam(CamProfile):
    """Symmetric cam designed in the acceleration domain (default profile).

    Opening half, measured from the start of the event (the closing half is its mirror
    image about the nose)::

        ramp:  s'' = a_r sin(π φ/β_a)           0 ≤ φ < β_a          (β_a = ramp_pulse_share β_r)
               s'' = 0                          β_a ≤ φ < β_r        (constant ramp velocity v_r)
        pulse: s'' = A₁ sin(π ψ)                ψ = (φ − β_r)/β₁      (β₁ = pulse_share β_h)
        neg.:  s'' = −[N sin(π ψ/2) + A₂ ψ(1−ψ)²]  ψ = (φ − β_r − β₁)/β₂ ∈ [0, 1]

    with β_r the ramp angle, β_h = event/2 − β_r the half main event, β₂ = β_h − β₁. The
    ramp rises ``ramp_height`` h_r, so v_r = h_r/(β_r − β_a/2) and a_r = π v_r/(2β_a). The
    nose acceleration N = r_b + L − ρ_n sets the nose radius of curvature ρ_n exactly
    (R = r_b + s + s''), and A₁, A₂ follow from zero velocity and lift L at the nose (a
    2×2 linear system). s'' is continuous; the jerk has finite jumps at the segment ends.

    Parameters (SI, angles in rad)
    ----------
    base_radius : r_b [m] (typical 0.015, :mod:`tribodyn.physics.typical`).
    max_lift : L [m] (Table 7: 9.3e-3), including the ramp.
    event_angle : total cam angle of the event incl. both ramps [rad] (default 171°).
    nose_radius : ρ_n, radius of curvature at the nose [m] (default 3 mm).
    ramp_height, ramp_angle : h_r [m], β_r [rad] (assumed: 0.2 mm over 20°).
    pulse_share : β₁/β_h, share of the half main event taken by the positive pulse,
        in (0, 1) (default 0.25: peak contact force ≈ 500 N at 3000 rpm).
    ramp_pulse_share : β_a/β_r in (0, 1] (default 0.5).
    nose_angle : cam angle of maximum lift [rad] (default π).
    tappet_radius : optional; if given, max |e| must stay below it.
    """

    def __init__(
        self,
        base_radius: float = typical_engine.CAM_BASE_RADIUS.value,
        max_lift: float = typical_engine.CAM_MAX_LIFT.value,
        *,
        event_angle: float = math.radians(171.0),
        nose_radius: float = 3e-3,
        ramp_height: float = 0.2e-3,
        ramp_angle: float = math.radians(20.0),
        pulse_share: float = 0.25,
        ramp_pulse_share: float = 0.5,
        nose_angle: float = math.pi,
        tappet_radius: float | None = None,
    ):
        self.base_radius = check_positive("base_radius", base_radius, "m")
        self.max_lift_design = check_positive("max_lift", max_lift, "m")
        self.event_angle_design = check_range(
            "event_angle", event_angle, 0.0, TWO_PI, lo_open=True, hi_open=True, unit="rad"
        )
        self.nose_radius = check_positive("nose_radius", nose_radius, "m")
        self.ramp_height = check_nonnegative("ramp_height", ramp_height, "m")
        self.ramp_angle = check_nonnegative("ramp_angle", ramp_angle, "rad")
        self.pulse_share = check_range(
            "pulse_share", pulse_share, 0.0, 1.0, lo_open=True, hi_open=True
        )
        self.ramp_pulse_share = check_range(
            "ramp_pulse_share", ramp_pulse_share, 0.0, 1.0, lo_open=True
        )
        self.nose_angle = check_range(
            "nose_angle", nose_angle, 0.0, TWO_PI, hi_open=True, unit="rad"
        )
        L, rb = self.max_lift_design, self.base_radius
        if (self.ramp_height > 0.0) != (self.ramp_angle > 0.0):
            raise InputError(
                "ramp_height and ramp_angle must both be > 0 or both be 0 "
                f"(got {self.ramp_height:g} m, {self.ramp_angle:g} rad)"
            )
        if self.ramp_height >= L:
            raise InputError(
                f"ramp_height must be < max_lift (got {self.ramp_height:g} m >= {L:g} m)"
            )
        beta_h = 0.5 * self.event_angle_design - self.ramp_angle
        if beta_h <= 0.0:
            raise InputError(
                f"event_angle must exceed twice the ramp_angle (got event "
                f"{math.degrees(self.event_angle_design):.4g}°, ramp "
                f"{math.degrees(self.ramp_angle):.4g}°)"
            )
        N = rb + L - self.nose_radius
        if N <= 0.0:
            raise InputError(
                f"nose_radius must be < base_radius + max_lift = {(rb + L) * 1e3:.4g} mm for a "
                f"lift event with negative nose acceleration (got {self.nose_radius * 1e3:.4g} mm)"
            )

        # Ramp: half-sine acceleration pulse then constant velocity.
        br, hr = self.ramp_angle, self.ramp_height
        segs: list[tuple[str, float, tuple[float, ...]]] = []  # (kind, beta, params)
        if br > 0.0:
            ba = self.ramp_pulse_share * br
            vr = hr / (br - 0.5 * ba)
            segs.append(("sine", ba, (0.5 * math.pi * vr / ba,)))
            if br - ba > 0.0:
                segs.append(("zero", br - ba, ()))
        else:
            vr = 0.0
        b1 = self.pulse_share * beta_h
        b2 = beta_h - b1
        # Velocity and lift conditions at the nose for (A1, A2) — see class docstring.
        c2, c4 = 2.0 / math.pi, 2.0 / math.pi - 4.0 / math.pi**2
        M = np.array(
            [
                [2.0 * b1 / math.pi, -b2 / 12.0],
                [b1**2 / math.pi + 2.0 * b1 * b2 / math.pi, -(b2**2) / 20.0],
            ]
        )
        rhs = np.array([b2 * c2 * N - vr, L - hr - vr * (b1 + b2) + b2**2 * N * c4])
        A1, A2 = np.linalg.solve(M, rhs)
        if not A1 > 0.0:
            raise InputError(
                "AccelerationCam: no positive acceleration pulse fits these parameters "
                f"(A1 = {A1:.4g} m/rad²); increase event_angle or nose_radius, or reduce "
                "max_lift"
            )
        if A2 < -0.5 * math.pi * N:
            raise InputError(
                "AccelerationCam: the negative region would change sign near its start "
                f"(A2 = {A2:.4g} m/rad² < −πN/2 = {-0.5 * math.pi * N:.4g}); increase "
                "pulse_share or event_angle"
            )
        segs.append(("sine", b1, (A1,)))
        segs.append(("neg", b2, (N, A2)))
        self.ramp_velocity = float(vr)

        # Segment start angles, lift and velocity (cumulative, from the event start).
        self._segs = []
        phi0, s0, v0 = 0.0, 0.0, 0.0
        for kind, beta, p in segs:
            self._segs.append((phi0, kind, beta, p, s0, v0))
            _, i1, i2 = _seg_eval(kind, beta, p, beta, math.sin, math.cos)
            s0, v0 = s0 + v0 * beta + i2, v0 + i1
            phi0 += beta
        self._half = phi0  # = event/2
        self._starts = [sg[0] for sg in self._segs]
        self.check(tappet_radius)

    def _breakpoints(self) -> np.ndarray:
        b = self._half - np.array(self._starts + [self._half])  # distance from the nose
        return np.concatenate([self.nose_angle - b, self.nose_angle + b]) % TWO_PI

    def derivatives(self, angle):
        # signed angle from the nose in (−π, π]; mirrored so φ runs from the event start
        d = (np.asarray(angle, dtype=float) - self.nose_angle + math.pi) % TWO_PI - math.pi
        sign = np.where(d < 0.0, 1.0, -1.0)  # opening side: s' > 0
        phi = self._half - np.abs(d)  # angle from the event start
        s = np.zeros_like(phi)
        s1 = np.zeros_like(phi)
        s2 = np.zeros_like(phi)
        for k, (p0, kind, beta, p, sa, va) in enumerate(self._segs):
            hi = self._segs[k + 1][0] if k + 1 < len(self._segs) else self._half + 1.0
            m = (phi >= p0) & (phi < hi)
            if not m.any():
                continue
            x = phi[m] - p0
            a, i1, i2 = _seg_eval(kind, beta, p, x, np.sin, np.cos)
            s[m] = sa + va * x + i2
            s1[m] = va + i1
            s2[m] = a
        return s, sign * s1, s2

    def scalar_derivatives(self, angle):
        d = (angle - self.nose_angle + math.pi) % TWO_PI - math.pi
        phi = self._half - abs(d)
        if phi < 0.0:
            return 0.0, 0.0, 0.0
        k = bisect.bisect_right(self._starts, phi) - 1
        p0, kind, beta, p, sa, va = self._segs[k]
        x = phi - p0
        a, i1, i2 = _seg_eval(kind, beta, p, x, math.sin, math.cos)
        v = va + i1
        return sa + va * x + i2, (v if d < 0.0 else -v), a


# --------------------------------------------------------------------------------------
# Circular-arc cam
# --------------------------------------------------------------------------------------
class CircularArcCam(CamProfile):
    """Symmetric circular-arc cam: base circle r_b, two flank arcs ρ_f, nose arc ρ_n.

    Geometry (cam frame, nose along +y): nose centre C_n = (0, d), d = r_b + L − ρ_n; the
    flank centre C_f lies where its arc is internally tangent to the base circle,
    |C_f| = ρ_f − r_b, and to the nose circle, |C_f − C_n| = ρ_f − ρ_n. A flat follower
    whose face normal makes angle φ with the nose direction sits at the support function
    h(φ) = max_{arc} (c·n + ρ), n = (sin φ, cos φ), so s = h − r_b and R = h + h'' = the
    radius of the arc in contact (Hertz radius changes in steps at the arc junctions).

    Parameters
    ----------
    base_radius, flank_radius, nose_radius : r_b, ρ_f, ρ_n [m], with ρ_f > r_b and
        ρ_n < r_b + L.
    max_lift : L [m].
    nose_angle : cam angle of maximum lift [rad] (default π).
    tappet_radius : optional check of max |e|.
    """

    def __init__(
        self,
        base_radius: float = typical_engine.CAM_BASE_RADIUS.value,
        max_lift: float = typical_engine.CAM_MAX_LIFT.value,
        *,
        flank_radius: float = 0.030,
        nose_radius: float = 3e-3,
        nose_angle: float = math.pi,
        tappet_radius: float | None = None,
    ):
        self.base_radius = rb = check_positive("base_radius", base_radius, "m")
        self.max_lift_design = L = check_positive("max_lift", max_lift, "m")
        self.flank_radius = rf = check_positive("flank_radius", flank_radius, "m")
        self.nose_radius = rn = check_positive("nose_radius", nose_radius, "m")
        self.nose_angle = check_range(
            "nose_angle", nose_angle, 0.0, TWO_PI, hi_open=True, unit="rad"
        )
        if rf <= rb:
            raise InputError(f"flank_radius must be > base_radius (got {rf:g} m <= {rb:g} m)")
        d = rb + L - rn
        if d <= 0.0:
            raise InputError(f"nose_radius must be < base_radius + max_lift (got {rn:g} m)")
        if rn >= rb:
            raise InputError(f"nose_radius must be < base_radius (got {rn:g} m >= {rb:g} m)")
        a, b = rf - rb, rf - rn  # |C_f|, |C_f − C_n|
        # C_f = (x, y): x² + y² = a², x² + (y − d)² = b²  ⇒  y = (a² − b² + d²)/(2d)
        y = (a * a - b * b + d * d) / (2.0 * d)
        x2 = a * a - y * y
        if x2 <= 0.0:
            raise InputError(
                "CircularArcCam: flank_radius too small to join the base and nose circles "
                f"tangentially (ρ_f = {rf:g} m, r_b = {rb:g} m, ρ_n = {rn:g} m, L = {L:g} m)"
            )
        self._cf = (-math.sqrt(x2), y)  # flank centre for the φ > 0 side
        self._d = d
        # Normal angles of the junctions: nose/flank along C_n − C_f, flank/base along −C_f.
        cx, cy = self._cf
        self._phi_nose = math.atan2(0.0 - cx, d - cy)
        self._phi_base = math.atan2(-cx, -cy)
        if not (0.0 < self._phi_nose < self._phi_base < math.pi):
            raise InputError("CircularArcCam: inconsistent arc junctions for these radii")
        self.check(tappet_radius)

    def _breakpoints(self):
        p = np.array([self._phi_nose, self._phi_base])
        return (
            np.concatenate([self.nose_angle - p, self.nose_angle + p, [self.nose_angle]]) % TWO_PI
        )

    def derivatives(self, angle):
        phi = (np.asarray(angle, dtype=float) - self.nose_angle + math.pi) % TWO_PI - math.pi
        a = np.abs(phi)
        sg = np.sign(phi)
        cx, cy = self._cf
        rb, d = self.base_radius, self._d
        sa, ca = np.sin(a), np.cos(a)
        # support function h(a) and derivatives on each arc (a = |φ|, symmetric)
        h_n, h1_n = d * ca + self.nose_radius, -d * sa
        h_f, h1_f = cx * sa + cy * ca + self.flank_radius, cx * ca - cy * sa
        nose = a <= self._phi_nose
        flank = (~nose) & (a <= self._phi_base)
        h = np.where(nose, h_n, np.where(flank, h_f, rb))
        h1 = np.where(nose, h1_n, np.where(flank, h1_f, 0.0))
        R = np.where(nose, self.nose_radius, np.where(flank, self.flank_radius, rb))
        s = h - rb
        s1 = sg * h1
        s2 = R - h  # R = h + h''
        return s, s1, s2

    def scalar_derivatives(self, angle):
        phi = (angle - self.nose_angle + math.pi) % TWO_PI - math.pi
        a = abs(phi)
        if a > self._phi_base:
            return 0.0, 0.0, 0.0
        sa, ca = math.sin(a), math.cos(a)
        if a <= self._phi_nose:
            h, h1, R = self._d * ca + self.nose_radius, -self._d * sa, self.nose_radius
        else:
            cx, cy = self._cf
            h, h1, R = cx * sa + cy * ca + self.flank_radius, cx * ca - cy * sa, self.flank_radius
        s1 = h1 if phi >= 0.0 else -h1
        return h - self.base_radius, s1, R - h

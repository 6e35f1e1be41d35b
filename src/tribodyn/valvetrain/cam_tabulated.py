"""Tabulated cam: a lift table (θ, s) fitted for a flat follower.

The fit itself (noise, base circle, curvature jumps, penalised spline) is in
:mod:`tribodyn.valvetrain.cam_fit`; reading files in :mod:`tribodyn.valvetrain.cam_table`.
"""

from __future__ import annotations

import bisect
import math

import numpy as np

from .._typing import ArrayLike
from .._validation import InputError, check_array, check_nonnegative, check_positive
from ..physics import limits as L
from .cams import TWO_PI, CamProfile

__all__ = ["TabulatedCam", "MAX_FIT_DEVIATION"]

#: A fit deviating from its table by more than this share of the maximum lift (RMS) is
#: flagged by :meth:`TabulatedCam.fit_warning`: far beyond a measurement's noise (≲ 1 µm
#: on a lift of millimetres), so the fitted profile is not the table's cam.
MAX_FIT_DEVIATION = 0.01


class TabulatedCam(CamProfile):
    """Lift table (θ, s), fitted robustly by a periodic quintic spline
    (:mod:`tribodyn.valvetrain.cam_fit`): jumps of s'' (three-arc cams, ramps) are found
    and kept as jumps (s, s' continuous), noise is smoothed to the table's precision.

    Parameters
    ----------
    angle : cam angles θ [rad], strictly increasing, at most one revolution: a full
        revolution (the first and last point may be one period apart, then their lifts
        must agree), or the lift event only — both ends on the base circle (lift within
        the precision of 0, at most 10 µm) — the rest of the revolution is filled with the
        base circle.
    lift : s [m] at those angles (≥ −10 µm; the base circle is s = 0).
    base_radius : r_b [m].
    smoothing : precision of the table, the RMS deviation allowed to the fit [m]
        (None: estimated from the table's noise and its rounding ``quantum``).
    quantum : rounding step of the lift values [m] (from the file's digits), or 0.
    tappet_radius : optional check of max |e|.

    ``curvature_jumps`` lists (θ [rad], R before, R after [m]) of the jumps found;
    ``precision`` is the precision used [m]; ``base_circle`` the cam angles (from, to)
    [rad] where the fit is exactly the base circle (s = s' = s'' = 0, R = r_b).
    At most 10⁶ rows (``physics.limits.LIFT_TABLE_ROWS``); the fit costs O(n).
    """

    def __init__(
        self,
        angle: ArrayLike,
        lift: ArrayLike,
        base_radius: float,
        *,
        smoothing: float | None = None,
        quantum: float = 0.0,
        tappet_radius: float | None = None,
    ):
        from .cam_fit import estimate_noise, fit_periodic_lift

        self.base_radius = check_positive("base_radius", base_radius, "m")
        self.smoothing = (
            None if smoothing is None else check_nonnegative("smoothing", smoothing, "m")
        )
        th = check_array("angle", angle, min_size=12)
        s = check_array("lift", lift, min_size=12)
        L.LIFT_TABLE_ROWS.check("number of lift table rows", th.size)
        if th.shape != s.shape:
            raise InputError(
                f"angle and lift must have the same length (got {th.size} and {s.size})"
            )
        dth = np.diff(th)
        if np.any(dth <= 0.0):
            k = int(np.argmax(dth <= 0.0))
            raise InputError(
                "angle must be strictly increasing (non-monotonic lift table at entry "
                f"{k + 1}: {math.degrees(th[k]):.4g}° then {math.degrees(th[k + 1]):.4g}°)"
            )
        span = th[-1] - th[0]
        tol = 1e-9 * TWO_PI
        if span > TWO_PI + tol:
            raise InputError(
                f"angle must span at most one revolution (got {math.degrees(span):.6g}°)"
            )
        if abs(span - TWO_PI) <= tol:
            if abs(s[-1] - s[0]) > max(1e-9, 1e-6 * np.ptp(s), 3.0 * (smoothing or 0.0)):
                raise InputError(
                    "lift table is not periodic: the lift at θ₀ + 360° must equal the lift at "
                    f"θ₀ (got {s[0] * 1e3:.6g} mm and {s[-1] * 1e3:.6g} mm)"
                )
            th, s = th[:-1], s[:-1]
            dth = np.diff(th)
        gap = th[0] + TWO_PI - th[-1]
        if gap > 2.0 * dth.max() + tol:
            # the lift event only: both ends on the base circle
            zero = max(3.0 * (smoothing or 0.0), 3.0 * estimate_noise(s), quantum, 1e-8)
            if max(abs(s[0]), abs(s[-1])) > min(zero, 1e-5):
                raise InputError(
                    f"lift table covers {math.degrees(span):.4g}° and does not end on the base "
                    f"circle (lift {s[0] * 1e3:.4g} mm at the start, {s[-1] * 1e3:.4g} mm at "
                    "the end): give a full revolution, or the event from base circle to "
                    "base circle"
                )
            if span < math.radians(20.0):
                raise InputError(
                    f"lift event of {math.degrees(span):.3g}° is implausibly "
                    "short: check the angle unit"
                )
            h = float(np.median(dth))
            k = int(math.floor(gap / h))
            fill = th[-1] + gap * np.arange(1, k) / k
            th = np.concatenate([th, fill])
            s = np.concatenate([s, np.zeros(fill.size)])
            self.event_only = True
        else:
            self.event_only = False
        if s.min() < -1e-5:
            raise InputError(
                f"lift must be >= 0 above the base circle (got min {s.min() * 1e3:.4g} mm)"
            )
        if not s.max() > 0.0:
            raise InputError("lift must rise above the base circle somewhere (max lift is 0)")
        self.angle = th
        self.lift_table = s
        fit = fit_periodic_lift(th, s, self.base_radius, self.smoothing, quantum)
        self.precision = fit.precision
        self.base_circle = fit.base_circle  # (from, to) [rad] where s ≡ 0, or None
        self._x = fit.breaks
        self._c = fit.coeffs  # (6, pieces), highest power first
        self._x0 = float(self._x[0])
        self._xlist = self._x[:-1].tolist()
        self._clist = [tuple(col) for col in self._c.T]
        self.curvature_jumps = []
        for a, _ in fit.jumps:
            lo, hi = self.radius_of_curvature(np.array([a - 1e-7, a + 1e-7]))
            self.curvature_jumps.append((a, float(lo), float(hi)))
        self.check(tappet_radius)

    def fit_warning(self) -> str | None:
        """None, or what to tell the user when the fit deviates from the table by more
        than :data:`MAX_FIT_DEVIATION` of the maximum lift (RMS over the table's points):
        a table too coarse or too noisy to define the curvature and acceleration, which the
        fit then smooths away."""
        table = np.asarray(self.lift_table)
        fitted = self.derivatives(np.asarray(self.angle))[0]
        rms = float(np.sqrt(np.mean((table - fitted) ** 2)))
        top = float(table.max())
        if not rms > MAX_FIT_DEVIATION * top:
            return None
        step = math.degrees(float(np.median(np.diff(self.angle))))
        lifted = int(np.count_nonzero(table > rms))
        return (
            f"cam table: the fitted profile differs from the table by {rms * 1e6:.3g} µm "
            f"RMS, {100 * rms / top:.2g} % of the {top * 1e3:.3g} mm lift (flagged above "
            f"{100 * MAX_FIT_DEVIATION:g} %): the table is too coarse ({step:.3g}° steps, "
            f"{lifted} points clearly above the base circle) or too noisy to define the "
            "cam's curvature and acceleration, so the dynamics and the EHL follow a "
            f"smoothed profile (max lift {float(fitted.max()) * 1e3:.4g} mm), not your "
            "table; give the lift at finer steps (measured tables have 0.1–1°), or "
            "cam.smoothing if you know the table's noise"
        )

    @classmethod
    def from_csv(
        cls,
        path,
        base_radius: float,
        *,
        smoothing: float | None = None,
        angle_unit: str = "auto",
        lift_unit: str = "auto",
        angle_column=None,
        lift_column=None,
        tappet_radius: float | None = None,
    ) -> TabulatedCam:
        """Read a lift table (CSV; units from the header or the arguments); see
        :func:`tribodyn.valvetrain.cam_table.load_lift_table`."""
        from .cam_table import load_lift_table

        t = load_lift_table(
            path,
            angle_unit=angle_unit,
            lift_unit=lift_unit,
            angle_column=angle_column,
            lift_column=lift_column,
        )
        return cls(
            t.angle,
            t.lift,
            base_radius,
            smoothing=smoothing,
            quantum=t.quantum,
            tappet_radius=tappet_radius,
        )

    def _breakpoints(self):
        return self._x[:-1] % TWO_PI

    def derivatives(self, angle):
        th = np.asarray(angle, dtype=float)
        u = (th - self._x0) % TWO_PI + self._x0
        k = np.clip(np.searchsorted(self._x, u, side="right") - 1, 0, self._c.shape[1] - 1)
        x = u - self._x[k]
        c = self._c[:, k]
        n = c.shape[0] - 1  # degree (5); c[j] multiplies x^(n−j)
        s = np.zeros_like(x)
        s1 = np.zeros_like(x)
        s2 = np.zeros_like(x)
        for j in range(n + 1):  # Horner for s, s' and s''
            p = n - j
            s = s * x + c[j]
            if p >= 1:
                s1 = s1 * x + p * c[j]
            if p >= 2:
                s2 = s2 * x + p * (p - 1) * c[j]
        return s, s1, s2

    def scalar_derivatives(self, angle):
        u = (angle - self._x0) % TWO_PI + self._x0
        k = bisect.bisect_right(self._xlist, u) - 1
        if k < 0:
            k = 0
        x = u - self._xlist[k]
        c0, c1, c2, c3, c4, c5 = self._clist[k]
        s = ((((c0 * x + c1) * x + c2) * x + c3) * x + c4) * x + c5
        s1 = (((5.0 * c0 * x + 4.0 * c1) * x + 3.0 * c2) * x + 2.0 * c3) * x + c4
        s2 = ((20.0 * c0 * x + 12.0 * c1) * x + 6.0 * c2) * x + 2.0 * c3
        return s, s1, s2

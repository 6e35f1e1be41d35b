"""Camshaft compliance seen by one lobe: torsion between drive and lobe, bending at the lobe.

Torsion (one DOF, the lobe's lag φ behind the driven angle; lobe angle θ_l = θ₀ + ωt − φ)::

    J φ̈ = T_L − k_t φ − c_t φ̇,     T_L = F_c s'(θ_l) + F_f (r_b + s)     (load torque)
    1/k_t = 1/k_drive + L_d/(G I_p),  I_p = π d⁴/32,  c_t = 2 ζ_t √(k_t J)

J is the lobe's polar inertia (its profile area × width × ρ, from the cam contour) plus a
third of the shaft segment between drive and lobe (Rayleigh's estimate for a shaft fixed
at the drive, Rayleigh 1877 / Timoshenko). The drive delivers T_d = k_t φ + c_t φ̇ at ω.

Bending (massless, in series with the contact): the lobe sits at distance a from one
bearing of a simply supported span L (b = L − a); the deflection under the contact force
is F a² b²/(3 E I L), I = π d⁴/64 (Roark's Formulas for Stress and Strain, 8th ed., Table
8.1 case 1e), plus the two bearings' deflections weighted by the lever rule,
F [(b/L)²/k_b + (a/L)²/k_b] with bearing stiffness k_b (absent: rigid bearings).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validation import InputError, check_nonnegative, check_positive, check_range
from ..physics import typical_engine
from .cams import CamProfile

__all__ = ["Camshaft", "lobe_polar_inertia"]


def lobe_polar_inertia(cam: CamProfile, width: float, density: float, n: int = 3600) -> float:
    """Polar moment of inertia of the lobe about the camshaft axis [kg·m²].

    The flat-follower cam contour is the envelope of the follower faces: at follower
    normal angle ψ the contact point is p = h n(ψ) + h' t(ψ), h = r_b + s the support
    function. J = ρ w ∮ (x² + y²)(x dy − y dx)/4 over the contour (Green's theorem)."""
    th = np.linspace(0.0, 2.0 * math.pi, n, endpoint=False)
    s, s1, _ = cam.derivatives(th)
    h = cam.base_radius + s
    c, sn = np.cos(th), np.sin(th)
    x = h * c - s1 * sn
    y = h * sn + s1 * c
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    Iz = np.sum(cross * (x * x + x * xn + xn * xn + y * y + y * yn + yn * yn)) / 12.0
    return float(density * width * abs(Iz))


@dataclass(frozen=True)
class Camshaft:
    """Camshaft compliance parameters (SI).

    diameter : shaft diameter d [m]; bearing_span : L [m]; lobe_position : a, the lobe's
    distance from the nearer bearing [m] (≤ L/2); drive_stiffness : torsional stiffness of
    the drive (belt/chain, sprocket) [N·m/rad]; drive_length : shaft length from the
    drive to the lobe [m]; E [Pa], nu [-], density [kg/m³]; bearing_stiffness : radial
    stiffness of each bearing [N/m] (None: rigid); torsional_damping_ratio : ζ_t;
    lobe_inertia : J of the lobe [kg·m²] (None: from the cam contour and width).
    """

    diameter: float
    bearing_span: float
    lobe_position: float
    drive_stiffness: float
    drive_length: float
    E: float = typical_engine.STEEL_MODULUS.value
    nu: float = typical_engine.STEEL_POISSON.value
    density: float = typical_engine.STEEL_DENSITY.value
    bearing_stiffness: float | None = None
    torsional_damping_ratio: float = 0.02
    lobe_inertia: float | None = None

    def __post_init__(self):
        for name, unit in (
            ("diameter", "m"),
            ("bearing_span", "m"),
            ("drive_stiffness", "N·m/rad"),
            ("drive_length", "m"),
            ("E", "Pa"),
            ("density", "kg/m³"),
        ):
            check_positive(name, getattr(self, name), unit)
        check_range("nu", self.nu, -1.0, 0.5, lo_open=True, hi_open=True)
        check_nonnegative("lobe_position", self.lobe_position, "m")
        if self.lobe_position > 0.5 * self.bearing_span:
            raise InputError(
                f"lobe_position must be <= bearing_span/2 = "
                f"{0.5 * self.bearing_span:g} m (distance from the nearer "
                f"bearing; got {self.lobe_position:g} m)"
            )
        check_range("torsional_damping_ratio", self.torsional_damping_ratio, 0.0, 1.0, hi_open=True)
        if self.bearing_stiffness is not None:
            check_positive("bearing_stiffness", self.bearing_stiffness, "N/m")
        if self.lobe_inertia is not None:
            check_positive("lobe_inertia", self.lobe_inertia, "kg·m²")

    @property
    def shear_modulus(self) -> float:
        return self.E / (2.0 * (1.0 + self.nu))

    @property
    def torsional_stiffness(self) -> float:
        """k_t of drive and shaft in series [N·m/rad]."""
        Ip = math.pi * self.diameter**4 / 32.0
        k_shaft = self.shear_modulus * Ip / self.drive_length
        return 1.0 / (1.0 / self.drive_stiffness + 1.0 / k_shaft)

    @property
    def bending_compliance(self) -> float:
        """Deflection per unit contact force at the lobe [m/N] (shaft + bearings)."""
        L, a = self.bearing_span, self.lobe_position
        b = L - a
        I = math.pi * self.diameter**4 / 64.0
        c = a * a * b * b / (3.0 * self.E * I * L)
        if self.bearing_stiffness is not None:
            c += ((b / L) ** 2 + (a / L) ** 2) / self.bearing_stiffness
        return c

    def inertia(self, cam: CamProfile, width: float) -> float:
        """J of the torsion DOF: lobe + a third of the shaft from drive to lobe [kg·m²]."""
        lobe = (
            self.lobe_inertia
            if self.lobe_inertia is not None
            else lobe_polar_inertia(cam, width, self.density)
        )
        shaft = self.density * math.pi * self.diameter**4 / 32.0 * self.drive_length
        return lobe + shaft / 3.0

"""Reference solutions for the elastic line contact of a cylinder on a plane (Hertz).

With E' the reduced modulus (1/E' = ½Σ(1−ν²)/E), load w per unit length and radius R
(Johnson, *Contact Mechanics*, 1985, §4.3, written with E' = 2E*)::

    b   = √(8 w R / (π E'))          half-width                 [m]
    p_h = √(w E' / (2π R))           peak pressure              [Pa]
    p(x) = p_h √(1 − x²/b²)          |x| ≤ b
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validation import check_positive

__all__ = ["HertzLineContact", "hertz_line_contact", "hertz_half_width"]


@dataclass(frozen=True)
class HertzLineContact:
    load: float
    radius: float
    reduced_modulus: float
    half_width: float
    max_pressure: float

    @property
    def mean_pressure(self) -> float:
        return math.pi / 4.0 * self.max_pressure

    def pressure(self, x) -> np.ndarray:
        """Hertz pressure p(x) [Pa]; zero outside the contact."""
        r = 1.0 - (np.asarray(x, dtype=float) / self.half_width) ** 2
        return self.max_pressure * np.sqrt(np.clip(r, 0.0, None))


def hertz_half_width(w: float, r: float, e: float) -> float:
    """b = √(8 w R / (π E')) [m], inputs not checked (positive floats: for solvers whose
    inputs were checked once upstream; :func:`hertz_line_contact` checks them)."""
    return math.sqrt(8.0 * w * r / (math.pi * e))


def hertz_line_contact(load: float, radius: float, reduced_modulus: float) -> HertzLineContact:
    """Hertz solution for load per unit length [N/m], radius [m], reduced modulus E' [Pa]."""
    w = check_positive("load", load, "N/m")
    r = check_positive("radius", radius, "m")
    e = check_positive("reduced_modulus", reduced_modulus, "Pa")
    ph = math.sqrt(w * e / (2.0 * math.pi * r))
    return HertzLineContact(w, r, e, hertz_half_width(w, r, e), ph)

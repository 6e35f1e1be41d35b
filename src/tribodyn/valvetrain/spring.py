"""Helical valve spring as a 1-D continuum with coil clash (pure physics).

Geometry → rate, mass and surge (Wahl, Mechanical Springs, 2nd ed., 1963; SAE HS-795)::

    rate of one coil    k_c = G d⁴ / (8 D³)            rate k = k_c / n_a
    active mass         m = ρ (π d²/4) (π D) n_a       surge f_n = (n/2) √(k/m)  (fixed–fixed)

The active coils are cut into ``elements_per_coil`` bar elements each (stiffness
k_c·elements_per_coil, mass m/(n_a·elements_per_coil), mixed mass matrix, see
:mod:`tribodyn.valvetrain.fe`): a 1-D continuum along the coil count. Each coil i has its
own free pitch p_i (variable-pitch, progressive springs); an element of coil i closes
when its compression reaches its share of the coil gap, g = (p_i − d)/elements_per_coil.
Beyond that the wires touch: the clash force follows Palmgren's line-contact law over the
wire length of the element, l = πD/elements_per_coil (δ = 3.84e-5 Q^0.9 l^−0.8 in mm, N;
Palmgren 1959), in parallel with the element. As coils close one by one the spring gets
stiffer (progressive force–deflection) and its surge frequencies rise.

Hand calculation (the reference of the tests): with equal coils, every open coil carries
the spring force F, so coil i closes at F_i = k_c g_i and the deflection is
δ(F) = Σ_i min(F/k_c, g_i) (rigid clash): piecewise linear, rate k_c/(number of open coils).

Node 0 is the retainer end, node N the head end; +x is valve opening (compression).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from .._validation import InputError, check_positive, check_range
from ..physics import typical_engine
from .fe import AxialFEModel, ModalBody, check_count
from .parameters import PALMGREN_COEFFICIENT

__all__ = ["HelicalSpring", "SpringStatics"]

_PALMGREN_EXP = 0.9


@dataclass(frozen=True)
class SpringStatics:
    """Static state at a spring compression: force [N], element compressions [m]."""

    force: float
    compressions: np.ndarray
    closed: np.ndarray  #: element closed (wires touching)


@dataclass(frozen=True)
class HelicalSpring(ModalBody):
    """Cylindrical helical compression spring (SI units).

    wire_diameter d, mean_diameter D [m]; active_coils n_a (may be fractional);
    free_length, installed_length [m] (installed < free: preload);
    pitches : free pitch of each active coil [m] (``None``: uniform pitch from the free
        length, (L₀ − (n_a + 2 n_dead) d)/n_a + d); a list has one entry per active coil
        (n_a must then be an integer) and sets the free length of the active part;
    dead_coils : closed end coils at each end (their mass at the retainer end moves with it);
    shear_modulus G [Pa], density ρ [kg/m³];
    elements_per_coil : FE mesh of the continuum; modes, cutoff, damping_ratio : the
        Craig–Bampton settings (:class:`~tribodyn.valvetrain.fe.ModalBody`; ζ of the
        surge modes);
    clash_margin : coils whose static closing force is below clash_margin × the largest
        working force are kept as interface nodes (their clash is resolved exactly);
    clash_damping : damping of a closed coil contact [N·s/m].
    """

    wire_diameter: float
    mean_diameter: float
    active_coils: float
    free_length: float
    installed_length: float
    pitches: tuple | None = None
    dead_coils: float = 1.0
    shear_modulus: float = 79.3e9
    density: float = typical_engine.STEEL_DENSITY.value
    elements_per_coil: int = 2
    clash_margin: float = 1.25
    clash_damping: float = 50.0
    _derived: dict = field(default_factory=dict, init=False, repr=False, compare=False)

    def __post_init__(self):
        for name, unit in (
            ("wire_diameter", "m"),
            ("mean_diameter", "m"),
            ("free_length", "m"),
            ("installed_length", "m"),
            ("shear_modulus", "Pa"),
            ("density", "kg/m³"),
            ("active_coils", ""),
            ("clash_margin", ""),
        ):
            check_positive(name, getattr(self, name), unit)
        check_range("dead_coils", self.dead_coils, 0.0, 10.0)
        self._check_modal()
        check_range("clash_damping", self.clash_damping, 0.0, 1e6)
        check_count("elements_per_coil", self.elements_per_coil, 1, 20)
        d, D = self.wire_diameter, self.mean_diameter
        if not D > d:
            raise InputError(
                f"mean_diameter must exceed wire_diameter (got D = {D:g} m, d = {d:g} m)"
            )
        if self.pitches is not None:
            p = np.asarray(self.pitches, dtype=float)
            if (
                p.ndim != 1
                or p.size != self.active_coils
                or abs(self.active_coils - round(self.active_coils)) > 1e-12
            ):
                raise InputError(
                    f"pitches must list one pitch per active coil "
                    f"({self.active_coils:g} coils; got {p.size})"
                )
            if np.any(~np.isfinite(p)) or np.any(p <= d):
                raise InputError(
                    f"pitches must all exceed the wire diameter {d * 1e3:g} mm "
                    f"(got min {p.min() * 1e3:g} mm)"
                )
            object.__setattr__(self, "pitches", tuple(float(x) for x in p))
            free = float(p.sum()) + 2.0 * self.dead_coils * d
            if abs(free - self.free_length) > 1e-4:
                raise InputError(
                    f"free_length {self.free_length * 1e3:.4g} mm disagrees with "
                    f"the pitches (Σ p + 2 n_dead d = {free * 1e3:.4g} mm)"
                )
        if not self.installed_length < self.free_length:
            raise InputError(
                f"installed_length must be below free_length (got "
                f"{self.installed_length:g} m >= {self.free_length:g} m)"
            )
        if self.installed_length <= self.solid_length:
            raise InputError(
                f"installed_length {self.installed_length * 1e3:.4g} mm is at or "
                f"below the solid length {self.solid_length * 1e3:.4g} mm"
            )
        if self.coil_gaps.min() <= 0.0:
            raise InputError(
                "free_length too short for the wire: the uniform pitch would "
                "not exceed the wire diameter"
            )

    # -- geometry ------------------------------------------------------------------------
    @property
    def coil_rate(self) -> float:
        """k_c = G d⁴/(8 D³), the rate of one coil [N/m]."""
        return self.shear_modulus * self.wire_diameter**4 / (8.0 * self.mean_diameter**3)

    @property
    def rate(self) -> float:
        """Initial rate k = k_c/n_a [N/m] (all coils open)."""
        return self.coil_rate / self.active_coils

    @property
    def wire_mass_per_coil(self) -> float:
        d, D = self.wire_diameter, self.mean_diameter
        return self.density * 0.25 * math.pi * d * d * math.pi * D

    @property
    def active_mass(self) -> float:
        """Mass of the active coils [kg]."""
        return self.wire_mass_per_coil * self.active_coils

    def surge_frequency(self, n: int = 1) -> float:
        """Continuum surge frequency (n/2)√(k/m) of the fixed–fixed spring [Hz]."""
        return 0.5 * n * math.sqrt(self.rate / self.active_mass)

    @property
    def solid_length(self) -> float:
        """(n_a + 2 n_dead) d [m]."""
        return (self.active_coils + 2.0 * self.dead_coils) * self.wire_diameter

    @property
    def coil_pitches(self) -> np.ndarray:
        """Free pitch of each active coil [m] (the last, fractional coil scaled)."""
        if self.pitches is not None:
            return np.asarray(self.pitches)
        d = self.wire_diameter
        p = (self.free_length - 2.0 * self.dead_coils * d) / self.active_coils
        n = int(math.ceil(self.active_coils - 1e-12))
        return np.full(n, p)

    @property
    def coil_gaps(self) -> np.ndarray:
        """Free gap of each active coil (pitch − d) [m]."""
        return self.coil_pitches - self.wire_diameter

    @property
    def installed_compression(self) -> float:
        """Compression at the installed length [m] (Σ pitches + 2 n_dead d when the
        pitches are given, which must match the free length within 0.1 mm)."""
        if self.pitches is not None:
            free = float(np.sum(self.pitches)) + 2.0 * self.dead_coils * self.wire_diameter
        else:
            free = self.free_length
        return free - self.installed_length

    # -- finite elements ----------------------------------------------------------------
    def _elements(self):
        """(stiffness, mass, gap, contact length) of each element (arrays)."""
        if "el" not in self._derived:
            e = self.elements_per_coil
            na = self.active_coils
            n_full = int(math.ceil(na - 1e-12))
            share = np.ones(n_full)
            share[-1] = na - (n_full - 1)  # fractional last coil
            frac = np.repeat(share, e) / e  # coils in each element
            k, m = self.coil_rate / frac, self.wire_mass_per_coil * frac
            g = np.repeat(self.coil_gaps[:n_full], e) * frac
            self._derived["el"] = (k, m, g, math.pi * self.mean_diameter / e)
        return self._derived["el"]

    def _chain(self, k) -> AxialFEModel:
        """Axial FE chain of the elements with stiffnesses ``k`` [N/m] and the elements'
        masses: nodes 0 (retainer end, "top") … N (head end, "bottom"); element masses
        follow the mixed mass matrix of :mod:`.fe`."""
        m = self._elements()[1]
        model = AxialFEModel("spring")
        a = model.node("top")
        for j in range(k.size):
            # a bar of length 1 with E = k, A = 1 and ρ = m reproduces k and m exactly
            a = model.bar(a, 1.0, k[j], 1.0, m[j], 1, "bottom" if j == k.size - 1 else None)
        return model

    def fe_model(self) -> AxialFEModel:
        """Axial FE model (:meth:`_chain`), the moving dead coils' mass (one end) on node 0."""
        model = self._chain(self._elements()[0])
        if self.dead_coils > 0.0:
            model.mass(0, self.wire_mass_per_coil * self.dead_coils)
        return model

    def clash_force(self, overlap: float) -> tuple[float, float]:
        """Palmgren clash force Q [N] and dQ/dδ [N/m] at wire overlap δ ≥ 0 [m]."""
        if overlap <= 0.0:
            return 0.0, 0.0
        C = self._palmgren_c
        z = overlap / C
        Q = z ** (1.0 / _PALMGREN_EXP)
        return Q, Q / (_PALMGREN_EXP * overlap)

    @property
    def _palmgren_c(self) -> float:
        return PALMGREN_COEFFICIENT * self._elements()[3] ** -0.8

    def element_compression(self, j: int, force: float) -> float:
        """Static compression of element j carrying ``force`` [N] (clash included)."""
        k, _, g, _ = self._elements()
        k, g = k[j], g[j]
        if force <= k * g:
            return force / k
        lo, hi = g, force / k  # k δ + Q(δ − g) = force
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if k * mid + self.clash_force(mid - g)[0] > force:
                hi = mid
            else:
                lo = mid
            if hi - lo < 1e-15:
                break
        return 0.5 * (lo + hi)

    def statics(self, compression: float) -> SpringStatics:
        """Static force and element compressions at a total compression [m]."""
        if compression <= 0.0:
            n = self._elements()[0].size
            return SpringStatics(0.0, np.zeros(n), np.zeros(n, bool))
        k, _, g, _ = self._elements()
        n = k.size

        def total(F):
            return sum(self.element_compression(j, F) for j in range(n))

        lo, hi = 0.0, compression * k.min()
        while total(hi) < compression:
            hi *= 2.0
            if hi > 1e9:
                raise InputError(
                    f"spring compression {compression * 1e3:.4g} mm is beyond the solid length"
                )
        for _ in range(200):
            mid = 0.5 * (lo + hi)
            if total(mid) > compression:
                hi = mid
            else:
                lo = mid
            if hi - lo <= 1e-12 * hi:
                break
        F = 0.5 * (lo + hi)
        comp = np.array([self.element_compression(j, F) for j in range(n)])
        return SpringStatics(F, comp, comp > g)

    @property
    def preload(self) -> float:
        """Installed force F₀ [N]."""
        return self.statics(self.installed_compression).force

    def clash_nodes(self, max_force: float) -> list[int]:
        """Nodes of the elements that may close up to clash_margin × max_force (an element
        closes at the static spring force k_e g_e)."""
        k, _, g, _ = self._elements()
        close = np.nonzero(k * g <= self.clash_margin * max_force)[0]
        return sorted({int(j) for j in close} | {int(j) + 1 for j in close})

    def surge_frequencies(self, compression: float, count: int = 3) -> np.ndarray:
        """Surge frequencies [Hz] of the spring held at both ends at a static compression
        [m]: the tangent stiffness includes the clash contact of closed coils, so they rise
        as coils close (the dead coil's mass is left out: both ends are fixed)."""
        st = self.statics(compression)
        k, _, g, _ = self._elements()
        kt = k + np.array([self.clash_force(st.compressions[j] - g[j])[1] for j in range(k.size)])
        return self._chain(kt).frequencies(fixed=(0, k.size), count=count)

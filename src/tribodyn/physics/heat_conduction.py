"""Thermal properties of the solids and the depth grid of a (coated) moving solid.

A body conducts heat as a layered half-space: a coating of thickness d (conductivity k_c,
volumetric heat capacity ρc_c) perfectly bonded to a substrate (k_s, ρc_s). In the frame of
the contact its material moves at its surface speed u along x, so the temperature rise θ
obeys (Carslaw & Jaeger 1959, *Conduction of Heat in Solids*, §10.7)::

    ρc (∂θ/∂t + u ∂θ/∂x) = ∂/∂x(k ∂θ/∂x) + ∂/∂z(k ∂θ/∂z)

with θ = 0 far below the surface and where material enters the domain, and the heat flux
from the film (or an imposed one) at z = 0. The finite-volume depth grid here puts a node
on the coating–substrate interface, so each cell is of one material; the energy
equation is assembled in :mod:`tribodyn.contact.ehl.energy`.

Effusivity e = √(kρc) and diffusivity κ = k/(ρc) set the response: for a short heat pulse
a coating of lower effusivity than its substrate heats more at the surface (reflection
coefficient R = (e_c − e_s)/(e_c + e_s) < 0 in the layered-solid solution).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._validation import InputError, check_positive
from . import limits as L

__all__ = ["ThermalProperties", "ThermalBody", "DepthGrid", "depth_grid", "LIMITS"]

#: the ranges :class:`ThermalProperties` checks, by argument
LIMITS = {
    "conductivity": L.SOLID_CONDUCTIVITY,
    "density": L.SOLID_DENSITY,
    "specific_heat": L.SOLID_SPECIFIC_HEAT,
}


@dataclass(frozen=True)
class ThermalProperties:
    """Thermal conductivity k [W/(m K)], density ρ [kg/m³], specific heat c [J/(kg K)]."""

    conductivity: float
    density: float
    specific_heat: float

    def __post_init__(self):
        L.check_fields(self, LIMITS)

    @property
    def volumetric_heat_capacity(self) -> float:
        """ρc [J/(m³ K)]."""
        return self.density * self.specific_heat

    @property
    def diffusivity(self) -> float:
        """κ = k/(ρc) [m²/s]."""
        return self.conductivity / self.volumetric_heat_capacity


@dataclass(frozen=True)
class ThermalBody:
    """Thermal model of one body: a substrate with an optional coating layer."""

    substrate: ThermalProperties
    coating: ThermalProperties | None = None
    thickness: float = 0.0

    def __post_init__(self):
        if not isinstance(self.substrate, ThermalProperties):
            raise InputError("substrate must be ThermalProperties")
        if self.coating is not None:
            if not isinstance(self.coating, ThermalProperties):
                raise InputError("coating must be ThermalProperties or None")
            check_positive("thickness", self.thickness, "m")
        elif self.thickness:
            raise InputError("thickness given without a coating")

    @property
    def surface(self) -> ThermalProperties:
        return self.coating if self.coating is not None else self.substrate


@dataclass(frozen=True)
class DepthGrid:
    """Nodes s₀ = 0 (surface) … s_n = depth (θ = 0 there) and the cells between them.

    k, rc : conductivity and ρc of each cell (s_j, s_j+1) [n cells]."""

    s: np.ndarray
    k: np.ndarray
    rc: np.ndarray

    @property
    def cells(self) -> np.ndarray:
        return np.diff(self.s)

    def _node_sum(self, per_cell: np.ndarray) -> np.ndarray:
        """Σ over the control volume of nodes 0…n−1 of a per-cell property × length:
        node j gets half of cells j−1 and j (node 0: half of cell 0)."""
        c = 0.5 * per_cell * self.cells
        out = c.copy()
        out[1:] += c[:-1]
        return out

    def node_capacity(self) -> np.ndarray:
        """ρc × control-volume length of nodes 0…n−1 [J/(m² K)] (node 0: half cell)."""
        return self._node_sum(self.rc)

    def node_x_conductance(self) -> np.ndarray:
        """k × control-volume length of nodes 0…n−1 [W/K] (x conduction)."""
        return self._node_sum(self.k)

    def face_conductance(self) -> np.ndarray:
        """k/L of each cell [W/(m² K)] (conductance between nodes j and j+1)."""
        return self.k / self.cells


def depth_grid(body: ThermalBody, depth: float, first: float, n: int) -> DepthGrid:
    """Depth nodes from 0 to ``depth`` [m]: the first cell ``first`` [m] thick, growing
    geometrically; a coating is resolved by at least four uniform cells and its interface
    is a node."""
    depth = check_positive("depth", depth, "m")
    first = min(check_positive("first", first, "m"), depth / 4.0)
    n = int(n)
    if n < 6:
        raise InputError(f"solid nodes must be >= 6 (got {n})")
    nodes: list[float] = [0.0]
    if body.coating is not None and body.thickness < depth:
        nc = max(4, int(math.ceil(body.thickness / first)))
        nc = min(nc, n // 2)
        nodes += list(np.linspace(0.0, body.thickness, nc + 1)[1:])
        first = body.thickness / nc
    m = n - (len(nodes) - 1)
    start, rest = nodes[-1], depth - nodes[-1]
    if m >= 1 and rest > 0:
        # geometric cells: first·(r^m − 1)/(r − 1) = rest
        if first * m >= rest:
            r = 1.0
        else:
            lo, hi = 1.0 + 1e-9, 10.0
            for _ in range(80):
                r = 0.5 * (lo + hi)
                if first * (r**m - 1.0) / (r - 1.0) > rest:
                    hi = r
                else:
                    lo = r
        cells = first * r ** np.arange(m) if r != 1.0 else np.full(m, rest / m)
        cells *= rest / cells.sum()
        nodes += list(start + np.cumsum(cells))
    s = np.asarray(nodes)
    mid = 0.5 * (s[1:] + s[:-1])
    in_coat = (mid < body.thickness) if body.coating is not None else np.zeros(mid.size, bool)
    sub, coat = body.substrate, body.coating
    k = np.where(in_coat, coat.conductivity if coat else 0.0, sub.conductivity)
    rc = np.where(
        in_coat, coat.volumetric_heat_capacity if coat else 0.0, sub.volumetric_heat_capacity
    )
    return DepthGrid(s, k.astype(float), rc.astype(float))

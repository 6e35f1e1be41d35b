"""One surface set of a case, ready for the solvers (:class:`SurfaceSet`; built by
:class:`~tribodyn.config.Case`, held by :class:`~tribodyn.config.build.BuiltCase`)."""

from __future__ import annotations

from dataclasses import dataclass

from ..physics import typical
from ..physics.asperity import Roughness
from ..physics.materials import Body, Coating

__all__ = ["SurfaceSet"]


@dataclass(frozen=True)
class SurfaceSet:
    """One surface set, ready for the solvers.

    name : identifier from the case.
    bodies : (cam, tappet) — the cam is uncoated, the tappet carries the coating.
    roughness : composite Greenwood–Tripp roughness of the pair (None: smooth).
    boundary_shear_coefficient : ς of Eq. 17 [-].
    coating_label : display label, e.g. ``"DLC 4 µm"`` or ``"uncoated"``.
    boundary_shear_strength : τ₀ of Eq. 17 [Pa].
    coating_material : key of the coating in the case's ``[materials]`` (None: uncoated).
    asperity_law : which asperity law the set uses, and why.
    """

    name: str
    bodies: tuple[Body, Body]
    roughness: Roughness | None
    boundary_shear_coefficient: float
    coating_label: str
    boundary_shear_strength: float = typical.BOUNDARY_SHEAR_STRENGTH.value
    coating_material: str | None = None
    #: which asperity law the set uses and why (for the run's output)
    asperity_law: str = ""

    @property
    def cam(self) -> Body:
        return self.bodies[0]

    @property
    def tappet(self) -> Body:
        return self.bodies[1]

    @property
    def coating(self) -> Coating | None:
        return self.bodies[1].coating

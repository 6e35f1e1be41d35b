"""Elastic materials, coatings and contacting bodies.

Conventions (docs/conventions.md, paper Eq. 10):

* plane-strain compliance of one body  c = (1 − ν²)/E            [1/Pa]
* reduced modulus of a pair            1/E' = ½ (c₁ + c₂)         [Pa]   (so E' = 2E*)
* half-plane surface compliance FRF    g̃(m) = 2c/|m|  per body,  Σ = 4/(E'|m|)  (Eq. 12)
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import TypeAlias

from .._validation import InputError
from . import typical_engine
from .limits import COATING_THICKNESS, POISSON_RATIO, YOUNGS_MODULUS, check_fields, unchecked

__all__ = ["Material", "Coating", "Body", "as_bodies", "reduced_modulus", "STEEL", "DLC", "WCC"]


_ELASTIC_LIMITS = {"E": YOUNGS_MODULUS, "nu": POISSON_RATIO}


@dataclass(frozen=True)
class Material:
    """Isotropic linear-elastic material.

    Parameters
    ----------
    E : Young's modulus [Pa], 1e6 … 2e12 (``limits.YOUNGS_MODULUS``).
    nu : Poisson's ratio [-], in (−1, 0.5).
    """

    E: float
    nu: float

    def __post_init__(self):
        check_fields(self, _ELASTIC_LIMITS)

    @property
    def compliance(self) -> float:
        """Plane-strain compliance (1 − ν²)/E [1/Pa]."""
        return (1.0 - self.nu**2) / self.E

    @property
    def shear_modulus(self) -> float:
        """μ = E / (2(1 + ν)) [Pa]."""
        return self.E / (2.0 * (1.0 + self.nu))


@dataclass(frozen=True)
class Coating(Material):
    """A uniform elastic layer perfectly bonded to a substrate.

    Parameters
    ----------
    E, nu : elastic constants of the coating [Pa], [-].
    thickness : layer thickness h_c [m], in (0, 1e-2].
    """

    thickness: float

    def __post_init__(self):
        check_fields(self, {**_ELASTIC_LIMITS, "thickness": COATING_THICKNESS})

    @classmethod
    def of(cls, material: Material, thickness: float) -> Coating:
        """A layer of ``material`` (E, ν checked when it was built), ``thickness`` [m]
        thick: only the thickness is checked."""
        layer = unchecked(cls, E=material.E, nu=material.nu, thickness=thickness)
        check_fields(layer, {"thickness": COATING_THICKNESS})
        return layer

    @property
    def material(self) -> Material:
        return unchecked(Material, E=self.E, nu=self.nu)


@dataclass(frozen=True)
class Body:
    """A contacting body: a substrate material with an optional coating on its surface."""

    material: Material
    coating: Coating | None = None

    def __post_init__(self):
        if not isinstance(self.material, Material) or isinstance(self.material, Coating):
            raise InputError(f"material must be a Material (got {type(self.material).__name__})")
        if self.coating is not None and not isinstance(self.coating, Coating):
            raise InputError(
                f"coating must be a Coating or None (got {type(self.coating).__name__})"
            )

    @property
    def surface(self) -> Material:
        """The material at the surface (coating if present): governs asperity contact."""
        return self.coating.material if self.coating is not None else self.material

    @property
    def is_coated(self) -> bool:
        return self.coating is not None


#: The two bodies of a contact, (cam, tappet): a tuple or any sequence of two Body.
BodyPair: TypeAlias = "Sequence[Body]"


def as_bodies(bodies: BodyPair) -> tuple[Body, Body]:
    """``bodies`` as a validated pair (Body, Body)."""
    try:
        bodies = tuple(bodies)
    except TypeError:
        raise InputError(f"bodies must be a pair (Body, Body) (got {bodies!r})") from None
    if len(bodies) != 2 or not all(isinstance(b, Body) for b in bodies):
        raise InputError(f"bodies must be a pair (Body, Body) (got {bodies!r})")
    return bodies


def reduced_modulus(bodies: BodyPair, *, surface: bool = False) -> float:
    """Reduced modulus E' of a pair: 1/E' = ½[(1−ν₁²)/E₁ + (1−ν₂²)/E₂] [Pa].

    ``surface=False`` uses the substrate (bulk) materials, as Hertz theory for a thin
    coating; ``surface=True`` uses the surface materials (the coating where present),
    as for asperity-scale contact (Greenwood–Tripp, paper Eq. 6).
    """
    b1, b2 = as_bodies(bodies)
    m1, m2 = (b1.surface, b2.surface) if surface else (b1.material, b2.material)
    return 2.0 / (m1.compliance + m2.compliance)


# Typical materials (tribodyn.physics.typical, with their sources); the paper's Table 6
# is stated in its case file, cases/andreou2023.toml.
STEEL = Material(E=typical_engine.STEEL_MODULUS.value, nu=typical_engine.STEEL_POISSON.value)
DLC = Material(E=typical_engine.DLC_MODULUS.value, nu=typical_engine.COATING_POISSON.value)
WCC = Material(E=typical_engine.WCC_MODULUS.value, nu=typical_engine.COATING_POISSON.value)

"""Flexible valvetrain bodies from geometry and material (paper Section 2.3, Table 3).

The paper's multi-body model makes every body flexible by component mode synthesis
(Craig–Bampton, its ref. 23) and joins them with axial-bearing ("AXBE") joints. Here:

* **valve** — stem as axial bar elements (collet groove → stem end), the retainer,
  collets and stem end above the groove as a point mass at the groove, the head as a mass
  behind a head stiffness (head and fillet compliance between stem end and seat face).
  Interfaces: groove (tappet joint and spring seat), seat face (valve seat).
* **tappet** — ``model = "fe"``: crown (a rigid disc) and skirt (a tube hanging from the
  crown, axial bars); interface: the face. ``model = "lumped"``: one rigid mass. Crown
  bending and axial compliance, shim, and the stem above the groove act in series in the
  tappet–valve joint.
* **spring** — :class:`~tribodyn.valvetrain.spring.HelicalSpring` (continuum with coil
  clash); interfaces: both ends and the nodes of coils that can close.
* **camshaft** — :class:`~tribodyn.valvetrain.camshaft.Camshaft` (optional).

Each FE body is reduced by Craig–Bampton (:func:`tribodyn.valvetrain.fe.craig_bampton`)
with its own number of fixed-interface modes (or a frequency cut-off) and modal damping.
The joints (unilateral cam contact, tappet–valve, valve seat, spring seat and support,
bore friction) keep the meaning and values of :class:`ValvetrainParameters`, which
:class:`FlexibleValvetrain` carries as ``joints``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import ClassVar

import numpy as np

from .._validation import InputError, check_positive
from ..physics import typical_engine
from .camshaft import Camshaft
from .fe import AxialFEModel, ModalBody, ReducedBody, check_count
from .parameters import ValvetrainParameters
from .spring import HelicalSpring

__all__ = ["ValveGeometry", "TappetGeometry", "FlexibleValvetrain"]

STEEL_DENSITY = typical_engine.STEEL_DENSITY.value  # kg/m³ (typical steel, assumed)
STEEL_E = typical_engine.STEEL_MODULUS.value  # Pa (typical steel, with its source)


@dataclass(frozen=True)
class ValveGeometry(ModalBody):
    """Poppet valve: stem_diameter, stem_length (tip to stem end) [m], retainer_position
    (tip to collet groove) [m], retainer_mass (retainer + collets) [kg], head_mass [kg],
    head_stiffness [N/m], seat_stiffness (seat insert + seat contact) [N/m], E [Pa],
    density [kg/m³], elements (stem bar elements); modes, cutoff, damping_ratio
    (:class:`~tribodyn.valvetrain.fe.ModalBody`)."""

    stem_diameter: float
    stem_length: float
    retainer_position: float
    retainer_mass: float
    head_mass: float
    head_stiffness: float
    seat_stiffness: float
    E: float = STEEL_E
    density: float = STEEL_DENSITY
    elements: int = 12

    def __post_init__(self):
        for n, u in (
            ("stem_diameter", "m"),
            ("stem_length", "m"),
            ("retainer_position", "m"),
            ("retainer_mass", "kg"),
            ("head_mass", "kg"),
            ("head_stiffness", "N/m"),
            ("seat_stiffness", "N/m"),
            ("E", "Pa"),
            ("density", "kg/m³"),
        ):
            check_positive(n, getattr(self, n), u)
        if self.retainer_position >= self.stem_length:
            raise InputError(
                f"retainer_position must be < stem_length (got "
                f"{self.retainer_position:g} m >= {self.stem_length:g} m)"
            )
        check_count("elements", self.elements, 2, 400)
        self._check_modal()

    @property
    def stem_area(self) -> float:
        return 0.25 * math.pi * self.stem_diameter**2

    @property
    def mass(self) -> float:
        """Valve + retainer + collets [kg]."""
        return (
            self.density * self.stem_area * self.stem_length + self.head_mass + self.retainer_mass
        )

    def fe_model(self) -> AxialFEModel:
        """Stem from the collet groove to the stem end as ``elements`` bars, retainer,
        collets and the stem end above the groove as point masses on the groove node,
        the head mass behind the head stiffness. The short stem end above the groove
        (tip to groove) acts as a spring in series with the tappet–valve joint
        (:attr:`tip_stiffness`): its own axial modes (> 100 kHz) are far above anything a
        cam excites and would only make the equations stiffer."""
        m = AxialFEModel("valve")
        ret = m.node("retainer")
        end = m.bar(
            ret,
            self.stem_length - self.retainer_position,
            self.E,
            self.stem_area,
            self.density,
            self.elements,
            "stem_end",
        )
        seat = m.node("seat")
        m.spring(end, seat, self.head_stiffness)
        m.mass(seat, self.head_mass)
        m.mass(ret, self.retainer_mass + self.density * self.stem_area * self.retainer_position)
        return m

    @property
    def tip_stiffness(self) -> float:
        """EA/l of the stem from the tip to the collet groove [N/m]."""
        return self.E * self.stem_area / self.retainer_position

    @property
    def stem_stiffness_below_retainer(self) -> float:
        """EA/L of the stem from the groove to the stem end [N/m]."""
        return self.E * self.stem_area / (self.stem_length - self.retainer_position)


@dataclass(frozen=True)
class TappetGeometry(ModalBody):
    """Bucket tappet: ``model`` "fe" (crown + skirt bars) or "lumped" (one mass ``mass``);
    radius (outer) [m], crown_thickness, skirt_length, skirt_thickness [m], E [Pa],
    density [kg/m³], elements (skirt; the crown gets 2); modes, cutoff, damping_ratio
    (:class:`~tribodyn.valvetrain.fe.ModalBody`)."""

    model: str = "fe"
    mass: float | None = None
    radius: float = 0.0165
    crown_thickness: float = 0.0035
    skirt_length: float = 0.02
    skirt_thickness: float = 0.001
    E: float = STEEL_E
    density: float = STEEL_DENSITY
    elements: int = 6

    def __post_init__(self):
        if self.model not in ("fe", "lumped"):
            raise InputError(f"tappet model must be 'fe' or 'lumped' (got {self.model!r})")
        if self.model == "lumped":
            if self.mass is None:
                raise InputError("tappet mass is required with model = 'lumped'")
            check_positive("mass", self.mass, "kg")
            return
        for n, u in (
            ("radius", "m"),
            ("crown_thickness", "m"),
            ("skirt_length", "m"),
            ("skirt_thickness", "m"),
            ("E", "Pa"),
            ("density", "kg/m³"),
        ):
            check_positive(n, getattr(self, n), u)
        if self.skirt_thickness >= self.radius:
            raise InputError("skirt_thickness must be below the tappet radius")
        check_count("elements", self.elements, 1, 400)
        self._check_modal()

    @property
    def total_mass(self) -> float:
        if self.model == "lumped":
            return float(self.mass)  # type: ignore[arg-type]  # required there (__post_init__)
        r, t = self.radius, self.skirt_thickness
        crown = math.pi * r * r * self.crown_thickness
        skirt = math.pi * (r * r - (r - t) ** 2) * self.skirt_length
        return self.density * (crown + skirt)

    def fe_model(self) -> AxialFEModel:
        """The crown as a rigid disc on the face node, the skirt as ``elements`` bars
        hanging from it ("lumped": the tappet mass on the face node). The crown's own
        axial compliance (t/(EA) ≈ 2e-11 m/N, modes > 300 kHz) is added to the tappet–valve
        joint with the crown bending (:attr:`crown_stiffness`)."""
        m = AxialFEModel("tappet")
        face = m.node("face")
        if self.model == "lumped":
            m.mass(face, self.total_mass)
            return m
        r, t = self.radius, self.skirt_thickness
        m.mass(face, self.density * math.pi * r * r * self.crown_thickness)
        m.bar(
            face,
            self.skirt_length,
            self.E,
            math.pi * (r * r - (r - t) ** 2),
            self.density,
            self.elements,
            "skirt_end",
        )
        return m

    @property
    def crown_stiffness(self) -> float | None:
        """Axial stiffness EA/t of the crown disc [N/m] (None for the lumped tappet)."""
        if self.model == "lumped":
            return None
        return self.E * math.pi * self.radius**2 / self.crown_thickness


@dataclass(frozen=True)
class FlexibleValvetrain:
    """The flexible valvetrain: bodies + the joint parameters of ``joints``.

    ``joints`` supplies the cam contact law (Palmgren or linear, damping), tappet–valve
    joint (crown bending + shim + tip), lash, valve-seat damping, spring seat and support
    stiffness, damping ramp, bore friction, tappet radius and cam width; its masses,
    spring rate, preload, seat and camshaft stiffness are not used (they follow from the
    bodies). ``camshaft`` None: rigid camshaft.
    """

    valve: ValveGeometry
    tappet: TappetGeometry
    spring: HelicalSpring
    joints: ValvetrainParameters = ValvetrainParameters()
    camshaft: Camshaft | None = None

    def __post_init__(self):
        for name, cls in (
            ("valve", ValveGeometry),
            ("tappet", TappetGeometry),
            ("spring", HelicalSpring),
            ("joints", ValvetrainParameters),
        ):
            if not isinstance(getattr(self, name), cls):
                raise InputError(f"{name} must be a {cls.__name__}")
        if self.camshaft is not None and not isinstance(self.camshaft, Camshaft):
            raise InputError("camshaft must be a Camshaft or None")

    # what the dynamics' shared code reads from its parameters
    @property
    def cam_width(self) -> float:
        return self.joints.cam_width

    @property
    def tappet_radius(self) -> float:
        return self.joints.tappet_radius

    @property
    def spring_preload(self) -> float:
        return self.spring.preload

    @property
    def tappet_valve_stiffness(self) -> float:
        """The tappet–valve joint: the case's tappet_valve_stiffness (crown bending, shim,
        tip contact) in series with the crown's axial stiffness and the stem above the
        collet groove [N/m]."""
        c = 1.0 / self.joints.tappet_valve_stiffness + 1.0 / self.valve.tip_stiffness
        if self.tappet.crown_stiffness is not None:
            c += 1.0 / self.tappet.crown_stiffness
        return 1.0 / c

    def replace(self, **changes) -> FlexibleValvetrain:
        return replace(self, **changes)

    # -- reduced bodies -------------------------------------------------------------------
    def reduced_bodies(self, max_lift: float) -> dict[str, ReducedBody]:
        """Craig–Bampton reduction of valve, tappet and spring (boundary order: valve
        [seat, groove], tappet [face], spring [top, clash…, bottom])."""
        v, t, s = self.valve, self.tappet, self.spring
        out = {}
        fv = v.fe_model()
        out["valve"] = v.reduce(fv, [fv.labels[k] for k in ("seat", "retainer")], "valve")
        ft = t.fe_model()
        out["tappet"] = t.reduce(ft, [ft.labels["face"]], "tappet")
        fs = s.fe_model()
        clash = s.clash_nodes(s.statics(s.installed_compression + max_lift).force)  # at peak lift
        bs = [0] + [j for j in clash if 0 < j < fs.n - 1] + [fs.n - 1]
        out["spring"] = s.reduce(fs, bs, "spring")
        return out

    # -- the lumped companion --------------------------------------------------------------
    #: the lumped companion (:meth:`lumped_equivalent`) differs from it: compare the two
    has_lumped_companion: ClassVar[bool] = True

    def surge_frequencies(self, modes: int = 3) -> np.ndarray:
        """The first ``modes`` surge frequencies [Hz]: the spring's continuum, both ends
        fixed at the installed length (:meth:`HelicalSpring.surge_frequencies`)."""
        return self.spring.surge_frequencies(self.spring.installed_compression, modes)

    def spring_advice(self) -> str:
        """The case keys that set the spring's preload and rate (its geometry)."""
        return "the spring's preload and rate ([valvetrain.spring] installed_length, wire_diameter)"

    def lumped_equivalent(self) -> ValvetrainParameters:
        """:class:`ValvetrainParameters` with the same masses, spring rate, preload and
        static compliances: valve mass incl. retainer, tappet mass, active spring mass
        and rate, installed preload; valve-seat stiffness = stem below the groove, head
        and seat in series; camshaft bending in series with the contact. The lumped spring
        gets 8 coil masses and the spring's surge damping ratio."""
        v = self.valve
        k_seat = 1.0 / (
            1.0 / v.stem_stiffness_below_retainer + 1.0 / v.head_stiffness + 1.0 / v.seat_stiffness
        )
        cs = self.camshaft
        k_cam = None if cs is None else 1.0 / cs.bending_compliance
        return self.joints.replace(
            tappet_valve_stiffness=self.tappet_valve_stiffness,
            valve_mass=v.mass,
            tappet_mass=self.tappet.total_mass,
            spring_mass=self.spring.active_mass,
            spring_rate=self.spring.rate,
            spring_preload=self.spring.preload,
            spring_damping_ratio=self.spring.damping_ratio,
            seat_stiffness=k_seat,
            camshaft_stiffness=k_cam,
        )

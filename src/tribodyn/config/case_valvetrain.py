"""Builders of the cam, the valvetrain and the dynamics' options and explicit tribology from
a validated case (:class:`~tribodyn.config.case.Case` inherits them).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from .._validation import InputError
from ..valvetrain.cam_tabulated import TabulatedCam
from ..valvetrain.cams import AccelerationCam, CamProfile, CircularArcCam
from ..valvetrain.camshaft import Camshaft
from ..valvetrain.flexible import FlexibleValvetrain, TappetGeometry, ValveGeometry
from ..valvetrain.parameters import ValvetrainParameters
from ..valvetrain.spring import HelicalSpring
from .errors import CaseKeyError
from .schema import SpringConfig, TappetConfig, ValveConfig

if TYPE_CHECKING:
    from pathlib import Path

    from ..physics.lubricant import Lubricant
    from ..valvetrain.tribology import AnalyticTribology
    from .schema import CamConfig, Engine, Numerics, Valvetrain
    from .surface_set import SurfaceSet


class CamValvetrainBuilders:
    """The cam profile, valvetrain parameters (lumped or flexible), dynamics options and
    explicit tribology of a :class:`~tribodyn.config.case.Case`."""

    if TYPE_CHECKING:  # the fields and methods of Case these builders use
        cam_config: CamConfig
        valvetrain: Valvetrain
        numerics: Numerics
        engine: Engine

        @property
        def cam_table_path(self) -> Path | None: ...

    def _build_cam(self) -> CamProfile:
        c = self.cam_config
        tr = self.valvetrain.tappet_radius
        if c.type != "table":  # its keys are the cam's arguments (*_deg: in degrees)
            cam_type = AccelerationCam if c.type == "acceleration" else CircularArcCam
            keys = c.model_dump(exclude={"type", "material", "width"})
            args = {
                k.removesuffix("_deg"): math.radians(v) if k.endswith("_deg") else v
                for k, v in keys.items()
            }
            return cam_type(**args, tappet_radius=tr)
        try:
            cam = TabulatedCam.from_csv(
                self.cam_table_path,
                c.base_radius,
                smoothing=c.smoothing,
                angle_unit=c.angle_unit,
                lift_unit=c.lift_unit,
                angle_column=c.angle_column,
                lift_column=c.lift_column,
                tappet_radius=tr,
            )
        except InputError as exc:  # the table's own message, filed under cam.path
            msg = str(exc)
            if str(self.cam_table_path) not in msg:
                msg = f"{self.cam_table_path}: {msg}"
            raise CaseKeyError("cam.path", msg) from None
        if c.max_lift is not None and abs(cam.max_lift / c.max_lift - 1.0) > 0.01:
            raise CaseKeyError(
                "cam.max_lift",
                f"{c.max_lift:g} m disagrees with the lift "
                f"table's maximum {cam.max_lift:g} m by more "
                "than 1 %",
            )
        return cam

    def _new_valvetrain_parameters(self) -> ValvetrainParameters | FlexibleValvetrain:
        """The valvetrain of the case: :class:`~tribodyn.valvetrain.ValvetrainParameters`
        (``model = "lumped"``) or :class:`~tribodyn.valvetrain.flexible.FlexibleValvetrain`
        (``"flexible"``); either runs in :func:`~tribodyn.valvetrain.simulate_valvetrain`."""
        d = self.valvetrain.model_dump(exclude={"model", "valve", "tappet", "spring", "camshaft"})
        joints = ValvetrainParameters(**d, cam_width=self.cam_config.width)
        return joints if self.valvetrain.model == "lumped" else self._flexible(joints)

    def _flexible(self, joints: ValvetrainParameters) -> FlexibleValvetrain:
        v = self.valvetrain
        vc = v.valve or ValveConfig()
        tc = v.tappet or TappetConfig()
        sc = v.spring or SpringConfig()
        valve = ValveGeometry(**vc.model_dump())
        tappet = TappetGeometry(**tc.model_dump(), radius=v.tappet_radius)
        sd = sc.model_dump()
        sd["pitches"] = None if sd["pitches"] is None else tuple(sd["pitches"])
        spring = HelicalSpring(**sd)
        cs = None if v.camshaft is None else Camshaft(**v.camshaft.model_dump())
        return FlexibleValvetrain(valve, tappet, spring, joints, cs)

    def _new_dynamics_options(self) -> dict:
        """Keyword arguments of :func:`~tribodyn.valvetrain.simulate_valvetrain` from the
        case (engine speed and ``[numerics]``)."""
        n = self.numerics
        return dict(
            engine_speed=self.engine.speed_rpm,
            cycles=n.cycles,
            output_step=n.output_step_deg,
            method=n.dynamics_method,
            rtol=n.dynamics_rtol,
            max_step=n.max_step_deg,
        )

    def _new_analytic_tribology(self, s: SurfaceSet, lubricant: Lubricant) -> AnalyticTribology:
        """Explicit tribology of the dynamics for one surface set
        (:class:`~tribodyn.valvetrain.AnalyticTribology` over the cam width)."""
        from ..valvetrain.tribology import AnalyticTribology

        n = self.numerics
        return AnalyticTribology(
            self.cam_config.width,
            bodies=s.bodies,
            lubricant=lubricant,
            roughness=s.roughness,
            boundary_shear_coefficient=s.boundary_shear_coefficient,
            boundary_shear_strength=s.boundary_shear_strength,
            viscous_model=n.viscous_model,
            film_formula=n.film_formula,
            limiting_shear=n.limiting_shear,
        )

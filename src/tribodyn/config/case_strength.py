"""Builders of the materials' strength and wear coefficients from a validated case
(:class:`~tribodyn.config.case.Case` inherits them): ``[strength.<material>]`` over the
typical values of :mod:`tribodyn.physics.strength`.
"""

from __future__ import annotations

import dataclasses
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    from .schema import CamConfig, StrengthConfig, SurfaceSetConfig


class StrengthBuilders:
    """The strengths and Archard wear coefficients of a :class:`~tribodyn.config.case.Case`'s
    materials."""

    if TYPE_CHECKING:  # the fields and methods of Case these builders use
        strength_configs: dict[str, StrengthConfig]
        cam_config: CamConfig

    def _new_material_strength(self, name: str):
        """:class:`~tribodyn.physics.strength.Strength` of material ``name``: the keys of
        ``[strength.<name>]`` over the typical values of steel, dlc or wcc when the
        material has that name; None when neither gives a tensile strength and a
        hardness."""
        from ..physics.strength import TYPICAL_STRENGTH, Strength

        base = TYPICAL_STRENGTH.get(name.lower())
        cfg = self.strength_configs.get(name)
        given = cfg.model_dump(exclude_none=True) if cfg is not None else {}
        given.pop("wear_coefficient", None)
        vals = dataclasses.asdict(base) if base is not None else {}
        vals.update(given)
        if given:
            vals["source"] = f"case [strength.{name}]" + (
                f"; otherwise {base.source}" if base else ""
            )
        if "tensile_strength" not in vals or "hardness" not in vals:
            return None
        return Strength(**vals)

    def _new_strengths(self, cfg: SurfaceSetConfig) -> dict:
        """{"cam": (substrate, None), "tappet": (substrate, coating)} strengths of a
        surface set for :func:`~tribodyn.workflow.stress_study.stress_along_cycle`."""
        cam = self._new_material_strength(self.cam_config.material)
        sub = self._new_material_strength(cfg.substrate)
        coat = self._new_material_strength(cfg.coating) if cfg.coating is not None else None
        return {"cam": (cam, None), "tappet": (sub, coat)}

    def _new_wear_coefficient(self, cfg: SurfaceSetConfig) -> tuple[float | None, str]:
        """Archard coefficient k [m³/(N m)] of the tappet's surface material (coating, or
        substrate if uncoated) and where it comes from: the case's ``[strength.<m>]``,
        else the ASSUMED typical value of physics.strength for steel, dlc, wcc (labelled
        so), else None."""
        from ..physics.strength import TYPICAL_WEAR_COEFFICIENT

        mat = cfg.coating if cfg.coating is not None else cfg.substrate
        sc = self.strength_configs.get(mat)
        if sc is not None and sc.wear_coefficient is not None:
            return float(sc.wear_coefficient), f"case [strength.{mat}]"
        k = TYPICAL_WEAR_COEFFICIENT.get(mat.lower())
        if k is not None:
            return float(k), "assumed typical value (tribodyn.physics.strength), not measured"
        return None, ""

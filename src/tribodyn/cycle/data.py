"""The data of an EHL pass along the cam cycle (:mod:`.driver`): the sampled cycle
(:class:`CycleInputs`, per sample :class:`SampleConditions`), the per-set result
(:class:`SetCycleResult`) and the outputs every sample records (:data:`SAMPLE_OUTPUTS`).

Outputs are totals over the cam width: loads and friction forces [N], friction power
P = (F_v + F_b) u_s [W]; films [m]; pressures [Pa].
"""

from __future__ import annotations

from dataclasses import dataclass, field, fields, replace
from typing import Any

import numpy as np

from .._validation import InputError


@dataclass(frozen=True)
class SampleConditions:
    """Conjunction conditions at one time (:meth:`CycleInputs.at`)."""

    force: float  #: contact force, total over the width [N]
    entrainment_speed: float  #: [m/s]
    sliding_speed: float  #: [m/s]
    radius: float  #: radius of curvature [m]


@dataclass
class CycleInputs:
    """Conjunction conditions over the presented cycle (from the dynamics)."""

    crank_angle: np.ndarray  #: [deg], strictly increasing
    time: np.ndarray  #: [s]
    contact_force: np.ndarray  #: total over the width [N]
    entrainment_speed: np.ndarray  #: [m/s]
    sliding_speed: np.ndarray  #: [m/s]
    radius: np.ndarray  #: radius of curvature [m]
    width: float  #: cam width [m]
    #: the dynamics' own output (time, F, u_e, u_s, R) at its finer output step, for
    #: conditions between the samples (sub-steps); None: interpolate the samples
    fine: tuple | None = None
    #: contact offset e = s' at the samples and at the fine output [m], and the cam
    #: speed ω [rad/s]: what :meth:`with_rotation` needs (None: not known)
    contact_offset: np.ndarray | None = None
    fine_contact_offset: np.ndarray | None = None
    cam_speed: float | None = None
    #: share s_x/|s| of the friction force against the cam's rotation (tappet rotation;
    #: None: 1, the friction acts along the cam motion)
    torque_share: np.ndarray | None = None
    #: the tappet rotation these speeds already include (None: a tappet that does not turn)
    rotation: Any = None

    def at(self, t: float) -> SampleConditions:
        """The conditions at time t [s] (linear interpolation of the finest data
        available)."""
        if self.fine is not None:
            tt, *cols = self.fine
        else:
            tt, cols = (
                self.time,
                [self.contact_force, self.entrainment_speed, self.sliding_speed, self.radius],
            )
        return SampleConditions(*(float(np.interp(t, tt, c)) for c in cols))

    def integral(self, values, where) -> float:
        """∫ v dt over the samples ``where``: Σ v_i Δt_i, Δt_i the central difference of
        the sample times (``np.gradient``, one-sided at the ends); a NaN value counts
        as 0 (e.g. friction power [W] → energy [J])."""
        return float(np.nansum(np.where(where, values, 0.0) * np.gradient(self.time)))

    @classmethod
    def from_dynamics(cls, res, crank_step_deg: float, width: float) -> CycleInputs:
        """Sample a :class:`~tribodyn.valvetrain.ValvetrainResult` every crank_step_deg."""
        c0, c1 = float(res.crank_angle[0]), float(res.crank_angle[-1])
        n = int(round((c1 - c0) / crank_step_deg)) + 1
        crank = c0 + crank_step_deg * np.arange(n)
        crank = crank[crank <= c1 + 1e-9]

        def at(v):
            return np.interp(crank, res.crank_angle, v)

        fine = (
            np.asarray(res.time, float),
            np.maximum(res.contact_force, 0.0),
            np.asarray(res.entrainment_speed, float),
            np.asarray(res.sliding_speed, float),
            np.asarray(res.radius_of_curvature, float),
        )
        e = getattr(res, "contact_offset", None)
        has_e = e is not None and len(e) == len(res.time)
        return cls(
            crank,
            at(res.time),
            np.maximum(at(res.contact_force), 0.0),
            at(res.entrainment_speed),
            at(res.sliding_speed),
            at(res.radius_of_curvature),
            float(width),
            fine,
            contact_offset=at(e) if has_e else None,
            fine_contact_offset=np.asarray(e, float) if has_e else None,
            cam_speed=getattr(res, "cam_speed", None),
        )

    def with_rotation(self, rotation) -> CycleInputs:
        """The inputs of a rotating bucket tappet
        (:class:`~tribodyn.valvetrain.tappet_rotation.TappetRotation`): u_e' = u_e +
        ω_t e_o/2 and the sliding speed |s| = √((u_s − ω_t e_o)² + (ω_t e)²) with the
        sign of its x part; :attr:`torque_share` = s_x/|s|. Unchanged when the tappet
        does not turn."""
        if rotation is None or not rotation.active or rotation == self.rotation:
            return self
        if self.rotation is not None:
            raise InputError(
                f"the inputs already include the tappet rotation {self.rotation}; "
                f"cannot apply {rotation} on top"
            )
        if self.contact_offset is None or self.cam_speed is None:
            raise InputError(
                "tappet rotation needs the contact offset and cam speed of the dynamics"
            )
        v = rotation.speeds(
            self.cam_speed, self.contact_offset, self.entrainment_speed, self.sliding_speed
        )
        fine = self.fine
        if fine is not None and self.fine_contact_offset is not None:
            tt, F, ue, us, R = fine
            vf = rotation.speeds(self.cam_speed, self.fine_contact_offset, ue, us)
            fine = (tt, F, vf.entrainment_speed, vf.signed_sliding_speed, R)
        return replace(
            self,
            entrainment_speed=v.entrainment_speed,
            sliding_speed=v.signed_sliding_speed,
            fine=fine,
            torque_share=v.torque_share,
            rotation=rotation,
        )


@dataclass
class SetCycleResult:
    """Transient EHL results of one surface set over the cycle (totals over the width)."""

    name: str
    label: str
    crank_angle: np.ndarray
    loaded: np.ndarray
    converged: np.ndarray
    iterations: np.ndarray
    central_film: np.ndarray
    min_film: np.ndarray
    max_pressure: np.ndarray
    hydrodynamic_load: np.ndarray
    asperity_load: np.ndarray
    viscous_friction: np.ndarray
    viscous_friction_newtonian: np.ndarray  #: the same film and pressure, Newtonian law
    viscous_friction_eyring: np.ndarray  #: the same film and pressure, Eyring law
    boundary_friction: np.ndarray
    rolling_friction: np.ndarray
    friction_power: np.ndarray
    lambda_ratio: np.ndarray  #: h_min/σ
    x: np.ndarray  #: (crank, k) profile positions [m], NaN where unloaded
    pressure: np.ndarray  #: (crank, k) [Pa], NaN where unloaded
    film: np.ndarray  #: (crank, k) [m]
    failures: list = field(default_factory=list)  #: [(crank_deg, message)]
    #: validity warnings of converged steps, by kind: {kind: (count, first crank_deg, text)}
    validity: dict = field(default_factory=dict)
    runtime_s: float = 0.0
    #: solver steps taken to reach each sample (1: the sample step itself; more where the
    #: time-error control or an engagement subdivided it; 0 where unloaded)
    substeps: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))

    @property
    def friction(self) -> np.ndarray:
        return self.viscous_friction + self.boundary_friction


#: The per-sample scalar outputs of a :class:`SetCycleResult` (NaN where unloaded): its
#: fields from ``central_film`` to ``lambda_ratio``.
_FIELDS = [f.name for f in fields(SetCycleResult)]
SAMPLE_OUTPUTS = tuple(_FIELDS[_FIELDS.index("central_film") : _FIELDS.index("lambda_ratio") + 1])

"""Cam profiles, flat-follower kinematics and single-valvetrain dynamics.

Public API::

    from tribodyn.valvetrain import (AccelerationCam, CircularArcCam, TabulatedCam,
        flat_follower_kinematics, ValvetrainParameters, simulate_valvetrain, speed_sweep)
"""

from .cam_tabulated import TabulatedCam
from .cams import AccelerationCam, CamProfile, CircularArcCam
from .compare import compare_results
from .dynamics import ValvetrainResult, simulate_valvetrain
from .kinematics import (
    FlatFollowerKinematics,
    flat_follower_kinematics,
    quasi_static_jump_speed,
    rpm_to_cam_speed,
)
from .model import ContactLawError, ValvetrainModel
from .parameters import ValvetrainParameters
from .sweep import SpeedSweepResult, jump_speed, speed_sweep
from .tribology import (
    TYPICAL_ROUGHNESS,
    AnalyticTribology,
    FilmStateTribology,
    FilmTableTribology,
    Frictionless,
    TribologyModel,
)

__all__ = [
    "AccelerationCam",
    "CamProfile",
    "CircularArcCam",
    "TabulatedCam",
    "FlatFollowerKinematics",
    "flat_follower_kinematics",
    "quasi_static_jump_speed",
    "rpm_to_cam_speed",
    "ValvetrainParameters",
    "ValvetrainModel",
    "ContactLawError",
    "ValvetrainResult",
    "simulate_valvetrain",
    "SpeedSweepResult",
    "speed_sweep",
    "jump_speed",
    "compare_results",
    "TribologyModel",
    "Frictionless",
    "AnalyticTribology",
    "FilmStateTribology",
    "FilmTableTribology",
    "TYPICAL_ROUGHNESS",
]

"""The valvetrain API accepts what the case file accepts, and nothing else: every argument
of simulate_valvetrain and of the valvetrain model constructors is checked against the
ranges of tribodyn.physics.limits, with an InputError naming the argument and the range."""

import math

import numpy as np
import pytest

from tribodyn import InputError
from tribodyn.physics import limits as L
from tribodyn.valvetrain import (
    AccelerationCam,
    ValvetrainParameters,
    flat_follower_kinematics,
    quasi_static_jump_speed,
    simulate_valvetrain,
)
from tribodyn.valvetrain.model import ValvetrainModel
from tribodyn.valvetrain.tribology import AnalyticTribology

CAM = AccelerationCam()


@pytest.mark.parametrize(
    "kw, match",
    [
        ({"output_step": 720.0}, r"output_step must be > 0 and <= 5"),
        ({"output_step": 0.0}, r"output_step must be > 0"),
        ({"output_step": math.nan}, r"output_step"),
        ({"engine_speed": 1e7}, r"engine_speed must be > 0 and <= 50000 \[rpm\]"),
        ({"engine_speed": -5.0}, r"engine_speed must be > 0"),
        ({"cycles": 0}, r"cycles must be an integer >= 1 and <= 50"),
        ({"cycles": 51}, r"cycles must be an integer >= 1 and <= 50"),
        ({"cycles": 1.5}, r"cycles must be an integer"),
        ({"rtol": 0.5}, r"rtol must be > 0 and < 0.1"),
        ({"max_step": 90.0}, r"max_step must be > 0 and <= 10"),
        ({"atol": -1.0}, r"atol must be > 0 and <= 0.01"),
        ({"atol": [1e-9, 1e-9]}, r"atol must be a number or \d+ numbers"),
        ({"jump_lift_threshold": 1.0}, r"jump_lift_threshold must be > 0 and <= 0.001 \[m\]"),
        ({"start_angle": math.inf}, r"start_angle"),
        ({"method": "RK45"}, r"method must be 'LSODA', 'Radau' or 'BDF'"),
        ({"tribology": "implicit"}, r"tribology must be"),
    ],
)
def test_simulate_valvetrain_rejects_out_of_range_arguments(kw, match):
    with pytest.raises(InputError, match=match):
        simulate_valvetrain(CAM, ValvetrainParameters(), **kw)


def test_api_ranges_are_the_case_file_ranges():
    """The [numerics] keys of the case file use the same limits objects."""
    from tribodyn.config.schema import Numerics

    f = Numerics.model_fields
    for key, lim in (
        ("cycles", L.DYNAMICS_CYCLES),
        ("output_step_deg", L.OUTPUT_STEP),
        ("max_step_deg", L.MAX_STEP),
        ("dynamics_rtol", L.DYNAMICS_RTOL),
    ):
        got = {
            k: getattr(m, k)
            for m in f[key].metadata
            for k in ("gt", "ge", "lt", "le")
            if getattr(m, k, None) is not None
        }
        assert got == lim.constraints(), key


@pytest.mark.parametrize(
    "args, match",
    [
        ((CAM, ValvetrainParameters(), 1e5, AnalyticTribology()), r"cam_speed must be > 0"),
        ((CAM, ValvetrainParameters(), -1.0, AnalyticTribology()), r"cam_speed must be > 0"),
        ((CAM, "params", 100.0, AnalyticTribology()), r"params must be a ValvetrainParameters"),
        ((None, ValvetrainParameters(), 100.0, AnalyticTribology()), r"cam must be a CamProfile"),
        ((CAM, ValvetrainParameters(), 100.0, "explicit"), r"tribology must be a TribologyModel"),
    ],
)
def test_model_constructor_ranges(args, match):
    with pytest.raises(InputError, match=match):
        ValvetrainModel(*args)


def test_flexible_model_constructor_ranges():
    from tribodyn.valvetrain.flexible_model import FlexibleValvetrainModel

    with pytest.raises(InputError, match=r"params must be a FlexibleValvetrain"):
        FlexibleValvetrainModel(CAM, ValvetrainParameters(), 100.0, AnalyticTribology())


def test_kinematic_helpers_ranges():
    with pytest.raises(InputError, match=r"cam_speed must be > 0 and <= 2617.99"):
        flat_follower_kinematics(CAM, 1e6, np.zeros(3))
    with pytest.raises(InputError, match=r"effective_mass must be >= 0.001"):
        quasi_static_jump_speed(CAM, 300.0, 3e4, 1e-9)
    with pytest.raises(InputError, match=r"n must be an integer >= 360"):
        quasi_static_jump_speed(CAM, 300.0, 3e4, 0.1, n=-5)

import numpy as np
import pytest

from tribodyn import Body, Coating, Material


@pytest.fixture
def steel():
    return Material(E=210e9, nu=0.3)


@pytest.fixture
def steel_pair(steel):
    return (Body(steel), Body(steel))


@pytest.fixture
def rng():
    return np.random.default_rng(12345)


def coated_pair(steel, E, nu, thickness):
    return (Body(steel), Body(steel, Coating(E=E, nu=nu, thickness=thickness)))

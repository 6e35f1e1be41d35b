import os

# One BLAS thread, as the command line runs the solvers (their matrices are small; set
# before numpy loads, since a runtime limit does not remove the threads' overhead).
for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402
import pytest  # noqa: E402

from tribodyn import Body, Coating, Material  # noqa: E402


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

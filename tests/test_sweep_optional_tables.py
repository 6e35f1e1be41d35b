"""Sweep paths into optional tables of a case (``X | None`` in the schema), e.g. the
flexible valvetrain's ``[valvetrain.spring]``: the key resolves to its field (unit and
range) like any other."""

import pytest

from tribodyn import InputError
from tribodyn.config import Case
from tribodyn.config.paths import schema_field
from tribodyn.config.schema import CAM_MODELS
from tribodyn.config.sweep import SweepSpec


@pytest.mark.parametrize(
    "path, unit",
    [
        ("valvetrain.spring.density", "kg/m³"),
        ("valvetrain.tappet.mass", "kg"),
        ("valvetrain.camshaft.diameter", "m"),
    ],
)
def test_schema_field_enters_optional_tables(path, unit):
    fi = schema_field(Case, path, {}, variants={"cam": CAM_MODELS})
    assert fi.json_schema_extra["unit"] == unit


def test_sweep_over_a_flexible_spring_key():
    text = """
[sweep]
name = "spring_density"
case = "andreou2023_flexible"

[[axes]]
path = "valvetrain.spring.density"
values = [7800.0, 7900.0]
"""
    spec = SweepSpec.from_toml_string(text)
    assert spec.n_points == 2
    with pytest.raises(InputError, match=r"valvetrain\.spring\.density"):
        SweepSpec.from_toml_string(text.replace("7900.0", "-1.0"))

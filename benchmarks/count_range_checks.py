"""How often the range checks run while a case file is read and validated.

Counts the calls of :meth:`tribodyn.physics.limits.Limit.check` and of
``tribodyn._validation.check_range`` (wherever a module imported it), and the bounds the
case-file schema checks (a field with ``gt``/``ge``/``lt``/``le`` given in the file; the
schema does not validate defaults). Each value is checked once when the number of checks
equals the number of distinct (name, value) pairs checked (equal values of one name in
different sections, e.g. two surface sets' ``rms``, count as one value: ``checked_twice``
lists them too). A key named otherwise than its constructor's argument
(``numerics.thermal_x_nodes`` → ``x_nodes``) is counted under the argument's name, from
the build's argument → key mappings; one in another unit (``lubricant.inlet_temperature_c``
→ ``inlet_temperature`` in K) under the argument's name and value.

Run: ``python benchmarks/count_range_checks.py [case.toml ...]`` (default: the bundled
paper case, its thermal variant with a datasheet oil, and the paper case made thermal with
its oil in the inlet form and with a datasheet given by its keys). Prints one JSON line per
case.
"""

from __future__ import annotations

import functools
import json
import sys
import tomllib
from collections import Counter
from collections.abc import Callable
from pathlib import Path

from pydantic import BaseModel

import tribodyn._validation as V
from tribodyn.config.build import SET_KEYS, THERMAL_KEYS
from tribodyn.config.case import CASES_DIR, DEFAULT_CASE, Case, load_case
from tribodyn.config.case_thermal import MATERIAL_KEYS
from tribodyn.config.schema_fields import Section
from tribodyn.config.schema_surfaces import OIL_KEYS
from tribodyn.physics import limits as L

_BOUNDS = ("gt", "ge", "lt", "le")
#: per section, the argument name of each key named otherwise (the build's mappings)
_ARGUMENTS = {
    section: {key.rsplit(".", 1)[-1]: arg for arg, key in keys.items()}
    for section, keys in (
        ("Numerics", THERMAL_KEYS),
        ("SurfaceSetConfig", SET_KEYS),
        ("MaterialConfig", MATERIAL_KEYS),
    )
}
#: per section, the keys in another unit than their argument (argument, conversion)
_CONVERTED = {"LubricantConfig": OIL_KEYS}


def _counted_as(model: BaseModel, name: str, value) -> tuple[str, str]:
    """(argument, repr of its value) of the key ``name`` of ``model``."""
    section = type(model).__name__
    conv = _CONVERTED.get(section, {}).get(name)
    if conv is not None:
        return conv.argument, repr(conv.value(value))
    return _ARGUMENTS.get(section, {}).get(name, name), repr(value)


def _schema_checks(model: BaseModel, out: Counter) -> None:
    """Add the bounded fields given in the file of ``model`` and its nested sections, as
    (key, value): a value the schema and a constructor both check counts as one value
    checked twice."""
    for name in model.model_fields_set:
        value = getattr(model, name)
        fi = type(model).model_fields[name]
        if value is not None and any(
            getattr(m, k, None) is not None for m in fi.metadata for k in _BOUNDS
        ):
            out[_counted_as(model, name, value)] += 1
    for name in type(model).model_fields:
        value = getattr(model, name)
        items = value.values() if isinstance(value, dict) else value
        for v in items if isinstance(items, list | tuple | type({}.values())) else [value]:
            if isinstance(v, Section):
                _schema_checks(v, out)


def _thermal(datasheet: bool) -> Case:
    """The paper case with the thermal model and its oil in the inlet form (μ, α at 90 °C
    and the temperature–viscosity coefficient β) or (``datasheet``) as datasheet keys."""
    data = tomllib.loads(DEFAULT_CASE.read_text(encoding="utf-8"))
    lub = data["lubricant"]
    lub.update(inlet_temperature_c=90.0, viscosity_temperature_coefficient=0.03)
    if datasheet:
        for k in ("viscosity", "density", "viscosity_temperature_coefficient"):
            lub.pop(k, None)
        lub.update(
            kinematic_viscosity_40_cst=48.0, kinematic_viscosity_100_cst=8.6, density_15=850.0
        )
    data["numerics"]["thermal"] = True
    return Case.from_dict(data, base_dir=DEFAULT_CASE.parent)


def count(label: str, make: Callable[[], Case]) -> dict:
    """Range checks run (constructors, schema) and distinct values checked while ``make``
    reads and validates a case."""
    calls: Counter = Counter()
    original_check, original_range = L.Limit.check, V.check_range

    def check(self, name, value):
        calls[(name, repr(value))] += 1
        return original_check(self, name, value)

    def check_range(name, value, *args, **kw):
        calls[(name, repr(value))] += 1
        return original_range(name, value, *args, **kw)

    patched = [
        m for m in list(sys.modules.values()) if getattr(m, "check_range", None) is original_range
    ]
    L.Limit.check = check  # type: ignore[method-assign]
    for m in patched:
        m.check_range = check_range
    try:
        case = make()
    finally:
        L.Limit.check = original_check  # type: ignore[method-assign]
        for m in patched:
            m.check_range = original_range
    schema: Counter = Counter()
    _schema_checks(case, schema)
    every = calls + schema
    return {
        "case": label,
        "checks": sum(every.values()),
        "values": len(every),
        "constructor_checks": sum(calls.values()),
        "schema_checks": sum(schema.values()),
        "checked_twice": sorted(f"{n}={v} x{c}" for (n, v), c in every.items() if c > 1),
    }


def main(argv: list[str]) -> None:
    paths = [Path(a) for a in argv] or [DEFAULT_CASE, CASES_DIR / "andreou2023_thermal.toml"]
    for p in paths:
        print(json.dumps(count(p.name, functools.partial(load_case, p)), ensure_ascii=False))
    if not argv:
        print(json.dumps(count("paper, thermal, inlet-form oil", lambda: _thermal(False))))
        print(json.dumps(count("paper, thermal, datasheet keys", lambda: _thermal(True))))


if __name__ == "__main__":
    main(sys.argv[1:])

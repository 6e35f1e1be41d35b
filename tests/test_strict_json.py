"""Every JSON tribodyn writes is strict: NaN and ±inf become null through one sanitizer
(strict parsers reject the bare ``NaN``/``Infinity`` tokens of :func:`json.dumps`)."""

import ast
import json
import math
from pathlib import Path

import numpy as np

from tribodyn import _json

SRC = Path(__file__).resolve().parents[1] / "src" / "tribodyn"


def _strict_loads(text):
    def refuse(token):
        raise ValueError(f"non-standard JSON token {token}")

    return json.loads(text, parse_constant=refuse)


def test_non_finite_numbers_become_null():
    data = {
        "inf": math.inf,
        "nested": [1.0, -math.inf, {"nan": math.nan}],
        "numpy": np.float64("inf"),
        "array": np.array([1.0, np.nan]),
        "tuple": (np.int64(3), 2.5),
        "text": "Infinity",
    }
    out = _strict_loads(_json.dumps(data))
    assert out == {
        "inf": None,
        "nested": [1.0, None, {"nan": None}],
        "numpy": None,
        "array": [1.0, None],
        "tuple": [3, 2.5],
        "text": "Infinity",
    }


def test_no_writer_bypasses_the_sanitizer():
    """No module calls json.dumps/json.dump itself (they would write NaN/Infinity)."""
    found = []
    for path in SRC.rglob("*.py"):
        if path.name == "_json.py" and path.parent == SRC:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if (
                isinstance(node, ast.Call)
                and isinstance(node.func, ast.Attribute)
                and node.func.attr in ("dumps", "dump")
                and isinstance(node.func.value, ast.Name)
                and node.func.value.id == "json"
            ):
                found.append(f"{path.relative_to(SRC)}:{node.lineno}")
    assert not found, found


def test_engine_summary_with_an_unknown_value_is_strict(tmp_path, monkeypatch):
    """The engine writer's summary.json: an unknown (NaN/inf) number is written as null."""
    from types import SimpleNamespace

    from tribodyn.output import engine as engine_output

    study = SimpleNamespace(
        summary=lambda: {"fmep_Pa": math.inf, "e": [math.nan, 1.0]},
        to_dataset=lambda: SimpleNamespace(to_netcdf=lambda path: Path(path).write_bytes(b"")),
        case=SimpleNamespace(name="engine"),
        labels={},
        warnings=[],
        runtime_s=1.0,
        timings={},
    )
    monkeypatch.setattr(engine_output, "_write_case", lambda case, folder: None)
    engine_output.write_engine_results(study, tmp_path / "out", figures=False, report=False)
    text = (tmp_path / "out" / "summary.json").read_text(encoding="utf-8")
    assert _strict_loads(text)["engine"] == {"fmep_Pa": None, "e": [None, 1.0]}

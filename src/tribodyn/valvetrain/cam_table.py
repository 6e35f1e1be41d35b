"""Reading cam lift tables as they come, for :class:`~tribodyn.valvetrain.cam_tabulated.TabulatedCam`.

* The file: a regular file (not a pipe or device) of at most
  :data:`~tribodyn._user_files.MAX_TABLE_BYTES` (64 MB), read by
  :mod:`tribodyn._user_files`.
* Text: UTF-8 (with or without BOM), UTF-16/32 with a BOM, or a legacy 8-bit code page
  (Windows-1252: "°" and "µ" in a header are common); a binary file is refused.
* Separators: comma, semicolon, tab or spaces; with semicolons or tabs a decimal comma
  ("1,25") is read as a decimal point.
* Any number of header lines before the first numeric row (the last one names the
  columns), lines starting with ``#`` and blank lines are skipped. Every data row must
  have the same number of columns; with more than two the angle and lift columns must be
  chosen (1-based number or header name): no column is dropped silently.
* Units: ``"auto"`` takes them from the header ("[deg]", "(rad)", "crank", "[mm]", "[m]",
  "µm", "in"), else degrees and millimetres; ``"crank_deg"`` halves crank angles to cam
  angles (four-stroke). A unit given explicitly that contradicts the header is an error.
* The rounding step of the lift column (its decimals) is returned as ``quantum``.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from .._user_files import MAX_TABLE_BYTES, read_user_text
from .._validation import InputError
from ..physics import limits as L

__all__ = ["load_lift_table", "LiftTable", "ANGLE_UNITS", "LIFT_UNITS"]

ANGLE_UNITS = {"deg": math.pi / 180.0, "rad": 1.0, "crank_deg": math.pi / 360.0}
LIFT_UNITS = {"mm": 1e-3, "m": 1.0, "um": 1e-6, "in": 0.0254}
_NUM = re.compile(r"^[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?$")


@dataclass
class LiftTable:
    """A lift table read from a file: θ [rad], s [m], the units used, the column names and
    the rounding step of the lift values [m]."""

    angle: np.ndarray
    lift: np.ndarray
    angle_unit: str
    lift_unit: str
    columns: list
    quantum: float


def _split(line: str, sep: str | None) -> list[str]:
    if sep is None:
        return line.split()
    return [f.strip() for f in line.split(sep)]


def _unit_in(text: str, units: dict) -> str | None:
    t = text.lower().replace("µ", "u").replace("μ", "u")
    pats = {
        "crank_deg": r"crank",
        "rad": r"\brad",
        "deg": r"deg|°|grad\b",
        "um": r"\bum\b|micro",
        "mm": r"\bmm\b",
        "in": r"\bin\b|inch",
        "m": r"\bm\b",
    }
    for unit, pat in pats.items():
        if unit in units and re.search(pat, t):
            return unit
    return None


def load_lift_table(
    path, *, angle_unit: str = "auto", lift_unit: str = "auto", angle_column=None, lift_column=None
) -> LiftTable:
    """Read a lift table file (see module docstring)."""
    if angle_unit not in ("auto", *ANGLE_UNITS):
        raise InputError(
            f"angle_unit must be 'auto' or one of {sorted(ANGLE_UNITS)} (got {angle_unit!r})"
        )
    if lift_unit not in ("auto", *LIFT_UNITS):
        raise InputError(
            f"lift_unit must be 'auto' or one of {sorted(LIFT_UNITS)} (got {lift_unit!r})"
        )
    p = Path(path)
    text = read_user_text(p, "lift table", limit=MAX_TABLE_BYTES).text
    lines = [(i, ln.strip()) for i, ln in enumerate(text.splitlines(), start=1)]
    lines = [(i, ln) for i, ln in lines if ln and not ln.startswith("#")]
    max_rows = int(L.LIFT_TABLE_ROWS.le or 0)
    if len(lines) > max_rows + 100:  # before parsing: header lines are few
        raise InputError(
            f"lift table {p.name!r} has {len(lines)} lines; at most {max_rows} rows are "
            "allowed (LIFT_TABLE_ROWS): decimate the table (a 0.01° table is ample)"
        )
    header: list[str] = []
    rows: list[list[str]] = []
    sep = None
    for lineno, line in lines:
        if not rows:
            cand = next((c for c in (";", "\t", ",") if c in line), None)
            fields = _split(line, cand)
            if (
                sep is None
                and cand == ","
                and all(_NUM.match(f.replace(",", ".")) for f in line.split())
                and not all(_NUM.match(f) for f in fields)
            ):
                cand, fields = None, line.split()
            conv = [f.replace(",", ".") if cand in (";", "\t") else f for f in fields]
            if (
                len(conv) >= 2
                and all(_NUM.match(f) for f in conv if f != "")
                and all(f != "" for f in conv)
            ):
                sep = cand
                rows.append(conv)
                ncol = len(conv)
                first = lineno
            else:
                header = fields
            continue
        fields = _split(line, sep)
        conv = [f.replace(",", ".") if sep in (";", "\t") else f for f in fields]
        if len(conv) != ncol or not all(_NUM.match(f) for f in conv):
            raise InputError(
                f"lift table {p.name!r}, line {lineno}: expected {ncol} numbers "
                f"like line {first}, got {line!r}"
            )
        rows.append(conv)
    if not rows:
        raise InputError(
            f"lift table {p.name!r} contains no data rows (two numeric columns: cam angle, lift)"
        )
    names = header if len(header) == ncol else [f"column {k + 1}" for k in range(ncol)]

    def pick(sel, key, default):
        if sel is None:
            if ncol != 2:
                raise InputError(
                    f"lift table {p.name!r} has {ncol} columns ({', '.join(names)}); choose "
                    "the angle and lift columns with angle_column and lift_column (1-based "
                    "number or header name)"
                )
            return default
        if isinstance(sel, bool):
            raise InputError(f"{key} must be a column number or name (got {sel!r})")
        if isinstance(sel, int):
            if not 1 <= sel <= ncol:
                raise InputError(f"{key} must be between 1 and {ncol} (got {sel})")
            return sel - 1
        hits = [k for k, n in enumerate(names) if n.strip().lower() == str(sel).strip().lower()]
        if not hits:
            raise InputError(
                f"{key} {sel!r} is not a column of {p.name!r} (columns: {', '.join(names)})"
            )
        return hits[0]

    if len(rows) > max_rows:
        raise InputError(
            f"lift table {p.name!r} has {len(rows)} rows; at most {max_rows} are allowed "
            "(LIFT_TABLE_ROWS): decimate the table (a 0.01° table is ample)"
        )
    ia = pick(angle_column, "angle_column", 0)
    il = pick(lift_column, "lift_column", 1)
    if ia == il:
        raise InputError("angle_column and lift_column must differ")
    data = np.array([[float(r[ia]), float(r[il])] for r in rows])
    if not np.all(np.isfinite(data)):
        raise InputError(f"lift table {p.name!r} contains NaN or inf")
    h_angle = _unit_in(names[ia], ANGLE_UNITS) if header else None
    h_lift = _unit_in(names[il], LIFT_UNITS) if header else None
    for key, given, found in (
        ("angle_unit", angle_unit, h_angle),
        ("lift_unit", lift_unit, h_lift),
    ):
        if given != "auto" and found is not None and found != given:
            raise InputError(
                f"{key} = {given!r} but the header of {p.name!r} says "
                f"{found!r} ({names[ia if key == 'angle_unit' else il]!r})"
            )
    au = angle_unit if angle_unit != "auto" else (h_angle or "deg")
    lu = lift_unit if lift_unit != "auto" else (h_lift or "mm")
    decimals = max(
        (
            len(r[il].split(".")[1].split("e")[0].split("E")[0])
            if "." in r[il] and "e" not in r[il].lower()
            else 0
        )
        for r in rows
    )
    quantum = 10.0**-decimals * LIFT_UNITS[lu] if decimals < 15 else 0.0
    return LiftTable(
        data[:, 0] * ANGLE_UNITS[au], data[:, 1] * LIFT_UNITS[lu], au, lu, names, quantum
    )

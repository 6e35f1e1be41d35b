"""Reading cam lift tables (CSV) for :class:`~tribodyn.valvetrain.cams.TabulatedCam`.

Format: two numeric columns, cam angle and follower lift (by default degrees and
millimetres, the way lift tables come from measurement or suppliers), separated by commas,
semicolons, tabs or spaces. Blank lines and lines starting with ``#`` are skipped; one
non-numeric header line at the top is allowed. Extra columns are ignored.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

import numpy as np

from .._validation import InputError

__all__ = ["read_lift_table", "ANGLE_UNITS", "LIFT_UNITS"]

ANGLE_UNITS = {"deg": math.pi / 180.0, "rad": 1.0}
LIFT_UNITS = {"mm": 1e-3, "m": 1.0, "um": 1e-6, "in": 0.0254}
_SPLIT = re.compile(r"[,;\s]+")


def read_lift_table(path, *, angle_unit: str = "deg",
                    lift_unit: str = "mm") -> tuple[np.ndarray, np.ndarray]:
    """Return (θ [rad], s [m]) from a two-column lift table file."""
    if angle_unit not in ANGLE_UNITS:
        raise InputError(f"angle_unit must be one of {sorted(ANGLE_UNITS)} (got {angle_unit!r})")
    if lift_unit not in LIFT_UNITS:
        raise InputError(f"lift_unit must be one of {sorted(LIFT_UNITS)} (got {lift_unit!r})")
    p = Path(path)
    try:
        text = p.read_text(encoding="utf-8-sig")
    except OSError as exc:
        raise InputError(f"cannot read lift table {str(p)!r}: {exc.strerror}") from None
    rows = []
    header_seen = False
    for lineno, line in enumerate(text.splitlines(), start=1):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        fields = [f for f in _SPLIT.split(line) if f]
        try:
            a, s = float(fields[0]), float(fields[1])
        except (ValueError, IndexError):
            if not rows and not header_seen:
                header_seen = True               # one header line is fine
                continue
            raise InputError(f"lift table {p.name!r}, line {lineno}: expected two numbers "
                             f"(cam angle, lift), got {line!r}") from None
        rows.append((a, s))
    if not rows:
        raise InputError(f"lift table {p.name!r} contains no data rows")
    data = np.asarray(rows, dtype=float)
    if not np.all(np.isfinite(data)):
        raise InputError(f"lift table {p.name!r} contains NaN or inf")
    return data[:, 0] * ANGLE_UNITS[angle_unit], data[:, 1] * LIFT_UNITS[lift_unit]

"""Exports of a cam-cycle study's results: CSV traces and a self-contained HTML report.

* ``traces.csv``: one row per transient-EHL sample (crank angle), the conjunction
  conditions and, per surface set, films, pressures, loads, friction, friction power and
  camshaft torque (column names ``quantity [unit]`` and ``set:quantity [unit]``).
* ``dynamics.csv``: one row per dynamics output sample (crank angle), the valvetrain's
  kinematics and forces.
* ``report.html``: report.md rendered (CommonMark with tables, ``markdown-it-py``), every
  figure embedded as a ``data:image/png;base64`` URI, inline CSS, no external resource:
  it opens offline and can be shared as one file. Only regular files of the result
  folder are embedded: a figure that is a link, or names a file elsewhere, is left out
  and named (a folder received from someone else must not carry a private file into a
  shared report).

Both are written with the results and by ``tribodyn export RESULTS`` from results.nc
and report.md.
"""

from __future__ import annotations

import base64
import csv
import html
import re
from pathlib import Path

import numpy as np

from .._safe_write import atomic_open
from .result_folder import regular_file_bytes

__all__ = ["CSV_FILES", "write_csv", "report_html", "report_markdown"]

#: The CSV files :func:`write_csv` writes.
CSV_FILES = ("traces.csv", "dynamics.csv")

#: Per-set EHL variables of traces.csv, in order.
_SET_COLUMNS = (
    "central_film",
    "min_film",
    "lambda_ratio",
    "max_pressure",
    "hertz_pressure",
    "asperity_load",
    "viscous_friction",
    "boundary_friction",
    "friction_power",
    "camshaft_friction_torque",
    "camshaft_drive_torque",
    "converged",
)
_CONDITIONS = (
    "ehl_contact_force",
    "ehl_entrainment_speed",
    "ehl_sliding_speed",
    "ehl_radius",
    "ehl_lift",
    "ehl_contact_offset",
)
_DYNAMICS = (
    "cam_lift",
    "contact_offset",
    "radius_of_curvature",
    "entrainment_speed",
    "sliding_speed",
    "contact_force",
    "tappet_displacement",
    "tappet_velocity",
    "tappet_acceleration",
    "valve_lift",
    "seat_force",
    "cam_torque",
)


def _add_columns(ds, names, header: list[str], cols: list[np.ndarray], prefix="", row=None):
    """Append the variables ``names`` present in ``ds`` (their row ``row`` for a per-set
    variable) to a table's header and columns."""
    for name in names:
        if name in ds:
            u = ds[name].attrs.get("units", "")
            header.append(f"{prefix}{name} [{u}]" if u else f"{prefix}{name}")
            v = ds[name].values
            cols.append(np.asarray(v if row is None else v[row], float))


def _write(path: Path, header: list[str], cols: list[np.ndarray]) -> Path:
    with atomic_open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        for row in zip(*cols):
            w.writerow(["" if not np.isfinite(v) else f"{v:.9g}" for v in row])
    return path


def write_csv(ds, folder) -> list[Path]:
    """Write :data:`CSV_FILES` from a results Dataset into ``folder`` (empty cells: no
    value, e.g. EHL quantities where the contact is unloaded)."""
    folder = Path(folder)
    if "ehl_crank" not in ds.coords or "crank_angle" not in ds.coords:
        return []  # not a cycle study's Dataset
    sets = [str(s) for s in ds["surface_set"].values]
    header = ["crank_angle [deg]"]
    cols = [np.asarray(ds["ehl_crank"].values, float)]
    _add_columns(ds, _CONDITIONS, header, cols)
    for k, s in enumerate(sets):
        _add_columns(ds, _SET_COLUMNS, header, cols, f"{s}:", k)
    out = [_write(folder / "traces.csv", header, cols)]
    header = ["crank_angle [deg]"]
    cols = [np.asarray(ds["crank_angle"].values, float)]
    _add_columns(ds, _DYNAMICS, header, cols)
    out.append(_write(folder / "dynamics.csv", header, cols))
    return out


_CSS = """
body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222;
line-height:1.45}
table{border-collapse:collapse;margin:1em 0;font-size:90%}
th,td{border:1px solid #bbb;padding:3px 6px;vertical-align:top}
th{background:#eee}
img{max-width:100%;height:auto;border:1px solid #ddd}
pre{background:#f6f6f6;padding:.6em;overflow-x:auto;font-size:85%}
code{background:#f6f6f6}
"""


def report_markdown(folder, warnings: list[str] | None = None) -> str:
    """The text of ``folder/report.md`` (a regular file in the folder, not a link);
    bytes that are not UTF-8 are replaced by U+FFFD and a line is added to
    ``warnings``. Raises :class:`FileNotFoundError` if there is no such file."""
    data = regular_file_bytes(Path(folder), "report.md")
    if data is None:
        raise FileNotFoundError(f"{folder}/report.md is missing, a link or not a regular file")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as exc:
        if warnings is not None:
            warnings.append(
                f"report.md is not valid UTF-8 (byte {exc.start}): the bytes that are "
                "not were replaced by \ufffd in report.html"
            )
        return data.decode("utf-8", errors="replace")


def report_html(markdown_text: str, folder, skipped: list[str] | None = None) -> str:
    """report.md as one HTML page with the figures it shows (files in ``folder``)
    embedded as data URIs. A figure file that is missing, or is not a regular file of
    ``folder`` (a link, a folder, a path elsewhere), is not embedded: the page names it
    instead and so does ``skipped``."""
    from markdown_it import MarkdownIt

    md = MarkdownIt("commonmark", {"html": False}).enable("table")
    body = md.render(markdown_text)
    folder = Path(folder)

    def embed(m: re.Match) -> str:
        name = html.unescape(m.group(1))
        data = regular_file_bytes(folder, name) if name.endswith(".png") else None
        if data is None:
            if skipped is not None:
                skipped.append(name)
            return f'alt="missing figure {html.escape(name)}" src=""'
        return f'src="data:image/png;base64,{base64.b64encode(data).decode("ascii")}"'

    body = re.sub(r'src="([^"]*)"', embed, body)
    title = markdown_text.splitlines()[0].lstrip("# ").strip() if markdown_text else "report"
    return (
        '<!DOCTYPE html>\n<html lang="en"><head><meta charset="utf-8">'
        f"<title>{html.escape(title)}</title><style>{_CSS}</style></head>\n"
        f"<body>\n{body}</body></html>\n"
    )

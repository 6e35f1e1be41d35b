"""``tribodyn calibrate DATA.csv``: measured friction of a line contact → case-file sections.

Fits boundary friction and rheology (:mod:`tribodyn.workflow.calibration`) and prints
(or writes, with ``--output``, never over an existing file) the ``[lubricant]`` keys and a
``[[surface_sets]]`` fragment with the fitted values and their 1σ uncertainties.
"""

from __future__ import annotations

import csv
import math
import re
import textwrap
import unicodedata
from pathlib import Path

import tomli_w
import typer
from rich.console import Console
from rich.markup import escape

from .. import _json
from ..physics import typical, typical_engine
from .failure import fail, writing

__all__ = ["calibrate_command", "read_friction_csv", "calibration_toml"]

#: the default surfaces: steel, E and ν of the typical steel row (physics.typical_engine)
_STEEL_E, _STEEL_NU = typical_engine.STEEL_MODULUS.value, typical_engine.STEEL_POISSON.value

_COLUMNS = ("entrainment_speed", "friction_coefficient")


#: A number written with a decimal comma (``0,5``, ``-1,25e-3``).
_DECIMAL_COMMA = re.compile(r"[+-]?\d*,\d+(?:[eE][+-]?\d+)?")


def _table_rows(path: Path, notes: list[str] | None) -> tuple[list[str], list[tuple[int, list]]]:
    """Header (lower case) and ``(line number, fields)`` of the data rows of DATA.

    The file is read by :mod:`tribodyn._user_files` (a regular file of at most 64 MB;
    UTF-8 with or without BOM, UTF-16/32 with a BOM, else Windows-1252 with a note). The
    separator is the header's: ``;`` or tab if it has one (then a decimal comma, ``0,5``,
    is a decimal point), else ``,``. A row with another number of fields than the header
    is an error (with a comma separator, decimal commas are the usual cause)."""
    from .._user_files import MAX_TABLE_BYTES, read_user_text
    from .._validation import InputError

    got = read_user_text(path, "DATA", limit=MAX_TABLE_BYTES)
    if got.note is not None and notes is not None:
        notes.append(got.note)
    shown = repr(str(path))
    lines = [
        (i, ln)
        for i, ln in enumerate(got.text.splitlines(), start=1)
        if ln.strip() and not ln.lstrip().startswith("#")
    ]
    if not lines:
        raise InputError(f"DATA {shown} has no header line and no data (see the guide)")
    sep = next((c for c in (";", "\t") if c in lines[0][1]), ",")
    split = list(csv.reader([ln for _, ln in lines], delimiter=sep))

    def trimmed(fields: list[str]) -> list[str]:  # a separator at the end of the line
        fields = [f.strip() for f in fields]
        while fields and not fields[-1]:
            fields.pop()
        return fields

    header = [h.lower() for h in trimmed(split[0])]
    twice = sorted({h for h in header if header.count(h) > 1})
    if twice:
        raise InputError(f"DATA {shown}: column(s) {', '.join(twice)} appear twice in the header")
    rows = []
    for (lineno, line), fields in zip(lines[1:], split[1:], strict=True):
        fields = trimmed(fields)
        if len(fields) != len(header):
            hint = ""
            if sep == "," and _DECIMAL_COMMA.search(line):
                hint = (
                    ": decimal commas (0,5)? Write numbers with a decimal point, or separate "
                    "the columns with ';' (then 0,5 is read as 0.5)"
                )
            raise InputError(
                f"DATA {shown}, line {lineno}: {len(fields)} fields, but the header has "
                f"{len(header)} columns ({', '.join(header)}){hint or '; give one value per column'}"
            )
        if sep != ",":
            fields = [f.replace(",", ".") if _DECIMAL_COMMA.fullmatch(f) else f for f in fields]
        rows.append((lineno, fields))
    return header, rows


def read_friction_csv(path: Path, load: float | None, notes: list[str] | None = None):
    """Read measured points: columns ``entrainment_speed`` [m/s], ``friction_coefficient``
    [-], and ``sliding_speed`` [m/s] or ``slide_roll_ratio`` [-] (u_s/u_e), optionally
    ``load`` [N/m] (else ``load`` applies to every row) and ``radius`` [m] (else
    --radius). Lines starting with # are skipped; the file, its encoding, separator and
    decimal commas as in :func:`_table_rows`. Notes on the file (an encoding guessed) are
    appended to ``notes``."""
    import numpy as np

    from .._validation import InputError
    from ..workflow.calibration import FrictionData

    header, rows = _table_rows(path, notes)
    shown = repr(str(path))
    missing = [c for c in _COLUMNS if c not in header]
    if missing or not ({"sliding_speed", "slide_roll_ratio"} & set(header)):
        raise InputError(
            f"DATA {shown}: needs the columns entrainment_speed, friction_coefficient and "
            f"sliding_speed or slide_roll_ratio (optional: load, radius); found {header}"
        )
    known = {*_COLUMNS, "sliding_speed", "slide_roll_ratio", "load", "radius"}
    cols: dict[str, list[float]] = {h: [] for h in header if h in known}
    for lineno, fields in rows:
        for key, value in zip(header, fields, strict=True):
            if key not in cols:
                continue
            try:
                cols[key].append(float(value))
            except ValueError:
                hint = ""
                if _DECIMAL_COMMA.fullmatch(value):
                    hint = " (a decimal comma: write 0.5, or separate the columns with ';')"
                raise InputError(
                    f"DATA {shown}, line {lineno}: {key} = {value!r} is not a number{hint}"
                ) from None
    ue = np.asarray(cols["entrainment_speed"])
    us = (
        np.asarray(cols["sliding_speed"])
        if "sliding_speed" in cols
        else ue * np.asarray(cols["slide_roll_ratio"])
    )
    if "load" in cols:
        w = np.asarray(cols["load"])
    elif load is not None:
        w = np.full(ue.size, float(load))
    else:
        raise InputError("give --load (N/m) or a load column in DATA")
    radius = np.asarray(cols["radius"]) if "radius" in cols else None
    return FrictionData(ue, np.abs(us), w, np.asarray(cols["friction_coefficient"]), radius)


#: Longest --label [characters] (it names the pair in a comment and the surface set).
MAX_LABEL = 200


def _check_label(label: str) -> None:
    """--label: one line of at most :data:`MAX_LABEL` printable characters."""
    from .._validation import InputError

    bad = sorted({repr(c)[1:-1] for c in label if unicodedata.category(c) == "Cc"})
    if bad:
        raise InputError(
            f"--label must be one line of text without control characters (found "
            f"{', '.join(bad)}: line breaks, tabs, NUL are not allowed)"
        )
    if len(label) > MAX_LABEL:
        raise InputError(f"--label must have at most {MAX_LABEL} characters (got {len(label)})")


def _fmt(v: float) -> str:
    return f"{v:.4g}"


def _name(label: str) -> str:
    """A surface-set identifier from a free-text label (letters, digits, _ . + -)."""
    out = re.sub(r"[^A-Za-z0-9_.+-]+", "_", label).strip("_")
    return out[:64] or "measured"


def _comment(text: str) -> list[str]:
    """``text`` as TOML comment lines: control characters (a line break would end the
    comment and start TOML of its own) shown escaped, long text wrapped."""
    safe = "".join(
        c if c == "\t" or unicodedata.category(c) != "Cc" else repr(c)[1:-1] for c in text
    )
    return ["# " + ln for ln in textwrap.wrap(safe, 86, break_on_hyphens=False)] or ["#"]


def _toml_string(key: str, value: str) -> str:
    """``key = "value"`` with the value escaped as TOML requires."""
    return tomli_w.dumps({key: value}).rstrip("\n")


def bundled_data(data: Path) -> Path:
    """``data`` if it exists; else the bundled example file of that bare name (e.g.
    ``example_friction.csv``, src/tribodyn/cases); else ``data`` (reading says it is
    missing)."""
    from ..config.case import CASES_DIR

    p = Path(data)
    if not p.exists() and p.parent == Path(".") and (CASES_DIR / p.name).is_file():
        return CASES_DIR / p.name
    return p


def _surface_law(rough, materials):
    """``rough`` with the default surface law (a self-affine surface with its σ and the
    typical spectrum, as a case-file set without measured_surface) at the pair's E'."""
    import dataclasses

    from ..config.measured_surface import typical_surface_law
    from ..physics.materials import Body

    law = typical_surface_law(rough.rms, (Body(materials[0]), Body(materials[1])))
    return dataclasses.replace(rough, law=law)


def calibration_toml(
    cal,
    source: str,
    label: str,
    roughness: dict | None = None,
    notes=(),
    asperity_model: str = "surface",
) -> str:
    """Case-file sections of a calibration (TOML text with the uncertainties as comments;
    ``notes``: remarks on the data file, as comments); the surface set asks for the
    asperity law the fit used."""
    lines = _comment(
        f"Calibrated by `tribodyn calibrate` from {source}: {cal.n_points} distinct points, "
        f"RMS residual of the friction coefficient {cal.rms_residual:.3g}. ± values are 1σ "
        "from the Jacobian covariance s²(JᵀJ)⁻¹ at the optimum, with s² = Σr²/(n − k) the "
        "scatter of the n points about the fit (k fitted parameters): they assume "
        "independent points of equal scatter (an exact repeat of a row is counted once). "
        "Isothermal effective values: use them at the test's oil temperature."
    )
    for note in (*notes, *getattr(cal, "warnings", ())):
        lines += _comment(f"NOTE: {note}")
    if not cal.converged:
        lines += _comment(f"WARNING: not converged: {cal.message}")

    def entry(name):
        if name in cal.values:
            sd = cal.std[name]
            unc = f"± {_fmt(sd)}" if math.isfinite(sd) else "± undetermined"
            if name in cal.bootstrap_std:
                unc += f", bootstrap ± {_fmt(cal.bootstrap_std[name])}"
            return f"{name} = {_fmt(cal.values[name])}  # {unc} (fitted)"
        if name in cal.fixed:
            return f"{name} = {_fmt(cal.fixed[name])}  # fixed"
        return None

    def entries(*names):
        return [e for e in map(entry, names) if e is not None]

    lub = entries("eyring_stress", "limiting_shear_coefficient", "limiting_shear_stress")
    if lub:
        lines += ["", "[lubricant]", *lub]
    surf = entries("boundary_shear_coefficient", "boundary_shear_strength")
    if surf:
        if not {"boundary_shear_strength"} & {*cal.values, *cal.fixed}:
            surf.append("boundary_shear_strength = 0.0  # τ₀ of the calibration model")
        r = roughness or {}
        lines += [
            "",
            *_comment(
                f"The measured pair ({label}) as a surface set: add substrate, coating and "
                "coating_thickness as in your case."
            ),
            "[[surface_sets]]",
            _toml_string("name", _name(label)),
            "roughness = { "
            + ", ".join(f"{k} = {v:.6g}" for k, v in r.items())
            + " }  # as used in the fit",
            *(
                ['asperity_model = "greenwood_tripp"  # as used in the fit']
                if asperity_model == "greenwood_tripp"
                else []
            ),
            *surf,
        ]
    if "roughness_parameter" in cal.values:
        lines += [
            "",
            f"# effective ηβσ = {_fmt(cal.values['roughness_parameter'])} "
            f"(± {_fmt(cal.std['roughness_parameter'])}): scale asperity_density of the "
            "pair's roughness by it over the measured ηβσ",
        ]
    return "\n".join(lines) + "\n"


def calibrate_command(
    data: Path = typer.Argument(..., help="CSV of measured friction (see the guide)."),
    radius: float | None = typer.Option(
        None, "--radius", help="reduced radius R \\[m] (unless DATA has a radius column)."
    ),
    load: float | None = typer.Option(
        None, "--load", help="load per unit length w [N/m] (unless DATA has a load column)."
    ),
    viscosity: float = typer.Option(..., "--viscosity", help="μ₀ at the test temperature [Pa·s]."),
    pressure_viscosity: float = typer.Option(
        ..., "--pressure-viscosity", help="α at the test temperature [1/Pa]."
    ),
    rms: float | None = typer.Option(
        None, "--rms", help="composite RMS roughness σ \\[m] (absent: smooth, rheology only)."
    ),
    asperity_model: str = typer.Option(
        "surface",
        "--asperity-model",
        help="asperity load and area: surface (default: the boundary-element law of a "
        "self-affine surface with --rms and the typical spectrum of physics.typical, as "
        "in a case file) or greenwood_tripp (with --roughness-parameter, --rms-to-radius).",
    ),
    roughness_parameter: float = typer.Option(
        typical.ROUGHNESS_PARAMETER.value,
        "--roughness-parameter",
        help="ηβσ (default: the typical value, physics.typical.ROUGHNESS_PARAMETER).",
    ),
    rms_to_radius: float = typer.Option(
        typical.RMS_TO_SUMMIT_RADIUS.value,
        "--rms-to-radius",
        help="σ/β (default: the typical value, physics.typical.RMS_TO_SUMMIT_RADIUS).",
    ),
    e1: float = typer.Option(_STEEL_E, "--E1", help="Young's modulus of surface 1 [Pa] (steel)."),
    nu1: float = typer.Option(_STEEL_NU, "--nu1", help="Poisson's ratio of surface 1 (steel)."),
    e2: float = typer.Option(_STEEL_E, "--E2", help="Young's modulus of surface 2 [Pa] (steel)."),
    nu2: float = typer.Option(_STEEL_NU, "--nu2", help="Poisson's ratio of surface 2 (steel)."),
    fit: str = typer.Option(
        "boundary_shear_coefficient,eyring_stress,limiting_shear_coefficient",
        "--fit",
        help="comma-separated parameters to fit (boundary_shear_coefficient, "
        "boundary_shear_strength, eyring_stress, limiting_shear_coefficient, "
        "limiting_shear_stress, roughness_parameter).",
    ),
    fix: list[str] = typer.Option([], "--fix", help="NAME=VALUE held fixed (repeatable)."),
    bootstrap: int = typer.Option(
        0, "--bootstrap", help="also a residual bootstrap with this many refits (e.g. 200)."
    ),
    label: str = typer.Option("measured pair", "--label", help="name of the pair in comments."),
    output: Path | None = typer.Option(
        None, "--output", "-o", help="write the TOML here (an existing file is never replaced)."
    ),
    as_json: bool = typer.Option(False, "--json", help="print the result as JSON."),
) -> None:
    """Fit boundary friction and rheology to measured friction; print case-file sections."""
    import numpy as np

    from .._validation import InputError
    from ..config.schema_surfaces import RoughnessConfig
    from ..physics.asperity import Roughness
    from ..physics.lubricant import Lubricant
    from ..physics.materials import Material
    from ..workflow.calibration import CalibrationSetup, calibrate_friction

    err = Console(stderr=True)
    try:
        fixed: dict[str, float] = {}
        for item in fix:
            name, sep, value = item.partition("=")
            try:
                fixed[name.strip()] = float(value)
            except ValueError:
                sep = ""
            if not sep:
                raise InputError(f"--fix must be NAME=VALUE with a number (got {item!r})")
        free = tuple(n.strip() for n in fit.split(",") if n.strip())
        _check_label(label)
        if output is not None and (output.exists() or output.is_symlink()):
            raise InputError(f"--output {str(output)!r} exists; give a new file name")
        if asperity_model not in ("surface", "greenwood_tripp"):
            raise InputError(
                f"--asperity-model must be surface or greenwood_tripp (got {asperity_model!r})"
            )
        notes: list[str] = []
        measured = read_friction_csv(bundled_data(data), load, notes)
        if radius is None:
            if measured.radius is None:
                raise InputError("give --radius [m] or a radius column in DATA")
            radius = float(np.median(measured.radius))  # not used: each row has its own
        roughness = None
        materials = (Material(e1, nu1), Material(e2, nu2))
        if rms is not None:
            if not (0.0 < rms_to_radius < 1.0 and roughness_parameter > 0.0):
                raise InputError("--rms-to-radius must lie in (0, 1) and --roughness-parameter > 0")
            beta = rms / rms_to_radius
            roughness = Roughness(roughness_parameter / (beta * rms), rms, beta)
            if asperity_model == "surface":
                roughness = _surface_law(roughness, materials)
        setup = CalibrationSetup(
            radius=radius,
            lubricant=Lubricant(viscosity, pressure_viscosity),
            roughness=roughness,
            materials=materials,
        )
        cal = calibrate_friction(measured, setup, free=free, fixed=fixed, bootstrap=bootstrap)
        keys = RoughnessConfig.model_fields  # the case file's roughness keys
        rough = None if roughness is None else {k: getattr(roughness, k) for k in keys}
        text = calibration_toml(cal, data.name, label, rough, notes, asperity_model)
        if output is not None:
            from .._safe_write import atomic_write

            with writing("--output", output):  # an existing file is never replaced
                atomic_write(output, text, replace=False)
    except InputError as exc:
        fail(err, exc)
    if as_json:
        typer.echo(
            _json.dumps(
                {
                    "values": cal.values,
                    "std": {k: (v if math.isfinite(v) else None) for k, v in cal.std.items()},
                    "bootstrap_std": cal.bootstrap_std,
                    "fixed": cal.fixed,
                    "rms_residual": cal.rms_residual,
                    "n_points": cal.n_points,
                    "converged": cal.converged,
                    "message": cal.message,
                    "warnings": [*notes, *cal.warnings],
                },
                indent=2,
            )
        )
    elif output is None:
        typer.echo(text, nl=False)
    else:
        typer.echo(f"wrote {output}")
    for note in (*notes, *cal.warnings):
        err.print(f"[yellow]note:[/yellow] {escape(note)}", highlight=False)
    if not cal.converged:
        err.print(f"[yellow]warning:[/yellow] {escape(cal.message)}", highlight=False)
        raise typer.Exit(code=1)

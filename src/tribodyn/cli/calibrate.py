"""``tribodyn calibrate DATA.csv``: measured friction of a line contact → case-file sections.

Fits boundary friction and rheology (:mod:`tribodyn.workflow.calibration`) and prints
(or writes, with ``--output``, never over an existing file) the ``[lubricant]`` keys and a
``[[surface_sets]]`` fragment with the fitted values and their 1σ uncertainties.
"""

from __future__ import annotations

import csv
import json
import math
import re
from pathlib import Path

import typer
from rich.console import Console
from rich.markup import escape

from .. import paper
from .failure import fail, writing

__all__ = ["calibrate_command", "read_friction_csv", "calibration_toml"]

_STEEL_E = paper.STEEL["E"]

_COLUMNS = ("entrainment_speed", "friction_coefficient")


def read_friction_csv(path: Path, load: float | None):
    """Read measured points: columns ``entrainment_speed`` [m/s], ``friction_coefficient``
    [-], and ``sliding_speed`` [m/s] or ``slide_roll_ratio`` [-] (u_s/u_e), optionally
    ``load`` [N/m] (else ``load`` applies to every row) and ``radius`` [m] (else
    --radius). Lines starting with # are skipped."""
    import numpy as np

    from .._validation import InputError
    from ..workflow.calibration import FrictionData

    try:
        with open(path, newline="", encoding="utf-8") as f:
            rows = [r for r in f if r.strip() and not r.lstrip().startswith("#")]
    except OSError as exc:
        raise InputError(f"DATA: cannot read {str(path)!r} ({exc.strerror or exc})") from None
    reader = csv.DictReader(rows)
    header = [h.strip() for h in (reader.fieldnames or [])]
    missing = [c for c in _COLUMNS if c not in header]
    if missing or not ({"sliding_speed", "slide_roll_ratio"} & set(header)):
        raise InputError(
            f"DATA {str(path)!r}: needs the columns entrainment_speed, friction_coefficient and "
            f"sliding_speed or slide_roll_ratio (optional: load, radius); found {header}"
        )
    cols: dict[str, list[float]] = {h: [] for h in header}
    for i, row in enumerate(reader, start=2):
        for key, value in row.items():
            if key is None or key.strip() not in cols:
                continue
            try:
                cols[key.strip()].append(float(value))
            except (TypeError, ValueError):
                raise InputError(
                    f"DATA {str(path)!r}, data row {i - 1}: {key.strip()} = {value!r} is not a number"
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


def _fmt(v: float) -> str:
    return f"{v:.4g}"


def _name(label: str) -> str:
    """A surface-set identifier from a free-text label (letters, digits, _ . + -)."""
    out = re.sub(r"[^A-Za-z0-9_.+-]+", "_", label).strip("_")
    return out[:64] or "measured"


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
    asperity_model: str = "surface",
) -> str:
    """Case-file sections of a calibration (TOML text with the uncertainties as comments);
    the surface set asks for the asperity law the fit used."""
    lines = [
        f"# Calibrated by `tribodyn calibrate` from {source}: {cal.n_points} points,",
        f"# RMS residual of the friction coefficient {cal.rms_residual:.3g}. ± values are 1σ",
        "# (Jacobian covariance). Isothermal effective values: use them at the test's oil",
        "# temperature.",
    ]
    if not cal.converged:
        lines.append(f"# WARNING: not converged: {cal.message}")

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

    lub = [e for e in map(entry, ("eyring_stress", "limiting_shear_coefficient")) if e]
    lub += [e for e in map(entry, ("limiting_shear_stress",)) if e]
    if lub:
        lines += ["", "[lubricant]", *lub]
    surf = [
        e
        for e in map(entry, ("boundary_shear_coefficient", "boundary_shear_strength"))
        if e is not None
    ]
    if surf:
        if "boundary_shear_strength" not in cal.values and "boundary_shear_strength" not in (
            cal.fixed
        ):
            surf.append("boundary_shear_strength = 0.0  # τ₀ of the calibration model")
        r = roughness or {}
        lines += [
            "",
            f"# The measured pair ({label}) as a surface set: add substrate, coating and",
            "# coating_thickness as in your case.",
            "[[surface_sets]]",
            f'name = "{_name(label)}"',
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
        None, "--radius", help="reduced radius R [m] (unless DATA has a radius column)."
    ),
    load: float | None = typer.Option(
        None, "--load", help="load per unit length w [N/m] (unless DATA has a load column)."
    ),
    viscosity: float = typer.Option(..., "--viscosity", help="μ₀ at the test temperature [Pa·s]."),
    pressure_viscosity: float = typer.Option(
        ..., "--pressure-viscosity", help="α at the test temperature [1/Pa]."
    ),
    rms: float | None = typer.Option(
        None, "--rms", help="composite RMS roughness σ [m] (absent: smooth, rheology only)."
    ),
    asperity_model: str = typer.Option(
        "surface",
        "--asperity-model",
        help="asperity load and area: surface (default: the boundary-element law of a "
        "self-affine surface with --rms and the typical spectrum of physics.typical, as "
        "in a case file) or greenwood_tripp (with --roughness-parameter, --rms-to-radius).",
    ),
    roughness_parameter: float = typer.Option(
        0.04, "--roughness-parameter", help="ηβσ (typical 0.04, physics.typical)."
    ),
    rms_to_radius: float = typer.Option(
        1e-3, "--rms-to-radius", help="σ/β (typical 1e-3, physics.typical)."
    ),
    e1: float = typer.Option(_STEEL_E, "--E1", help="Young's modulus of surface 1 [Pa] (steel)."),
    nu1: float = typer.Option(0.3, "--nu1", help="Poisson's ratio of surface 1."),
    e2: float = typer.Option(_STEEL_E, "--E2", help="Young's modulus of surface 2 [Pa] (steel)."),
    nu2: float = typer.Option(0.3, "--nu2", help="Poisson's ratio of surface 2."),
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
        if output is not None and (output.exists() or output.is_symlink()):
            raise InputError(f"--output {str(output)!r} exists; give a new file name")
        if asperity_model not in ("surface", "greenwood_tripp"):
            raise InputError(
                f"--asperity-model must be surface or greenwood_tripp (got {asperity_model!r})"
            )
        measured = read_friction_csv(bundled_data(data), load)
        if radius is None:
            if measured.radius is None:
                raise InputError("give --radius [m] or a radius column in DATA")
            radius = float(np.median(measured.radius))  # not used: each row has its own
        roughness = None
        if rms is not None:
            if not (0.0 < rms_to_radius < 1.0 and roughness_parameter > 0.0):
                raise InputError("--rms-to-radius must lie in (0, 1) and --roughness-parameter > 0")
            beta = rms / rms_to_radius
            roughness = Roughness(roughness_parameter / (beta * rms), rms, beta)
            if asperity_model == "surface":
                roughness = _surface_law(roughness, (Material(e1, nu1), Material(e2, nu2)))
        setup = CalibrationSetup(
            radius=radius,
            lubricant=Lubricant(viscosity, pressure_viscosity),
            roughness=roughness,
            materials=(Material(e1, nu1), Material(e2, nu2)),
        )
        cal = calibrate_friction(measured, setup, free=free, fixed=fixed, bootstrap=bootstrap)
        rough = (
            None
            if roughness is None
            else {
                "asperity_density": roughness.asperity_density,
                "rms": roughness.rms,
                "summit_radius": roughness.summit_radius,
            }
        )
        text = calibration_toml(cal, data.name, label, rough, asperity_model)
        if output is not None:
            with writing("--output", output), open(output, "x", encoding="utf-8") as f:
                f.write(text)
    except InputError as exc:
        fail(err, exc)
    if as_json:
        typer.echo(
            json.dumps(
                {
                    "values": cal.values,
                    "std": {k: (v if math.isfinite(v) else None) for k, v in cal.std.items()},
                    "bootstrap_std": cal.bootstrap_std,
                    "fixed": cal.fixed,
                    "rms_residual": cal.rms_residual,
                    "n_points": cal.n_points,
                    "converged": cal.converged,
                    "message": cal.message,
                },
                indent=2,
            )
        )
    elif output is None:
        typer.echo(text, nl=False)
    else:
        typer.echo(f"wrote {output}")
    if not cal.converged:
        err.print(f"[yellow]warning:[/yellow] {escape(cal.message)}", highlight=False)
        raise typer.Exit(code=1)

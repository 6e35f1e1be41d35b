"""Writing a design sweep: ``sweep.nc``, ``sweep_report.md``, the figures, ``sweep.toml``
and ``base_case.toml`` next to the point files in the output folder.

Each file is written to a temporary name and renamed into place (the point files in
``points/`` are the sweep's own record and are never touched here), with the permissions
the umask gives; the folder's marker lists them with their SHA-256. A file of the user's
in the folder (not written by tribodyn, or changed since, see
:func:`~tribodyn.output.writer.foreign_files`) is never replaced: if one has the name of a
file the sweep writes, nothing is written and :class:`~tribodyn.InputError` names it. The
report formats
what the combined Dataset holds: inputs, per-point tables, onset speeds of jump and
bounce, figures, failed points with their errors, and warnings.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .._safe_write import atomic_write, atomic_write_with, make_dirs
from .._typing import PathLike
from .._validation import InputError
from .report_stress import table_number
from .result_folder import (
    _clashes,
    _marker_info,
    _sha256,
    folder_kind,
    is_result_folder,
    mark_folder,
)

if TYPE_CHECKING:
    from ..workflow.sweep import SweepResult

__all__ = ["write_sweep", "sweep_report_text", "check_resume", "sweep_identity"]

_MAX_ROWS = 60


def write_sweep(result: SweepResult, out_dir: PathLike, *, figures: bool = True) -> dict:
    """Write the files of a :class:`~tribodyn.workflow.sweep.SweepResult` into
    ``out_dir``; returns ``{"dataset": path, "report": path, "figures": {…}}``.
    Raises :class:`~tribodyn.InputError`, before writing, if the user's files in
    ``out_dir`` have the names of files it writes (module docstring)."""
    out = Path(out_dir)
    if out.is_dir() and any(out.iterdir()):
        if not is_result_folder(out):
            raise InputError(
                f"{str(out)!r} is a folder that tribodyn did not write; the sweep "
                "writes only into its own result folders: give a new or empty folder"
            )
        if folder_kind(out) not in (None, "sweep"):
            raise InputError(
                f"{str(out)!r} holds the results of `tribodyn {folder_kind(out)}`; the "
                "sweep would replace them: give another folder"
            )
        clash = _clashes(out, {})
        if clash:
            raise InputError(
                f"{str(out)!r}: {', '.join(clash)} changed since tribodyn wrote it, or "
                "was not written by tribodyn, and the sweep would replace it: move it "
                "elsewhere (the point files stay; write_sweep again)"
            )
    make_dirs(out)
    ds = result.dataset
    atomic_write_with(out / "sweep.nc", lambda tmp: ds.to_netcdf(tmp, engine="h5netcdf"))
    atomic_write(out / "sweep.toml", result.spec.to_toml())
    atomic_write(out / "base_case.toml", result.spec.base.to_toml(resolve_paths=True))
    figs = {}
    if figures:
        from .figures.sweep import sweep_figures

        figs = sweep_figures(ds, out)
    atomic_write(out / "sweep_report.md", sweep_report_text(result, figs))
    written = ["sweep.nc", "sweep.toml", "base_case.toml", "sweep_report.md"]
    written += [Path(p).name for p in figs.values()]
    listed = _marker_info(out).get("files")
    files = dict(listed) if isinstance(listed, dict) else {}
    files.update({name: _sha256(out / name) for name in written})
    mark_folder(
        out, files, {"kind": "sweep", "sweep": result.spec.name, **sweep_identity(result.spec)}
    )
    return {"dataset": out / "sweep.nc", "report": out / "sweep_report.md", "figures": figs}


def sweep_identity(spec) -> dict:
    """What makes a sweep the same sweep when it is resumed (recorded in the marker): its
    mode and dimensions. Values may change (a sweep extended by another speed)."""
    return {"sweep_mode": spec.mode, "sweep_dims": [d for d, _ in spec.dims]}


def check_resume(out_dir: PathLike, spec, option: str = "--resume") -> None:
    """Raise :class:`~tribodyn.InputError` if ``out_dir`` holds the results of another
    sweep than ``spec``: another name, mode or set of dimensions (the marker's record;
    :func:`sweep_identity`). A sweep whose values changed (extended) may resume."""
    info = _marker_info(Path(out_dir))
    if info.get("kind") != "sweep":
        return
    now = {"sweep": spec.name, **sweep_identity(spec)}
    had = {k: info.get(k) for k in now}
    differ = [k for k in now if had.get(k) is not None and had[k] != now[k]]
    if differ:
        what = {"sweep": "name", "sweep_mode": "mode", "sweep_dims": "dimensions"}
        diff = "; ".join(f"{what[k]} {had[k]!r} there, {now[k]!r} here" for k in differ)
        raise InputError(
            f"{option}: {str(out_dir)!r} holds the results of another sweep ({diff}); "
            "resuming would replace its sweep.nc and report: give another folder"
        )


#: What a point of each sweep mode computes (report text).
_MODE_TEXT = {
    "study": "the full cam-cycle study",
    "dynamics": "the valvetrain dynamics alone",
    "engine": "the whole engine's valvetrain (each lobe kind once, phase-shifted)",
}


def _values_text(values) -> str:
    vals = [f"{v:.6g}" if isinstance(v, float) else str(v) for v in values]
    return (
        ", ".join(vals)
        if len(vals) <= 8
        else f"{vals[0]}, {vals[1]}, … {vals[-1]} ({len(vals)} values)"
    )


def _at(da, spec, pos):
    sel = {d: i for (d, _), i in zip(spec.dims, pos)}
    return da.isel(sel)


def sweep_report_text(result, figures: dict | None = None) -> str:
    """The Markdown report of a sweep."""
    from .figures.sweep import SWEEP_FIGURES, onset_speeds

    spec, ds = result.spec, result.dataset
    figures = figures or {}
    n, nf = len(result.points), len(result.failed)
    lines = [f"# Sweep `{spec.name}`", ""]
    if spec.config.sweep.description:
        lines += [spec.config.sweep.description, ""]
    where = f"Dask scheduler {result.scheduler}" if result.scheduler else "a local cluster"
    lines += [
        f"* base case: `{spec.base_source}` (`{spec.base.name}`; complete case in "
        "`base_case.toml` and in the `base_case_toml` attribute of `sweep.nc`)",
        f"* per point: {_MODE_TEXT.get(spec.mode, spec.mode)}"
        f"{' with cycle traces' if spec.traces else ''}",
        f"* points: {n} ({n - nf} finished, {nf} failed); {result.ran} run now, "
        f"{result.skipped} taken from an earlier run",
        f"* run time {result.runtime_s:.1f} s on {result.workers} worker(s), {where}; "
        f"tribodyn {ds.attrs.get('tribodyn_version', '')}",
        "",
    ]
    lines += ["## Axes", "", "| dimension | key path | unit | values |", "|---|---|---|---|"]
    lines += [
        f"| {dim} | `{a.path}` | {a.unit or '–'} | {_values_text(a.values)} |"
        for dim, axes in spec.dims
        for a in axes
    ]
    lines += [
        "",
        f"Combination: {spec.config.sweep.combine}"
        + (" (axes sharing a group are zipped)" if any(len(a) > 1 for _, a in spec.dims) else ""),
        "",
    ]
    if spec.config.fixed:
        lines += ["Fixed changes to the base case at every point:", ""]
        lines += [f"* `{k}` = {v!r}" for k, v in spec.config.fixed.items()] + [""]
    lines += _results_tables(result)
    lines += _onsets(ds, onset_speeds)
    if figures:
        lines += ["## Figures", ""]
        for name, path in figures.items():
            lines += [
                f"![{SWEEP_FIGURES.get(name, name)}]({Path(path).name})",
                "",
                f"*{SWEEP_FIGURES.get(name, name)}.*",
                "",
            ]
    lines += _failures_and_warnings(result)
    lines += [
        "## Files",
        "",
        "* `sweep.nc` — all points in one xarray Dataset indexed by the sweep "
        "dimensions (and `surface_set`); `status` 1/0 and `error` per point; units "
        "in the `units` attributes",
        "* `points/<key>.nc` — one file per point (the record `--resume` uses)",
        "* `sweep.toml` — the sweep as run; `base_case.toml` — the base case",
        "",
    ]
    return "\n".join(lines)


def _results_tables(result) -> list[str]:
    spec, ds = result.spec, result.dataset
    rows = [(p.label, p.position) for p in result.points[:_MAX_ROWS]]  # capped
    out = ["## Results", ""]
    if len(result.points) > _MAX_ROWS:
        out += [f"The first {_MAX_ROWS} of {len(result.points)} points; all are in `sweep.nc`.", ""]
    dyn_cols = [
        ("peak_contact_force_N", "peak F [N]", ".4g"),
        ("min_contact_force_in_event_N", "min F in event [N]", ".4g"),
        ("jump", "jump", None),
        ("valve_bounce", "bounce", None),
        ("seating_velocity_m_s", "seating v [m/s]", ".3g"),
        ("runtime_s", "run time [s]", ".3g"),
        ("cpu_s", "CPU [s]", ".3g"),
    ]
    dyn_cols = [c for c in dyn_cols if c[0] in ds]
    if dyn_cols:
        out += [
            "Valvetrain dynamics (explicit tribology of the reference set):",
            "",
            "| point | " + " | ".join(c[1] for c in dyn_cols) + " |",
            "|---|" + "---|" * len(dyn_cols),
        ]
        for label, pos in rows:
            cells = []
            for name, _, fmt in dyn_cols:
                v = float(_at(ds[name], spec, pos).values)
                cells.append(
                    ("yes" if v == 1 else "no" if v == 0 else "–")
                    if fmt is None
                    else table_number(v, fmt)
                )
            out.append(f"| {label} | " + " | ".join(cells) + " |")
        out.append("")
    if "surface_set" not in ds.dims:
        return out
    sets = [str(s) for s in ds["surface_set"].values]
    for name, title, scale, fmt in (
        ("friction_energy_per_cycle_J", "Friction energy per engine cycle [J]", 1, ".4g"),
        ("valvetrain_friction_mep_Pa", "Valvetrain friction MEP of the engine [kPa]", 1e-3, ".4g"),
        (
            "engine_friction_torque_Nm",
            "Mean camshaft friction torque, all camshafts [N m]",
            1,
            ".4g",
        ),
        ("engine_friction_power_W", "Valvetrain friction power of the engine [W]", 1, ".4g"),
        (
            "engine_friction_energy_change_pct",
            "Engine valvetrain friction energy per cycle (and FMEP), change against the "
            "reference set [%, negative = less]",
            1,
            ".3g",
        ),
        ("mean_friction_power_W", "Mean friction power [W]", 1, ".4g"),
        ("min_film_m", "Minimum film thickness in the cam event [µm]", 1e6, ".4g"),
        ("min_lambda", "Minimum λ = h_min/σ in the cam event", 1, ".3g"),
        (
            "friction_energy_change_pct",
            "Friction energy per cycle, change against the reference set [%, negative = less]",
            1,
            ".3g",
        ),
        (
            "boundary_friction_cycle_integral_change_pct",
            "Boundary friction ∫F_b dt over the cam event, change against the reference set "
            "[%, negative = less]",
            1,
            ".3g",
        ),
        ("failed_steps", "Transient-EHL steps that did not converge", 1, ".0f"),
    ):
        if name not in ds:
            continue
        out += [
            f"{title}:",
            "",
            "| point | " + " | ".join(sets) + " |",
            "|---|" + "---|" * len(sets),
        ]
        for label, pos in rows:
            vals = np.asarray(_at(ds[name], spec, pos).values, float) * scale
            out.append(
                f"| {label} | " + " | ".join(table_number(float(x), fmt) for x in vals) + " |"
            )
        out.append("")
    return out


def _onsets(ds, onset_speeds) -> list[str]:
    out = []
    for var, what in (
        ("jump", "Jump (cam contact lost while the cam lifts)"),
        ("valve_bounce", "Valve bounce"),
    ):
        res = onset_speeds(ds, var)
        if not res:
            continue
        out += [f"{what}:", ""]
        for label, lo, hi in res:
            head = f"* {label}: " if label else "* "
            if not math.isfinite(hi):
                out.append(head + "none in the swept range")
            elif not math.isfinite(lo):
                out.append(head + f"already at the lowest swept value ({hi:g})")
            else:
                out.append(
                    head + f"onset between {lo:g} and {hi:g} (first occurrence at "
                    f"{hi:g}; resolution = the sweep's step)"
                )
        out.append("")
    return (["## Onset of jump and bounce", ""] + out) if out else []


def _failures_and_warnings(result) -> list[str]:
    out = []
    if result.failed:
        out += [
            "## Failed points",
            "",
            f"{len(result.failed)} point(s) failed; the others "
            "completed. Their variables are NaN in `sweep.nc` (`status` = 0).",
            "",
            "| point | error |",
            "|---|---|",
        ]
        out += [
            f"| {p.label} | {str(err).replace('|', '/').splitlines()[0] if err else ''} |"
            for p, err in result.failed[:_MAX_ROWS]
        ]
        out.append("")
    ds = result.dataset
    warnings = ds.get("warnings")
    bad = [
        f"* {p.label}: {w}"
        for p in result.points
        if warnings is not None and (w := str(_at(warnings, result.spec, p.position).values))
    ]
    if bad:
        out += [
            "## Warnings",
            "",
            "Finished points whose study reported a problem "
            "(non-converged EHL steps are also counted per surface set in "
            "`failed_steps`; the implicit coupling only feeds the explicit-vs-implicit "
            "comparison, not the EHL of the surface sets):",
            "",
        ]
        out += bad[:_MAX_ROWS] + [""]
    if "jump" in ds and float(np.nansum(ds["jump"].values)) > 0 and "surface_set" in ds.dims:
        out += [
            "Where the follower jumps, the cam and tappet separate during the event: "
            "the EHL is not solved while the contact force is below "
            "`numerics.min_load`, and the film and friction figures at those speeds "
            "describe the remaining loaded part of the event.",
            "",
        ]
    return out

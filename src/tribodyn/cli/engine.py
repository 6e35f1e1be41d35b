"""``tribodyn engine``: a whole engine's direct-acting valvetrain (camshaft torque,
friction energy per cycle, valvetrain FMEP, auxiliary friction) from a case with
``[engine] cylinders``."""

from __future__ import annotations

from pathlib import Path

import typer
from rich.console import Console
from rich.markup import escape

from .._validation import InputError
from ..physics.limits import WORKERS
from .failure import fail

__all__ = ["engine_command"]

console = Console()


def engine_command(
    case: Path = typer.Argument(
        ..., help="case file (TOML) with [engine] cylinders, or a bundled name"
    ),
    out: Path = typer.Option(Path("results_engine"), "-o", "--out", help="output folder"),
    workers: int | None = typer.Option(
        None, "--workers", "-j", help="processes (default: the case's numerics.workers)"
    ),
    no_figures: bool = typer.Option(False, "--no-figures", help="skip the figures"),
):
    """Run the engine's valvetrain: each lobe kind once, phase-shifted to every valve.

    Writes OUT/results.nc, summary.json, case.toml, the figures
    (engine_camshaft_torque.png, engine_lobe_contributions.png) and the report
    (report.md, report.html with interactive traces). Exit codes: 0 done,
    1 study or writing failed, 2 bad input.
    """
    from ..config import load_case
    from ..output import check_output_dir
    from ..output.engine import write_engine_results
    from ..workflow.cycle import StudyError
    from ..workflow.engine import run_engine_study

    try:
        c = load_case(case)
        if c.engine.cylinders is None:
            raise InputError(
                "engine.cylinders: the case describes one valve; add [engine] cylinders, "
                "firing_order, displacement, [engine.intake] and [engine.exhaust] "
                "(docs: case files, [engine]) or use tribodyn run"
            )
        if workers is not None:
            WORKERS.check("-j/--workers", workers)
        out = check_output_dir(out, option="-o/--out", kind="engine")
    except InputError as exc:
        fail(console, exc, label="error in the case")
    n_workers = workers if workers is not None else (c.numerics.workers or None)
    console.print(
        f"engine [bold]{c.name}[/bold]: {c.engine.cylinders} cylinders, "
        f"{c.engine.speed_rpm:g} rpm, {len(c.surface_set_names)} surface sets → {out}"
    )
    try:
        study = run_engine_study(c, workers=n_workers)
    except StudyError as exc:
        fail(console, exc, code=1, label="study failed")
    try:
        res = write_engine_results(study, out, figures=not no_figures)
    except (OSError, InputError) as exc:
        fail(console, exc, code=1)
    ref = res["summary"]["engine"]["reference_set"]
    for name, d in res["summary"]["engine"]["surface_sets"].items():
        change = d.get("friction_energy_change_pct")
        console.print(
            f"{name:>12}: {d['engine_friction_energy_per_cycle_J']:.3f} J/cycle, "
            f"FMEP {d['valvetrain_friction_mep_Pa'] / 1e3:.2f} kPa, "
            f"{d['mean_friction_power_W']:.1f} W"
            + ("" if name == ref else f", {change:+.2f} % vs {ref}" if change is not None else "")
        )
    console.print(
        f"% vs {ref}: change of the friction energy per cycle (and FMEP), "
        "100·(x/x_ref − 1), negative = less"
    )
    sets = res["summary"]["engine"]["surface_sets"]
    for law in sorted({d.get("asperity_law") for d in sets.values()} - {None, ""}):
        console.print(f"asperity law: {escape(law)}")
    for d in sets.values():
        if d.get("coating_verdict"):
            console.print(f"verdict (FMEP): {escape(d['coating_verdict']['sentence'])}")
    for w in study.warnings:
        console.print(f"[yellow]warning:[/yellow] {escape(w)}")
    console.print(
        f"wrote {out}/results.nc, summary.json, case.toml, report.md, report.html in "
        f"{study.runtime_s:.1f} s"
    )

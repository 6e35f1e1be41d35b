"""``tribodyn sweep``: a design sweep on Dask, with a progress bar and a summary."""

from __future__ import annotations

from pathlib import Path

import typer
from rich.console import Console
from rich.markup import escape
from rich.progress import (
    BarColumn,
    MofNCompleteColumn,
    Progress,
    TextColumn,
    TimeElapsedColumn,
    TimeRemainingColumn,
)

from .._validation import InputError
from .failure import dask_client, fail

__all__ = ["sweep_command"]

console = Console()


def _duration(s: float) -> str:
    if s < 120:
        return f"{s:.0f} s"
    if s < 7200:
        return f"{s / 60:.1f} min"
    return f"{s / 3600:.1f} h"


def sweep_command(
    sweep: Path = typer.Argument(..., help="sweep file (TOML), or a bundled sweep name"),
    out: Path = typer.Option(
        ..., "-o", "--out", help="output folder (point files, sweep.nc, report, figures)"
    ),
    scheduler: str | None = typer.Option(
        None,
        "--scheduler",
        metavar="ADDRESS",
        help="existing Dask scheduler (tcp://host:8786, or a scheduler file); default: "
        "a local cluster sized to the machine",
    ),
    workers: int | None = typer.Option(
        None,
        "--workers",
        "-j",
        help="local cluster: worker processes (default: one "
        "per CPU core); with --scheduler: wait for this "
        "many workers",
    ),
    resume: bool = typer.Option(
        False, "--resume", help="go on with the sweep in OUT: skip the finished points"
    ),
    dry_run: bool = typer.Option(
        False,
        "--dry-run",
        help="validate, print the number of points and an estimate of the time; run nothing",
    ),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="no progress bar"),
):
    """Run a design sweep: one task per point on a Dask cluster (local by default).

    Writes OUT/points/<key>.nc as each point finishes, then OUT/sweep.nc,
    sweep_report.md, the figures, sweep.toml and base_case.toml. OUT must be new, empty
    or a tribodyn result folder; files tribodyn did not write there are kept. Exit code
    2 on bad input, 1 if any point failed (everything is still written).
    """
    from ..config.sweep import load_sweep
    from ..workflow.sweep import PLAN_CHECK_LIMIT, estimate_sweep, machine_workers, run_sweep

    try:
        spec = load_sweep(sweep)
        if workers is not None and workers < 1:
            raise InputError(f"--workers: must be >= 1 (got {workers})")
    except InputError as exc:
        fail(console, exc, label="error in the sweep")
    shape = " × ".join(f"{d} {len(a[0].values)}" for d, a in spec.dims)
    console.print(
        f"sweep [bold]{spec.name}[/bold]: {spec.n_points} points ({shape}), "
        f"mode {spec.mode}, base case {spec.base.name} → {out}"
    )
    if dry_run:
        n_w = workers or machine_workers()
        try:
            est = estimate_sweep(spec, workers=n_w, out_dir=out if resume else None)
        except Exception as exc:  # an estimate that cannot be made is not fatal
            console.print(f"[yellow]no time estimate:[/yellow] {type(exc).__name__}: {exc}")
            raise typer.Exit(0)
        if est["checked"]:
            console.print(
                f"{est['points']} points: {est['invalid']} invalid combinations, "
                f"{est['done']} already finished, {est['todo']} to run"
            )
        else:
            console.print(
                f"{est['points']} points: {est['done']} already finished, {est['todo']} "
                f"to run (combinations are validated up to {PLAN_CHECK_LIMIT} points only; "
                "invalid ones are found when the sweep runs)"
            )
        console.print(
            f"estimate: {est['seconds_per_point']:.1f} s per point on one core "
            f"({est['method']}) → about {_duration(est['seconds'])} on "
            f"{est['workers']} worker(s)"
        )
        raise typer.Exit(0)

    from ..output import check_output_dir
    from ..output.sweep import check_resume

    try:  # before computing: a file, a foreign folder, a name too long, no space
        out = check_output_dir(out, option="-o/--out", kind="sweep")
        if resume:
            check_resume(out, spec)
    except InputError as exc:
        fail(console, exc)
    with (
        dask_client(console, scheduler, workers=workers) as client,
        Progress(
            TextColumn("{task.description}"),
            BarColumn(),
            MofNCompleteColumn(),
            TextColumn("[red]{task.fields[failed]} failed"),
            TimeElapsedColumn(),
            TextColumn("ETA"),
            TimeRemainingColumn(),
            console=console,
            disable=quiet,
            transient=False,
        ) as bar,
    ):
        task = bar.add_task("points", total=spec.n_points, failed=0)

        def progress(event, **info):
            if event == "start":
                bar.update(
                    task, completed=info["skipped"] + info["invalid"], failed=info["invalid"]
                )
                where = info["scheduler"] or "local cluster"
                run = (
                    f"{info['todo']} points to run on {info['workers']} worker(s) ({where})"
                    if info["todo"]
                    else "nothing to run"
                )
                bar.console.print(
                    f"{run}; {info['skipped']} already finished, "
                    f"{info['invalid']} invalid combinations"
                )
            elif event == "point":
                bar.update(task, completed=info["done"], failed=info["failed"])
                if info["status"] != "ok":
                    bar.console.print(
                        f"[yellow]point failed[/yellow] ({info['label']}): {info['error']}"
                    )

        try:
            result = run_sweep(
                spec, client, out_dir=out, resume=resume, workers=workers, progress=progress
            )
        except InputError as exc:
            fail(console, exc)
    from ..output.sweep import write_sweep

    try:
        files = write_sweep(result, out)
    except (InputError, OSError) as exc:  # changed meanwhile; the point files are kept
        console.print(f"[red]error writing the sweep files:[/red] {escape(str(exc))}")
        console.print(f"the finished points are in {out}/points (rerun with --resume)")
        raise typer.Exit(1)
    console.print(
        f"{result.n_ok} of {len(result.points)} points finished "
        f"({result.ran} run now, {result.skipped} resumed), {len(result.failed)} "
        f"failed, in {_duration(result.runtime_s)}"
    )
    console.print(f"wrote {out}/sweep.nc, sweep_report.md and {len(files['figures'])} figures")
    if result.failed:
        raise typer.Exit(1)

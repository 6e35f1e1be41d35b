"""``tribodyn run``: the cam-cycle study of a case, with a progress bar and a summary table."""

from __future__ import annotations

import multiprocessing
import os
import signal
import sys
import threading
from contextlib import suppress
from pathlib import Path

import typer
from rich import box
from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn
from rich.table import Table

from .._validation import InputError
from ..physics.limits import WORKERS
from .failure import dask_client, fail
from .heap import long_lived_heap
from .help_defaults import stating

__all__ = ["run_command", "RunCommand"]

console = Console()


def stated_defaults() -> dict[str, str]:
    """The values ``tribodyn run --help`` quotes: the bundled case it runs without CASE."""
    from ..config import DEFAULT_CASE

    return {"case": DEFAULT_CASE.stem}


#: the command's class: its --help quotes :func:`stated_defaults`
RunCommand = stating(stated_defaults)


def run_command(
    case: Path | None = typer.Argument(
        None, help="case file (TOML) or bundled case name; default: the bundled case {case}"
    ),
    out: Path = typer.Option(Path("results"), "-o", "--out", help="output folder"),
    workers: int | None = typer.Option(
        None,
        "--workers",
        "-j",
        help="processes (default: the case's numerics.workers; 0 there means one per CPU core)",
    ),
    implicit: bool | None = typer.Option(
        None,
        "--implicit/--no-implicit",
        help="run the implicit dynamics for the comparison (default: from the case)",
    ),
    scheduler: str | None = typer.Option(
        None,
        "--scheduler",
        metavar="ADDRESS",
        help="run the surface sets and the coupling chain on an existing Dask "
        "scheduler (tcp://host:8786, or a scheduler file) instead of local "
        "processes",
    ),
    compare_paper: bool | None = typer.Option(
        None,
        "--compare-paper/--no-compare-paper",
        help="add the paper's comparison (claims table, paper figure numbers, Figs. 5/6 "
        "at the paper's conditions); default: only for the paper's case",
    ),
    figures: bool = typer.Option(
        False,
        "--figures/--no-figures",
        help="draw the static figures (PNG) too; later: tribodyn figures OUT",
    ),
    quiet: bool = typer.Option(False, "--quiet", "-q", help="no progress bar"),
):
    """Run the cam-cycle study: dynamics, transient EHL per surface set, report.

    Writes OUT/results.nc, summary.json, report.md, report.html (self-contained, with
    interactive traces), traces.csv, dynamics.csv and case.toml (with copies of the files
    it reads in OUT/inputs); the static figures (PNG) with --figures, or later by
    `tribodyn figures OUT`; the folder is replaced only when everything has
    been written, and only if it is a previous result folder (or new, or empty); files
    that tribodyn did not write there are kept. If writing fails, the results are saved
    elsewhere and the message says where. Exit codes: 0 done, 1 study or writing failed, 2 bad input,
    130/143 interrupted (Ctrl-C/SIGTERM; nothing written).
    """
    from ..config import load_case
    from ..output import check_output_dir
    from ..output.writer import case_inputs

    try:
        c = load_case(case)
        if implicit is not None:
            c = c.updated({"numerics.implicit_coupling": implicit})
    except InputError as exc:
        msg = str(exc)
        if case is not None and not (case.exists() or case.is_symlink()):
            msg += f"; {_bundled_names()}"
        fail(console, msg, label="error in the case")
    try:
        if workers is not None:
            WORKERS.check("-j/--workers", workers)
        # before hours of computing
        out = check_output_dir(out, option="-o/--out", writes=case_inputs(c)[1], kind="run")
    except InputError as exc:
        fail(console, exc)
    with _terminate_as_interrupt():
        try:
            _run(c, out, workers, quiet, scheduler, compare_paper, figures)
        except typer.Exit:
            raise
        except BaseException as exc:
            # Ctrl-C, SIGTERM, or an error raised while the workers are being stopped
            if not (isinstance(exc, KeyboardInterrupt) or _terminated):
                raise
            _clear_interrupt_flag()
            rescued = getattr(exc.__cause__, "rescued", None)
            console.print(
                f"[red]interrupted:[/red] nothing written; {escape(str(out))} is unchanged"
                + (
                    f"; the computed results were saved to {escape(str(rescued))}"
                    if rescued
                    else ""
                )
            )
            raise typer.Exit(143 if _terminated else 130)
        if _terminated:  # the signal came after the results were complete
            _clear_interrupt_flag()
            console.print(
                f"[red]terminated[/red] after the results were written to {escape(str(out))}"
            )
            raise typer.Exit(143)


def _bundled_names() -> str:
    """The bundled cases and sweeps, for a name that is not a file."""
    from ..config import bundled_cases, bundled_sweeps

    return (
        f"bundled cases: {', '.join(bundled_cases())}; bundled sweeps (tribodyn "
        f"sweep NAME -o DIR): {', '.join(bundled_sweeps())}"
    )


_terminated = False


def _clear_interrupt_flag() -> None:
    """Let the exit code stand after a handled interrupt. A KeyboardInterrupt that passed
    through ``exec`` of source text (dataclasses and namedtuples are made that way) sets
    CPython's flag of an unhandled interrupt even when it is caught later, and
    ``python -m`` then ends the process as killed by SIGINT (-2) instead of with its exit
    code; running any source text clears the flag."""
    exec("pass")


def _workers() -> list:
    """The worker processes of this process (not a manager, which shuts down itself)."""
    return [c for c in multiprocessing.active_children() if not c.name.startswith("SyncManager")]


def _stop_workers() -> None:
    """Kill the worker processes of this process (they hold no output)."""
    for child in _workers():
        child.kill()


class _ImportsAhead:
    """The writing's imports (:func:`~tribodyn.output.writer.import_writing_modules`)
    made in a thread while this process waits for its study's worker processes: started
    at the first progress event after they were forked (an import under way in a fork
    would stay locked in the child), so not with one worker or a Dask scheduler."""

    def __init__(self) -> None:
        self.thread: threading.Thread | None = None

    def poll(self) -> None:
        if self.thread is None and _workers():
            self.thread = threading.Thread(target=self._run, daemon=True)
            self.thread.start()

    @staticmethod
    def _run() -> None:
        from ..output.writer import import_writing_modules

        with suppress(Exception):  # the writing imports them again and reports the error
            import_writing_modules()

    def join(self) -> None:
        if self.thread is not None:
            self.thread.join()


def stop_if_terminated() -> None:
    """Raise the interrupt of a SIGTERM whose KeyboardInterrupt was lost in a callback. A
    signal during a fork is such a case: the handler cannot stop the worker being forked,
    and its interrupt is raised inside the after-fork hook, so the run would go on; it is
    stopped here, at the next event in this process, its workers with it."""
    if _terminated:
        _stop_workers()
        raise KeyboardInterrupt


class _terminate_as_interrupt:
    """SIGTERM is handled like Ctrl-C (KeyboardInterrupt), so that temporary output is
    removed; worker processes are stopped first."""

    def __enter__(self):
        global _terminated
        _terminated = False
        main = os.getpid()

        def handler(signum, frame):
            global _terminated
            if os.getpid() != main:  # a forked worker inherited the handler
                signal.signal(signal.SIGTERM, signal.SIG_DFL)
                os.kill(os.getpid(), signal.SIGTERM)
                return
            _terminated = True
            _stop_workers()
            raise KeyboardInterrupt

        def unraisable(info):
            # the interrupt raised inside a callback (a weakref's, a finaliser, an
            # after-fork hook) is lost there; the stopped workers then fail the run, or
            # the next progress event stops it (stop_if_terminated): it ends as
            # interrupted. After the signal, the finalisers of objects the interrupt cut
            # short (e.g. a results.nc file half opened) fail too: the run ends, quietly
            if not _terminated:
                self._old_hook(info)

        try:
            self._old = signal.signal(signal.SIGTERM, handler)
        except ValueError:  # not the main thread: leave signals alone
            self._old = None
        self._old_hook = sys.unraisablehook
        sys.unraisablehook = unraisable
        return self

    def __exit__(self, *exc):
        if self._old is not None:
            signal.signal(signal.SIGTERM, self._old)
        if not _terminated:  # else kept until the process ends (see unraisable)
            sys.unraisablehook = self._old_hook
        return False


def _run(
    c,
    out: Path,
    workers,
    quiet: bool,
    scheduler: str | None = None,
    compare_paper: bool | None = None,
    figures: bool = False,
) -> None:
    """Compute the study, write it (the static figures with ``figures``), print the
    summary table."""
    from ..output import OutputWriteError, write_results
    from ..workflow.cycle import StudyError, run_cycle_study

    n_workers = workers if workers is not None else (c.numerics.workers or None)
    console.print(
        f"case [bold]{c.name}[/bold]: {len(c.surface_set_names)} surface sets, "
        f"{c.engine_speed:g} rpm → {out}"
    )
    with (
        dask_client(console, scheduler) as client,
        Progress(
            TextColumn("{task.description:<24}"),
            BarColumn(),
            TextColumn("{task.percentage:>5.1f} %"),
            TimeElapsedColumn(),
            console=console,
            disable=quiet,
            transient=False,
        ) as bar,
        long_lived_heap() as keep,  # the imports and the case: out of full collections
    ):
        executor = None
        if client is not None:
            executor = client.get_executor(pure=False)
            n_dask = len(client.scheduler_info().get("workers", {}))
            bar.console.print(f"Dask scheduler {scheduler}: {n_dask} workers")
        tasks = {}
        ahead = _ImportsAhead()

        def progress(event, **info):
            stop_if_terminated()
            ahead.poll()
            if event == "dynamics":
                tasks["dyn"] = bar.add_task("valvetrain dynamics", total=1)
            elif event == "set":
                name = info["name"]
                if "dyn" in tasks:
                    bar.update(tasks["dyn"], completed=1)
                if name not in tasks:
                    tasks[name] = bar.add_task(f"EHL {name}", total=info["total"])
                bar.update(tasks[name], completed=info["done"])

        try:
            study = run_cycle_study(
                c,
                workers=n_workers,
                progress=progress,
                executor=executor,
                compare_paper=compare_paper,
            )
        except StudyError as exc:
            if _terminated:  # the workers were stopped by the signal
                raise KeyboardInterrupt from exc
            fail(console, exc, code=1, label="study failed")
        stop_if_terminated()  # a signal lost in a callback: nothing is written
        ahead.join()
        keep()  # the writing's modules too
        if "dyn" in tasks:
            bar.update(tasks["dyn"], completed=1)
        t_write = bar.add_task("figures and report" if figures else "report", total=1)
        try:
            res = write_results(study, out, figures=figures, workers=n_workers)
        except OutputWriteError as exc:
            if _terminated:  # the drawing processes were stopped by the signal
                raise KeyboardInterrupt from exc
            fail(console, exc, code=1)
        bar.update(t_write, completed=1)

    summ = res["summary"]
    console.print(summary_table(summ, c.name))
    ie = summ["implicit_vs_explicit"]
    if ie.get("max_contact_force_diff_pct") is not None:
        stable = ""
        if ie.get("rms_contact_force_diff_pct") is not None:
            stable += f"; RMS over the event {ie['rms_contact_force_diff_pct']:.2f} %"
        if ie.get("valve_closing_shift_deg") is not None:
            stable += f", valve closing shifted by {ie['valve_closing_shift_deg']:+.2f}°"
        console.print(
            f"implicit vs explicit: contact force differs by at most "
            f"{ie['max_contact_force_diff_pct']:.1f} % of its peak (at "
            f"{ie['max_contact_force_diff_crank_deg']:.1f}°{stable}), tappet velocity by "
            f"{ie['max_velocity_diff_pct']:.2f} %"
        )
    laws = {v.get("asperity_law") for v in summ["surface_sets"].values()}
    for law in sorted(x for x in laws if x):
        console.print(f"asperity law: {law}")
    for v in summ["surface_sets"].values():
        if v.get("coating_verdict"):
            console.print(f"verdict: {v['coating_verdict']['sentence']}")
    for w in summ["warnings"]:
        console.print(f"[yellow]warning:[/yellow] {w}")
    drawn = (
        f" and {len(res['figures'])} figures"
        if figures
        else f"; the static figures: tribodyn figures {out}"
    )
    console.print(
        f"wrote {out}/results.nc, summary.json, report.md, report.html, traces.csv"
        f"{drawn}; the study took {summ['runtime_s']:.1f} s (+ writing)"
    )


#: Columns of the summary table: header (name, then unit), summary key, scale, format.
_COLUMNS = (
    ("min\nfilm\nµm", "min_film_m", 1e6, ".3f"),
    ("max\nh_c\nµm", "max_central_film_m", 1e6, ".2f"),
    ("film\ngain\n%", "max_film_gain_vs_uncoated_pct", 1.0, "+.2f"),
    ("max\nF_b\nN", "max_boundary_friction_N", 1.0, ".4g"),
    ("max\nF_v\nN", "max_viscous_friction_N", 1.0, ".4g"),
    ("∫F_b dt\nchange\n%", "boundary_friction_cycle_integral_change_pct", 1.0, "+.1f"),
    ("\nenergy\nJ/cycle", "friction_energy_per_cycle_J", 1.0, ".3f"),
    ("\nfailed\nsteps", "failed_steps", 1.0, "d"),
)


def summary_table(summ: dict, name: str) -> Table:
    """The per-surface summary of ``tribodyn run``: fits 80 columns (two-line headers,
    no vertical rules); the gain and change columns are explained in the caption."""
    ref = summ.get("reference_set")
    ref_label = summ.get("surface_sets", {}).get(ref, {}).get("label", ref)
    table = Table(
        title=f"{name}: per tappet surface (cam event)",
        caption=f"film gain (max over the event) and ∫F_b dt change (cycle integral over "
        f"the event) vs {ref_label}: 100·(x/x_ref − 1), negative = less",
        box=box.SIMPLE_HEAD,
        padding=(0, 0, 0, 1),  # with the box's space: two between the columns
        pad_edge=False,
    )
    labels = [str(v["label"]) for v in summ["surface_sets"].values()]
    # headers (and labels longer than 16 characters) wrap at spaces; numbers do not
    table.add_column("surface", min_width=min(14, max(map(len, labels), default=7)))
    for head, *_ in _COLUMNS:
        table.add_column(head, justify="right")
    for label, v in zip(labels, summ["surface_sets"].values()):
        cells = [
            "–" if (x := v.get(key)) is None else format(x * scale + 0.0 if fmt != "d" else x, fmt)
            for _, key, scale, fmt in _COLUMNS
        ]
        table.add_row(label, *cells)
    return table

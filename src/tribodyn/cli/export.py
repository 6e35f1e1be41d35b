"""``tribodyn export RESULTS``: CSV traces and the self-contained HTML report of a result
folder (:mod:`tribodyn.output.export`), e.g. one written before these existed."""

from __future__ import annotations

from pathlib import Path

import typer
from rich.console import Console
from rich.markup import escape

from .._validation import InputError
from .failure import fail

__all__ = ["export_command"]

console = Console()


def export_command(
    results: Path = typer.Argument(..., help="result folder of `tribodyn run` (with results.nc)"),
    out: Path | None = typer.Option(
        None, "-o", "--out", help="folder to write into (default: the result folder)"
    ),
):
    """Write traces.csv and dynamics.csv (from results.nc) and report.html (report.md
    with its figures embedded; no external resources) into OUT.

    A file of those names that tribodyn did not write (or that was changed since) is
    never replaced: the export stops before writing and names it. Only regular files of
    RESULTS are embedded (a figure that is a link or lies elsewhere is left out, with a
    warning). Exit codes: 0 done, 1 OUT cannot be written, 2 bad input.
    """
    try:
        _export(results, out if out is not None else results)
    except InputError as exc:
        fail(console, exc)


def _export(results: Path, out: Path) -> None:
    import os

    from .._safe_write import make_dirs
    from ..output.dataset import load_run_results
    from ..output.explorer import write_report_html
    from ..output.export import CSV_FILES, report_markdown, write_csv
    from ..output.result_folder import add_own_files
    from ..output.writer import MARKER, own_files

    nc = results / "results.nc"
    if not nc.is_file():
        raise InputError(f"RESULTS: {results} has no results.nc (a `tribodyn run` result folder)")
    if out.exists() and not out.is_dir():
        raise InputError(f"-o/--out: {out} is a file, not a folder")
    md = results / "report.md"
    names = [*CSV_FILES, *(["report.html"] if os.path.lexists(md) else [])]
    own = own_files(out) if (out / MARKER).is_file() else set()
    taken = [n for n in names if os.path.lexists(out / n) and n not in own]
    if taken:
        raise InputError(
            f"-o/--out: {out} holds {', '.join(taken)}, not written by tribodyn (or "
            "changed since): move them or export elsewhere with -o"
        )
    ds = load_run_results(nc)
    notes: list[str] = []
    text = None
    if os.path.lexists(md):
        try:
            text = report_markdown(results, notes)
        except FileNotFoundError:
            notes.append(
                "report.md is a link or not a regular file of the result folder: "
                "report.html is not written"
            )
    try:
        make_dirs(out)
        try:
            written = write_csv(ds, out)
        except (KeyError, IndexError, ValueError, TypeError) as exc:
            raise InputError(
                f"RESULTS: {nc} is not a tribodyn results file of a cam-cycle study "
                f"({type(exc).__name__}: {exc})"
            ) from None
        if text is not None:  # figures are read from the result folder
            skipped: list[str] = []
            written.append(write_report_html(text, results, out / "report.html", skipped))
            if skipped:
                notes.append(
                    f"not embedded in report.html (missing, a link, or not a "
                    f"regular file of {results}): {', '.join(skipped)}"
                )
        add_own_files(out, written)  # a result folder: these are its own now
    except OSError as exc:  # a folder without write permission, a full disk, …
        fail(console, f"-o/--out: cannot write in {str(out)!r} ({exc.strerror or exc})", code=1)
    for n in notes:
        console.print(f"[yellow]warning:[/yellow] {escape(n)}", highlight=False, soft_wrap=True)
    console.print(f"wrote {escape(', '.join(str(p) for p in written))}")

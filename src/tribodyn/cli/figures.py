"""``tribodyn figures RESULTS``: the static figures of a ``tribodyn run`` result folder,
drawn from its results.nc into it (:mod:`tribodyn.output.figures_folder`)."""

from __future__ import annotations

from pathlib import Path

import typer
from rich.console import Console
from rich.markup import escape

from .._validation import InputError
from .failure import fail
from .help_defaults import stating

__all__ = ["figures_command", "FiguresCommand"]

console = Console()


def stated_defaults() -> dict[str, int]:
    """The values ``tribodyn figures --help`` quotes: the drawing processes on this machine."""
    from ..output.figures_folder import figure_workers

    return {"workers": figure_workers()}


#: the command's class: its --help quotes :func:`stated_defaults`
FiguresCommand = stating(stated_defaults)


def figures_command(
    results: Path = typer.Argument(..., help="result folder of `tribodyn run` (with results.nc)"),
    workers: int | None = typer.Option(
        None,
        "--workers",
        "-j",
        min=1,
        help="drawing processes (default: {workers}, one per CPU core)",
    ),
):
    """Draw the static figures (PNG) of a `tribodyn run` result folder into it, from its
    results.nc, and list them in its report.md and report.html.

    A file of a figure's name that tribodyn did not write (or that was changed since) is
    never replaced: nothing is drawn and the message names it; a report.md or report.html
    of the user's is left as it is. Drawing again replaces the figures drawn before. Exit
    codes: 0 done, 1 the folder cannot be written, 2 not a run result folder or a name
    taken.
    """
    from ..output.figures_folder import draw_figures

    notes: list[str] = []
    try:
        figs = draw_figures(results, workers=workers, notes=notes)
    except InputError as exc:
        fail(console, exc)
    except OSError as exc:  # a folder without write permission, a full disk, …
        fail(console, f"RESULTS: cannot write in {str(results)!r} ({exc.strerror or exc})", code=1)
    for n in notes:
        console.print(f"[yellow]warning:[/yellow] {escape(n)}", highlight=False, soft_wrap=True)
    console.print(f"drew {len(figs)} figures into {escape(str(results))}")

"""The ``tribodyn`` command-line application: ``run``, ``figures``, ``export``, ``sweep``,
``contact``, ``topography``, ``calibrate``, ``warmup``, ``engine``, ``view``."""

from __future__ import annotations

import inspect
from collections.abc import Callable
from typing import Any

import typer

from .._version import __version__
from .calibrate import calibrate_command
from .contact import ContactCommand, contact_command
from .engine import engine_command
from .export import export_command
from .figures import FiguresCommand, figures_command
from .heap import skip_collections_at_exit
from .run import RunCommand, run_command
from .sweep import sweep_command
from .topography import TopographyCommand, topography_command
from .view import view_command
from .warmup import warmup_command

__all__ = ["app", "main"]

app = typer.Typer(
    add_completion=False,
    no_args_is_help=True,
    help="Tribo-dynamics of coated cam–flat-tappet contacts.",
)


def _print_version(value: bool) -> None:
    if value:
        typer.echo(f"tribodyn {__version__}")
        raise typer.Exit()


@app.callback()
def _main(
    version: bool = typer.Option(
        False,
        "--version",
        callback=_print_version,
        is_eager=True,
        help="Print the version and exit.",
    ),
) -> None:
    """tribodyn: cam–tappet tribo-dynamics with coated surfaces."""


def help_text(doc: str | None) -> str:
    """A command's docstring as ``--help`` shows it: paragraphs (separated by blank lines)
    whose lines are joined, for the terminal to wrap at its width; an indented paragraph
    (an example command) is kept as written."""
    paragraphs = inspect.cleandoc(doc or "").split("\n\n")
    return "\n\n".join(
        p if p.startswith(" ") else " ".join(line.strip() for line in p.splitlines())
        for p in paragraphs
    )


def _command(name: str, function: Callable[..., Any], cls: type | None = None) -> None:
    """Register ``function`` as the command ``name`` with its help from its docstring."""
    app.command(name, cls=cls, help=help_text(function.__doc__))(function)


_command("run", run_command, RunCommand)
_command("figures", figures_command, FiguresCommand)
_command("export", export_command)
_command("sweep", sweep_command)
_command("contact", contact_command, ContactCommand)
_command("topography", topography_command, TopographyCommand)
_command("calibrate", calibrate_command)
_command("warmup", warmup_command)
_command("engine", engine_command)
_command("view", view_command)


def main() -> None:
    """The ``tribodyn`` command (console script, ``python -m tribodyn``): the application,
    in a process that skips the interpreter's collections at exit
    (:func:`~tribodyn.cli.heap.skip_collections_at_exit`)."""
    skip_collections_at_exit()
    app(prog_name="tribodyn")

"""The ``tribodyn`` command-line application: ``run``, ``figures``, ``export``, ``sweep``,
``contact``, ``topography``, ``calibrate``, ``warmup``, ``engine``, ``view``."""

from __future__ import annotations

import typer

from .._version import __version__
from .calibrate import calibrate_command
from .contact import ContactCommand, contact_command
from .engine import engine_command
from .export import export_command
from .figures import FiguresCommand, figures_command
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


app.command("run", cls=RunCommand)(run_command)
app.command("figures", cls=FiguresCommand)(figures_command)
app.command("export")(export_command)
app.command("sweep")(sweep_command)
app.command("contact", cls=ContactCommand)(contact_command)
app.command("topography", cls=TopographyCommand)(topography_command)
app.command("calibrate")(calibrate_command)
app.command("warmup")(warmup_command)
app.command("engine")(engine_command)
app.command("view")(view_command)


def main():  # pragma: no cover
    app()

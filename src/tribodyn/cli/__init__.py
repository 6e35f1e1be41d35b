"""Command line: :mod:`.app` (the typer application) with one module per command."""

from .app import app, main

__all__ = ["app", "main"]

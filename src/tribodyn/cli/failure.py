"""How a command ends on a user's mistake: one red line, then exit code 2 (1 for a
failure to write results). The message is escaped: rich would otherwise read the
``[section]`` names and paths in tribodyn's messages as markup and drop them, or fail on
a closing ``[/…]``."""

from __future__ import annotations

from typing import NoReturn

import typer
from rich.console import Console
from rich.markup import escape

__all__ = ["fail"]


def fail(console: Console, message: object, *, code: int = 2, label: str = "error") -> NoReturn:
    """Print ``label: message`` (``message`` as plain text, not wrapped) on ``console``
    and leave the command with exit ``code``."""
    console.print(f"[red]{label}:[/red] {escape(str(message))}", highlight=False, soft_wrap=True)
    raise typer.Exit(code)

"""How a command ends on a user's mistake: one red line, then exit code 2 (1 for a
failure to write results). The message is escaped: rich would otherwise read the
``[section]`` names and paths in tribodyn's messages as markup and drop them, or fail on
a closing ``[/…]``."""

from __future__ import annotations

from collections.abc import Iterator
from contextlib import contextmanager
from typing import TYPE_CHECKING, NoReturn

import typer
from rich.console import Console
from rich.markup import escape

if TYPE_CHECKING:
    from distributed import Client

__all__ = ["dask_client", "fail", "writing"]


def fail(console: Console, message: object, *, code: int = 2, label: str = "error") -> NoReturn:
    """Print ``label: message`` (``message`` as plain text, not wrapped) on ``console``
    and leave the command with exit ``code``."""
    console.print(f"[red]{label}:[/red] {escape(str(message))}", highlight=False, soft_wrap=True)
    raise typer.Exit(code)


@contextmanager
def writing(option: str, path: object) -> Iterator[None]:
    """Inside: an :class:`OSError` becomes an :class:`~tribodyn.InputError`
    ``option: cannot write 'path' (reason)`` (the file a command option names)."""
    try:
        yield
    except OSError as exc:
        from .._validation import InputError  # numpy: only once a command runs

        raise InputError(f"{option}: cannot write {str(path)!r} ({exc.strerror or exc})") from None


@contextmanager
def dask_client(
    console: Console, scheduler: str | None, *, workers: int | None = None
) -> Iterator[Client | None]:
    """Inside: a client of the Dask scheduler ``scheduler`` (None: no scheduler, yields
    None), with ``workers`` connected if given
    (:func:`~tribodyn.workflow.sweep.connect`); closed on the way out. A scheduler that
    cannot be reached ends the command with :func:`fail`."""
    if scheduler is None:
        yield None
        return
    from .._validation import InputError
    from ..workflow.sweep import connect

    try:
        client = connect(scheduler, workers=workers)
    except InputError as exc:
        fail(console, exc)
    try:
        yield client
    finally:
        client.close()

"""Command line: :mod:`.app` (the typer application) with one module per command.

The command line runs the solvers with one BLAS thread (:mod:`tribodyn._threads`): the
environment is set here, before numpy is first imported.
"""

from .._threads import set_blas_env

set_blas_env()

from .app import app, main  # noqa: E402  (after the BLAS environment)

__all__ = ["app", "main"]

"""``tribodyn view``: one self-contained interactive HTML page comparing result folders
of ``tribodyn run``, ``engine`` and ``sweep`` (:mod:`tribodyn.output.explorer`)."""

from __future__ import annotations

import time
from pathlib import Path

import typer
from rich.console import Console

from .._validation import InputError
from .failure import fail

__all__ = ["view_command"]

console = Console()


def view_command(
    results: list[Path] = typer.Argument(
        ..., help="result folders of tribodyn run, engine or sweep, in the order to compare"
    ),
    out: Path | None = typer.Option(
        None,
        "-o",
        "--out",
        help="the page to write (default: tribodyn_view.html here, or the next free name)",
    ),
    force: bool = typer.Option(False, "--force", help="replace an existing -o file"),
    serve: bool = typer.Option(
        False, "--serve", help="also serve the page on 127.0.0.1 (this machine only) until Ctrl-C"
    ),
    port: int = typer.Option(8765, "--port", help="the port of --serve (0: any free port)"),
):
    """Compare results on one interactive page that opens offline in a browser.

    Overlays over crank angle (film, λ, pressure, forces, torque, power) of every
    surface set of every run, the engines' camshaft torques, the sweeps' friction loss
    and heat maps, the summary numbers side by side with the differences against the
    first column, the coating verdicts and how the case files differ. The page needs no
    network and no server; --serve offers it at http://127.0.0.1:PORT/ as well. Exit
    codes: 0 written, 2 bad input (a folder that is not a result, an existing page
    without --force, a port in use).
    """
    from ..output.explorer import build_page, default_page_path, write_page

    t0 = time.perf_counter()
    try:
        page, n = build_page(results)
        path = write_page(page, out if out is not None else default_page_path(), force=force)
    except InputError as exc:
        fail(console, exc)
    except OSError as exc:
        fail(console, exc, code=1)
    size = path.stat().st_size / 1e6
    console.print(
        f"wrote {path} ({size:.2f} MB, {n} figures) in {time.perf_counter() - t0:.1f} s; "
        "open it in a browser"
    )
    if serve:
        from .view_serve import page_server

        if not 0 <= port <= 65535:
            fail(console, f"--port must be 0…65535 (got {port})")
        try:
            server = page_server(page.encode("utf-8"), port)
        except OSError as exc:
            fail(console, f"--port {port}: cannot listen on 127.0.0.1 ({exc.strerror or exc})")
        bound = server.server_address[1]
        console.print(f"serving at http://127.0.0.1:{bound}/ (this machine only); Ctrl-C stops")
        try:
            server.serve_forever()
        except KeyboardInterrupt:
            pass
        finally:
            server.server_close()

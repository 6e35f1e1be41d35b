"""``tribodyn export RESULTS``: CSV traces and the self-contained HTML report of a result
folder (:mod:`tribodyn.output.export`), e.g. one written before these existed."""

from __future__ import annotations

from pathlib import Path

import typer
from rich.console import Console

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
    never replaced: the export stops before writing and names it. Exit codes: 0 done,
    2 bad input.
    """
    try:
        _export(results, out if out is not None else results)
    except InputError as exc:
        fail(console, exc)


def _export(results: Path, out: Path) -> None:
    import xarray as xr

    from ..output.explorer import write_report_html
    from ..output.export import CSV_FILES, write_csv
    from ..output.writer import MARKER, _marker_info, _sha256, mark_folder, own_files

    nc = results / "results.nc"
    if not nc.is_file():
        raise InputError(f"RESULTS: {results} has no results.nc (a `tribodyn run` result folder)")
    if out.exists() and not out.is_dir():
        raise InputError(f"-o/--out: {out} is a file, not a folder")
    out.mkdir(parents=True, exist_ok=True)
    md = results / "report.md"
    names = [*CSV_FILES, *(["report.html"] if md.is_file() else [])]
    own = own_files(out) if (out / MARKER).is_file() else set()
    taken = [n for n in names if (out / n).exists() and n not in own]
    if taken:
        raise InputError(
            f"-o/--out: {out} holds {', '.join(taken)}, not written by tribodyn (or "
            "changed since): move them or export elsewhere with -o"
        )
    try:
        with xr.open_dataset(nc, engine="h5netcdf") as ds:
            ds.load()
    except (OSError, ValueError) as exc:
        raise InputError(f"RESULTS: cannot read {nc}: {exc}") from exc
    if "ehl_crank" not in ds.coords:
        raise InputError(f"RESULTS: {nc} is not the results of a cam-cycle study")
    written = write_csv(ds, out)
    if md.is_file():  # figures are read from the result folder
        html = write_report_html(md.read_text(encoding="utf-8"), results, path=out / "report.html")
        written.append(html)
    info = _marker_info(out)
    if isinstance(info.get("files"), dict):  # a result folder: these are its own now
        files = {**info.pop("files"), **{p.name: _sha256(p) for p in written}}
        mark_folder(out, files, {k: v for k, v in info.items() if k not in ("tool", "written")})
    console.print(f"wrote {', '.join(str(p) for p in written)}")

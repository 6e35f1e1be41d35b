"""The static figures of a ``tribodyn run`` result folder, drawn on request from the
folder's results.nc (``tribodyn figures RESULTS``, ``tribodyn run --figures``).

:func:`draw_figures` writes the PNGs into the folder (each atomically,
:mod:`tribodyn._safe_write`), lists them in report.md's figure section, renders
report.html again and records the new files in the folder's marker as tribodyn's own
(so that a new run replaces them). A file of a figure's name that tribodyn did not
write, or that was changed since, is never replaced: the drawing stops before it
begins and names it; a report.md or report.html of the user's is left as it is.
"""

from __future__ import annotations

import os
from pathlib import Path

from .._safe_write import atomic_write
from .._typing import PathLike
from .._validation import InputError

__all__ = ["draw_figures", "figure_workers"]


def figure_workers() -> int:
    """Processes drawing the figures by default: one per CPU core, at most 4."""
    return min(os.cpu_count() or 1, 4)


def _results(folder: Path):
    """The loaded results Dataset of the run result folder ``folder``; InputError if it
    is not one."""
    from .dataset import load_run_results
    from .result_folder import folder_kind

    nc = folder / "results.nc"
    kind = folder_kind(folder) if folder.is_dir() else None
    if kind not in (None, "run") or not nc.is_file():
        what = f"a `tribodyn {kind}` result folder" if kind else "not a result folder"
        raise InputError(
            f"RESULTS: {folder} is {what}; `tribodyn figures` draws the figures of a "
            "`tribodyn run` result folder (one with results.nc)"
        )
    return load_run_results(nc)


def draw_figures(
    folder: PathLike, *, workers: int | None = None, notes: list[str] | None = None
) -> dict[str, Path]:
    """Draw the figures of the run result folder ``folder`` into it (module docstring);
    returns ``{file name: path}`` of the figures written. ``workers``: drawing processes
    (default :func:`figure_workers`). ``notes`` receives what was left alone (a
    report of the user's). Raises :class:`~tribodyn._validation.InputError` for a folder
    that is not a run's, or one where a figure's name is taken by a file of the user's."""
    from .figures import figure_files, make_figures
    from .result_folder import add_own_files, is_result_folder, own_files

    folder = Path(folder)
    ds = _results(folder)
    own = own_files(folder) if is_result_folder(folder) else set()
    taken = [n for n in figure_files(ds) if os.path.lexists(folder / n) and n not in own]
    if taken:
        raise InputError(
            f"RESULTS: {folder} holds {', '.join(taken)}, not written by tribodyn (or "
            "changed since): move them, then draw the figures again"
        )
    figs = make_figures(ds, folder, workers=workers or figure_workers())
    if notes is not None and "gV" in ds and "regime_map" not in ds:
        notes.append(
            "Fig. 12 (Greenwood chart) is not drawn: these results predate its stored "
            "regime map; run the study again to draw it"
        )
    written = list(figs.values())
    if "report.md" in own:
        written += _list_in_report(folder, ds, figs, "report.html" in own, notes)
    elif notes is not None and os.path.lexists(folder / "report.md"):
        notes.append(
            "report.md is not tribodyn's (or was changed): the figures are not listed in it"
        )
    add_own_files(folder, written)  # these are the folder's own files now
    return figs


def _list_in_report(folder: Path, ds, figs: dict, html_own: bool, notes) -> list[Path]:
    """Show ``figs`` in report.md's figure section and render report.html again (unless
    the user's); returns the files written."""
    from .explorer import write_report_html
    from .export import report_markdown
    from .report import with_figures

    try:
        text = with_figures(report_markdown(folder), ds, figs)
    except ValueError:  # a report without a figure section: left as it is
        if notes is not None:
            notes.append("report.md has no figure section: the figures are not listed in it")
        return []
    out = [atomic_write(folder / "report.md", text)]
    if html_own or not os.path.lexists(folder / "report.html"):
        out.append(write_report_html(text, folder))
    elif notes is not None:
        notes.append("report.html is not tribodyn's (or was changed): it is left as it is")
    return out

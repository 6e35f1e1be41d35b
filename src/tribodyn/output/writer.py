"""Writing a cycle study: results.nc, summary.json, case.toml, figures and report.md, into
one folder, atomically, without ever losing results or replacing someone else's files.

* **Check first.** :func:`check_output_dir` runs before the computation: the target must
  be absent, an empty folder or a previous tribodyn result folder (marked by the file
  ``.tribodyn-results``, or, from tribodyn 0.1, holding results.nc, summary.json and
  case.toml; a sweep folder: sweep.nc or ``points/``); its name must fit the file system;
  its parent must be (or become) a writable folder, proven by writing and deleting a
  probe file of ``PROBE_BYTES``, with at least ``MIN_FREE_BYTES`` free.
* **Other files are kept.** The marker lists every file tribodyn wrote with its SHA-256.
  Files of a result folder that are not listed, or were changed since (notes, a cam
  table, an edited report), are the user's (:func:`foreign_files`): a new run keeps them
  in place and replaces only tribodyn's own files. If one of them has the name of a file
  the run writes, the run is refused before computing, naming the file. Folders marked
  without a list (tribodyn 0.2 and earlier) and 0.1 folders count the names tribodyn writes
  (results.nc, figNN_*.png, …) as its own.
* **Atomic.** Everything goes to a temporary folder ``.NAME.tmp-PID-TOKEN`` next to the
  target (the user's files are hard-linked into it, or copied where links are not
  possible), which then replaces the target in one rename (the previous results are kept
  until then). An exception, Ctrl-C or SIGTERM (see ``cli/run.py``) during writing removes
  the temporary folder; temporary and ``.NAME.old-PID-TOKEN`` folders left by runs that
  were killed (their process no longer exists) are cleaned up by the next write, after
  moving any user file found only there back into the target, and only if they hold
  tribodyn's proof of origin (:data:`~.result_folder.ORIGIN`, with the PID and token of
  their name): a folder of someone else's named alike is never touched.
* **One kind per folder.** The marker records the command (``run``, ``engine``,
  ``sweep``); a folder holding another command's results is refused before computing.
  A link given as the target is followed: the results go to the folder it points to.
* **Re-runnable.** ``case.toml`` refers to copies of the files the case reads (the cam
  table, measured maps: :data:`~tribodyn.config.paths.FILE_KEYS`) in ``inputs/``, by
  relative path, so a moved or shared result folder runs again with
  ``tribodyn run FOLDER/case.toml``.
* **Permissions.** New files and folders follow the umask (0o666, 0o777, masked); a
  re-run gives the new folder the mode (set-group-ID bit included) and group of the
  folder it replaces, and the user's folders in it keep theirs, so nothing becomes more
  widely readable. A folder owned by someone else (and a run that is not root's) is not
  replaced: the new files are moved into it one by one (its owner, group, mode and the
  user's files stay; while they move, the marker lists the earlier files' hashes too).
  The temporary folder is private (0o700) while it is written. Every file is written by
  :mod:`tribodyn._safe_write` (never through a link).
* **Never lost.** If writing still fails after the computation (disk full, folder
  removed, permissions changed), the results (results.nc, summary.json, case.toml) are
  written to a rescue folder ``tribodyn-rescue-CASE-TIME-PID`` in the system's temporary
  folder (else the current folder, else the home folder), and
  :class:`OutputWriteError` says where.
"""

from __future__ import annotations

import errno
import os
import stat
import sys
import tempfile
import time
from collections.abc import Callable, Iterator
from contextlib import contextmanager, suppress
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .. import _json
from .._safe_write import atomic_write, atomic_write_with, copy_file, make_dirs, remove_tree
from .._typing import PathLike
from .dataset import study_to_dataset, write_netcdf
from .figures_folder import figure_workers

# the `x as x` import is a re-export (tests import it here)
from .result_folder import _NAME_OVERHEAD as _NAME_OVERHEAD
from .result_folder import (
    INPUTS,
    MARKER,
    MIN_FREE_BYTES,
    ORIGIN,
    PROBE_BYTES,
    _all_files,
    _sha256,
    check_output_dir,
    folder_kind,
    foreign_files,
    is_result_folder,
    mark_folder,
    own_files,
    resolve_target,
)
from .work_folder import (
    _keep_foreign,
    _salvage,
    adopt_attributes,
    clean_stale,
    folder_attributes,
    make_work_folder,
    must_update_in_place,
    old_name,
    prove_origin,
    update_in_place,
)

if TYPE_CHECKING:
    from ..workflow.cycle import CycleStudy

__all__ = [
    "write_atomic",
    "write_results",
    "import_writing_modules",
    "check_output_dir",
    "is_result_folder",
    "foreign_files",
    "own_files",
    "mark_folder",
    "case_inputs",
    "INPUTS",
    "clean_stale",
    "OutputWriteError",
    "MARKER",
    "PROBE_BYTES",
    "MIN_FREE_BYTES",
]


class OutputWriteError(RuntimeError):
    """Writing the results failed after the computation. ``target`` is the folder that
    was not written; ``rescued`` the folder that holds the computed results instead (None
    if even that failed); ``cause`` the original error."""

    def __init__(self, message: str, target: Path, rescued: Path | None, cause: BaseException):
        super().__init__(message)
        self.target, self.rescued, self.cause = target, rescued, cause


# ----------------------------------------------------------------------------- writing
def write_atomic(
    target: Path, writer: Callable[[Path], object], *, meta: dict | None = None
) -> Path:
    """Call ``writer(tmpdir)`` to fill a fresh folder, mark it, then replace ``target``.

    ``target`` must be absent, empty or a tribodyn result folder (:func:`check_output_dir`
    rules, without the probe; a link to a folder: that folder). The user's files in
    ``target`` (:func:`foreign_files`) are kept; tribodyn's own are replaced; the folder
    and the user's folders in it keep their mode and group (and owner: a folder of
    someone else's is updated in place, :func:`~.work_folder.update_in_place`). If
    ``writer`` raises (or the process is interrupted), ``target`` is left exactly as it
    was and the temporary folder is removed.
    """
    target = resolve_target(target)
    kind = (meta or {}).get("kind")
    if target.exists() and (
        not target.is_dir()
        or (any(target.iterdir()) and not is_result_folder(target))
        or (kind is not None and folder_kind(target) not in (None, kind))
    ):
        check_output_dir(target, kind=kind)  # raises with the reason
    clean_stale(target)
    make_dirs(target.parent)
    tmp, like = make_work_folder(target)  # 0o700 while written
    try:
        kept = folder_attributes(target)
        if kept is not None:  # the group first, so that new files inherit it (setgid)
            like = kept
            adopt_attributes(tmp, like, 0o700 | (stat.S_IMODE(like.st_mode) & stat.S_ISGID))
        writer(tmp)
        files = {rel: _sha256(tmp / rel) for rel in _all_files(tmp) if (tmp / rel).is_file()}
        files.pop(MARKER, None)
        files.pop(ORIGIN, None)
        if must_update_in_place(target):  # someone else's folder: it stays, files move
            update_in_place(target, tmp, files, meta or {})
            remove_tree(tmp, ignore_errors=True)
            return target
        if target.is_dir():
            _keep_foreign(target, tmp, files)
        mark_folder(tmp, files, meta)
        os.chmod(tmp, stat.S_IMODE(like.st_mode))
    except BaseException:
        remove_tree(tmp, ignore_errors=True)
        raise
    old = None
    try:
        if target.exists():
            old = old_name(target)
            # before the rename, so that the .old folder is always proven (a folder without
            # write permission: left unproven)
            with suppress(OSError):
                prove_origin(target, old.name)
            try:
                target.rename(old)
            except BaseException:
                (target / ORIGIN).unlink(missing_ok=True)
                raise
        tmp.rename(target)
    except BaseException:
        if old is not None and old.exists() and not target.exists():
            old.rename(target)
            (target / ORIGIN).unlink(missing_ok=True)
        remove_tree(tmp, ignore_errors=True)
        raise
    (target / ORIGIN).unlink(missing_ok=True)
    if old is not None:
        try:
            _salvage(old, target)  # a file the user added meanwhile
        except OSError:
            pass  # then the .old folder stays, for the next write to salvage
        else:
            remove_tree(old, ignore_errors=True)
    return target


def _rescue_dirs(case_name: str):
    stamp = time.strftime("%Y%m%d-%H%M%S")
    name = f"tribodyn-rescue-{case_name}-{stamp}-{os.getpid()}"
    for base in (Path(tempfile.gettempdir()), Path.cwd(), Path.home()):
        yield base / name


def case_inputs(case) -> tuple[dict, dict[str, Path]]:
    """The files a case reads, to copy into a result folder: ``(data, copies)`` with
    ``data`` the case's dict in which each file key (:data:`~tribodyn.config.paths.FILE_KEYS`,
    every place it addresses: each surface set's map, and the same keys in an engine's
    ``[engine.<kind>] changes``) names ``inputs/NAME``, relative to the folder, and
    ``copies`` mapping that relative path to the source file. One file read at several
    places is copied once; different files of the same name get distinct names
    (``NAME-2.SUF``, …)."""
    from ..config.paths import FILE_KEYS, Key, find_paths, parse_path, set_path

    data = case.to_dict(resolve_paths=True)
    base = case.source.parent if getattr(case, "source", None) is not None else Path.cwd()
    copies: dict[str, Path] = {}
    named: dict[Path, str] = {}  # resolved source -> its name in inputs/

    def copy_name(src: Path) -> str:
        same = Path(os.path.realpath(src))
        rel = named.get(same)
        if rel is None:
            rel = f"{INPUTS}/{src.name}"
            n = 1
            while rel in copies:  # two files of the same name
                n += 1
                rel = f"{INPUTS}/{src.stem}-{n}{src.suffix}"
            copies[rel] = src
            named[same] = rel
        return rel

    for key in FILE_KEYS:
        for where, value in find_paths(data, key):
            src = Path(value).expanduser()
            set_path(data, where, copy_name(src if src.is_absolute() else base / src))

    def keys_of(path: str) -> tuple[str, ...]:  # the path's keys, selectors left out
        return tuple(t.name for t in parse_path(path) if isinstance(t, Key))

    file_keys = {keys_of(k) for k in FILE_KEYS}
    engine = data.get("engine") or {}
    for kind in ("intake", "exhaust"):
        changes = (engine.get(kind) or {}).get("changes") or {}
        for key, value in changes.items():
            if isinstance(value, str) and keys_of(key) in file_keys:
                changes[key] = copy_name(case.resolve_path(value))
    return data, copies


def _write_case(case, folder: Path) -> None:
    """case.toml, with the files it reads copied to ``folder/inputs``."""
    from ..config.case import to_toml

    data, copies = case_inputs(case)
    for rel, src in copies.items():
        make_dirs((folder / rel).parent)
        copy_file(src, folder / rel)
    head = [
        f"tribodyn case {case.name!r} (all keys, SI units unless the key says otherwise)",
        *(["the files it reads are copies in inputs/"] if copies else []),
    ]
    atomic_write(folder / "case.toml", to_toml(data, header=head))


def import_writing_modules() -> None:
    """Import what :func:`write_results` imports on its first use (about a second on the
    paper case): xarray's check for dask arrays (made at its first variable), h5netcdf,
    the report's modules, markdown-it and Bokeh. Only a speed-up, for a caller that waits
    anyway (the command line calls it in a thread during the study, once no more worker
    processes will be forked: a fork during an import would leave that module locked in
    the child); whatever is still missing is imported by the writing."""
    import h5netcdf  # noqa: F401
    import markdown_it  # noqa: F401
    import numpy as np
    import xarray as xr
    from bokeh import layouts  # noqa: F401
    from bokeh.resources import Resources  # noqa: F401

    from . import explorer, export, report  # noqa: F401

    xr.Variable("x", np.zeros(1))


def _write_netcdf(ds, path: Path, encoding: dict) -> None:
    """results.nc, by :func:`~tribodyn._safe_write.atomic_write_with`."""
    atomic_write_with(path, lambda tmp: write_netcdf(ds, tmp, encoding))


_HELD: list = []  # the Dataset and encoding of the process that writes results.nc


def _hold(ds, encoding: dict, starter: int) -> None:
    from .._system import exit_with_parent

    exit_with_parent(starter)
    _HELD[:] = [ds, encoding]


def _write_held(path: Path) -> None:
    _write_netcdf(_HELD[0], path, _HELD[1])


@contextmanager
def _netcdf_meanwhile(ds, path: Path, encoding: dict) -> Iterator[None]:
    """Write ``ds`` to the netCDF file ``path`` while the body of the ``with`` writes the
    other files: in a forked process on Linux when this process runs no other thread
    (it shares the Dataset; compressing and writing results.nc takes about a second on
    the paper case; a fork beside another thread could leave a lock that thread holds
    locked in the child), else first. Leaving the ``with`` waits for that process (also
    after an error in the body, so that nothing is written into a folder being removed)
    and raises its error."""
    import threading

    if not sys.platform.startswith("linux") or threading.active_count() > 1:
        _write_netcdf(ds, path, encoding)
        yield
        return
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor

    with ProcessPoolExecutor(
        max_workers=1,
        mp_context=mp.get_context("fork"),
        initializer=_hold,
        initargs=(ds, encoding, os.getpid()),
    ) as pool:
        part = pool.submit(_write_held, path)
        try:
            yield
        except BaseException:
            pool.shutdown(wait=True, cancel_futures=True)
            raise
        part.result()


def write_results(
    study: CycleStudy,
    out_dir: PathLike,
    *,
    figures: bool | list[str] = False,
    report: bool = True,
    workers: int | None = None,
) -> dict:
    """Write results.nc, summary.json, case.toml (with copies of the files the case reads
    in ``inputs/``), traces.csv and dynamics.csv (:mod:`.export`), report.md, the
    self-contained report.html and, on request, the static figures atomically into
    ``out_dir``. Returns ``{"summary": …, "figures": {name: path}, "path": out_dir}``.
    ``figures``: none (False, the default: :func:`draw_figures` adds them to the folder
    later), all (True) or a list of file names; they are drawn in ``workers`` processes
    (default: :func:`figure_workers`).

    Raises :class:`OutputWriteError` if ``out_dir`` may not be replaced (an existing file
    or a foreign folder, see :func:`check_output_dir`, which the command line calls before
    computing) or if writing fails, after saving the computed results to a rescue folder
    (module docstring)."""
    from .. import __version__

    ds = study_to_dataset(study)
    summ = study.analyse().summary
    written: dict[str, Any] = {}
    enc = {
        v: {"compression": "gzip", "compression_opts": 4}
        for v in ("profile_x", "pressure", "film", "stress_map_von_mises", "regime_map")
        if v in ds
    }

    def essentials(folder: Path, netcdf: bool = True):
        from .export import write_csv

        if netcdf:
            _write_netcdf(ds, folder / "results.nc", enc)
        atomic_write(folder / "summary.json", _json.dumps(summ, indent=2))
        _write_case(study.case, folder)
        write_csv(ds, folder)

    def reports(tmp: Path, figs: dict):
        if report:
            from .explorer import write_report_html
            from .export import report_markdown
            from .report import write_report

            write_report(study, ds, figs, tmp / "report.md")
            write_report_html(report_markdown(tmp), tmp, ds=ds)  # results.nc not read again

    def writer(tmp: Path):
        figs = {}
        if figures:
            from .figures import make_figures

            n = workers if workers is not None else figure_workers()
            only = figures if isinstance(figures, list) else None
            # the data files are written while other processes draw
            figs = make_figures(ds, tmp, only=only, workers=n, meanwhile=lambda: essentials(tmp))
            reports(tmp, figs)
        else:  # results.nc in another process while the other files are written
            with _netcdf_meanwhile(ds, tmp / "results.nc", enc):
                essentials(tmp, netcdf=False)
                reports(tmp, figs)
        written.update(figures=figs)

    target = Path(out_dir).expanduser().absolute()
    try:
        write_atomic(
            target, writer, meta={"kind": "run", "version": __version__, "case": study.case.name}
        )
    except Exception as exc:  # disk full, folder removed or taken, permissions, a figure
        rescued = None
        for folder in _rescue_dirs(study.case.name):
            try:
                folder.mkdir(parents=True)
                essentials(folder)
                rescued = folder
                break
            except OSError:
                remove_tree(folder, ignore_errors=True)  # made above: ours
        why = getattr(exc, "strerror", None) or f"{type(exc).__name__}: {exc}"
        if getattr(exc, "errno", None) == errno.ENOSPC:
            why = "no space left on the device"
        where = (
            f"the computed results (results.nc, summary.json, case.toml) were saved to {rescued}"
            if rescued is not None
            else "the results could not be saved anywhere else either"
        )
        raise OutputWriteError(
            f"cannot write the results to {target}: {why}; {where}", target, rescued, exc
        ) from exc
    return {"summary": summ, "path": target, **written}

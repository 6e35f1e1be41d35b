"""Writing a cycle study: results.nc, summary.json, case.toml, figures and report.md, into
one folder, atomically, without ever losing results or replacing someone else's files.

* **Check first.** :func:`check_output_dir` runs before the computation: the target must
  be absent, an empty folder or a previous tribodyn result folder (marked by the file
  ``.tribodyn-results``, or, from tribodyn 0.1, holding results.nc, summary.json and
  case.toml); its parent must be (or become) a writable folder, proven by writing and
  deleting a probe file of ``PROBE_BYTES``, with at least ``MIN_FREE_BYTES`` free.
* **Atomic.** Everything goes to a temporary folder ``.NAME.tmp-PID-XXXX`` next to the
  target, which then replaces the target in one rename (the previous results are kept
  until then). An exception, Ctrl-C or SIGTERM (see ``cli/run.py``) during writing removes
  the temporary folder; temporary and ``.NAME.old-PID`` folders left by runs that were
  killed (their process no longer exists) are cleaned up by the next write.
* **Never lost.** If writing still fails after the computation (disk full, folder
  removed, permissions changed), the results (results.nc, summary.json, case.toml) are
  written to a rescue folder ``tribodyn-rescue-CASE-TIME-PID`` in the system's temporary
  folder (else the current folder, else the home folder), and
  :class:`OutputWriteError` says where.
"""

from __future__ import annotations

import errno
import json
import os
import re
import shutil
import tempfile
import time
from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .._typing import PathLike
from .._validation import InputError
from .dataset import study_to_dataset

if TYPE_CHECKING:
    from ..workflow.cycle import CycleStudy

__all__ = [
    "write_atomic",
    "write_results",
    "check_output_dir",
    "is_result_folder",
    "clean_stale",
    "OutputWriteError",
    "MARKER",
    "PROBE_BYTES",
    "MIN_FREE_BYTES",
]

#: File that marks a folder as written by tribodyn (JSON: tool, version, case, time).
MARKER = ".tribodyn-results"
#: Files of a result folder written before the marker existed (tribodyn 0.1).
_LEGACY_FILES = ("results.nc", "summary.json", "case.toml")
#: Size of the write probe [bytes]: a full or read-only disk fails on it.
PROBE_BYTES = 1 << 20
#: Free space required before computing [bytes]: the paper case writes 17 MB
#: (results.nc 14 MB, 15 figures, report); 0.25° crank steps write about four times the
#: profiles, so 128 MB leaves room for them with a margin.
MIN_FREE_BYTES = 128 << 20
#: Temporary folders of processes that no longer exist are removed; so are those in the
#: 0.1 naming (no PID) not touched for this long [s].
_LEGACY_STALE_AGE = 3600.0


class OutputWriteError(RuntimeError):
    """Writing the results failed after the computation. ``target`` is the folder that
    was not written; ``rescued`` the folder that holds the computed results instead (None
    if even that failed); ``cause`` the original error."""

    def __init__(self, message: str, target: Path, rescued: Path | None, cause: BaseException):
        super().__init__(message)
        self.target, self.rescued, self.cause = target, rescued, cause


# ----------------------------------------------------------------------------- checks
def is_result_folder(path: PathLike) -> bool:
    """True for a folder written by tribodyn (marker, or the 0.1 set of files)."""
    p = Path(path)
    if not p.is_dir():
        return False
    return (p / MARKER).is_file() or all((p / f).is_file() for f in _LEGACY_FILES)


def _existing_ancestor(p: Path) -> Path:
    q = p
    while not q.exists() and q != q.parent:
        q = q.parent
    return q


def check_output_dir(path: PathLike, *, option: str = "output folder") -> Path:
    """Check that results can be written to ``path`` before anything is computed.

    Returns the absolute path. Raises :class:`~tribodyn.InputError` naming ``option``
    if ``path`` is an existing file, a folder with contents that tribodyn did not write,
    below a file, not writable, or on a disk with less than ``MIN_FREE_BYTES`` free (the
    probe writes ``PROBE_BYTES``).
    """
    target = Path(path).expanduser().absolute()
    if target.exists() or target.is_symlink():
        if not target.is_dir():
            raise InputError(
                f"{option} {str(target)!r} is an existing file, not a result "
                "folder; tribodyn replaces only result folders it wrote: give "
                "a new folder name"
            )
        if any(target.iterdir()) and not is_result_folder(target):
            raise InputError(
                f"{option} {str(target)!r} is a folder that tribodyn did not "
                f"write (no {MARKER} marker); it replaces only its own result "
                "folders: give a new or empty folder"
            )
    base = _existing_ancestor(target.parent)
    if not base.is_dir():
        raise InputError(f"{option} {str(target)!r}: {str(base)!r} is a file, not a folder")
    _probe(base, target, option)
    return target


def _probe(folder: Path, target: Path, option: str) -> None:
    """Write and remove PROBE_BYTES in ``folder``; check the free space."""
    probe = folder / f".{target.name}.probe-{os.getpid()}"
    try:
        with open(probe, "wb") as f:
            f.write(b"\0" * PROBE_BYTES)
            f.flush()
            os.fsync(f.fileno())
    except OSError as exc:
        raise InputError(
            f"{option} {str(target)!r}: cannot write in {str(folder)!r} ({exc.strerror or exc})"
        ) from None
    finally:
        try:
            probe.unlink()
        except OSError:
            pass
    free = shutil.disk_usage(folder).free
    if free < MIN_FREE_BYTES:
        raise InputError(
            f"{option} {str(target)!r}: only {free / 2**20:.0f} MB free in "
            f"{str(folder)!r}; the results need up to {MIN_FREE_BYTES >> 20} MB"
        )


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # exists, owned by someone else
        return True
    return True


def clean_stale(target: PathLike) -> list[Path]:
    """Remove ``.NAME.tmp-*`` and ``.NAME.old-*`` folders next to ``target`` left by runs
    that were killed (process gone; 0.1-style names after an hour). An ``.old`` folder is
    moved back to ``target`` if the target is missing (the kill came between the two
    renames). Returns what was removed or restored."""
    target = Path(target).absolute()
    parent = target.parent
    if not parent.is_dir():
        return []
    done = []
    head = f".{target.name}."
    for p in parent.iterdir():
        if not p.name.startswith(head) or not p.is_dir() or p.is_symlink():
            continue
        rest = p.name[len(head) :]
        m = (
            re.fullmatch(r"(tmp)-(\d+)-.+", rest)
            or re.fullmatch(r"(old)-(\d+)", rest)
            or re.fullmatch(r"(tmp)-()[^-]+", rest)
        )  # last: 0.1 name, no PID
        if not m:
            continue
        kind, pid = m.group(1), m.group(2) or None
        if pid is not None:
            if int(pid) == os.getpid() or _pid_alive(int(pid)):
                continue
        elif time.time() - p.stat().st_mtime < _LEGACY_STALE_AGE:
            continue
        if kind == "old" and not target.exists():
            p.rename(target)
        else:
            shutil.rmtree(p, ignore_errors=True)
        done.append(p)
    return done


# ----------------------------------------------------------------------------- writing
def write_atomic(
    target: Path, writer: Callable[[Path], object], *, meta: dict | None = None
) -> Path:
    """Call ``writer(tmpdir)`` to fill a fresh folder, mark it, then replace ``target``.

    ``target`` must be absent, empty or a tribodyn result folder (:func:`check_output_dir`
    rules, without the probe). If ``writer`` raises (or the process is interrupted),
    ``target`` is left exactly as it was and the temporary folder is removed.
    """
    target = Path(target).expanduser().absolute()
    if target.exists() and (
        not target.is_dir() or (any(target.iterdir()) and not is_result_folder(target))
    ):
        check_output_dir(target)  # raises with the reason
    clean_stale(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = Path(tempfile.mkdtemp(prefix=f".{target.name}.tmp-{os.getpid()}-", dir=target.parent))
    try:
        writer(tmp)
        info = {"tool": "tribodyn", "written": time.strftime("%Y-%m-%dT%H:%M:%S%z"), **(meta or {})}
        (tmp / MARKER).write_text(json.dumps(info, indent=1) + "\n")
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    old = None
    try:
        if target.exists():
            old = target.with_name(f".{target.name}.old-{os.getpid()}")
            if old.exists():
                shutil.rmtree(old)
            target.rename(old)
        tmp.rename(target)
    except BaseException:
        if old is not None and old.exists() and not target.exists():
            old.rename(target)
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)
    return target


def _rescue_dirs(case_name: str):
    stamp = time.strftime("%Y%m%d-%H%M%S")
    name = f"tribodyn-rescue-{case_name}-{stamp}-{os.getpid()}"
    for base in (Path(tempfile.gettempdir()), Path.cwd(), Path.home()):
        yield base / name


def write_results(
    study: CycleStudy,
    out_dir: PathLike,
    *,
    figures: bool | list[str] = True,
    report: bool = True,
    workers: int | None = None,
) -> dict:
    """Write results.nc, summary.json, case.toml, figures and report.md atomically into
    ``out_dir``. Returns ``{"summary": …, "figures": {name: path}, "path": out_dir}``.
    ``figures``: all (True), none (False) or a list of file names; they are drawn in
    ``workers`` processes (default: the CPU count, at most 4).

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
        for v in ("profile_x", "pressure", "film")
        if v in ds
    }

    def essentials(folder: Path):
        ds.to_netcdf(folder / "results.nc", engine="h5netcdf", encoding=enc)
        (folder / "summary.json").write_text(json.dumps(summ, indent=2))
        study.case.write_toml(folder / "case.toml")

    def writer(tmp: Path):
        figs = {}
        if figures:
            from .figures import make_figures

            n = workers if workers is not None else min(os.cpu_count() or 1, 4)
            only = figures if isinstance(figures, list) else None
            # the data files are written while other processes draw
            figs = make_figures(ds, tmp, only=only, workers=n, meanwhile=lambda: essentials(tmp))
        else:
            essentials(tmp)
        if report:
            from .report import write_report

            write_report(study, ds, figs, tmp / "report.md")
        written.update(figures=figs)

    target = Path(out_dir).expanduser().absolute()
    try:
        write_atomic(target, writer, meta={"version": __version__, "case": study.case.name})
    except Exception as exc:  # disk full, folder removed or taken, permissions, a figure
        rescued = None
        for folder in _rescue_dirs(study.case.name):
            try:
                folder.mkdir(parents=True)
                essentials(folder)
                rescued = folder
                break
            except OSError:
                shutil.rmtree(folder, ignore_errors=True)
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

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
* **Atomic.** Everything goes to a temporary folder ``.NAME.tmp-PID-XXXX`` next to the
  target (the user's files are hard-linked into it, or copied where links are not
  possible), which then replaces the target in one rename (the previous results are kept
  until then). An exception, Ctrl-C or SIGTERM (see ``cli/run.py``) during writing removes
  the temporary folder; temporary and ``.NAME.old-PID`` folders left by runs that were
  killed (their process no longer exists) are cleaned up by the next write, after moving
  any user file found only there back into the target.
* **Re-runnable.** ``case.toml`` refers to copies of the files the case reads (the cam
  table, :data:`~tribodyn.config.paths.FILE_KEYS`) in ``inputs/``, by relative path, so
  a moved or shared result folder runs again with ``tribodyn run FOLDER/case.toml``.
* **Permissions** follow the umask (folders 0o777, files 0o666, masked).
* **Never lost.** If writing still fails after the computation (disk full, folder
  removed, permissions changed), the results (results.nc, summary.json, case.toml) are
  written to a rescue folder ``tribodyn-rescue-CASE-TIME-PID`` in the system's temporary
  folder (else the current folder, else the home folder), and
  :class:`OutputWriteError` says where.
"""

from __future__ import annotations

import errno
import filecmp
import hashlib
import json
import os
import re
import shutil
import tempfile
import time
from collections.abc import Callable, Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from .._system import new_dir, new_file
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

#: File that marks a folder as written by tribodyn (JSON: tool, version, case, time).
MARKER = ".tribodyn-results"
#: Files of a result folder written before the marker existed (tribodyn 0.1).
_LEGACY_FILES = ("results.nc", "summary.json", "case.toml")
#: Figures of a case other than the paper's, named by content (without ``figNN_``).
_CONTENT_FIGURES = (
    "dry_pressure|ehl_pressure_film|tappet_velocity|contact_force|tappet_acceleration"
    "|entrainment_speed|greenwood_chart|pressure_film_points|coatings_pressure_film"
    "|central_film|boundary_load|boundary_friction|viscous_friction|friction_power"
    "|min_film_lambda|temperatures|thermal_vs_isothermal|camshaft_torque"
    "|contact_pressure|cam_kinematics|spring_surge",
)
#: Names of the files tribodyn writes in a result folder (cycle study and sweep); in a
#: folder whose marker does not list its files, these are tribodyn's own.
_OWN_NAMES = re.compile(
    r"results\.nc|summary\.json|case\.toml|report\.md|fig\d\d_[A-Za-z0-9_-]+\.png"
    r"|report\.html|traces\.csv|dynamics\.csv|(?:" + "|".join(_CONTENT_FIGURES) + r")\.png"
    r"|sweep\.nc|sweep\.toml|sweep_report\.md|base_case\.toml|sweep_[A-Za-z0-9_-]+\.png"
)
#: Point files of a sweep (``points/<key>.nc``): always tribodyn's own.
_POINT_FILE = re.compile(r"points/[0-9a-f]+\.nc")
#: Folder of a result folder that holds copies of the files the case reads.
INPUTS = "inputs"
#: Characters the temporary names add to the folder's name: ``.`` + ``.tmp-PID-`` (PIDs
#: up to 7 digits) + 8 random ones.
_NAME_OVERHEAD = 1 + 5 + 7 + 1 + 8
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
    """True for a folder written by tribodyn (marker, or the 0.1 set of files, or a
    sweep's sweep.nc or point files)."""
    p = Path(path)
    if not p.is_dir():
        return False
    return (
        (p / MARKER).is_file()
        or all((p / f).is_file() for f in _LEGACY_FILES)
        or (p / "sweep.nc").is_file()
        or any(_POINT_FILE.fullmatch(f"points/{q.name}") for q in _iter_dir(p / "points"))
    )


def _iter_dir(p: Path):
    try:
        return list(p.iterdir())
    except OSError:
        return []


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for block in iter(lambda: f.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _all_files(folder: Path) -> list[str]:
    """Relative (POSIX) paths of the files, links and empty folders below ``folder``;
    links to folders are not followed."""
    out = []
    for root, dirs, files in os.walk(folder):
        r = Path(root)
        rel = r.relative_to(folder)
        links = [d for d in dirs if (r / d).is_symlink()]
        dirs[:] = [d for d in dirs if d not in links]
        out += [(rel / f).as_posix() for f in (*files, *links)]
        if not dirs and not files and not links and r != folder:
            out.append(rel.as_posix() + "/")
    return sorted(out)


def _marker_info(folder: Path) -> dict:
    try:
        info = json.loads((folder / MARKER).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return info if isinstance(info, dict) else {}


def own_files(folder: PathLike) -> set[str]:
    """Relative paths of the files in ``folder`` that tribodyn wrote and no one has
    changed since: listed in the marker with the same SHA-256 (or, in a folder whose
    marker has no list, named as tribodyn names its files); point files of a sweep."""
    folder = Path(folder)
    listed = _marker_info(folder).get("files")
    own = set()
    for rel in _all_files(folder):
        p = folder / rel
        if rel == MARKER or (_POINT_FILE.fullmatch(rel) and p.is_file()):
            own.add(rel)
        elif p.is_symlink() or not p.is_file():
            continue
        elif isinstance(listed, dict):
            if rel in listed and listed[rel] == _sha256(p):
                own.add(rel)
        elif _OWN_NAMES.fullmatch(rel):
            own.add(rel)
    return own


def foreign_files(folder: PathLike) -> list[str]:
    """Relative paths of everything in ``folder`` that tribodyn did not write (or that was
    changed since): the files a new run keeps. Empty folders end with ``/``."""
    folder = Path(folder)
    own = own_files(folder)
    return [f for f in _all_files(folder) if f not in own]


def _clashes(folder: Path, writes: Mapping[str, Path | None]) -> list[str]:
    """The user's files in ``folder`` that have the name of one tribodyn writes (its own
    names, or those in ``writes`` unless they are the same as the file copied there)."""
    bad = []
    for f in foreign_files(folder):
        g = f.rstrip("/")
        if g in writes and not f.endswith("/"):
            src = writes[g]
            if src is None or not _same_file_content(folder / g, src):
                bad.append(f)
        elif _OWN_NAMES.fullmatch(g.split("/")[0]) or any(
            g == w or g.startswith(w + "/") or (w.startswith(g + "/") and not f.endswith("/"))
            for w in writes
        ):  # the same name, below a file tribodyn writes, or a file where it needs a folder
            bad.append(f)
    return bad


def _same_file_content(a: Path, b: Path) -> bool:
    try:
        return a.is_file() and b.is_file() and filecmp.cmp(a, b, shallow=False)
    except OSError:
        return False


def _listing(files: list[str], n: int = 5) -> str:
    more = f" and {len(files) - n} more" if len(files) > n else ""
    return ", ".join(files[:n]) + more


def _existing_ancestor(p: Path) -> Path:
    q = p
    while not q.exists() and q != q.parent:
        q = q.parent
    return q


def check_output_dir(
    path: PathLike,
    *,
    option: str = "output folder",
    writes: Mapping[str, Path | None] | None = None,
) -> Path:
    """Check that results can be written to ``path`` before anything is computed.

    Returns the absolute path. Raises :class:`~tribodyn.InputError` naming ``option``
    if ``path`` is an existing file, a folder with contents that tribodyn did not write,
    a result folder holding a user's file with the name of one tribodyn writes (its
    usual names, or the keys of ``writes``: relative path → the file copied there, or
    None), a name too long for the file system, below a file, not writable, or on a disk
    with less than ``MIN_FREE_BYTES`` free (the probe writes ``PROBE_BYTES``).
    """
    target = Path(path).expanduser().absolute()
    try:
        _check_name(target, option)
        _check_target(target, option, writes or {})
        base = _existing_ancestor(target.parent)
    except OSError as exc:
        if exc.errno == errno.ENAMETOOLONG:
            raise InputError(
                f"{option} {str(target)!r}: the path is too long for the file system "
                "(ENAMETOOLONG): give a shorter name"
            ) from None
        raise
    if not base.is_dir():
        raise InputError(f"{option} {str(target)!r}: {str(base)!r} is a file, not a folder")
    _probe(base, target, option)
    return target


def _check_name(target: Path, option: str) -> None:
    """Each part of the path, and the temporary names made from the folder's name, must
    fit the file system's longest name (NAME_MAX, 255 bytes on most)."""
    try:
        limit = os.pathconf(_existing_ancestor(target.parent), "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):
        limit = 255
    for part in target.parts[1:-1]:
        if len(os.fsencode(part)) > limit:
            raise InputError(
                f"{option} {str(target)!r}: the folder name {part[:40]!r}… is "
                f"{len(os.fsencode(part))} bytes long; this file system allows {limit}"
            )
    n = len(os.fsencode(target.name))
    if n + _NAME_OVERHEAD > limit:
        raise InputError(
            f"{option} {str(target)!r}: the name is {n} bytes long; on this file system "
            f"a result folder's name may have at most {limit - _NAME_OVERHEAD} (the "
            f"temporary folder adds {_NAME_OVERHEAD} to the limit of {limit}): give a "
            "shorter name"
        )


def _check_target(target: Path, option: str, writes: Mapping[str, Path | None]) -> None:
    if not (target.exists() or target.is_symlink()):
        return
    if not target.is_dir():
        raise InputError(
            f"{option} {str(target)!r} is an existing file, not a result "
            "folder; tribodyn replaces only result folders it wrote: give "
            "a new folder name"
        )
    if not any(target.iterdir()):
        return
    if not is_result_folder(target):
        raise InputError(
            f"{option} {str(target)!r} is a folder that tribodyn did not "
            f"write (no {MARKER} marker; it holds {_listing(_all_files(target))}); it "
            "writes only into its own result folders: give a new or empty folder"
        )
    clash = _clashes(target, writes)
    if clash:
        raise InputError(
            f"{option} {str(target)!r}: {_listing(clash)} in this result folder "
            "changed since tribodyn wrote it, or was not written by tribodyn, and the "
            "new results would replace it: move it elsewhere or give another folder"
        )


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
            if kind == "old":
                _salvage(p, target)
            shutil.rmtree(p, ignore_errors=True)
        done.append(p)
    return done


def _salvage(old: Path, target: Path) -> None:
    """Move the user's files found in the replaced folder ``old`` but not in ``target``
    into ``target`` (files added while the new results were being written)."""
    for rel in foreign_files(old):
        dst = target / rel.rstrip("/")
        if os.path.lexists(dst):
            continue
        dst.parent.mkdir(parents=True, exist_ok=True)
        if rel.endswith("/"):
            dst.mkdir(exist_ok=True)
        else:
            os.rename(old / rel, dst)


def _keep_foreign(target: Path, tmp: Path, files: dict[str, str]) -> None:
    """Hard-link (else copy) the user's files of ``target`` into the new folder ``tmp``;
    a file tribodyn wrote with the same content as the user's gives way to the user's
    (and leaves ``files``, the list of tribodyn's own). Any other clash raises."""
    for rel in foreign_files(target):
        src, dst = target / rel.rstrip("/"), tmp / rel.rstrip("/")
        if rel.endswith("/"):
            dst.mkdir(parents=True, exist_ok=True)
            continue
        if os.path.lexists(dst):
            if dst.is_dir() or not _same_file_content(src, dst):
                raise InputError(
                    f"{str(target)!r}: {rel} was not written by tribodyn (or changed "
                    "since) and the new results have a file of that name; it was left "
                    "as it is"
                )
            dst.unlink()
            files.pop(rel, None)
        dst.parent.mkdir(parents=True, exist_ok=True)
        try:
            os.link(src, dst, follow_symlinks=False)
        except OSError:  # no hard links here: a copy (the original stays until the swap)
            shutil.copy2(src, dst, follow_symlinks=False)


def mark_folder(folder: PathLike, files: Mapping[str, str], meta: dict | None = None) -> Path:
    """Write the marker of ``folder``: tool, time, ``meta`` and ``files`` (relative path
    → SHA-256 of each file tribodyn wrote), via a temporary file and a rename."""
    folder = Path(folder)
    info = {
        "tool": "tribodyn",
        "written": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        **(meta or {}),
        "files": dict(sorted(files.items())),
    }
    fd, tmp = new_file(folder, f".{MARKER}.", ".tmp")
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(json.dumps(info, indent=1) + "\n")
        os.replace(tmp, folder / MARKER)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    return folder / MARKER


# ----------------------------------------------------------------------------- writing
def write_atomic(
    target: Path, writer: Callable[[Path], object], *, meta: dict | None = None
) -> Path:
    """Call ``writer(tmpdir)`` to fill a fresh folder, mark it, then replace ``target``.

    ``target`` must be absent, empty or a tribodyn result folder (:func:`check_output_dir`
    rules, without the probe). The user's files in ``target`` (:func:`foreign_files`)
    are kept; tribodyn's own are replaced. If ``writer`` raises (or the process is
    interrupted), ``target`` is left exactly as it was and the temporary folder is
    removed.
    """
    target = Path(target).expanduser().absolute()
    if target.exists() and (
        not target.is_dir() or (any(target.iterdir()) and not is_result_folder(target))
    ):
        check_output_dir(target)  # raises with the reason
    clean_stale(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    tmp = new_dir(target.parent, f".{target.name}.tmp-{os.getpid()}-")
    try:
        writer(tmp)
        files = {rel: _sha256(tmp / rel) for rel in _all_files(tmp) if (tmp / rel).is_file()}
        files.pop(MARKER, None)
        if target.is_dir():
            _keep_foreign(target, tmp, files)
        mark_folder(tmp, files, meta)
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    old = None
    try:
        if target.exists():
            old = target.with_name(f".{target.name}.old-{os.getpid()}")
            if old.exists():
                _salvage(old, target)
                shutil.rmtree(old)
            target.rename(old)
        tmp.rename(target)
    except BaseException:
        if old is not None and old.exists() and not target.exists():
            old.rename(target)
        shutil.rmtree(tmp, ignore_errors=True)
        raise
    if old is not None:
        try:
            _salvage(old, target)  # a file the user added meanwhile
        except OSError:
            pass  # then the .old folder stays, for the next write to salvage
        else:
            shutil.rmtree(old, ignore_errors=True)
    return target


def _rescue_dirs(case_name: str):
    stamp = time.strftime("%Y%m%d-%H%M%S")
    name = f"tribodyn-rescue-{case_name}-{stamp}-{os.getpid()}"
    for base in (Path(tempfile.gettempdir()), Path.cwd(), Path.home()):
        yield base / name


def case_inputs(case) -> tuple[dict, dict[str, Path]]:
    """The files a case reads, to copy into a result folder: ``(data, copies)`` with
    ``data`` the case's dict in which each file key (:data:`~tribodyn.config.paths.FILE_KEYS`)
    names ``inputs/NAME``, relative to the folder, and ``copies`` mapping that relative
    path to the source file."""
    from ..config.paths import FILE_KEYS, get_path, set_path

    data = case.to_dict(resolve_paths=True)
    base = case.source.parent if getattr(case, "source", None) is not None else Path.cwd()
    copies: dict[str, Path] = {}
    for key in FILE_KEYS:
        try:
            values = get_path(data, key)
        except InputError:  # the case has no such table (e.g. an analytic cam)
            continue
        if not values:
            continue
        src = Path(values[0]).expanduser()
        src = src if src.is_absolute() else base / src
        rel = f"{INPUTS}/{src.name}"
        n = 1
        while rel in copies:  # two files of the same name
            n += 1
            rel = f"{INPUTS}/{src.stem}-{n}{src.suffix}"
        set_path(data, key, rel)
        copies[rel] = src
    return data, copies


def _write_case(case, folder: Path) -> None:
    """case.toml, with the files it reads copied to ``folder/inputs``."""
    from ..config.case import to_toml

    data, copies = case_inputs(case)
    for rel, src in copies.items():
        (folder / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copyfile(src, folder / rel)
    head = [
        f"tribodyn case {case.name!r} (all keys, SI units unless the key says otherwise)",
        *(["the files it reads are copies in inputs/"] if copies else []),
    ]
    (folder / "case.toml").write_text(to_toml(data, header=head), encoding="utf-8")


def write_results(
    study: CycleStudy,
    out_dir: PathLike,
    *,
    figures: bool | list[str] = True,
    report: bool = True,
    workers: int | None = None,
) -> dict:
    """Write results.nc, summary.json, case.toml (with copies of the files the case reads
    in ``inputs/``), traces.csv and dynamics.csv (:mod:`.export`), figures, report.md and
    the self-contained report.html atomically into ``out_dir``. Returns ``{"summary": …, "figures": {name: path}, "path": out_dir}``.
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
        from .export import write_csv

        ds.to_netcdf(folder / "results.nc", engine="h5netcdf", encoding=enc)
        (folder / "summary.json").write_text(json.dumps(summ, indent=2))
        _write_case(study.case, folder)
        write_csv(ds, folder)

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
            from .export import write_html
            from .report import write_report

            write_report(study, ds, figs, tmp / "report.md")
            write_html((tmp / "report.md").read_text(encoding="utf-8"), tmp)
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

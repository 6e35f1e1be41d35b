"""The result folder: what in it is tribodyn's (the marker, its list of files and their
SHA-256, the names tribodyn writes) and what is the user's; the checks before computing
(name, parent, probe, free space); the cleanup of folders left by killed runs; marking a
written folder. The writing itself and the rules it follows: :mod:`.writer`.
"""

from __future__ import annotations

import errno
import filecmp
import hashlib
import json
import os
import re
import shutil
import time
from collections.abc import Mapping
from pathlib import Path

from .. import _json
from .._system import new_file
from .._typing import PathLike
from .._user_files import MAX_MARKER_BYTES, read_user_bytes
from .._validation import InputError

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
    "|contact_pressure|cam_kinematics|spring_surge|stress_map",
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
    """The marker's JSON object; {} if there is none or it is not one (also a marker
    that is not a regular file or is larger than :data:`MAX_MARKER_BYTES`: never read
    from a pipe or device, never read without bound)."""
    try:
        raw = read_user_bytes(folder / MARKER, "result-folder marker", limit=MAX_MARKER_BYTES)
        info = json.loads(raw.decode("utf-8"))
    except (InputError, ValueError, RecursionError):
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
            f.write(_json.dumps(info, indent=1) + "\n")
        os.replace(tmp, folder / MARKER)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
    return folder / MARKER

"""The result folder: what in it is tribodyn's (the marker, its list of files and their
SHA-256, the names tribodyn writes) and what is the user's; the checks before computing
(name, parent, probe, free space, the kind of study it holds); marking a written folder.
The temporary folder and the cleanup of folders left by killed runs: :mod:`.work_folder`;
the writing itself and the rules it follows: :mod:`.writer`.
"""

from __future__ import annotations

import errno
import filecmp
import hashlib
import json
import os
import re
import shutil
import stat
import time
from collections.abc import Mapping
from contextlib import suppress
from pathlib import Path

from .. import _json
from .._safe_write import TOKEN_CHARS, atomic_write, new_file
from .._typing import PathLike
from .._user_files import MAX_MARKER_BYTES, read_user_bytes
from .._validation import InputError
from .figure_names import FIGURES, content_name

#: File that marks a folder as written by tribodyn (JSON: tool, version, case, time).
MARKER = ".tribodyn-results"

#: File that proves a temporary (``.NAME.tmp-PID-TOKEN``) or replaced
#: (``.NAME.old-PID-TOKEN``) folder is tribodyn's: JSON with the tool, the PID and the
#: random token of the folder's name. Only such folders are ever removed.
ORIGIN = ".tribodyn-origin"

#: Most files, links and folders tribodyn keeps for the user in a result folder: a folder
#: holding more is not treated as a result folder (e.g. a home folder into which a
#: result folder's files, marker included, were copied).
MAX_FOREIGN = 2000


#: Files of a result folder written before the marker existed (tribodyn 0.1).
_LEGACY_FILES = ("results.nc", "summary.json", "case.toml")


#: Names of the files tribodyn writes in a result folder (cycle study and sweep); in a
#: folder whose marker does not list its files, these are tribodyn's own.
_OWN_NAMES = re.compile(
    r"results\.nc|summary\.json|case\.toml|report\.md|fig\d\d_[A-Za-z0-9_-]+\.png"
    r"|report\.html|traces\.csv|dynamics\.csv|(?:"
    + "|".join(re.escape(content_name(n)) for n in FIGURES)  # a case other than the paper's
    + r")"
    r"|sweep\.nc|sweep\.toml|sweep_report\.md|base_case\.toml|sweep_[A-Za-z0-9_-]+\.png"
)


#: Point files of a sweep (``points/<key>.nc``): always tribodyn's own.
_POINT_FILE = re.compile(r"points/[0-9a-f]+\.nc")


#: Folder of a result folder that holds copies of the files the case reads.
INPUTS = "inputs"


#: Characters the temporary names add to the folder's name: ``.`` + ``.tmp-PID-`` (PIDs
#: up to 7 digits) + the random token.
_NAME_OVERHEAD = 1 + 5 + 7 + 1 + TOKEN_CHARS


#: Longest path the kernel accepts [bytes] (PATH_MAX on Linux).
_PATH_MAX = 4096


#: Size of the write probe [bytes]: a full or read-only disk fails on it.
PROBE_BYTES = 1 << 20


#: Free space required before computing [bytes]: the paper case writes 17 MB
#: (results.nc 14 MB, 15 figures, report); 0.25° crank steps write about four times the
#: profiles, so 128 MB leaves room for them with a margin.
MIN_FREE_BYTES = 128 << 20


def is_result_folder(path: PathLike) -> bool:
    """True for a folder written by tribodyn (marker, or the 0.1 set of files, or a
    sweep's sweep.nc or point files)."""
    p = Path(path)
    if not p.is_dir():
        return False
    return (
        (p / MARKER).is_file()
        or all((p / f).is_file() for f in _LEGACY_FILES)
        or folder_kind(p) == "sweep"  # sweep.nc or point files
    )


def _iter_dir(p: Path):
    try:
        return list(p.iterdir())
    except OSError:
        return []


def _sha256(path: Path) -> str:
    with open(path, "rb") as f:
        return hashlib.file_digest(f, "sha256").hexdigest()


def _walk(folder: Path):
    """(relative POSIX path, its entries) of ``folder`` and of every folder below it, links
    to folders not followed; without recursion (any depth). An unreadable folder has no
    entries."""
    stack = [""]
    while stack:
        rel = stack.pop()
        try:
            with os.scandir(folder / rel if rel else folder) as it:
                entries = [(f"{rel}/{e.name}" if rel else e.name, e) for e in it]
        except OSError:
            entries = []
        yield rel, entries
        stack += [r for r, e in entries if e.is_dir(follow_symlinks=False)]


def _all_files(folder: Path, limit: int | None = None) -> list[str]:
    """Relative (POSIX) paths of the files, links and empty folders below ``folder``
    (:func:`_walk`). With ``limit``, the walk stops after ``limit + 1`` entries."""
    out: list[str] = []
    for rel, entries in _walk(folder):
        if not entries and rel:
            out.append(rel + "/")
        out += [r for r, e in entries if not e.is_dir(follow_symlinks=False)]
        if limit is not None and len(out) > limit:
            break
    return sorted(out)


def _dirs(folder: Path) -> list[str]:
    """Relative (POSIX) paths of the folders below ``folder`` (:func:`_walk`), parents
    first."""
    out = [r for _, entries in _walk(folder) for r, e in entries if e.is_dir(follow_symlinks=False)]
    return sorted(out, key=lambda r: r.count("/"))


def regular_file_bytes(folder: Path, name: str, limit: int = -1) -> bytes | None:
    """The content (at most ``limit`` bytes) of the regular file ``folder/name`` (a plain
    name: no folder part), or None if it is missing, a link, not a regular file (a
    folder, a FIFO, a device) or not in ``folder``: a result folder received from
    someone else may hold a link to a private file, which must not end up in a shared
    report, and a temporary folder's proof of origin is never read through a link."""
    if not name or "/" in name or os.sep in name or name in (".", ".."):
        return None
    p = Path(folder) / name
    flags = os.O_RDONLY | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_NONBLOCK", 0)
    try:
        fd = os.open(p, flags)
    except OSError:  # missing, a link (ELOOP), unreadable
        return None
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            return None
        with os.fdopen(fd, "rb", closefd=False) as f:
            return f.read(limit)
    finally:
        os.close(fd)


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
    changed since: listed in the marker with the same SHA-256 (also those of the
    ``previous`` list a folder updated in place has while its files are replaced; or, in a
    folder whose marker has no list, named as tribodyn names its files); point files of a
    sweep."""
    folder = Path(folder)
    info = _marker_info(folder)
    listed, previous = info.get("files"), info.get("previous")
    if not isinstance(previous, dict):
        previous = {}
    own = set()
    for rel in _all_files(folder):
        p = folder / rel
        if rel in (MARKER, ORIGIN) or (_POINT_FILE.fullmatch(rel) and p.is_file()):
            own.add(rel)
        elif p.is_symlink() or not p.is_file():
            continue
        elif isinstance(listed, dict):
            if (rel in listed or rel in previous) and _sha256(p) in (
                listed.get(rel),
                previous.get(rel),
            ):
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


def resolve_target(path: PathLike) -> Path:
    """The absolute path of an output folder; a symbolic link to a folder is replaced by
    the folder it points to (the results go there, the link stays)."""
    target = Path(path).expanduser().absolute()
    with suppress(OSError):  # a name too long: the checks say so
        if target.is_symlink() and target.is_dir():
            target = Path(os.path.realpath(target))
    return target


#: What each kind of study writes: ``kind`` of the marker → the command.
KINDS = {"run": "tribodyn run", "engine": "tribodyn engine", "sweep": "tribodyn sweep"}


def folder_kind(folder: PathLike) -> str | None:
    """The kind of study whose results ``folder`` holds (a key of :data:`KINDS`), or None
    if it is not known (no results, or a folder of a version that did not record it)."""
    folder = Path(folder)
    kind = _marker_info(folder).get("kind")
    if kind in KINDS:
        return kind
    if (folder / "sweep.nc").is_file() or any(
        _POINT_FILE.fullmatch(f"points/{q.name}") for q in _iter_dir(folder / "points")
    ):
        return "sweep"
    return None


def check_output_dir(
    path: PathLike,
    *,
    option: str = "output folder",
    writes: Mapping[str, Path | None] | None = None,
    kind: str | None = None,
) -> Path:
    """Check that results can be written to ``path`` before anything is computed.

    Returns the absolute path (that of the folder a link ``path`` points to). Raises
    :class:`~tribodyn.InputError` naming ``option`` if ``path`` is an existing file, a
    folder with contents that tribodyn did not write, a result folder holding a user's
    file with the name of one tribodyn writes (its usual names, or the keys of
    ``writes``: relative path → the file copied there, or None), a folder named like
    the marker, the results of another ``kind`` of study (:data:`KINDS`), a home folder
    or one with more than :data:`MAX_FOREIGN` files of the user's, a name too long for
    the file system, below a file, not writable, or on a disk with less than
    ``MIN_FREE_BYTES`` free (the probe writes ``PROBE_BYTES``).
    """
    target = resolve_target(path)
    try:
        _check_name(target, option)
        _check_target(target, option, writes or {}, kind)
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


def _check_target(
    target: Path, option: str, writes: Mapping[str, Path | None], kind: str | None = None
) -> None:
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
    marker = target / MARKER
    if os.path.lexists(marker) and (marker.is_symlink() or not marker.is_file()):
        raise InputError(
            f"{option} {str(target)!r} holds {MARKER}, which is not a regular file (a "
            f"folder or a link) but has the name of tribodyn's marker: rename or move it, "
            "or give another folder"
        )
    if not is_result_folder(target):
        raise InputError(
            f"{option} {str(target)!r} is a folder that tribodyn did not "
            f"write (no {MARKER} marker; it holds {_listing(_all_files(target, 10))}); it "
            "writes only into its own result folders: give a new or empty folder"
        )
    home = Path.home().absolute()
    if target == home or target in home.parents:
        raise InputError(
            f"{option} {str(target)!r} is your home folder (or holds it); tribodyn "
            f"rebuilds a result folder when it writes into it, so it does not write into "
            f"this one although it holds a {MARKER} marker: give a new folder"
        )
    have = folder_kind(target)
    if kind is not None and have is not None and have != kind:
        raise InputError(
            f"{option} {str(target)!r} holds the results of `{KINDS[have]}`; "
            f"`{KINDS[kind]}` would replace them: give another folder"
        )
    n_own = len(own_files(target))
    entries = _all_files(target, MAX_FOREIGN + n_own)
    if len(entries) > MAX_FOREIGN + n_own:
        raise InputError(
            f"{option} {str(target)!r} holds more than {MAX_FOREIGN} files that tribodyn "
            f"did not write, beside a {MARKER} marker; it does not look like a result "
            "folder (a copied marker?) and is left as it is: give a new folder"
        )
    points = target / "points"
    if kind == "sweep" and os.path.lexists(points) and (points.is_symlink() or not points.is_dir()):
        raise InputError(
            f"{option} {str(target)!r}: points is a link or a file, not the sweep's folder "
            "of point files: move it or give another folder"
        )
    longest = max((len(os.fsencode(str(target / rel))) for rel in entries), default=0)
    if longest + _NAME_OVERHEAD >= _PATH_MAX:
        raise InputError(
            f"{option} {str(target)!r} holds a path of {longest} bytes; in the temporary "
            f"folder it would exceed the file system's limit of {_PATH_MAX}: move the "
            "deepest folders elsewhere or give another folder"
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
    probe = None
    try:
        fd, probe = new_file(folder, f".{target.name}.p-{os.getpid()}-")
        with os.fdopen(fd, "wb") as f:
            f.write(b"\0" * PROBE_BYTES)
            f.flush()
            os.fsync(f.fileno())
    except OSError as exc:
        raise InputError(
            f"{option} {str(target)!r}: cannot write in {str(folder)!r} ({exc.strerror or exc})"
        ) from None
    finally:
        if probe is not None:
            with suppress(OSError):
                probe.unlink()
    free = shutil.disk_usage(folder).free
    if free < MIN_FREE_BYTES:
        raise InputError(
            f"{option} {str(target)!r}: only {free / 2**20:.0f} MB free in "
            f"{str(folder)!r}; the results need up to {MIN_FREE_BYTES >> 20} MB"
        )


def mark_folder(folder: PathLike, files: Mapping[str, str], meta: dict | None = None) -> Path:
    """Write the marker of ``folder``: tool, time, ``meta`` and ``files`` (relative path
    → SHA-256 of each file tribodyn wrote) (:func:`~tribodyn._safe_write.atomic_write`)."""
    folder = Path(folder)
    info = {
        "tool": "tribodyn",
        "written": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
        **(meta or {}),
        "files": dict(sorted(files.items())),
    }
    return atomic_write(folder / MARKER, _json.dumps(info, indent=1) + "\n")


def add_own_files(folder: Path, written) -> None:
    """Record the files ``written`` (paths in ``folder``) in the marker as tribodyn's own,
    with their SHA-256; a folder whose marker lists no files is left as it is."""
    info = _marker_info(folder)
    if isinstance(info.get("files"), dict):
        files = {**info.pop("files"), **{p.name: _sha256(p) for p in written}}
        mark_folder(folder, files, {k: v for k, v in info.items() if k not in ("tool", "written")})
